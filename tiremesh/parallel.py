"""One parallel map for the whole project: in this process, in local worker
processes, or on a Dask cluster.

Whatever a task needs (options, thresholds) travels with it as an argument: worker
processes import the packages afresh, so module-level settings changed by the caller
would not reach them. Pass option objects explicitly (``functools.partial`` or
``kwargs``).

Local worker processes die with their parent: each watches the process that started
the pool and exits when it is gone (also after ``kill -9``), so no worker is left
blocked forever.

A Dask scheduler is checked before Dask is asked to connect (:func:`check_scheduler`):
a plain TCP connection within ``scheduler_timeout`` seconds, then the scheduler's
handshake, which a Dask scheduler sends as soon as a client connects. A refused
connection, an unknown host, a silent service and a service that answers something
else (an HTTP server, such as the Dask dashboard) all raise :class:`SchedulerError`
naming the address, within the timeout.
"""

from __future__ import annotations

import math
import os
import time
import warnings
from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING

from .errors import InvalidParameter, TireModelError

if TYPE_CHECKING:
    import socket

DEFAULT_SCHEDULER_TIMEOUT = 10.0
"""Seconds to wait for a Dask scheduler to accept and answer (``--scheduler-timeout``)."""
DEFAULT_SCHEDULER_PORT = 8786
"""Port of a scheduler address given without one (Dask's default)."""
_MAX_HANDSHAKE = 1 << 24  # a Dask handshake is a few hundred bytes
_PARENT_POLL = 0.5  # s between a worker's checks that its parent is alive


class SchedulerError(TireModelError, ConnectionError):
    """A Dask scheduler could not be reached or is not a Dask scheduler.

    Attributes
    ----------
    address : str
        The scheduler address as given.
    reason : str
        What went wrong, in words.
    """

    def __init__(self, address: str, reason: str) -> None:
        self.address = str(address)
        self.reason = reason
        super().__init__(f"Dask scheduler {address}: {reason}")


def _host_port(address: str) -> tuple[str, str | None, int | None]:
    """``(scheme, host, port)``; host and port None for schemes other than tcp."""
    text = str(address).strip()
    scheme, sep, rest = text.partition("://")
    if not sep:
        scheme, rest = "tcp", text
    if scheme.lower() != "tcp":
        return scheme.lower(), None, None
    if rest.endswith("]") or ":" not in rest:
        host, port = rest, str(DEFAULT_SCHEDULER_PORT)
    else:
        host, _, port = rest.rpartition(":")
    host = host.strip("[]")
    try:
        number = int(port)
    except ValueError:
        number = -1
    if not host or not 0 < number < 65536:
        raise SchedulerError(address, "expected an address like tcp://HOST:8786")
    return "tcp", host, number


def _validate_timeout(timeout) -> float:
    try:
        t = float(timeout)
    except (TypeError, ValueError) as exc:
        raise InvalidParameter("scheduler_timeout", timeout, "a number of seconds > 0") from exc
    if not (math.isfinite(t) and t > 0):
        raise InvalidParameter("scheduler_timeout", timeout, "a number of seconds > 0")
    return t


def _read_head(sock: socket.socket, address: str, deadline: float, timeout: float) -> bytes:
    """The first 8 bytes the service sends (Dask: the handshake's frame length)."""
    head = b""
    while len(head) < 8:
        sock.settimeout(max(deadline - time.monotonic(), 1e-3))
        try:
            chunk = sock.recv(8 - len(head))
        except TimeoutError:
            raise SchedulerError(
                address,
                f"connected, but no Dask handshake within {timeout:g} s: not a Dask "
                "scheduler (a silent service, or an HTTP server such as the Dask "
                "dashboard, usually on :8787; the scheduler listens on :8786)",
            ) from None
        except OSError as exc:
            raise SchedulerError(address, f"connection lost: {exc.strerror or exc}") from exc
        if not chunk:
            raise SchedulerError(address, "the service closed the connection without a handshake")
        head += chunk
    return head


