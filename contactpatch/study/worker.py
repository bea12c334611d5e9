"""Run one function of the report in a separate Python process.

The report renders and validates while it draws its figures. A fresh interpreter
does that work, started with a few lines of code (:data:`RUNNER`) that put this
``contactpatch``'s folder first on the path, unpickle the function's module, name
and arguments, call it and pickle back its value or exception. Unlike a forked or
forkserver child it never re-imports the caller's ``__main__`` (scripts need no
``if __name__ == "__main__"`` guard), shares no threads or OpenGL state with the
caller, and imports only what the function needs (a :mod:`tiremesh` function does
not import :mod:`contactpatch`).

:class:`Job` starts it; :meth:`Job.result` waits and returns the function's value,
or raises its exception (with the worker's traceback).
"""

from __future__ import annotations

import pickle
import subprocess
import sys
import tempfile
from pathlib import Path

#: the worker's program: ``python -c RUNNER ROOT IN.pkl OUT.pkl``
RUNNER = """
import importlib, pickle, sys, traceback
root, inp, out = sys.argv[1:4]
sys.path.insert(0, root)
with open(inp, "rb") as fh:
    module, name, args, kwargs = pickle.load(fh)
try:
    func = importlib.import_module(module)
    for part in name.split("."):
        func = getattr(func, part)
    result = (True, func(*args, **kwargs), "")
except Exception as exc:
    result = (False, exc, traceback.format_exc())
try:
    data = pickle.dumps(result)
except Exception as exc:
    data = pickle.dumps((False, RuntimeError(repr(exc)), traceback.format_exc()))
with open(out, "wb") as fh:
    fh.write(data)
"""


class WorkerError(RuntimeError):
    """The worker process failed outside the function (e.g. it could not start)."""


class Job:
    """``func(*args, **kwargs)`` running in a new Python process.

    Parameters
    ----------
    func : callable
        A module-level function (found again by module and name).
    *args, **kwargs
        Picklable arguments.
    """

    def __init__(self, func, *args, **kwargs) -> None:
        self._dir = tempfile.TemporaryDirectory(prefix="report-job-")
        d = Path(self._dir.name)
        self._out = d / "out.pkl"
        self.name = func.__qualname__
        job = (func.__module__, func.__qualname__, args, kwargs)
        (d / "in.pkl").write_bytes(pickle.dumps(job))
        root = str(Path(__file__).resolve().parents[2])  # the folder holding contactpatch
        self._proc = subprocess.Popen(
            [sys.executable, "-c", RUNNER, root, str(d / "in.pkl"), str(self._out)],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )

    def result(self, timeout: float | None = None):
        """Wait for the function and return its value.

        Parameters
        ----------
        timeout : float, optional [s]
            Wait at most this long; then the process is stopped and
            :class:`WorkerError` raised (default: no limit).

        Returns
        -------
        object

        Raises
        ------
        Exception
            The function's own exception, its worker traceback chained.
        WorkerError
            When the process failed before returning anything, or did not finish
            within ``timeout``.
        """
        try:
            try:
                _, err = self._proc.communicate(timeout=timeout)
            except subprocess.TimeoutExpired:
                self._proc.kill()
                self._proc.communicate()
                raise WorkerError(
                    f"report worker ({self.name}) did not finish within {timeout:g} s; stopped"
                ) from None
            if not self._out.is_file():
                tail = err.decode("utf-8", "replace")[-3000:]
                raise WorkerError(f"report worker exited with {self._proc.returncode}: {tail}")
            ok, value, tb = pickle.loads(self._out.read_bytes())
        finally:
            self._dir.cleanup()
        if not ok:
            raise value from WorkerError(tb)
        return value

    def cancel(self) -> None:
        """Stop the process if it still runs, and remove its files."""
        if self._proc.poll() is None:
            self._proc.kill()
            self._proc.wait()
        self._dir.cleanup()


__all__ = ["RUNNER", "Job", "WorkerError"]
