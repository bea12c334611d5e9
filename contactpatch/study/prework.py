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


def model_parts(rows: list[dict], fig_dir, *, renders: bool = True) -> dict:
    """The model's columns of every load case of ``rows`` and the renders and 3D-view
    meshes of their representative cases (run in a worker).

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


__all__ = ["PREWORK_TIMEOUT_S", "Prework", "model_parts"]
