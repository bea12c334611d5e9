"""Rotta's model in 3D: sections around the wheel and the contact patch
(sections 5.2 to 5.5).

Each radial section at angle ``phi`` from bottom dead centre is pressed into the
support surface by (Eq. 5-17, 5-18 to 5-21)::

    dv(phi) = (R - (R - dw) / cos phi) cos(camber) - D_drum(phi)

and displaced sideways by (Eq. 5-13 with the imposed lateral displacement,
slip and disk terms of Appendix C and Eq. 5-22 to 5-24)::

    dh(phi) = lateral + dv tan(camber) + x(phi) tan(slip) + D_disk(phi) - offset

where ``x = (R - dv) sin phi`` is the section's forward position along the ground
(the appendix's ``dy`` increments) and ``offset`` puts the patch ends of a disk
where they would be on a straight track (section 5.3.2, solved to convergence
instead of the appendix's hard-coded 1.4 mm).

The patch ends are the roots of the section width ``e2 - e1`` along the wheel,
found by a bracketed Newton iteration with analytic derivatives (not quantized to
the section spacing, as in the appendix). Between them, sections sit on
Clenshaw-Curtis nodes, so the integrals of Eq. 5-25 and 5-26 converge spectrally.

Ground frame: ``x`` forward (rolling direction), ``y`` lateral toward section
side 2 (the side the wheel top leans to for positive camber), ``z`` up; origin on
the ground below the centre of the central section (for a drum, ``x`` is arc
length along the drum surface, as on paper wrapped around the drum).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from . import _validate as v
from ._roots import newton_bracketed
from ._tol import tol
from .errors import InvalidParameter, NoContact, NotConverged, TireModelError
from .geometry import TireGeometry
from .section import SectionSolution, _solve_sections
from .surface import Disk, Drum, Flat, Surface, curvature_drop


@functools.lru_cache(maxsize=32)
def clenshaw_curtis(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Clenshaw-Curtis nodes (ascending, endpoints included) and weights on [-1, 1].

    Parameters
    ----------
    n : int
        Number of nodes, >= 3.

    Returns
    -------
    nodes, weights : (n,) float
    """
    N = n - 1
    k = np.arange(n)
    nodes = -np.cos(np.pi * k / N)
    j = np.arange(1, N // 2 + 1)
    b = np.where(2 * j == N, 1.0, 2.0)
    c = np.where((k == 0) | (k == N), 1.0, 2.0)
    terms = (b / (4.0 * j * j - 1.0))[None, :] * np.cos(2.0 * np.pi * np.outer(k, j) / N)
    weights = c / N * (1.0 - terms.sum(axis=1))
    nodes.setflags(write=False)
    weights.setflags(write=False)
    return nodes, weights


@dataclass(frozen=True)
class _Cases:
    """Broadcast parameters of m load cases, each of shape (m, 1)."""

    r0: np.ndarray
    w: np.ndarray
    R: np.ndarray
    gamma: np.ndarray
    slip: np.ndarray
    lateral: np.ndarray
    k_drum: np.ndarray
    k_disk: np.ndarray  # signed: > 0 when the track centre is on +y
    pressure: np.ndarray

    @property
    def m(self) -> int:
        return self.r0.shape[0]

    @property
    def rim_height(self) -> np.ndarray:
        return self.r0 + np.sqrt(self.r0**2 - 0.25 * self.w**2)

    def max_deflection(self) -> np.ndarray:
        """Largest wheel deflection before a bead reaches the ground or a bulge runs
        out of carcass at the central section, times ``tol.rim_clearance``."""
        from .section import bead_positions

        cg, sg = np.cos(self.gamma), np.sin(self.gamma)
        xb1, zb1, xb2, zb2 = bead_positions(self.r0, self.w, self.gamma)
        limit = (np.minimum(zb1, zb2) + self.r0) / cg
        half_s0 = self.r0 * (np.pi - np.arcsin(0.5 * self.w / self.r0))
        delta = self.r0 * self.gamma
        c1_room = half_s0 + delta + xb1 - self.lateral  # c1 > 0 -> dv tan g < c1_room
        c2_room = half_s0 - delta - xb2 + self.lateral  # c2 > 0 -> dv tan g > -c2_room
        with np.errstate(all="ignore"):
            lim1 = np.where(sg > 0, c1_room / sg, np.inf)
            lim2 = np.where(sg < 0, -c2_room / sg, np.inf)
        return tol.rim_clearance * np.minimum(limit, np.minimum(lim1, lim2))


def _cases(
    tire_radius,
    rim_width,
    bead_seat_diameter,
    pressure,
    camber,
    slip,
    lateral,
    drum_diameter,
    disk_diameter,
    disk_side,
) -> _Cases:
    """Validate and broadcast case parameters to (m, 1) arrays."""
    r0 = v.positive("tire_radius", tire_radius, unit="mm")
    w = v.positive("rim_width", rim_width, unit="mm")
    if np.any(w >= 2 * r0):
        raise InvalidParameter("rim_width", float(np.max(w)), "< 2 x tire_radius [mm]")
    d = v.positive("bead_seat_diameter", bead_seat_diameter, unit="mm")
    p = v.positive("pressure", pressure, unit="N/mm^2")
    g = v.in_range("camber", camber, -np.pi / 2, np.pi / 2, unit="rad")
    a = v.in_range("slip", slip, -np.pi / 2, np.pi / 2, unit="rad")
    lat = v.finite("lateral", lateral, unit="mm")
    dd = np.asarray(drum_diameter, float)
    if np.any(np.isnan(dd)) or np.any(dd <= 0):
        raise InvalidParameter("drum_diameter", dd, "> 0 mm (inf for flat ground)")
    kd = np.where(np.isinf(dd), 0.0, 2.0 / np.where(np.isinf(dd), 1.0, dd))
    kd_ = np.asarray(disk_diameter, float)
    if np.any(np.isnan(kd_)) or np.any(kd_ <= 0):
        raise InvalidParameter("disk_diameter", kd_, "> 0 mm (inf for a straight track)")
    ks = np.asarray(disk_side, float)
    if np.any((ks != 1) & (ks != -1)):
        raise InvalidParameter("disk_side", ks, "+1 or -1")
    kk = np.where(np.isinf(kd_), 0.0, 2.0 / np.where(np.isinf(kd_), 1.0, kd_)) * ks
    hr = np.sqrt(r0**2 - 0.25 * w**2)
    R = 0.5 * d + r0 + hr
    arrs = np.broadcast_arrays(r0, w, R, g, a, lat, kd, kk, p)
    col = [np.atleast_1d(x).reshape(-1, 1).astype(float) for x in arrs]
    return _Cases(*col)


def _displacements(phi, dw, cs: _Cases, offset):
    """Per-section dv, dh, forward position x and their phi-derivatives."""
    cg, tg, ta = np.cos(cs.gamma), np.tan(cs.gamma), np.tan(cs.slip)
    sp, cp = np.sin(phi), np.cos(phi)
    dv = cg * (cs.R - (cs.R - dw) / cp)  # Eq. 5-17
    ddv = -cg * (cs.R - dw) * sp / (cp * cp)
    drop, ddrop = curvature_drop(phi, cs.R, cs.k_drum)  # Eq. 5-19 to 5-21
    dv, ddv = dv - drop, ddv - ddrop
    x = (cs.R - dv) * sp
    dx = -ddv * sp + (cs.R - dv) * cp
    shift, dshift = curvature_drop(phi, cs.R, cs.k_disk)  # Eq. 5-22 to 5-24
    dh = cs.lateral + dv * tg + x * ta + (shift - offset)
    ddh = ddv * tg + dx * ta + dshift
    return dv, ddv, dh, ddh, x, dx


def _blame(cs: _Cases, bad) -> str:
    idx = np.nonzero(np.any(np.atleast_2d(bad), axis=-1))[0]
    i = int(idx[0]) if idx.size else 0
    if cs.slip[i, 0] != 0:
        return "slip"
    if cs.lateral[i, 0] != 0:
        return "lateral"
    return "camber"


def _sections_at(phi, dw, cs: _Cases, offset, broadcast=False):
    dv, ddv, dh, ddh, x, dx = _displacements(phi, dw, cs, offset)
    sol, bad_h, bad_c = _solve_sections(cs.r0, cs.w, dv, dh, cs.gamma, cs.r0 * cs.gamma, broadcast)
    if np.any(bad_h):
        raise InvalidParameter(
            "deflection",
            float(np.max(np.broadcast_to(dw, bad_h.shape)[bad_h])),
            "small enough that no bead reaches the support surface",
        )
    if np.any(bad_c):
        name = _blame(cs, bad_c)
        raise InvalidParameter(
            name,
            "(see input)",
            "a value for which every side bulge keeps more carcass than its chord",
            "the section displacement dh reached the limit of Rotta's construction",
        )
    return sol, (dv, ddv, dh, ddh, x, dx)


def _patch_ends(dw, cs: _Cases, offset, guess=None, *, touching_only=False):
    """Angles (rear, front) of the patch ends, each (m, 1) [rad].

    Roots of the section width along the wheel (section 5.2), bracketed by the
    central section (in contact) and 1.05 x the flat-ground end, where ``dv < 0``.
    With ``touching_only``, cases whose central section is out of contact do not
    raise; their ends are returned as 0 and the mask of touching cases is returned
    as a third value.
    """
    phi_flat = np.arccos(np.clip((cs.R - dw) / cs.R, -1.0, 1.0))
    outer = np.minimum(1.05 * phi_flat + 1e-9, 1.2)
    zero = np.zeros_like(outer)
    probe, _ = _sections_at(np.stack([zero, outer, -outer]), dw, cs, offset)
    width0 = probe.width[0]
    if touching_only:
        touching = width0 > 0
        if not np.all(touching):
            dmax = cs.max_deflection()
            dw_t = np.where(touching, dw, dmax)
            rear, front = _patch_ends(dw_t, cs, offset)
            return np.where(touching, rear, 0.0), np.where(touching, front, 0.0), touching
    if np.any(width0 <= 0):
        i = int(np.argmax(width0.ravel() <= 0))
        raise NoContact(
            f"no contact: the central section's edges cross (width {width0.flat[i]:.4g} mm) "
            f"at deflection {np.broadcast_to(dw, cs.r0.shape)[i, 0]:.6g} mm; increase the "
            "deflection or load, or reduce the lateral displacement"
        )
    if np.any(probe.width[1:] > 0):
        raise TireModelError(
            "contact patch end not bracketed: a section beyond the flat-ground end "
            "(where the surface no longer reaches it) still has positive width"
        )

    def fun(phi):
        sol, (_, ddv, _, ddh, _, _) = _sections_at(phi, dw, cs, offset)
        return sol.width, sol.dwidth_ddv * ddv + sol.dwidth_ddh * ddh

    lo = np.stack([-outer, zero])
    hi = np.stack([zero, outer])
    x0 = np.stack([-phi_flat, phi_flat]) if guess is None else np.stack(guess)
    sign_lo = np.stack([-np.ones_like(zero), np.ones_like(zero)])
    ends = newton_bracketed(
        fun, x0, lo, hi, xtol=tol.end_xtol, what="contact patch end (section 5.2)", sign_lo=sign_lo
    )
    if touching_only:
        return ends[0], ends[1], np.ones(width0.shape, bool)
    return ends[0], ends[1]


def _disk_offset(dw, cs: _Cases):
    """Offset of section 5.3.2: D_disk at the patch ends (mean of both ends)."""
    if not np.any(cs.k_disk):
        return np.zeros_like(cs.r0), None
    offset = curvature_drop(np.arccos(np.clip((cs.R - dw) / cs.R, -1, 1)), cs.R, cs.k_disk)[0]
    for _ in range(tol.max_iter):
        rear, front = _patch_ends(dw, cs, offset)
        new = 0.5 * (
            curvature_drop(rear, cs.R, cs.k_disk)[0] + curvature_drop(front, cs.R, cs.k_disk)[0]
        )
        if np.all(np.abs(new - offset) <= tol.disk_offset_atol):
            return new, (rear, front)
        offset = new
    raise NotConverged(
        "disk offset (section 5.3.2)", {"iterations": tol.max_iter, "offset_mm": offset.ravel()}
    )


def section_to_ground(xs, zs, phi, *, tire_radius, wheel_radius, camber, ground_z):
    """Map section-frame points to the ground frame (Appendix C's R3x, R3y rotations).

    Parameters
    ----------
    xs, zs : (...) float [mm]
        Points in the (cambered, ground-aligned) section frame of :mod:`.section`.
    phi : (...) float [rad]
        Section angle.
    tire_radius, wheel_radius, camber : (...) float [mm, mm, rad]
    ground_z : (...) float [mm]
        Height of the support surface below the axle (returned z is relative to it).

    Returns
    -------
    x, y, z : (...) float [mm]
        Forward, lateral (toward side 2), up.
    """
    c, s = np.cos(camber), np.sin(camber)
    xw, zw = c * xs - s * zs, s * xs + c * zs  # undo camber in the section plane
    rho = wheel_radius - tire_radius - zw  # distance from the axle along the section
    x = rho * np.sin(phi)
    y = c * xw - s * rho * np.cos(phi) + s * (wheel_radius - tire_radius)
    z = -s * xw - c * rho * np.cos(phi) - ground_z
    return x, y, z


def area_jacobian(sol, dv, ddv, phi, cs: _Cases, xm=None):
    """Ground area per unit section width and per radian of ``phi`` [mm/rad].

    The contact segment ``[e1, e2]`` of the section at ``phi`` maps to the ground by
    :func:`section_to_ground`, which is linear in the section coordinate, so the
    patch area is exactly ``integral (e2 - e1) |J(x_mid, phi)| dphi`` with ``J`` the
    Jacobian determinant of ``(x_s, phi) -> (x, y)`` at the segment midpoint. For an
    uncambered tire ``|J| = dx/dphi`` (Eq. 5-26's ``dy``); a cambered section plane is
    tilted, which makes its ground footprint slightly smaller (the appendix, which
    takes ``polyarea`` of the projected outline, includes this too). On a drum the
    area is measured along the drum surface (unrolled), as an ink print would be.
    """
    c, s = np.cos(cs.gamma), np.sin(cs.gamma)
    zs, dzs = -cs.r0 + dv, ddv
    xm = 0.5 * (sol.edge1 + sol.edge2) if xm is None else xm
    rho = cs.R - cs.r0 - (s * xm + c * zs)
    drho = -c * dzs
    sp, cp = np.sin(phi), np.cos(phi)
    dx_dxs, dy_dxs = -s * sp, c * c + s * s * cp
    dx_dphi = drho * sp + rho * cp
    dy_dphi = -c * s * dzs - s * (drho * cp - rho * sp)
    jac = np.abs(dx_dxs * dy_dphi - dx_dphi * dy_dxs)
    if np.any(cs.k_drum):
        u = cs.k_drum * rho * sp
        jac = jac / np.sqrt(np.maximum(1.0 - u * u, 1e-300))
    return jac


def _refined_extreme(phi, f, sign):
    """Max (sign=+1) or min (sign=-1) over nodes along the last axis, refined by a
    parabola through the extreme node and its neighbours."""
    g = sign * f
    k = np.clip(np.argmax(g, axis=-1), 1, f.shape[-1] - 2)[..., None]
    x0, x1, x2 = (np.take_along_axis(phi, k + d, -1)[..., 0] for d in (-1, 0, 1))
    y0, y1, y2 = (np.take_along_axis(g, k + d, -1)[..., 0] for d in (-1, 0, 1))
    d01, d12 = (y1 - y0) / (x1 - x0), (y2 - y1) / (x2 - x1)
    a = (d12 - d01) / (x2 - x0)
    with np.errstate(divide="ignore", invalid="ignore"):
        xv = 0.5 * (x0 + x1) - d01 / (2 * a)
    b = d01 - a * (x0 + x1)
    yv = a * xv * xv + b * xv + (y0 - a * x0 * x0 - b * x0)
    ok = (a < 0) & (xv >= x0) & (xv <= x2) & np.isfinite(yv)
    return sign * np.maximum(np.where(ok, yv, -np.inf), np.max(g, axis=-1))


def _evaluate(cs: _Cases, dw, n: int, *, ends=None):
    """Everything about m patches at wheel deflections ``dw`` (m, 1); ``ends`` are
    already-converged patch-end angles (rear, front) when the caller has them."""
    offset, disk_ends = _disk_offset(dw, cs)
    if disk_ends is not None:
        ends = disk_ends
    rear, front = ends if ends is not None else _patch_ends(dw, cs, offset)
    t, wts = clenshaw_curtis(n)
    half = 0.5 * (front - rear)
    phi = 0.5 * (front + rear) + half * t
    sol, (dv, ddv, dh, _, x, dx) = _sections_at(phi, dw, cs, offset, broadcast=True)
    width = np.maximum(sol.width, 0.0)
    area = half[:, 0] * (wts * width * area_jacobian(sol, dv, ddv, phi, cs)).sum(-1)
    x_weights = half * wts * dx  # integral f dx = sum(x_weights * f)
    lat = cs.pressure[:, 0] * half[:, 0] * (wts * (sol.radius1 - sol.radius2) * dx).sum(-1)
    out = {
        "phi": phi,
        "sections": sol,
        "x": x,
        "dxdphi": dx,
        "area": area,
        "lateral_force": lat,
        "vertical_force": cs.pressure[:, 0] * area,
        "offset": offset[:, 0],
        "ends": (rear, front),
        "x_weights": x_weights,
    }
    # ground height: central section's contact line (exactly flat across the section)
    dv0 = np.cos(cs.gamma) * dw - curvature_drop(np.zeros_like(dw), cs.R, cs.k_drum)[0]
    ground_z = (-cs.r0 + dv0) - np.cos(cs.gamma) * (cs.R - cs.r0)
    kw = {"tire_radius": cs.r0, "wheel_radius": cs.R, "camber": cs.gamma, "ground_z": ground_z}
    x1, y1, z1 = section_to_ground(sol.edge1, sol.ground_z, phi, **kw)
    x2, y2, z2 = section_to_ground(sol.edge2, sol.ground_z, phi, **kw)
    xc, yc, _ = section_to_ground(sol.lowest1, sol.ground_z, phi, **kw)
    # height of the edges above the support surface (a drum falls away as x^2 / 2R)
    kd = cs.k_drum
    z1 = z1 + kd * x1 * x1 / (1.0 + np.sqrt(np.maximum(1.0 - (kd * x1) ** 2, 0.0)))
    z2 = z2 + kd * x2 * x2 / (1.0 + np.sqrt(np.maximum(1.0 - (kd * x2) ** 2, 0.0)))
    if np.any(cs.k_drum):  # unroll along the drum surface
        k = cs.k_drum
        unroll = lambda xx: np.where(
            k > 0, np.arcsin(np.clip(k * xx, -1, 1)) / np.where(k > 0, k, 1), xx
        )
        x1, x2, xc = unroll(x1), unroll(x2), unroll(xc)
    out.update(edge1_xy=(x1, y1), edge2_xy=(x2, y2), centre_xy=(xc, yc), edge_z=(z1, z2))
    out["surface_z"] = ground_z[:, 0]
    out["length"] = np.maximum(x1[:, -1], x2[:, -1]) - np.minimum(x1[:, 0], x2[:, 0])
    out["width"] = _refined_extreme(phi, y2, +1) - _refined_extreme(phi, y1, -1)
    out["dv"], out["dh"] = dv, dh
    return out


@dataclass(frozen=True)
class ContactPatch:
    """Solved Rotta tire: per-section arrays, patch outline, forces.

    Units: mm, N, N/mm^2, rad. Ground frame: ``x`` forward, ``y`` toward section
    side 2 (the side the wheel top leans to for positive camber), ``z`` up.

    Attributes
    ----------
    tire : TireGeometry
    pressure, deflection, camber, slip, lateral : float
        Inputs [N/mm^2, mm, rad, rad, mm]; ``deflection`` is the wheel's
        displacement in its own plane (``delta_w``).
    surface : Flat | Drum | Disk
    phi : (n,) float [rad]
        Section angles from bottom dead centre (Clenshaw-Curtis nodes between the
        exact patch ends).
    x : (n,) float [mm]
        Forward position of each section (``(R - dv) sin phi``).
    sections : SectionSolution
        Section geometry, arrays of shape (n,).
    outline : (2n + 1, 2) float [mm]
        Closed counter-clockwise patch polygon in ground ``(x, y)`` (first point
        repeated at the end).
    centerline : (n, 2) float [mm]
        Where each section's first-touching carcass point lies (Figure 5-8).
    length, width, area : float [mm, mm, mm^2]
        Extent along x, extent along y, and ``integral (e2 - e1) dx`` (Eq. 5-26).
    vertical_force, lateral_force : float [N]
        ``p * area`` and ``integral p (r1 - r2) dx`` (Eq. 5-25, 5-26).
    disk_offset : float [mm]
        Offset of section 5.3.2 (0 off a disk).
    flatness : float [mm]
        Largest height of a patch edge above/below the central contact line
        (Figure 5-9: the 3D Rotta patch of a cambered tire is not exactly flat).
    x_weights : (n,) float [mm]
        Quadrature weights along the patch: ``integral f dx = sum(x_weights * f)``
        (Clenshaw-Curtis between the exact ends).
    """

    tire: TireGeometry
    pressure: float
    deflection: float
    camber: float
    slip: float
    lateral: float
    surface: Surface
    phi: np.ndarray
    x: np.ndarray
    sections: SectionSolution = field(repr=False)
    outline: np.ndarray = field(repr=False)
    centerline: np.ndarray = field(repr=False)
    length: float
    width: float
    area: float
    vertical_force: float
    lateral_force: float
    disk_offset: float
    flatness: float
    surface_z: float = 0.0
    phi_ends: tuple[float, float] = (0.0, 0.0)
    x_weights: np.ndarray = field(default=None, repr=False)

    @property
    def net_force_orientation(self) -> float:
        """Angle of the ground reaction from the vertical, ``atan2(Fy, Fz)`` [rad]."""
        return float(np.arctan2(self.lateral_force, self.vertical_force))

    @property
    def sinkage(self) -> float:
        """Wheel deflection over rim height [-] (section 6.1.2 reports it in %)."""
        return self.deflection / self.tire.rim_height

    @property
    def lateral_force_density(self) -> np.ndarray:
        """dS/dx per section [N/mm], Eq. 5-25."""
        return self.sections.lateral_force_density(self.pressure)

    @property
    def vertical_force_density(self) -> np.ndarray:
        """dN/dx per section [N/mm], Eq. 5-26."""
        return self.sections.vertical_force_density(self.pressure)

    @property
    def min_friction(self) -> np.ndarray:
        """Minimum friction coefficient per section, ``dS / dN`` (Eq. 5-27)."""
        dn = self.vertical_force_density
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(dn > 0, np.abs(self.lateral_force_density) / dn, np.inf)

    def sections_at(self, phi) -> tuple[SectionSolution, np.ndarray]:
        """Rotta sections of this load case at any angles ``phi`` (n,) [rad], inside or
        beyond the patch (beyond it the edges cross: negative width).

        Returns
        -------
        sections : SectionSolution, arrays (n,)
        x : (n,) float [mm]
            Forward position ``(R - dv) sin phi``.
        """
        cs = _single_cases(
            self.tire, self.pressure, self.camber, self.slip, self.lateral, self.surface
        )
        phi = np.atleast_1d(np.asarray(phi, float))[None, :]
        sol, disp = _sections_at(phi, np.array([[self.deflection]]), cs, self.disk_offset, True)
        flat = {}
        for f in sol.__dataclass_fields__:
            val = getattr(sol, f)
            if isinstance(val, tuple):
                flat[f] = tuple(np.broadcast_to(a, phi.shape)[0] for a in val)
            else:
                flat[f] = np.broadcast_to(val, phi.shape)[0]
        return SectionSolution(**flat), disp[4][0]

    def to_ground(self, xs, zs, phi):
        """Section-frame points -> ground frame ``(x, y, z)`` [mm] (z = 0 on the surface
        under the central section), see :func:`section_to_ground`."""
        return section_to_ground(
            xs,
            zs,
            phi,
            tire_radius=self.tire.tire_radius,
            wheel_radius=self.tire.wheel_radius,
            camber=self.camber,
            ground_z=self.surface_z,
        )

    def summary(self) -> dict[str, float | str]:
        """Scalar results with unit-carrying names (for tables, JSON, CSV)."""
        t = self.tire
        return {
            "tire": t.name or f"r0={t.tire_radius:.4g}mm",
            "tire_radius_mm": t.tire_radius,
            "arc_length_mm": t.arc_length,
            "rim_width_mm": t.rim_width,
            "bead_seat_diameter_mm": t.bead_seat_diameter,
            "rim_height_mm": t.rim_height,
            "surface": self.surface.describe(),
            "pressure_bar": self.pressure / 0.1,
            "camber_deg": float(np.degrees(self.camber)),
            "slip_deg": float(np.degrees(self.slip)),
            "lateral_mm": self.lateral,
            "deflection_mm": self.deflection,
            "sinkage_pct": 100.0 * self.sinkage,
            "length_mm": self.length,
            "width_mm": self.width,
            "area_mm2": self.area,
            "vertical_force_N": self.vertical_force,
            "lateral_force_N": self.lateral_force,
            "net_force_orientation_deg": float(np.degrees(self.net_force_orientation)),
            "disk_offset_mm": self.disk_offset,
            "flatness_mm": self.flatness,
        }


def _surface_arrays(surface: Surface, camber: float):
    if isinstance(surface, Flat):
        return np.inf, np.inf, 1.0
    if isinstance(surface, Drum):
        return surface.diameter, np.inf, 1.0
    if isinstance(surface, Disk):
        return np.inf, surface.diameter, surface.center_side(camber)
    raise InvalidParameter("surface", surface, "Flat(), Drum(diameter) or Disk(diameter, curving)")


def _single_cases(tire: TireGeometry, pressure, camber, slip, lateral, surface) -> _Cases:
    if not isinstance(tire, TireGeometry):
        raise InvalidParameter("tire", tire, "a TireGeometry")
    for name, val in (
        ("pressure", pressure),
        ("camber", camber),
        ("slip", slip),
        ("lateral", lateral),
    ):
        if np.ndim(val) != 0:
            raise InvalidParameter(name, val, "a scalar (use tiremesh.solve_many for arrays)")
    drum, disk, side = _surface_arrays(surface, float(camber))
    return _cases(
        tire.tire_radius,
        tire.rim_width,
        tire.bead_seat_diameter,
        pressure,
        camber,
        slip,
        lateral,
        drum,
        disk,
        side,
    )


def _check_deflection(dw, cs: _Cases, name="deflection"):
    dw = v.positive(name, dw, unit="mm")
    dmax = cs.max_deflection()[:, 0]
    if np.any(dw > dmax):
        raise InvalidParameter(
            name,
            float(np.max(dw)),
            f"0 < {name} <= {float(np.min(dmax)):.6g} mm",
            "a bead would reach the support surface or a bulge run out of carcass",
        )
    return dw


def _build(
    tire, cs: _Cases, dw: float, out, surface, pressure, camber, slip, lateral
) -> ContactPatch:
    sq = lambda a: np.asarray(a)[0]
    sol = out["sections"]
    sol1 = SectionSolution(
        **{
            f: (
                tuple(sq(a) for a in getattr(sol, f))
                if isinstance(getattr(sol, f), tuple)
                else sq(getattr(sol, f))
            )
            for f in sol.__dataclass_fields__
        }
    )
    x1, y1 = (sq(a) for a in out["edge1_xy"])
    x2, y2 = (sq(a) for a in out["edge2_xy"])
    ring = np.concatenate([np.column_stack([x1, y1]), np.column_stack([x2, y2])[::-1]])
    ring = np.vstack([ring, ring[:1]])
    z1, z2 = (sq(a) for a in out["edge_z"])
    return ContactPatch(
        tire=tire,
        pressure=float(pressure),
        deflection=float(dw),
        camber=float(camber),
        slip=float(slip),
        lateral=float(lateral),
        surface=surface,
        phi=sq(out["phi"]),
        x=sq(out["x"]),
        sections=sol1,
        outline=ring,
        centerline=np.column_stack([sq(out["centre_xy"][0]), sq(out["centre_xy"][1])]),
        length=float(out["length"][0]),
        width=float(out["width"][0]),
        area=float(out["area"][0]),
        vertical_force=float(out["vertical_force"][0]),
        lateral_force=float(out["lateral_force"][0]),
        disk_offset=float(out["offset"][0]),
        flatness=float(max(np.abs(z1).max(), np.abs(z2).max())),
        surface_z=float(out["surface_z"][0]),
        phi_ends=(float(out["ends"][0][0, 0]), float(out["ends"][1][0, 0])),
        x_weights=sq(out["x_weights"]),
    )


def solve_patch(
    tire: TireGeometry,
    deflection: float,
    *,
    pressure: float,
    camber: float = 0.0,
    slip: float = 0.0,
    lateral: float = 0.0,
    surface: Surface = Flat(),
    n_sections: int = 201,
) -> ContactPatch:
    """Solve the 3D Rotta model at a given wheel deflection (sections 5.2 to 5.5).

    Parameters
    ----------
    tire : TireGeometry
    deflection : float [mm]
        Wheel displacement toward the surface in the plane of the wheel (``delta_w``).
    pressure : float [N/mm^2]
        Inflation pressure (enters the forces only).
    camber : float [rad]
        Positive leans the wheel top toward ``+y``; |camber| < pi/2.
    slip : float [rad]
        Turns the patch centre line: ``dh += x tan(slip)``.
    lateral : float [mm]
        Imposed lateral displacement of the patch relative to the rim (``+y``).
    surface : Flat | Drum | Disk
    n_sections : int
        Sections between the exact patch ends (Clenshaw-Curtis nodes), 9 to 20001.

    Returns
    -------
    ContactPatch
    """
    n = v.integer("n_sections", n_sections, 9, 20001)
    cs = _single_cases(tire, pressure, camber, slip, lateral, surface)
    dw = _check_deflection(np.array([[deflection]], float), cs)
    out = _evaluate(cs, dw, n)
    return _build(tire, cs, float(deflection), out, surface, pressure, camber, slip, lateral)
