"""The parts of the report that need only the manifest, started before the scans are
analysed.

The model's columns of every load case, the renders and 3D-view meshes of the
representative cases and the validation section depend on the manifest's load
cases (tire, pressure, load, surface) and the measurement data, not on what the
analysis of the scans finds. ``inkprint batch ... --report`` starts them in worker
processes (:class:`contactpatch.study.worker.Job`) with :class:`Prework` before it
analyses the scans, and hands them to :func:`contactpatch.study.report.build_report`
(``precomputed=``).

The report is the same as without them: the model's columns are found by load
case (a case the manifest did not name is solved as usual), the renders and meshes
are used only when the batch's rows give the same representative cases, and a
worker that failed is run again the usual way, so that its error reads as it does
without prework. A worker that does not finish within ``timeout`` is stopped with a
:class:`contactpatch.study.worker.WorkerError`.
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

#: longest wait for a prework worker [s] (a cold validation takes ~6-20 s)
PREWORK_TIMEOUT_S = 900.0


#: bump when what :func:`model_parts` returns changes without a source change
PREWORK_VERSION = 1
#: model parts kept in the cache (the most recently used)
CACHE_ENTRIES = 16


def parts_key(rows: list[dict], renders: bool) -> str:
    """Hash of what :func:`model_parts` depends on: the rows, the render flag, the
    source of :mod:`tiremesh` and :mod:`contactpatch`, and the versions of Python,
    NumPy and VTK (any change computes the parts again).

    Parameters
    ----------
    rows : list of dict
    renders : bool

    Returns
    -------
    str
        SHA-256 hex digest (64 characters).
    """
    import hashlib
    import json
    import platform

    import numpy as np

    import tiremesh as tm

    try:
        from vtkmodules.vtkCommonCore import vtkVersion

        vtk = vtkVersion.GetVTKVersion()
    except ImportError:
        vtk = ""
    head = [PREWORK_VERSION, renders, platform.python_version(), np.__version__, vtk, rows]
    h = hashlib.sha256(json.dumps(head, sort_keys=True, default=repr).encode())
    for root in (Path(tm.__file__).parent, Path(__file__).resolve().parents[1]):
        for f in sorted(root.rglob("*.py")):
            h.update(str(f.relative_to(root)).encode())
            h.update(f.read_bytes())
    return h.hexdigest()


def _cache_dir() -> Path:
    import os

    root = os.environ.get("ROTTA_CACHE_DIR", Path.home() / ".cache" / "rotta-tire")
    return Path(root) / "report-model"


def _read_cached(path: Path, fig_dir) -> dict | None:
    """The cached parts, their renders written to ``fig_dir``; None if unreadable."""
    import pickle

    try:
        parts = pickle.loads(path.read_bytes())
        path.touch()  # recently used
    except Exception:  # a damaged or foreign entry: computed again
        return None
    if parts["renders"] is not None:
        out = []
        for name, png in parts["renders"]:
            (Path(fig_dir) / name).write_bytes(png)
            out.append(Path(fig_dir) / name)
        parts = {**parts, "renders": out}
    return parts


def _write_cached(path: Path, parts: dict) -> None:
    import os
    import pickle

    stored = dict(parts)
    if parts["renders"] is not None:
        stored["renders"] = [(p.name, p.read_bytes()) for p in parts["renders"]]
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_bytes(pickle.dumps(stored))
    os.replace(tmp, path)
    old = sorted(path.parent.glob("*.pkl"), key=lambda f: f.stat().st_mtime, reverse=True)
    for f in old[CACHE_ENTRIES:]:
        f.unlink(missing_ok=True)


def model_parts(rows: list[dict], fig_dir, *, renders: bool = True) -> dict:
    """The model's columns of every load case of ``rows`` and the renders and 3D-view
    meshes of their representative cases (run in a worker), read from the cache
    (``$ROTTA_CACHE_DIR/report-model`` or ``~/.cache/rotta-tire/report-model``) when
    the same rows were worked out by the same code before (:func:`parts_key`).

    Parameters
    ----------
    rows : list of dict
        Manifest rows (tire, pressure_bar, load_N, surface, ...), taken as ``ok``
        prints.
    fig_dir : str or PathLike
        Where the renders are written.
    renders : bool
        Render the representative cases.

    Returns
    -------
    dict
        ``cache`` (:class:`tiremesh.LoadCase` -> model columns, as
        :func:`contactpatch.pair_prints` fills it), ``cases`` (list of
        :class:`contactpatch.study.report.ModelCase`), ``renders`` (list of Path or
        None), ``viewer`` (list of dict).
    """
    path = _cache_dir() / f"{parts_key(rows, renders)}.pkl"
    if path.is_file():
        parts = _read_cached(path, fig_dir)
        if parts is not None:
            return parts
    parts = _compute_parts(rows, fig_dir, renders)
    try:
        _write_cached(path, parts)
    except OSError:
        pass  # a read-only cache: computed again next time
    return parts


def _compute_parts(rows: list[dict], fig_dir, renders: bool) -> dict:
    from tiremesh.render import render_many

    from . import report as R
    from .compare import pair_prints

    ok = [{**r, "status": "ok"} for r in rows]
    cache: dict = {}
    pair_prints(ok, cache=cache)
    cases = R.representative_cases(ok)
    paths = None
    if renders and cases:
        paths = render_many(R.render_items(cases, fig_dir), size=R.RENDER_SIZE)
    return {"cache": cache, "cases": cases, "renders": paths, "viewer": R.viewer_cases(cases)}


class Prework:
    """Workers computing the manifest-only parts of a report.

    Parameters
    ----------
    rows : list of dict
        Manifest rows.
    renders : bool
        Render the representative cases.
    validation : bool
        Compute (or read from its cache) the validation section.
    timeout : float [s]
        Longest wait for each worker.
    """

    def __init__(
        self,
        rows: list[dict],
        *,
        renders: bool = True,
        validation: bool = True,
        timeout: float = PREWORK_TIMEOUT_S,
    ) -> None:
        from .report import validation_section
        from .worker import Job

        self.renders, self.validation, self.timeout = renders, validation, timeout
        self._dir = tempfile.TemporaryDirectory(prefix="report-prework-")
        self._jobs = {"model": Job(model_parts, rows, Path(self._dir.name), renders=renders)}
        if validation:
            self._jobs["validation"] = Job(validation_section)
        self._done: dict = {}

    def result(self, name: str):
        """The value of worker ``name`` ('model' or 'validation'), or None when it
        raised (the caller then computes the part itself).

        Parameters
        ----------
        name : str

        Returns
        -------
        object or None

        Raises
        ------
        contactpatch.study.worker.WorkerError
            The worker did not finish within ``timeout``.
        """
        from .worker import WorkerError

        if name not in self._done:
            job = self._jobs.get(name)
            try:
                self._done[name] = None if job is None else job.result(timeout=self.timeout)
            except WorkerError as exc:
                if "did not finish" in str(exc):
                    self.cancel()
                    raise
                self._done[name] = None
            except Exception:
                self._done[name] = None  # computed again in the report: the same error
        return self._done[name]

    def copy_render(self, path: Path, fig_dir) -> Path:
        """Copy a render of the model worker into ``fig_dir``.

        Parameters
        ----------
        path : Path
            As :func:`model_parts` returned it.
        fig_dir : str or PathLike

        Returns
        -------
        Path
            ``fig_dir / path.name``.
        """
        dst = Path(fig_dir) / path.name
        shutil.copyfile(path, dst)
        return dst

    def cancel(self) -> None:
        """Stop the workers still running and remove their files."""
        for job in self._jobs.values():
            job.cancel()
        self._dir.cleanup()

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.cancel()


__all__ = [
    "CACHE_ENTRIES",
    "PREWORK_TIMEOUT_S",
    "PREWORK_VERSION",
    "Prework",
    "model_parts",
    "parts_key",
]
