"""Model patches as measurable regions, and the appendix's ellipse (section 5.4).

Figure 5-15's ellipse (98.49 x 9.783 mm for the 55 mm Big Apple at 5 mm
deflection) is Appendix C's ``fit_ellipse`` -- a plain least-squares conic -- fitted
to *all* patch points the appendix stores: both edges *and* the patch centre line
(the lowest points of each section, inside the patch), on 151 sections per half
over 15 degrees. :func:`appendix_ellipse` reproduces that to the printed digits.
The centre-line points pull the fit toward the middle and shorten the ellipse:
fitted to the edges alone the same routine gives ~107 mm; the direct fit to the
outline (:func:`contactpatch.measure`) gives a longer ellipse still. Say which one
a number is.
"""

from __future__ import annotations

import numpy as np

from .ellipse import EllipseFit, fit_ellipse_lsq
from .errors import InvalidInput


def patch_polygon(patch):
    """The solver's patch outline as a shapely Polygon (ground x, y [mm])."""
    import shapely

    return shapely.Polygon(patch.outline)


def appendix_points(patch, *, sections_per_half: int = 151, last_angle_deg: float = 15.0):
    """The point set Appendix C fits its ellipse to: patch edges and centre line of
    the sections in contact, on ``sections_per_half`` sections per half of the
    wheel spaced uniformly from 0 to ``last_angle_deg``.

    Returns
    -------
    points : (n, 2) float [mm], as (y, x): lateral, forward
    """
    if not isinstance(sections_per_half, int) or sections_per_half < 3:
        raise InvalidInput("sections_per_half", sections_per_half, "an integer >= 3")
    if not 0 < last_angle_deg < 90:
        raise InvalidInput("last_angle_deg", last_angle_deg, "(0, 90) degrees")
    half = np.linspace(0.0, np.radians(last_angle_deg), sections_per_half)
    phi = np.concatenate([-half[::-1], half])
    sol, _ = patch.sections_at(phi)
    keep = sol.width > 0
    phi = phi[keep]
    pts = []
    for xs in (sol.edge1[keep], sol.lowest1[keep], sol.lowest2[keep], sol.edge2[keep]):
        x, y, _ = patch.to_ground(xs, np.broadcast_to(sol.ground_z, sol.edge1.shape)[keep], phi)
        pts.append(np.column_stack([y, x]))
    return np.concatenate(pts)


def appendix_ellipse(patch, **kwargs) -> EllipseFit:
    """Figure 5-15's ellipse: :func:`fit_ellipse_lsq` on :func:`appendix_points`
    (section 5.4). Returned in ground (x, y) coordinates (angle from +x)."""
    pts = appendix_points(patch, **kwargs)
    e = fit_ellipse_lsq(pts[:, ::-1])
    if e:
        return EllipseFit(e.center, e.length, e.width, e.angle, "appendix-lsq")
    return e
