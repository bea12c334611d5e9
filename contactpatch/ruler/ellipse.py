"""Ellipse fits, shared by model patches and ink prints (Dressel 2013, section 5.4,
Figure 5-15).

Three estimators, each returning an :class:`EllipseFit` (falsy when it fails):

* :func:`fit_ellipse_direct`: direct least-squares fit of Fitzgibbon, Pilu and
  Fisher (1999) in the numerically stable form of Halir and Flusser (1998); always
  an ellipse when one exists. Use it on a boundary (e.g. the convex hull).
* :func:`fit_ellipse_lsq`: the plain algebraic least-squares conic
  ``a x^2 + b xy + c y^2 + d x + e y = -1`` about the data mean (the ``fit_ellipse``
  routine Appendix C calls "the same algorithm used for ink prints"); it reproduces
  Figure 5-15. It can return a non-ellipse conic, reported as a failed fit.
* :func:`ellipse_from_moments`: the ellipse with the same area centroid and second
  moments as a region (what ``regionprops`` reports): a different quantity from a
  boundary fit.

Conventions: ``length >= width`` are full axis lengths; ``angle`` is the direction
of the major axis from +x, in (-pi/2, pi/2]. Data are centred and scaled before
fitting (the pitfall of fitting far from the origin).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._tol import tol

#: a conic has 5 degrees of freedom: fewer distinct points cannot fix an ellipse
MIN_FIT_POINTS = 5


@dataclass(frozen=True)
class EllipseFit:
    """A fitted ellipse, or a failed fit (falsy, with a reason).

    Parameters
    ----------
    center : (2,) float [mm]
        Centre in the coordinates of the fitted points.
    length, width : float [mm]
        Full major and minor axes (``length >= width``).
    angle : float [rad]
        Major-axis direction from +x, in (-pi/2, pi/2].
    method : str
        Estimator: ``'direct'``, ``'lsq'``, ``'moments'`` or ``'appendix-lsq'``.
    success : bool
        False for a failed fit (the numbers are then NaN).
    reason : str
        Why the fit failed (empty on success).

    Examples
    --------
    >>> e = EllipseFit((0.0, 0.0), 4.0, 2.0, 0.0)
    >>> round(e.area, 6), bool(e)
    (6.283185, True)
    """

    center: tuple[float, float] = (np.nan, np.nan)
    length: float = np.nan
    width: float = np.nan
    angle: float = np.nan
    method: str = ""
    success: bool = True
    reason: str = ""

    def __bool__(self) -> bool:
        return self.success

    @property
    def area(self) -> float:
        """``pi * length * width / 4`` [mm^2]."""
        return float(np.pi * self.length * self.width / 4.0)

    def boundary(self, n: int = 100) -> np.ndarray:
        """Points on the ellipse, first and last equal.

        Parameters
        ----------
        n : int
            Number of points.

        Returns
        -------
        points : (n, 2) float [mm]
        """
        t = np.linspace(0.0, 2 * np.pi, n)
        a, b = 0.5 * self.length, 0.5 * self.width
        c, s = np.cos(self.angle), np.sin(self.angle)
        x, y = a * np.cos(t), b * np.sin(t)
        return np.column_stack([self.center[0] + c * x - s * y, self.center[1] + s * x + c * y])

    @classmethod
    def failed(cls, method: str, reason: str) -> EllipseFit:
        """A failed fit.

        Parameters
        ----------
        method : str
            The estimator that failed.
        reason : str
            Why, for the user.

        Returns
        -------
        EllipseFit
            Falsy, all numbers NaN.
        """
        return cls(method=method, success=False, reason=reason)


def axis_angle(vx: float, vy: float) -> float:
    """Direction of an axis (a line, not an arrow) from +x.

    Parameters
    ----------
    vx, vy : float
        A vector along the axis.

    Returns
    -------
    angle : float [rad]
        In (-pi/2, pi/2], the convention of every fit here.
    """
    angle = float(np.arctan2(vy, vx))
    if angle <= -np.pi / 2:
        angle += np.pi
    elif angle > np.pi / 2:
        angle -= np.pi
    return angle


def _count_distinct(p: np.ndarray) -> int:
    """Distinct rows of finite (n, 2) points (``len(np.unique(p, axis=0))`` at a
    sixth of the cost: equal rows are neighbours once sorted by x, then y)."""
    if len(p) < 2:
        return len(p)
    q = p[np.lexsort((p[:, 1], p[:, 0]))]
    return 1 + int(np.count_nonzero((q[1:] != q[:-1]).any(axis=1)))


def _prepare(points, method):
    """Centred and scaled points, their mean and scale, or a failed fit."""
    p = np.asarray(points, dtype=float)
    fail = None
    if p.ndim != 2 or p.shape[1] != 2:
        fail = f"points must be (n, 2), got {p.shape}"
    elif not np.all(np.isfinite(p)):
        fail = "points contain NaN or inf"
    elif (distinct := _count_distinct(p)) < MIN_FIT_POINTS:
        # repeated points keep their weight in the fit; only distinct ones count here
        fail = f"{distinct} distinct points, need >= {MIN_FIT_POINTS}"
    if fail is not None:
        return None, None, None, EllipseFit.failed(method, fail)
    mean = p.mean(axis=0)
    scale = np.sqrt(np.mean(np.sum((p - mean) ** 2, axis=1)))
    if scale == 0:
        return None, None, None, EllipseFit.failed(method, "all points coincide")
    return (p - mean) / scale, mean, scale, None


def conic_to_ellipse(coef, *, method: str = "", mean=(0.0, 0.0), scale: float = 1.0) -> EllipseFit:
    """Ellipse of the conic ``A x^2 + B xy + C y^2 + D x + E y + F = 0``.

    Parameters
    ----------
    coef : (6,) float
        ``A, B, C, D, E, F`` in the normalized coordinates ``(p - mean) / scale``.
    method : str
        Recorded in the result.
    mean : (2,) float [mm]
        Mean removed from the data before fitting.
    scale : float [mm]
        Scale the centred data were divided by.

    Returns
    -------
    EllipseFit
        In the original coordinates; failed if the conic is not a real ellipse.
    """
    A, B, C, D, E, F = np.asarray(coef, float) / np.linalg.norm(coef)
    disc = 4 * A * C - B * B
    if not np.isfinite(disc) or disc <= tol.ellipse_discriminant:
        return EllipseFit.failed(
            method, f"the fitted conic is not an ellipse (4AC - B^2 = {disc:.3g})"
        )
    x0, y0 = np.linalg.solve([[2 * A, B], [B, 2 * C]], [-D, -E])
    f0 = A * x0 * x0 + B * x0 * y0 + C * y0 * y0 + D * x0 + E * y0 + F
    lam, vec = np.linalg.eigh([[A, B / 2], [B / 2, C]])
    with np.errstate(divide="ignore", invalid="ignore"):
        semi2 = -f0 / lam
    if not np.all(np.isfinite(semi2)) or np.any(semi2 <= 0):
        return EllipseFit.failed(method, "the fitted conic is an imaginary ellipse")
    semi = np.sqrt(semi2)
    k = int(np.argmax(semi))  # major axis: the smaller |eigenvalue|
    center = (float(mean[0] + scale * x0), float(mean[1] + scale * y0))
    return EllipseFit(
        center,
        float(2 * scale * semi[k]),
        float(2 * scale * semi[1 - k]),
        axis_angle(*vec[:, k]),
        method,
    )


def fit_ellipse_direct(points) -> EllipseFit:
    """Direct least-squares ellipse (Fitzgibbon 1999, Halir-Flusser 1998 form).

    The fit :func:`contactpatch.measure` applies to a patch's hull boundary; a
    different ellipse from Figure 5-15's (see :func:`fit_ellipse_lsq`).

    Parameters
    ----------
    points : (n, 2) float [mm]
        Boundary points, at least 5 distinct.

    Returns
    -------
    EllipseFit
        Falsy with a reason for < 5 points, collinear points or no ellipse.
    """
    method = "direct"
    p, mean, scale, fail = _prepare(points, method)
    if fail is not None:
        return fail
    x, y = p[:, 0], p[:, 1]
    D1 = np.column_stack([x * x, x * y, y * y])
    D2 = np.column_stack([x, y, np.ones_like(x)])
    S1, S2, S3 = D1.T @ D1, D1.T @ D2, D2.T @ D2
    if np.linalg.cond(S3) > 1 / tol.conic_rcond:
        return EllipseFit.failed(method, "points are collinear or degenerate")
    T = -np.linalg.solve(S3, S2.T)
    M = S1 + S2 @ T
    M = np.array([M[2] / 2, -M[1], M[0] / 2])  # C1^-1 M
    with np.errstate(all="ignore"):
        w, vecs = np.linalg.eig(M)
    # the ellipse is a real eigenpair (for exact data, the zero eigenvalue; the other
    # two may then form a complex pair): keep real ones with 4AC - B^2 > 0
    wmax = max(np.max(np.abs(w)), np.finfo(float).tiny)
    real = np.abs(np.imag(w)) <= tol.eigen_imag_rtol * wmax
    vecs = np.real(vecs)
    cond = 4 * vecs[0] * vecs[2] - vecs[1] ** 2
    ok = np.nonzero(real & (cond > 0))[0]
    if ok.size == 0:
        return EllipseFit.failed(method, "no elliptical solution")
    a1 = vecs[:, ok[np.argmin(np.abs(w[ok]))]]
    return conic_to_ellipse(np.concatenate([a1, T @ a1]), method=method, mean=mean, scale=scale)


def fit_ellipse_lsq(points) -> EllipseFit:
    """Algebraic least-squares conic about the data mean (Appendix C's ``fit_ellipse``).

    Solves ``a x^2 + b xy + c y^2 + d x + e y = -1`` for centred points. Reproduces
    the ellipse of Figure 5-15 (Dressel 2013, section 5.4) from the appendix's point
    set (patch edges and centre line, :func:`contactpatch.appendix_points`).

    Parameters
    ----------
    points : (n, 2) float [mm]
        At least 5 distinct points.

    Returns
    -------
    EllipseFit
        Falsy with a reason for degenerate points or a conic that is not an ellipse
        (e.g. a hyperbola).
    """
    method = "lsq"
    p, mean, scale, fail = _prepare(points, method)
    if fail is not None:
        return fail
    x, y = p[:, 0], p[:, 1]
    A = np.column_stack([x * x, x * y, y * y, x, y])
    sol, _, rank, _ = np.linalg.lstsq(A, -np.ones_like(x), rcond=None)
    if rank < 5:
        return EllipseFit.failed(method, "points are collinear or degenerate")
    return conic_to_ellipse(np.append(sol, 1.0), method=method, mean=mean, scale=scale)


def polygon_moments(geom):
    """Area, centroid and central second moments of a region (Green's theorem).

    Parameters
    ----------
    geom : shapely Polygon or MultiPolygon
        Holes count negatively.

    Returns
    -------
    (area, centroid, cov) or None
        ``area`` float [mm^2], ``centroid`` (2,) [mm], ``cov`` (2, 2) float [mm^2]
        (second moments about the centroid per unit area); None for zero area.
    """
    from shapely.geometry.polygon import orient

    polys = list(getattr(geom, "geoms", [geom]))
    a = sx = sy = sxx = syy = sxy = 0.0
    for poly in polys:
        poly = orient(poly, 1.0)
        for ring in [poly.exterior, *poly.interiors]:
            c = np.asarray(ring.coords)
            x0, y0, x1, y1 = c[:-1, 0], c[:-1, 1], c[1:, 0], c[1:, 1]
            cr = x0 * y1 - x1 * y0
            a += cr.sum() / 2
            sx += ((x0 + x1) * cr).sum() / 6
            sy += ((y0 + y1) * cr).sum() / 6
            sxx += ((x0 * x0 + x0 * x1 + x1 * x1) * cr).sum() / 12
            syy += ((y0 * y0 + y0 * y1 + y1 * y1) * cr).sum() / 12
            sxy += ((x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * cr).sum() / 24
    if a <= 0:
        return None
    cx, cy = sx / a, sy / a
    return (
        a,
        (cx, cy),
        np.array([[sxx / a - cx * cx, sxy / a - cx * cy], [sxy / a - cx * cy, syy / a - cy * cy]]),
    )


def _cov_to_ellipse(center, cov, method) -> EllipseFit:
    """The uniform ellipse with this centroid and covariance."""
    lam, vec = np.linalg.eigh(cov)
    if not np.all(np.isfinite(lam)) or lam[0] <= 0:
        return EllipseFit.failed(method, "region has no area in one direction")
    # a uniform ellipse with semi-axes a, b has variances a^2 / 4 and b^2 / 4
    return EllipseFit(
        (float(center[0]), float(center[1])),
        float(4 * np.sqrt(lam[1])),
        float(4 * np.sqrt(lam[0])),
        axis_angle(*vec[:, 1]),
        method,
    )


def ellipse_from_moments(region) -> EllipseFit:
    """Ellipse with the area centroid and second moments of a region.

    Parameters
    ----------
    region : shapely Polygon or MultiPolygon [mm]

    Returns
    -------
    EllipseFit
        Method ``'moments'``; failed for an empty region or zero area.
    """
    method = "moments"
    if region is None or getattr(region, "is_empty", True):
        return EllipseFit.failed(method, "empty region")
    m = polygon_moments(region)
    if m is None:
        return EllipseFit.failed(method, "region has zero area")
    return _cov_to_ellipse(m[1], m[2], method)


def ellipse_from_mask(mask, *, pixel_size: float = 1.0) -> EllipseFit:
    """Moments ellipse of a boolean image; each pixel counts as a filled square
    (variance + 1/12 px^2).

    Parameters
    ----------
    mask : (rows, cols) bool
        Image, indexed (row, col); ``x`` = column, ``y`` = row.
    pixel_size : float [mm/px]
        Pixel pitch; the result is in these units.

    Returns
    -------
    EllipseFit
        Method ``'moments'``; failed for an empty mask.
    """
    method = "moments"
    m = np.asarray(mask, bool)
    rows, cols = np.nonzero(m)
    if rows.size == 0:
        return EllipseFit.failed(method, "empty mask")
    x, y = cols.astype(float), rows.astype(float)
    cov = np.cov(np.vstack([x, y]), bias=True) + np.eye(2) / 12.0
    return _cov_to_ellipse(
        (x.mean() * pixel_size, y.mean() * pixel_size), cov * pixel_size**2, method
    )
