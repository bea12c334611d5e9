"""Numerical tolerances of :mod:`contactpatch`, in one documented place."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class Tolerances:
    """Attributes
    ----------
    min_fit_points : int
        An ellipse has 5 degrees of freedom: fewer points is a failed fit.
    conic_rcond : float [-]
        Relative singularity threshold of the normalized scatter matrices; below it
        the points are (nearly) collinear or coincident: a failed fit.
    ellipse_discriminant : float [-]
        ``4AC - B^2`` of the normalized conic must exceed this (scale-free: the
        conic is normalized to unit coefficient norm) or the fit is not an ellipse.
    surface_atol : float [mm]
        A mesh vertex within this distance of the support surface is on it.
    boundary_samples : int
        Points per hull boundary for the direct ellipse fit (uniform in arc length,
        so the fit does not depend on how the outline happens to be sampled).
    """

    min_fit_points: int = 5
    conic_rcond: float = 1e-12
    ellipse_discriminant: float = 1e-12
    surface_atol: float = 1e-6
    boundary_samples: int = 360


tol = Tolerances()
