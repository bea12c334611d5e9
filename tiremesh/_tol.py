"""All numerical tolerances of :mod:`tiremesh`, in one documented place.

Modelled on ``trimesh.tol``: no stray epsilons elsewhere in the package. Only
numerical epsilons live here (convergence tolerances and iteration safeguards of
the root finders), which change a result at most at the rounding level; a change
(e.g. ``tiremesh.tol.load_rtol = 1e-12``) applies to this process only, not to
worker processes. Judgement thresholds (rim clearance, when a force counts as zero,
Appendix C's friction iteration) are :class:`tiremesh.SolverOptions`, passed
explicitly as ``options=`` and sent to workers.
"""

from __future__ import annotations

from dataclasses import dataclass

MOVED_TO_OPTIONS = ("rim_clearance", "force_rtol", "friction_rtol")
"""Former fields, now judgement thresholds of :class:`tiremesh.SolverOptions`."""


@dataclass
class Tolerances:
    """Numerical tolerances (mutable on purpose, like ``trimesh.tol``).

    Attributes
    ----------
    angle_xtol : float [rad]
        Absolute step below which the Newton solve for a side-bulge angle
        (section 5.1) has converged. 4e-15 rad is ~ 1e-14 mm of arc on a 25 mm bulge:
        machine precision for the section geometry.
    end_xtol : float [rad]
        Absolute step below which the patch-end root (zero patch width along the
        wheel, section 5.2) has converged; 1e-13 rad is 3e-11 mm at the tread.
    load_rtol : float [-]
        Relative tolerance of the load search (``find_sinkage``) on the vertical
        force. The issue asks for 1e-6; 1e-10 costs one more Newton step.
    disk_offset_atol : float [mm]
        Convergence of the disk offset fixed point (section 5.3.2).
    max_iter : int
        Iteration cap of every Newton / fixed-point root loop (a safeguard: they
        converge in a few steps). Exceeding it raises :class:`tiremesh.NotConverged`
        with the state reached.
    geometry_xtol : float [rad]
        Convergence of the rim-angle root of equation 5-6 (arc length -> tire radius).
    search_sections : int
        Clenshaw-Curtis sections per patch used inside the load search. The patch
        integrals converge spectrally (the patch width is analytic between its
        exact ends), so 65 nodes already give the area to ~1e-12 relative.
    end_width_atol : float [mm]
        Patch width at a converged patch end in the joint load search; the end
        angle is then exact to ~1e-11 rad (4e-9 mm along the patch).
    bulge_fast_step : float [rad]
        The second Newton step for a side-bulge angle from its table guess is
        ~1e-15 rad; a larger step means the guess was poor (ratio outside the
        table) and the bracketed solver takes over.
    series_below : float [rad]
        Below this bulge angle, ``theta - sin(theta)`` is evaluated by its Taylor
        series (no cancellation).
    zero_force_xtol : float [mm]
        Root of a section's zero-lateral-force displacement (friction sliding).
    """

    angle_xtol: float = 4e-15
    end_xtol: float = 1e-13
    load_rtol: float = 1e-10
    disk_offset_atol: float = 1e-11
    max_iter: int = 60
    geometry_xtol: float = 1e-15
    search_sections: int = 65
    end_width_atol: float = 1e-9
    bulge_fast_step: float = 1e-11
    series_below: float = 0.3
    zero_force_xtol: float = 1e-10

    def __setattr__(self, name: str, value) -> None:
        # a misspelled or moved name must not pass silently
        if name in MOVED_TO_OPTIONS or name not in type(self).__dataclass_fields__:
            from .errors import InvalidParameter

            raise InvalidParameter(
                f"tol.{name}",
                value,
                "a numerical tolerance of Tolerances; judgement thresholds are "
                f"SolverOptions fields, e.g. solve(..., options=SolverOptions({name}=...))",
            )
        object.__setattr__(self, name, value)


tol = Tolerances()
