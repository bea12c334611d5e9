"""Numerical tolerances of :mod:`contactpatch`, in one documented place.

Only numerical epsilons live here (thresholds that guard floating-point arithmetic).
Judgement thresholds with a physical meaning are keyword options of the functions
that use them: ``atol`` of :func:`contactpatch.contact_faces` (when a mesh vertex is
on the support surface, mm) and ``boundary_samples`` of :func:`contactpatch.measure`.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class Tolerances:
    """Numerical epsilons (mutable on purpose, like ``tiremesh.tol``).

    Attributes
    ----------
    conic_rcond : float [-]
        Relative singularity threshold of the normalized scatter matrices; below it
        the points are (nearly) collinear or coincident: a failed fit.
    ellipse_discriminant : float [-]
        ``4AC - B^2`` of the normalized conic must exceed this (scale-free: the
        conic is normalized to unit coefficient norm) or the fit is not an ellipse.
    eigen_imag_rtol : float [-]
        An eigenvalue of the direct fit is real when its imaginary part is below
        this fraction of the largest eigenvalue's magnitude.
    area_rtol : float [-]
        Relative slack allowed when a given net area exceeds the hull area
        (round-off of the two area computations).
    """

    conic_rcond: float = 1e-12
    ellipse_discriminant: float = 1e-12
    eigen_imag_rtol: float = 1e-8
    area_rtol: float = 1e-9


tol = Tolerances()