def check_scheduler(address: str, *, timeout: float = DEFAULT_SCHEDULER_TIMEOUT) -> str:
    """Check that a Dask scheduler listens at ``address``, within ``timeout`` seconds.

    Opens a plain TCP connection and reads the start of the handshake a Dask
    scheduler sends at once; nothing is sent to the service. Addresses of other
    schemes (``tls://``, ``ws://``, ``inproc://``) are returned unchecked.

    Parameters
    ----------
    address : str
        ``tcp://HOST:PORT``, ``HOST:PORT`` or ``HOST`` (port 8786).
    timeout : float [s]
        For the connection and the handshake together.

    Returns
    -------
    str
        ``address``, unchanged.

    Raises
    ------
    SchedulerError
        Malformed address, unknown host, connection refused or timed out, a silent
        service, or one that does not speak Dask's protocol (e.g. HTTP).
    InvalidParameter
        ``timeout`` not a number > 0.
    """
    import socket  # here: importing the module (for its defaults) needs no network

    timeout = _validate_timeout(timeout)
    scheme, host, port = _host_port(address)
    if scheme != "tcp":
        return address
    deadline = time.monotonic() + timeout
    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except ConnectionRefusedError:
        raise SchedulerError(address, "connection refused: no scheduler listens there") from None
    except socket.gaierror as exc:
        raise SchedulerError(address, f"unknown host {host!r} ({exc.strerror})") from None
    except TimeoutError:
        raise SchedulerError(address, f"no connection within {timeout:g} s") from None
    except OSError as exc:
        raise SchedulerError(address, f"cannot connect: {exc.strerror or exc}") from None
    with sock:
        head = _read_head(sock, address, deadline, timeout)
    if head[:4].upper() == b"HTTP" or head[:1] == b"<":
        raise SchedulerError(
            address,
            "an HTTP server answered, not a Dask scheduler (the dashboard? the "
            "scheduler usually listens on :8786)",
        )
    if not 0 < int.from_bytes(head, "little") <= _MAX_HANDSHAKE:
        raise SchedulerError(address, "the service there does not speak Dask's protocol")
    return address


def connect_scheduler(address: str, *, timeout: float = DEFAULT_SCHEDULER_TIMEOUT):
    """Connect a Dask client to the scheduler at ``address`` (checked first).

    Parameters
    ----------
    address : str
        Scheduler address (``tcp://HOST:8786``).
    timeout : float [s]
        For the check (:func:`check_scheduler`) and for Dask's own connection.

    Returns
    -------
    distributed.Client
        Not set as Dask's default client; close it (or use it in ``with``) when done.

    Raises
    ------
    SchedulerError
        The scheduler cannot be reached, is not a Dask scheduler, or Dask's
        connection fails.
    """
    check_scheduler(address, timeout=timeout)
    return _client(address, _validate_timeout(timeout))


def _client(address: str, timeout: float):
    from dask.distributed import Client

    try:
        return Client(address, timeout=f"{timeout}s", set_as_default=False)
    except (OSError, TimeoutError) as exc:
        raise SchedulerError(address, str(exc) or type(exc).__name__) from exc


_WATCHING: set[int] = set()  # parent pids this process already watches


def watch_parent(pid: int, *, interval: float = _PARENT_POLL, exit_code: int = 1) -> bool:
    """In a worker process: exit as soon as process ``pid`` (the pool's owner) is gone,
    or as soon as this worker is re-parented (its forkserver died with the owner).

    A daemon thread polls every ``interval`` seconds and ends the process with
    ``os._exit(exit_code)``, so no worker is left blocked on a dead parent's queue.
    Calling it again for the same ``pid``, or with this process's own pid (the
    in-process path), does nothing.

    Parameters
    ----------
    pid : int
        Process id of the process that started the worker.
    interval : float, optional
        Seconds between checks [s].
    exit_code : int, optional
        Exit status of the worker when the parent is gone.

    Returns
    -------
    bool
        True if a watcher thread was started, False if none was needed.
    """
    import threading

    if pid == os.getpid() or pid in _WATCHING:
        return False
    _WATCHING.add(pid)
    ppid = os.getppid()

    def watch() -> None:
        while True:
            time.sleep(interval)
            try:
                os.kill(pid, 0)
            except ProcessLookupError:
                os._exit(exit_code)
            except PermissionError:
                pass
            if os.getppid() != ppid:
                os._exit(exit_code)

    threading.Thread(target=watch, name=f"parent-watch-{pid}", daemon=True).start()
    return True


