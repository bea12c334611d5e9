"""One parallel map for the whole project: in this process, in local worker
processes, or on a Dask cluster.

Whatever a task needs (options, thresholds) travels with it as an argument: worker
processes import the packages afresh, so module-level settings changed by the caller
would not reach them. Pass option objects explicitly (``functools.partial`` or
``kwargs``).
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Callable, Iterator, Sequence


def parallel_map(
    func: Callable,
    items: Sequence,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    kwargs: dict | None = None,
    min_items: int = 2,
) -> Iterator[tuple[int, object]]:
    """Apply ``func(item, **kwargs)`` to every item; yield ``(index, result)`` as each
    completes (in completion order).

    Parameters
    ----------
    func : callable
        Importable (module-level) function, so worker processes can load it.
    items : sequence
    workers : int, optional
        Local worker processes (default: the number of CPUs); 1 runs in this process.
    scheduler : str, optional
        Address of a Dask scheduler (``tcp://host:8786``); overrides ``workers``.
    kwargs : dict, optional
        Keyword arguments passed to every call (options objects, thresholds).
    min_items : int
        Fewer items than this run in this process (a pool costs ~0.3 s to start).

    Yields
    ------
    index : int
    result : object
    """
    kwargs = kwargs or {}
    if not items:
        return
    if scheduler:
        from dask.distributed import Client, as_completed

        with Client(scheduler, timeout="30s") as client:
            futures = client.map(func, list(items), pure=False, **kwargs)
            index = {f.key: i for i, f in enumerate(futures)}
            for fut in as_completed(futures):
                yield index[fut.key], fut.result()
        return
    n = workers if workers is not None else (os.cpu_count() or 1)
    if n < 1:
        raise ValueError(f"workers must be >= 1, got {workers}")
    if n == 1 or len(items) < min_items:
        for i, item in enumerate(items):
            yield i, func(item, **kwargs)
        return
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    ctx = mp.get_context("spawn" if os.name == "nt" else "forkserver")
    pending = dict(enumerate(items))
    try:
        with ProcessPoolExecutor(max_workers=min(n, len(items)), mp_context=ctx) as pool:
            futures = {pool.submit(func, it, **kwargs): i for i, it in pending.items()}
            for fut in as_completed(futures):
                i = futures[fut]
                result = fut.result()
                del pending[i]
                yield i, result
    except BrokenProcessPool:
        # e.g. run from a notebook or stdin, whose __main__ worker processes cannot
        # import: finish in this process rather than lose the work
        warnings.warn("worker processes failed to start; finishing in this process", stacklevel=2)
        for i in sorted(pending):
            yield i, func(pending[i], **kwargs)


__all__ = ["parallel_map"]
