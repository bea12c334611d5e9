"""Rotta's cross section (section 5.1, equations 5-7, 5-10, 5-11, 5-12 and 5-13;
forces per length, equations 5-25 and 5-26).

Each radial cross section pressed onto the ground is a flat contact segment
``[e1, e2]`` plus two circular side bulges, each tangent to the ground at its patch
edge and passing through its rim bead, with the bead-to-bead carcass arc length
conserved.

Frame (Figure 5-1, Appendix C): origin at the centre of the *undeformed* section
circle, ``x`` horizontal toward side 2, ``z`` up toward the rim, ground at
``z = -r0 + dv``. Side 1 is at ``-x`` and side 2 at ``+x``; in the ground frame of
:mod:`tiremesh.solver` side 2 is ``+y``. Positive camber rotates the rim toward
``+x`` (the wheel top leans to ``+y``).

Closed form used here (a departure from the appendix's nested ``fzero``)
-------------------------------------------------------------------------
For a bulge of bead height ``H`` above the ground and swept angle ``theta``
(tangent point to bead), equations 5-11 and 5-12 give ``r = H / (1 - cos theta)``
and the horizontal bead-to-edge offset ``d = r sin theta = H cot(theta / 2)``.
Substituting into the arc-length condition ``r theta = s`` of equation 5-13, with the
side's arc length ``s`` from equation 5-10, leaves, per side, the circular-segment
relation::

    q(theta) = (theta - sin theta) / (1 - cos theta) = c / H,     theta in (0, 2 pi)

with ``c = s - d`` a known constant (arc length minus horizontal offset). ``q``
increases monotonically from 0 to infinity, so each side has exactly one root,
found here by a bracketed Newton iteration to machine precision, vectorized over
all sections. ``theta = pi - 2 atan(d / H)`` also removes the branch error of the
appendix's ``pi - asin(d / r)``, which is wrong when the bead lies below the
bulge centre (``d > H``).

Camber delta (section 5.1): the appendix estimates ``delta = r0 sin(camber)`` and
corrects it until the lowest point computed from side 1 equals the section's
horizontal displacement, stopping at 0.1 mm. Writing out the lowest-point
formula of Table 5-4 shows that the correction is exact after one step: the fixed
point is ``delta = r0 * camber`` (the arc distance of section 5.2 from the carcass
centre line to the lowest point of the cambered tire). Table 5-4's 10.9956 is
``14 mm * pi / 4``. We use the fixed point; :func:`camber_delta_iteration`
reproduces the dissertation's iteration for the tests.

References
----------
A. E. Dressel (2013), section 5.1 and Tables 5-3, 5-4. The index of equations
(equation -> function -> test) is in ``docs/model.md``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import validate as v
from ._roots import newton_bracketed
from ._tol import tol
from .errors import InvalidParameter
from .geometry import arc_length, rim_angle

TWO_PI = 2.0 * np.pi


def _theta_minus_sin(t):
    t = np.asarray(t, float)
    if t.size and t.min() >= tol.series_below:
        return t - np.sin(t)
    t2 = t * t
    series = (t2 * t / 6.0) * (
        1.0
        - t2
        / 20.0
        * (1.0 - t2 / 42.0 * (1.0 - t2 / 72.0 * (1.0 - t2 / 110.0 * (1.0 - t2 / 156.0))))
    )
    return np.where(t < tol.series_below, series, t - np.sin(t))


def bulge_ratio(theta):
    """Circular-segment ratio ``q = (theta - sin theta) / (1 - cos theta)``.

    ``q`` is (arc length - chord-wise bead offset) / bead height of a Rotta side
    bulge: the arc-length condition of equation 5-13 written in the bulge angle
    (section 5.1; see module docstring).

    Parameters
    ----------
    theta : (...) float [rad], in [0, 2 pi)

    Returns
    -------
    q : (...) float [-]
    dq : (...) float [1/rad]
        Derivative ``dq/dtheta = 1 - q cot(theta / 2)``.
    """
    t = np.asarray(theta, float)
    half = 0.5 * t
    one_minus_cos = 2.0 * np.sin(half) ** 2
    with np.errstate(divide="ignore", invalid="ignore"):
        q = _theta_minus_sin(t) / one_minus_cos
        dq = 1.0 - q * np.cos(half) / np.sin(half)
    if t.size and t.min() < 1e-6:
        tiny = t < 1e-6
        q = np.where(tiny, t / 3.0, q)
        dq = np.where(tiny, 1.0 / 3.0, dq)
    return q, dq


def _initial_angle(y):
    # inverse of q: q ~ theta/3 near 0, q ~ 4 pi / (2 pi - theta)^2 near 2 pi;
    # a table in log(q) gives ~1e-5 rad, leaving 2-3 Newton steps.
    ly = np.log(np.maximum(y, 1e-300))
    return np.interp(ly, _LOGQ_TABLE, _THETA_TABLE, left=np.nan, right=np.nan)


_THETA_TABLE = np.linspace(1e-3, TWO_PI - 1e-3, 8193)
_LOGQ_TABLE = np.log(bulge_ratio(_THETA_TABLE)[0])


def solve_bulge_angle(ratio):
    """Invert :func:`bulge_ratio`: the swept bulge angle with ``q(theta) = ratio``.

    A table in ``log q`` gives theta to ~1e-8 rad; two Newton steps then reach
    machine precision (quadratic convergence). Any element whose last step is not
    negligible (ratios outside the table, ~theta < 1e-3 or > 2 pi - 1e-3) is
    re-solved by the bracketed Newton iteration.

    Parameters
    ----------
    ratio : (...) float [-], > 0

    Returns
    -------
    theta : (...) float [rad], in (0, 2 pi)
    """
    y = np.asarray(ratio, float)
    theta = _initial_angle(y)
    for _ in range(2):
        q, dq = bulge_ratio(theta)
        step = (q - y) / dq
        theta = theta - step
    if np.all(np.abs(step) <= tol.bulge_fast_step):
        return theta
    x0 = np.where(
        np.isfinite(theta), theta, np.where(y < 1.0, 3.0 * y, TWO_PI - np.sqrt(4 * np.pi / y))
    )

    def fun(t):
        q, dq = bulge_ratio(t)
        return q - y, dq

    return newton_bracketed(
        fun,
        np.clip(x0, 0.0, TWO_PI),
        np.zeros_like(y),
        np.full_like(y, TWO_PI),
        xtol=tol.angle_xtol,
        what="side-bulge angle (section 5.1)",
        sign_lo=-1.0,
    )


def bead_positions(tire_radius, rim_width, camber):
    """Rim bead points of a cambered section (Figure 5-3, Appendix C ``R2z``).

    Parameters
    ----------
    tire_radius, rim_width : (...) float [mm]
    camber : (...) float [rad]

    Returns
    -------
    xb1, zb1, xb2, zb2 : (...) float [mm]
        Beads of side 1 and side 2 in the section frame.
    """
    r0 = np.asarray(tire_radius, float)
    half_w = 0.5 * np.asarray(rim_width, float)
    hr = np.sqrt(r0 * r0 - half_w * half_w)  # = r0 cos(theta0 / 2) = h - r0
    c, s = np.cos(camber), np.sin(camber)
    return -c * half_w + s * hr, s * half_w + c * hr, c * half_w + s * hr, -s * half_w + c * hr


@dataclass(frozen=True)
class SectionSolution:
    """Geometry of Rotta cross sections (all arrays broadcast to one shape).

    Attributes
    ----------
    edge1, edge2 : (...) float [mm]
        Contact-patch edges ``e1 < e2`` in the section frame (Table 5-4 ``cp_edges``).
    radius1, radius2 : (...) float [mm]
        Side-bulge radii ``r1, r2`` (equation 5-11).
    angle1, angle2 : (...) float [rad]
        Angles swept by the bulges, tangent point to bead (equation 5-12, on every
        branch).
    height1, height2 : (...) float [mm]
        Bead heights above the ground, ``H = z_bead + r0 - dv``.
    bead1, bead2 : tuple of (...) float [mm]
        ``(x, z)`` of the beads.
    ground_z : (...) float [mm]
        Ground line ``z = -r0 + dv``.
    vert_deflection, horz_deflection : (...) float [mm]
        The section's ``dv`` and ``dh`` (the position of the carcass point that
        first touched the ground).
    delta : (...) float [mm]
        Camber delta used (``r0 * camber`` unless given).
    lowest1, lowest2 : (...) float [mm]
        Where the first-touching carcass point lies, computed from side 1 and from
        side 2 (Table 5-4 ``cp_mids``); equal when both roots are exact.
    dwidth_ddv, dwidth_ddh : (...) float [-]
        Sensitivities of the patch width to ``dv`` and ``dh`` (implicit
        differentiation of the two root equations).
    dmid_ddv, dmid_ddh : (...) float [-]
        Sensitivities of the patch midpoint ``(e1 + e2) / 2``.
    """

    edge1: np.ndarray
    edge2: np.ndarray
    radius1: np.ndarray
    radius2: np.ndarray
    angle1: np.ndarray
    angle2: np.ndarray
    height1: np.ndarray
    height2: np.ndarray
    bead1: tuple[np.ndarray, np.ndarray]
    bead2: tuple[np.ndarray, np.ndarray]
    ground_z: np.ndarray
    vert_deflection: np.ndarray
    horz_deflection: np.ndarray
    delta: np.ndarray
    lowest1: np.ndarray
    lowest2: np.ndarray
    dwidth_ddv: np.ndarray
    dwidth_ddh: np.ndarray
    dmid_ddv: np.ndarray
    dmid_ddh: np.ndarray

    @property
    def width(self) -> np.ndarray:
        """Flat contact width ``e2 - e1`` [mm] (negative: edges crossed, no contact)."""
        return self.edge2 - self.edge1

    @property
    def arc1(self) -> np.ndarray:
        """Side-1 bulge arc length ``r1 theta1`` [mm]."""
        return self.radius1 * self.angle1

    @property
    def arc2(self) -> np.ndarray:
        """Side-2 bulge arc length ``r2 theta2`` [mm]."""
        return self.radius2 * self.angle2

    def lateral_force_density(self, pressure) -> np.ndarray:
        """``dS/dy = p (r1 - r2)``, equation 5-25.

        Parameters
        ----------
        pressure : (...) float [N/mm^2]

        Returns
        -------
        (...) float [N/mm]
            Lateral force per unit length of the section's track, positive toward side 2.
        """
        return np.asarray(pressure) * (self.radius1 - self.radius2)

    def vertical_force_density(self, pressure) -> np.ndarray:
        """``dN/dy = p (e2 - e1)``, equation 5-26.

        Parameters
        ----------
        pressure : (...) float [N/mm^2]

        Returns
        -------
        (...) float [N/mm]
            Vertical force per unit length; zero where the edges cross.
        """
        return np.asarray(pressure) * np.maximum(self.width, 0.0)


def section_arrays(r0, w, dv, dh, *, camber, delta, broadcast=False):
    """Unchecked core of :func:`solve_sections` (equations 5-10, 5-13, 5-11, 5-12).

    Parameters
    ----------
    r0, w, dv, dh, delta : (...) float [mm], broadcastable ((m, 1), (m, n) in the solver)
    camber : (...) float [rad]
    broadcast : bool, whether to broadcast every field of the solution to one shape

    Returns
    -------
    sol, bad_h, bad_c : SectionSolution, (...) bool; flags: bead at/below ground, c <= 0"""
    theta0 = rim_angle(w, r0)
    half_s0 = 0.5 * arc_length(r0, theta0)
    xb1, zb1, xb2, zb2 = bead_positions(r0, w, camber)
    zg = -r0 + dv
    h1, h2 = zb1 - zg, zb2 - zg
    c1 = half_s0 + delta + xb1 - dh  # Eq. 5-10 (side 1): c1 = s1 - d1, e1 = xb1 + d1
    c2 = half_s0 - delta - xb2 + dh  # side 2 of equation 5-10: c2 = s2 - d2
    bad_h = (h1 <= 0) | (h2 <= 0)
    bad_c = (c1 <= 0) | (c2 <= 0)
    h1s, h2s = np.where(bad_h | bad_c, 1.0, h1), np.where(bad_h | bad_c, 1.0, h2)
    y1, y2 = np.where(bad_c | bad_h, 1.0, c1) / h1s, np.where(bad_c | bad_h, 1.0, c2) / h2s
    th = solve_bulge_angle(np.stack(np.broadcast_arrays(y1, y2)))  # Eq. 5-13
    half = 0.5 * th
    sin_h = np.sin(half)
    cot = np.cos(half) / sin_h
    hs = np.stack(np.broadcast_arrays(h1s, h2s))
    r = hs / (2.0 * sin_h * sin_h)  # Eq. 5-11: r = H / (1 - cos theta)
    _, dq = bulge_ratio(th)
    (th1, th2), (cot1, cot2), (r1, r2), (dq1, dq2) = th, cot, r, dq
    e1, e2 = xb1 + h1s * cot1, xb2 - h2s * cot2  # Eq. 5-12: d = r sin theta = H cot(theta/2)
    low1 = e1 - (r1 * th1 - r0 * (np.pi - 0.5 * theta0 + camber))  # lowest point from side 1
    low2 = e2 + (r2 * th2 - r0 * (np.pi - 0.5 * theta0 - camber))  # and side 2 (Table 5-4 cp_mids)
    dd1_dv = -cot1 - r1 * (y1 / h1s) / dq1  # width sensitivities: d(d_i) = cot dH - r dtheta,
    dd2_dv = -cot2 - r2 * (y2 / h2s) / dq2  # with dtheta = dy / q'
    dwidth_ddv = -(dd1_dv + dd2_dv)
    dd1_dh, dd2_dh = r1 / (h1s * dq1), -r2 / (h2s * dq2)
    dwidth_ddh = -(dd1_dh + dd2_dh)
    dmid_ddv = 0.5 * (dd1_dv - dd2_dv)
    dmid_ddh = 0.5 * (dd1_dh - dd2_dh)
    shape = np.broadcast(e1, e2).shape
    b = (lambda a: np.broadcast_to(a, shape)) if broadcast else (lambda a: a)
    sol = SectionSolution(
        edge1=b(e1),
        edge2=b(e2),
        radius1=b(r1),
        radius2=b(r2),
        angle1=b(th1),
        angle2=b(th2),
        height1=b(h1),
        height2=b(h2),
        bead1=(b(xb1), b(zb1)),
        bead2=(b(xb2), b(zb2)),
        ground_z=b(zg),
        vert_deflection=b(dv),
        horz_deflection=b(dh),
        delta=b(delta),
        lowest1=b(low1),
        lowest2=b(low2),
        dwidth_ddv=b(dwidth_ddv),
        dwidth_ddh=b(dwidth_ddh),
        dmid_ddv=b(dmid_ddv),
        dmid_ddh=b(dmid_ddh),
    )
    if not broadcast:
        return sol, bad_h, bad_c
    return sol, np.broadcast_to(bad_h, shape), np.broadcast_to(bad_c, shape)


def solve_sections(
    tire_radius, rim_width, vert_deflection, horz_deflection=0.0, camber=0.0, *, delta=None
) -> SectionSolution:
    """Solve Rotta cross sections, vectorized over any broadcastable inputs.

    Section 5.1; Table 5-4 is the worked example.

    Parameters
    ----------
    tire_radius : (...) float [mm]
        Undeformed carcass radius ``r0``.
    rim_width : (...) float [mm]
        Inner rim width ``w``.
    vert_deflection : (...) float [mm]
        ``dv``: how far the ground is pressed into the section, perpendicular to the
        ground. May be <= 0 (the edges then cross: no contact).
    horz_deflection : (...) float [mm]
        ``dh``: horizontal position of the carcass point that first touched the
        ground (``dv tan(camber)`` for a rolling cambered tire, equation 5-7; around
        the wheel, equation 5-17).
    camber : (...) float [rad]
        Camber angle, |camber| < pi/2.
    delta : (...) float [mm], optional
        Camber delta; default is the exact fixed point ``r0 * camber``.

    Returns
    -------
    SectionSolution

    Raises
    ------
    InvalidParameter
        Non-finite or out-of-range input, a bead at or below the ground
        (``vert_deflection`` too large), or a displacement that leaves a bulge no
        carcass (``horz_deflection`` too large).

    Notes
    -----
    Dressel (2013), section 5.1: equations 5-10, 5-11, 5-12 and 5-13, solved in
    closed form per side (module docstring); see :func:`section_arrays`.
    """
    r0 = v.positive("tire_radius", tire_radius, unit="mm")
    w = v.positive("rim_width", rim_width, unit="mm")
    if np.any(w >= 2 * r0):
        raise InvalidParameter("rim_width", _first(w), "< 2 x tire_radius [mm]")
    dv = v.finite("vert_deflection", vert_deflection, unit="mm")
    dh = v.finite("horz_deflection", horz_deflection, unit="mm")
    gamma = v.in_range("camber", camber, -np.pi / 2, np.pi / 2, unit="rad")
    dl = r0 * gamma if delta is None else v.finite("delta", delta, unit="mm")
    sol, bad_h, bad_c = section_arrays(r0, w, dv, dh, camber=gamma, delta=dl, broadcast=True)
    if np.any(bad_h):
        hmin = np.minimum(sol.height1, sol.height2)
        raise InvalidParameter(
            "vert_deflection",
            _first(np.broadcast_to(dv, bad_h.shape)[bad_h]),
            "less than the height of the lower bead above the ground",
            f"bead height would be {_first(hmin[bad_h]):.4g} mm",
        )
    if np.any(bad_c):
        raise InvalidParameter(
            "horz_deflection",
            _first(np.broadcast_to(dh, bad_c.shape)[bad_c]),
            "small enough that each side bulge keeps more carcass than its chord",
        )
    return sol


def camber_delta_iteration(tire_radius, rim_width, vert_deflection, camber, *, steps=5):
    """The dissertation's camber-delta correction (section 5.1, Table 5-4), run exactly.

    Starts at ``delta = r0 sin(camber)`` and repeats ``delta += lowest1 - dh`` with
    ``dh = dv tan(camber)`` (equation 5-7). Returns the sequence of deltas
    (``steps + 1`` values); the first correction already lands on the fixed point
    ``r0 * camber``.

    Parameters
    ----------
    tire_radius, rim_width : (...) float [mm]
    vert_deflection : (...) float [mm]
        ``dv`` of the central section.
    camber : (...) float [rad]
    steps : int
        Corrections to run.

    Returns
    -------
    deltas : (steps + 1, ...) float [mm]
    """
    r0 = np.asarray(tire_radius, float)
    dh = np.asarray(vert_deflection, float) * np.tan(camber)  # Eq. 5-7
    deltas = [r0 * np.sin(camber)]
    for _ in range(steps):
        sol = solve_sections(r0, rim_width, vert_deflection, dh, camber, delta=deltas[-1])
        deltas.append(deltas[-1] + (sol.lowest1 - dh))
    return np.stack(np.broadcast_arrays(*deltas))


def _first(a):
    a = np.asarray(a)
    return float(a.flat[0]) if a.size else float("nan")
