"""Independent scalar reference for Rotta's cross section (section 5.1).

Written straight from equations 5-7, 5-8, 5-9, 5-10, 5-11 and 5-12 and the
dissertation's camber-delta iteration, one ``scipy.optimize.brentq`` per section and
side, in the patch-edge variable ``e`` (as the appendix's ``fzero``), with the swept
angle taken from the bead's position relative to the bulge centre (atan2, valid on
every branch). It shares no code with :mod:`tiremesh.section`.
"""

from __future__ import annotations

import math

from scipy.optimize import brentq


def _beads(r0, w, camber):
    hr = math.sqrt(r0 * r0 - w * w / 4)  # rim line above the section centre (Eq. 5-3: h - r0)
    c, s = math.cos(camber), math.sin(camber)
    rot = lambda x, z: (c * x + s * z, -s * x + c * z)  # Appendix C R2z
    return rot(-w / 2, hr), rot(w / 2, hr)


def _bulge(e, bead, zg, side):
    """Radius (Eq. 5-9) and swept angle of the bulge tangent to the ground at e."""
    xb, zb = bead
    height = zb - zg
    r = ((xb - e) ** 2 + height**2) / (2 * height)
    # point(psi) = centre + r (-/+ sin psi, -cos psi), centre = (e, zg + r)
    sx = -1.0 if side == 1 else 1.0
    psi = math.atan2(sx * (xb - e), -(zb - zg - r)) % (2 * math.pi)
    return r, psi


def reference_section(r0, w, dv, dh, camber, *, delta=None):
    """Edges, radii and angles of one section; delta by the dissertation's iteration.

    Returns
    -------
    dict with e1, e2, r1, r2, a1, a2, delta, low1, low2
    """
    theta0 = 2 * math.asin(w / (2 * r0))
    s0 = r0 * (2 * math.pi - theta0)
    bead1, bead2 = _beads(r0, w, camber)
    zg = -r0 + dv

    def solve(delta):
        u = dh - delta
        f1 = lambda e: (lambda ra: ra[0] * ra[1])(_bulge(e, bead1, zg, 1)) - (s0 / 2 + e - u)
        f2 = lambda e: (lambda ra: ra[0] * ra[1])(_bulge(e, bead2, zg, 2)) - (s0 / 2 - e + u)
        span = 10 * s0
        e1 = brentq(f1, bead1[0] - span, bead1[0] + span, xtol=1e-14, rtol=1e-15, maxiter=500)
        e2 = brentq(f2, bead2[0] - span, bead2[0] + span, xtol=1e-14, rtol=1e-15, maxiter=500)
        r1, a1 = _bulge(e1, bead1, zg, 1)
        r2, a2 = _bulge(e2, bead2, zg, 2)
        # Table 5-4 cp_mids
        low1 = e1 - (r1 * a1 - r0 * (math.pi - theta0 / 2 + camber))
        low2 = e2 + (r2 * a2 - r0 * (math.pi - theta0 / 2 - camber))
        return dict(e1=e1, e2=e2, r1=r1, r2=r2, a1=a1, a2=a2, low1=low1, low2=low2)

    if delta is not None:
        return {**solve(delta), "delta": delta}
    delta = r0 * math.sin(camber)  # section 5.1 step 1
    for _ in range(50):  # step 2, repeated until nothing changes
        out = solve(delta)
        correction = out["low1"] - dh
        if abs(correction) < 1e-12:
            return {**out, "delta": delta}
        delta += correction
    raise RuntimeError("reference camber delta did not converge")
