"""Everything about m patches at given wheel deflections (sections 5.2, 5.3, 5.4 and
5.5): sections on Clenshaw-Curtis nodes between the exact ends, area, forces
(equations 5-25 and 5-26), outline."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..section import SectionSolution
from .arrays import CaseArrays
from .ends import patch_ends, track_offset
from .kinematics import area_jacobian, section_to_ground, sections_at
from .quadrature import clenshaw_curtis


@dataclass(frozen=True)
class PatchArrays:
    """Solved patches of m cases with n sections each.

    Attributes
    ----------
    phi, x, dxdphi : (m, n) float [rad, mm, mm/rad]
    sections : SectionSolution of (m, n) arrays
    dv, dh : (m, n) float [mm]
    x_weights : (m, n) float [mm]
        Quadrature weights of the lateral-force integral along the patch, in the
        case's ``force_convention``: ``integral f dl = sum(x_weights * f)``.
    rear, front : (m, 1) float [rad]
        Patch-end angles.
    offset : (m,) float [mm]
        Track offset (section 5.3.2; 0 on a straight track).
    area : (m,) float [mm^2]
    vertical_force, lateral_force : (m,) float [N]
    length, width : (m,) float [mm]
    edge1_xy, edge2_xy, centre_xy : tuple of (m, n) float [mm]
        Ground ``(x, y)`` of both patch edges and of the first-touching point; ``x``
        along the surface (unrolled).
    edge_z : tuple of (m, n) float [mm]
        Height of each edge above the support surface.
    surface_z : (m,) float [mm]
        Height of the support surface below the axle.
    """

    phi: np.ndarray
    x: np.ndarray
    dxdphi: np.ndarray
    sections: SectionSolution
    dv: np.ndarray
    dh: np.ndarray
    x_weights: np.ndarray
    rear: np.ndarray
    front: np.ndarray
    offset: np.ndarray
    area: np.ndarray
    vertical_force: np.ndarray
    lateral_force: np.ndarray
    length: np.ndarray
    width: np.ndarray
    edge1_xy: tuple
    edge2_xy: tuple
    centre_xy: tuple
    edge_z: tuple
    surface_z: np.ndarray

    def ends_and_offset(self):
        """``((rear, front), offset)`` with the offset as (m, 1), for re-evaluation.

        Returns
        -------
        ends : (rear, front) of (m, 1) float [rad]
        offset : (m, 1) float [mm]
        """
        return (self.rear, self.front), self.offset[:, None]


def _appendix(cs: CaseArrays) -> np.ndarray:
    return np.zeros(cs.r0.shape, bool) if cs.appendix_forces is None else cs.appendix_forces


def ground_length(sol: SectionSolution, d, phi, cs: CaseArrays) -> np.ndarray:
    """Ground length per radian of each patch slice [mm/rad]: the speed of the
    contact segment's midpoint along the surface as ``phi`` advances (the true length
    of the slice on the ground; ``force_convention='ground'``).

    For an upright tire on flat ground it is ``d[(R - dv) sin phi] / dphi`` (Appendix
    C's ``dy``); a cambered section's contact lies off the wheel plane, at a smaller
    distance from the axle, and the slices are shorter there (-1.5 % of the patch
    length at 45 degrees).

    Parameters
    ----------
    sol : SectionSolution of (m, n) arrays
    d : Displacements
        Section displacements and their ``phi`` derivatives.
    phi : (m, n) float [rad]
    cs : CaseArrays

    Returns
    -------
    (m, n) float [mm/rad]
    """
    c, s = np.cos(cs.gamma), np.sin(cs.gamma)
    xs, zs = 0.5 * (sol.edge1 + sol.edge2), sol.ground_z
    dxs, dzs = sol.dmid_ddv * d.ddv + sol.dmid_ddh * d.ddh, d.ddv
    rho = cs.R - cs.r0 - (s * xs + c * zs)
    drho = -(s * dxs + c * dzs)
    sp, cp = np.sin(phi), np.cos(phi)
    dx = drho * sp + rho * cp
    dy = c * (c * dxs - s * dzs) - s * (drho * cp - rho * sp)
    return np.hypot(dx, dy) * cs.surface.stretch(rho * sp)


def refined_extreme(phi, f, sign):
    """Max (sign=+1) or min (sign=-1) over nodes along the last axis, refined by a
    parabola through the extreme node and its neighbours (used for the patch width).

    Parameters
    ----------
    phi : (m, n) float [rad]
        Node positions, ascending, n >= 3.
    f : (m, n) float [any unit]
        Values at the nodes.
    sign : {+1, -1}
        Maximum or minimum.

    Returns
    -------
    extreme : (m,) float [unit of ``f``]
        The parabola's vertex where it lies between the neighbours and beats the
        best node, else the best node.
    """
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


def _ground_outline(sol: SectionSolution, phi, dw, cs: CaseArrays):
    """Edges and centre line on the ground (unrolled along the surface), edge heights
    above the surface, and the surface height below the axle."""
    drop0, _ = cs.surface.drop(np.zeros_like(dw), cs.R)
    dv0 = np.cos(cs.gamma) * dw - drop0  # Eq. 5-8 (central section), less the drop
    ground_z = (-cs.r0 + dv0) - np.cos(cs.gamma) * (cs.R - cs.r0)
    kw = {"tire_radius": cs.r0, "wheel_radius": cs.R, "camber": cs.gamma, "ground_z": ground_z}
    x1, y1, z1 = section_to_ground(sol.edge1, sol.ground_z, phi, **kw)
    x2, y2, z2 = section_to_ground(sol.edge2, sol.ground_z, phi, **kw)
    xc, yc, _ = section_to_ground(sol.lowest1, sol.ground_z, phi, **kw)
    surf = cs.surface
    z1, z2 = z1 - surf.height(x1), z2 - surf.height(x2)
    x1, x2, xc = surf.unroll(x1), surf.unroll(x2), surf.unroll(xc)
    return (x1, y1), (x2, y2), (xc, yc), (z1, z2), ground_z[:, 0]


def evaluate(cs: CaseArrays, dw, n: int, *, ends=None, offset=None) -> PatchArrays:
    """Solve m patches at given wheel deflections with ``n`` sections each.

    Parameters
    ----------
    cs : CaseArrays
        m load cases, parameters (m, 1).
    dw : (m, 1) float [mm]
        Wheel deflection.
    n : int
        Sections (Clenshaw-Curtis nodes) between the exact patch ends, >= 3.
    ends : (rear, front) of (m, 1) float [rad], optional
        Already-converged patch ends (found here if not given).
    offset : (m, 1) float [mm], optional
        Already-converged track offset (section 5.3.2); give it with ``ends``, or
        give ``ends`` alone on a straight track.

    Returns
    -------
    PatchArrays
        Per-section arrays (m, n), per-case results (m,).

    Notes
    -----
    Dressel (2013), section 5.5: the lateral force is the sum of ``dS = p (r1 - r2)
    dy`` (equation 5-25) and the vertical force the sum of ``dN = p (e2 - e1) dy``
    (equation 5-26), both as Clenshaw-Curtis integrals between the exact patch ends;
    ``dy`` of equation 5-26 is the exact ground area element (see
    :func:`~tiremesh.solver.kinematics.area_jacobian` and ``docs/model.md``).
    """
    if offset is None:
        offset, track_ends = track_offset(dw, cs)
        if track_ends is not None:
            ends = track_ends
    rear, front = ends if ends is not None else patch_ends(dw, cs, offset)
    t, wts = clenshaw_curtis(n)
    half = 0.5 * (front - rear)
    phi = 0.5 * (front + rear) + half * t
    sol, d = sections_at(phi, dw, cs, offset, broadcast=True)
    width = np.maximum(sol.width, 0.0)
    # integral of (e2 - e1) dy of equation 5-26, dy the exact ground area element
    area = half[:, 0] * (wts * width * area_jacobian(sol, d.dv, d.ddv, phi, cs)).sum(-1)
    x_weights = np.where(
        _appendix(cs), half * wts * d.dx, half * wts * ground_length(sol, d, phi, cs)
    )
    lat = cs.pressure[:, 0] * (x_weights * (sol.radius1 - sol.radius2)).sum(-1)  # Eq. 5-25
    e1, e2, centre, edge_z, surface_z = _ground_outline(sol, phi, dw, cs)
    (x1, y1), (x2, y2) = e1, e2
    return PatchArrays(
        phi=phi,
        x=d.x,
        dxdphi=d.dx,
        sections=sol,
        dv=d.dv,
        dh=d.dh,
        x_weights=x_weights,
        rear=rear,
        front=front,
        offset=offset[:, 0],
        area=area,
        vertical_force=cs.pressure[:, 0] * area,  # Eq. 5-26
        lateral_force=lat,
        length=np.maximum(x1[:, -1], x2[:, -1]) - np.minimum(x1[:, 0], x2[:, 0]),
        width=refined_extreme(phi, y2, +1) - refined_extreme(phi, y1, -1),
        edge1_xy=e1,
        edge2_xy=e2,
        centre_xy=centre,
        edge_z=edge_z,
        surface_z=surface_z,
    )