def _check_workers(workers) -> int:
    if workers is None:
        return os.cpu_count() or 1
    if isinstance(workers, bool) or not isinstance(workers, int):
        raise InvalidParameter("workers", workers, "an integer >= 1 (or None: one per CPU)")
    if workers < 1:
        raise InvalidParameter("workers", workers, "an integer >= 1 (or None: one per CPU)")
    return workers


def _dask_map(func, items, scheduler, timeout: float, kwargs: dict):
    """Map on a Dask cluster; ``scheduler`` an address or a connected Client."""
    from dask.distributed import as_completed

    own = isinstance(scheduler, str)
    # an address was checked by parallel_map: connect without probing again
    client = _client(scheduler, timeout) if own else scheduler
    try:
        futures = client.map(func, list(items), pure=False, **kwargs)
        index = {f.key: i for i, f in enumerate(futures)}
        for fut in as_completed(futures, loop=client.loop):
            yield index[fut.key], fut.result()
    finally:
        if own:
            client.close()


def _pool_map(func, items: Sequence, n: int, kwargs: dict):
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    ctx = mp.get_context("spawn" if os.name == "nt" else "forkserver")
    pending = dict(enumerate(items))
    pool_kw = dict(mp_context=ctx, initializer=watch_parent, initargs=(os.getpid(),))
    try:
        with ProcessPoolExecutor(max_workers=min(n, len(items)), **pool_kw) as pool:
            futures = {pool.submit(func, it, **kwargs): i for i, it in pending.items()}
            for fut in as_completed(futures):
                i = futures[fut]
                result = fut.result()
                del pending[i]
                yield i, result
    except BrokenProcessPool:
        # e.g. run from a notebook or stdin, whose __main__ worker processes cannot
        # import: finish in this process rather than lose the work
        warnings.warn("worker processes failed to start; finishing in this process", stacklevel=3)
        for i in sorted(pending):
            yield i, func(pending[i], **kwargs)


def parallel_map(
    func: Callable,
    items: Sequence,
    *,
    workers: int | None = None,
    scheduler=None,
    scheduler_timeout: float = DEFAULT_SCHEDULER_TIMEOUT,
    kwargs: dict | None = None,
    min_items: int = 2,
) -> Iterator[tuple[int, object]]:
    """Apply ``func(item, **kwargs)`` to every item; iterate ``(index, result)`` as
    each completes (in completion order).

    The arguments are checked at the call, before any work, also when there are no
    items: a scheduler address is probed (:func:`check_scheduler`), so a wrong one
    is never silently ignored.

    Parameters
    ----------
    func : callable
        Importable (module-level) function, so worker processes can load it.
    items : sequence
    workers : int, optional
        Local worker processes, >= 1 (default: the number of CPUs); 1 runs in this
        process. Workers exit when this process dies.
    scheduler : str or distributed.Client, optional
        Address of a Dask scheduler (``tcp://host:8786``), or a connected client
        (used, not closed); overrides ``workers``.
    scheduler_timeout : float [s]
        How long to wait for the scheduler to accept and answer (default 10).
    kwargs : dict, optional
        Keyword arguments passed to every call (options objects, thresholds).
    min_items : int
        Fewer items than this run in this process (a pool costs ~0.3 s to start).

    Returns
    -------
    iterator of (int, object)
        ``(index into items, result)`` pairs, in completion order.

    Raises
    ------
    InvalidParameter
        ``workers`` not an integer >= 1, or ``scheduler_timeout`` not > 0.
    SchedulerError
        The scheduler cannot be reached within ``scheduler_timeout`` or is not a Dask
        scheduler (the message names the address).
    """
    kwargs = kwargs or {}
    n = _check_workers(workers)
    timeout = _validate_timeout(scheduler_timeout)
    if isinstance(scheduler, str):
        scheduler = scheduler.strip() or None
        if scheduler is not None:
            check_scheduler(scheduler, timeout=timeout)
    if not items:
        return iter(())
    if scheduler is not None:
        return _dask_map(func, items, scheduler, timeout, kwargs)
    if n == 1 or len(items) < min_items:
        return ((i, func(item, **kwargs)) for i, item in enumerate(items))
    return _pool_map(func, items, n, kwargs)


__all__ = [
    "DEFAULT_SCHEDULER_PORT",
    "DEFAULT_SCHEDULER_TIMEOUT",
    "SchedulerError",
    "check_scheduler",
    "connect_scheduler",
    "parallel_map",
    "watch_parent",
]
