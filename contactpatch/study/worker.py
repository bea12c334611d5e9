"""Run one function of the report in a separate Python process.

The report renders and validates while it draws its figures. A fresh interpreter
(``python -m contactpatch.study.worker IN OUT``) does that work: unlike a forked or
forkserver child it never re-imports the caller's ``__main__`` (scripts need no
``if __name__ == "__main__"`` guard) and shares no threads or OpenGL state with it.

:class:`Job` starts it; :meth:`Job.result` waits and returns the function's value,
or raises its exception (with the worker's traceback).
"""

from __future__ import annotations

import importlib
import os
import pickle
import subprocess
import sys
import tempfile
import traceback
from pathlib import Path


class WorkerError(RuntimeError):
    """The worker process failed outside the function (e.g. it could not start)."""


class Job:
    """``func(*args)`` running in a new Python process.

    Parameters
    ----------
    func : callable
        A module-level function (found again by module and name).
    *args
        Picklable arguments.
    """

    def __init__(self, func, *args) -> None:
        self._dir = tempfile.TemporaryDirectory(prefix="report-job-")
        d = Path(self._dir.name)
        self._out = d / "out.pkl"
        (d / "in.pkl").write_bytes(pickle.dumps((func.__module__, func.__qualname__, args)))
        root = str(Path(__file__).resolve().parents[2])  # the folder holding contactpatch
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(p for p in (root, env.get("PYTHONPATH")) if p)
        self._proc = subprocess.Popen(
            [sys.executable, "-m", "contactpatch.study.worker", str(d / "in.pkl"), str(self._out)],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            env=env,
        )

    def result(self):
        """Wait for the function and return its value.

        Returns
        -------
        object

        Raises
        ------
        Exception
            The function's own exception, its worker traceback chained.
        WorkerError
            When the process failed before returning anything.
        """
        try:
            _, err = self._proc.communicate()
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


def main(argv=None) -> int:
    """Worker entry point: ``IN.pkl OUT.pkl``.

    Parameters
    ----------
    argv : list of str, optional

    Returns
    -------
    int
        Exit status (0 also when the function raised: the exception is in OUT).
    """
    inp, out = argv if argv is not None else sys.argv[1:]
    module, name, args = pickle.loads(Path(inp).read_bytes())
    try:
        func = importlib.import_module(module)
        for part in name.split("."):
            func = getattr(func, part)
        result = (True, func(*args), "")
    except Exception as exc:  # sent back to the caller, which raises it
        result = (False, exc, traceback.format_exc())
    try:
        data = pickle.dumps(result)
    except Exception as exc:  # an unpicklable value or exception
        data = pickle.dumps((False, WorkerError(repr(exc)), traceback.format_exc()))
    Path(out).write_bytes(data)
    return 0


if __name__ == "__main__":
    sys.exit(main())
