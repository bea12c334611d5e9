"""Model patches as measurable regions, and the appendix's ellipse (Dressel 2013,
section 5.4, Figure 5-15).

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

from ..errors import InvalidInput
from .ellipse import EllipseFit, fit_ellipse_lsq
from .metrics import as_geometry


def patch_polygon(patch):
    """The solver's patch outline as a valid region (as :func:`contactpatch.measure`
    sees it).

    Parameters
    ----------
    patch : tiremesh.ContactPatch

    Returns
    -------
    shapely Polygon [mm]
        ``(s, y)``: arc length along the surface (ground ``x`` on flat ground) and
        lateral. Made valid: the pointed ends may close with a round-off bow tie.
    """
    return as_geometry(patch)


def appendix_points(patch, *, sections_per_half: int = 151, last_angle_deg: float = 15.0):
    """The point set Appendix C fits its ellipse to (Figure 5-15): the patch edges and
    centre line of the sections in contact.

    Parameters
    ----------
    patch : tiremesh.ContactPatch
    sections_per_half : int
        Sections per half of the wheel, spaced uniformly in angle (>= 3).
    last_angle_deg : float [deg]
        Angle of the last section from bottom dead centre, in (0, 90).

    Returns
    -------
    points : (n, 2) float [mm]
        As (y, x): lateral, forward (the appendix's order).
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


def appendix_ellipse(patch, *, sections_per_half: int = 151, last_angle_deg: float = 15.0):
    """Figure 5-15's ellipse (section 5.4): :func:`fit_ellipse_lsq` on
    :func:`appendix_points`.

    Parameters
    ----------
    patch : tiremesh.ContactPatch
    sections_per_half, last_angle_deg : int, float [deg]
        As in :func:`appendix_points`.

    Returns
    -------
    EllipseFit
        Method ``'appendix-lsq'``, in ground ``(x, y)`` [mm] (angle from +x);
        falsy if the fit fails.
    """
    pts = appendix_points(
        patch, sections_per_half=sections_per_half, last_angle_deg=last_angle_deg
    )
    e = fit_ellipse_lsq(pts[:, ::-1])
    if e:
        return EllipseFit(e.center, e.length, e.width, e.angle, "appendix-lsq")
    return e
