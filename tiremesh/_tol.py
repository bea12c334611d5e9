"""All numerical tolerances of :mod:`tiremesh`, in one documented place.

Modelled on ``trimesh.tol``: no stray epsilons elsewhere in the package. Change
a value here (e.g. ``tiremesh.tol.load_rtol = 1e-12``) and every solver uses it.
"""

from __future__ import annotations

from dataclasses import dataclass


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
        Iteration cap of every Newton / fixed-point loop. Exceeding it raises
        :class:`tiremesh.NotConverged` with the state reached.
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
    friction_rtol : float [-]
        Convergence of the total lateral force in the friction iteration (5.6).
    zero_force_xtol : float [mm]
        Root of a section's zero-lateral-force displacement (friction sliding).
    force_rtol : float [-]
        A lateral force below this fraction of the vertical force is zero (the
        rounding level of the force integrals); the pneumatic trail is then NaN.
    rim_clearance : float [-]
        Largest usable wheel deflection as a fraction of the deflection at which a
        bead reaches the ground (where Rotta's bulge radius becomes infinite).
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
    friction_rtol: float = 1e-9
    zero_force_xtol: float = 1e-10
    force_rtol: float = 1e-12
    rim_clearance: float = 0.995


tol = Tolerances()
