"""Judgement thresholds of the solver, passed explicitly (never module globals).

:class:`SolverOptions` is a frozen value given as ``options=`` to
:func:`tiremesh.solve`, :func:`tiremesh.solve_many`, :func:`tiremesh.solve_lateral`,
:func:`tiremesh.max_load` and :func:`tiremesh.sweep.run_sweep`. ``run_sweep`` sends it
with every task to local worker processes and Dask workers, so a threshold set by the
caller gives the same rows with one worker, many, or a cluster. (A module global such
as the former ``tiremesh.tol.rim_clearance`` was re-imported at its default by every
worker process: LoadTooHigh rows with ``workers=1``, ok rows with ``workers=2``.)

Inside one call the options are active in a :class:`contextvars.ContextVar`
(:func:`active`), so nested calls (``solve_lateral`` -> ``solve``) inherit them
without threading them through every numerical kernel; a call without ``options``
uses the ones of the enclosing call, or the defaults.

:data:`tiremesh.tol` keeps only numerical epsilons (convergence tolerances and
iteration safeguards of root finders), which do not change a result beyond rounding.
"""

from __future__ import annotations

import contextlib
import math
from contextvars import ContextVar
from dataclasses import dataclass, fields

from .errors import InvalidParameter


@dataclass(frozen=True)
class SolverOptions:
    """Judgement thresholds: settings that change which cases solve or what is reported.

    Attributes
    ----------
    rim_clearance : float [-]
        Largest usable wheel deflection as a fraction of the deflection at which a
        bead reaches the ground (where Rotta's bulge radius becomes infinite), in
        (0, 1]. Loads beyond it raise ``LoadTooHigh``.
    force_rtol : float [-]
        A patch lateral force below this fraction of the vertical force counts as
        zero: the pneumatic trail is then NaN. >= 0.
    trail_min_patch_share : float [-]
        Below this share of the lateral force carried by the patch's own sections
        the pneumatic trail is NaN (its centroid is meaningless; the validation found
        -660 mm there). In [0, 1].
    friction_rtol : float [-]
        Convergence of the total lateral force in Appendix C's friction iteration
        (``friction_model='appendix'``, section 5.6). > 0.
    friction_max_iter : int
        Iterations of that friction loop before ``NotConverged``. >= 1.
    """

    rim_clearance: float = 0.995
    force_rtol: float = 1e-12
    trail_min_patch_share: float = 0.1
    friction_rtol: float = 1e-9
    friction_max_iter: int = 60

    def __post_init__(self) -> None:
        ranges = {
            "rim_clearance": (lambda x: 0 < x <= 1, "in (0, 1]"),
            "force_rtol": (lambda x: x >= 0, ">= 0 and finite"),
            "trail_min_patch_share": (lambda x: 0 <= x <= 1, "in [0, 1]"),
            "friction_rtol": (lambda x: x > 0, "> 0 and finite"),
        }
        for name, (inside, text) in ranges.items():
            val = getattr(self, name)
            real = isinstance(val, int | float) and not isinstance(val, bool)
            if not (real and math.isfinite(val) and inside(val)):
                raise InvalidParameter(name, val, text)
        n = self.friction_max_iter
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise InvalidParameter("friction_max_iter", n, "an integer >= 1")

    def replace(self, **changes) -> SolverOptions:
        """A copy with ``changes`` (validated).

        Parameters
        ----------
        **changes
            Field values.

        Returns
        -------
        SolverOptions
        """
        unknown = set(changes) - {f.name for f in fields(self)}
        if unknown:
            raise InvalidParameter("options", sorted(unknown), "fields of SolverOptions")
        return SolverOptions(**{**self.__dict__, **changes})


DEFAULT = SolverOptions()
_ACTIVE: ContextVar[SolverOptions] = ContextVar("tiremesh_solver_options", default=DEFAULT)


def active() -> SolverOptions:
    """The options of the enclosing solver call (the defaults outside any call).

    Returns
    -------
    SolverOptions
    """
    return _ACTIVE.get()


def check(options) -> SolverOptions:
    """``options`` as SolverOptions: None gives the active ones.

    Parameters
    ----------
    options : SolverOptions or None

    Returns
    -------
    SolverOptions

    Raises
    ------
    InvalidParameter
        Not a SolverOptions (e.g. a dict).
    """
    if options is None:
        return active()
    if not isinstance(options, SolverOptions):
        raise InvalidParameter("options", type(options).__name__, "a tiremesh.SolverOptions")
    return options


@contextlib.contextmanager
def using(options):
    """Make ``options`` active for the enclosed calls (None: keep the active ones).

    Parameters
    ----------
    options : SolverOptions or None

    Returns
    -------
    context manager yielding SolverOptions
    """
    opts = check(options)
    token = _ACTIVE.set(opts)
    try:
        yield opts
    finally:
        _ACTIVE.reset(token)
