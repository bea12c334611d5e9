"""Lateral mechanics: deflection beyond the patch, friction, stiffnesses
(sections 2.4, 5.5 to 5.8, 6.1; Appendix C).

Beyond the patch (5.7, 5.8, Eq. 5-28, 5-29): a section beyond a patch end keeps the
end section's vertical and lateral displacement decayed as ``exp((i - 1) s)``, with
``s`` the distance along the wheel [mm] and ``i`` the relaxation rate (0.9 .. 0.999
per mm); it is solved as a Rotta section that no longer touches (zero contact
width, two distinct bulge radii, Figure 5-18) and carries ``dS = p (r1 - r2)`` but
no vertical load. The decay length is ``1 / (1 - i)``. Leading and trailing sides
have their own rates.

Friction (5.6, Eq. 5-27): a patch section whose lateral force (plus its share of
the force from beyond the patch, shared in proportion to its own) exceeds
``mu dN`` slides toward the position where it carries no lateral force, following
its gripping neighbour nearer the patch centre at the sliding relaxation rate
(Appendix C limits a section's slide by its neighbour's). The share of the beyond-patch
force depends on the result, so the whole is iterated to a converged total
lateral force (the dissertation needs 3 to 4 iterations); oscillation is detected
and damped by averaging.

Slip (Appendix C turns the patch centre line about the patch centre, so a pure slip
angle gives antisymmetric displacements and no net force; the appendix then guesses
a lateral displacement). Here, by default (``slip_anchor='leading'``), the tread
enters the patch at the leading edge undisplaced and the rim moves sideways at
``tan(slip)`` per mm rolled (the brush model's kinematics): ``dh = lateral + (x -
x_lead) tan(slip)``, found by a fixed point on the leading-edge position. That
gives the cornering force and a positive pneumatic trail. ``slip_anchor='centre'``
keeps the appendix's form.

Departures: the appendix slides toward ``dh = 0``; here toward each section's
zero-force displacement, so that zero friction gives zero lateral force also with
camber. It scales the beyond-patch share as ``dy * F / F_cp`` (a dimensional slip);
here ``dS * F / F_cp``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import _validate as v
from ._roots import newton_bracketed
from ._tol import tol
from .errors import InvalidParameter, NotConverged
from .geometry import TireGeometry
from .load import solve
from .patch import ContactPatch, clenshaw_curtis
from .section import _solve_sections
from .surface import Flat, Surface


@dataclass(frozen=True)
class Relaxation:
    """Relaxation rates of Appendix C, per mm along the wheel (Eq. 5-28).

    Attributes
    ----------
    lead_out : float
        Beyond the leading patch end (before the tread touches the ground).
    trail_out : float
        Beyond the trailing end (after it leaves the ground).
    lead_in, trail_in : float
        Sliding inside the front / rear half of the patch.
    """

    lead_out: float = 0.993
    trail_out: float = 0.993
    lead_in: float = 0.993
    trail_in: float = 0.993

    def __post_init__(self) -> None:
        for name in ("lead_out", "trail_out", "lead_in", "trail_in"):
            val = getattr(self, name)
            if not (isinstance(val, int | float) and 0.0 <= val < 1.0):
                raise InvalidParameter(
                    f"relaxation.{name}", val, "[0, 1) per mm (0.9 .. 0.999 typical)"
                )

    @staticmethod
    def decay_length(rate: float) -> float:
        """``1 / (1 - i)`` [mm] (Eq. 5-28, 5-29)."""
        return 1.0 / (1.0 - rate)

    @classmethod
    def uniform(cls, rate: float) -> Relaxation:
        return cls(rate, rate, rate, rate)


@dataclass(frozen=True)
class LateralResult:
    """Patch plus beyond-patch sections, with friction.

    Per-section arrays run along the wheel from the trailing side to the leading side
    (``s`` forward, 0 at the patch centre line's x = 0).

    Attributes
    ----------
    patch : ContactPatch
        The no-slide patch (geometry, vertical force).
    s : (n,) float [mm]
    in_patch, sliding : (n,) bool
    dv, dh : (n,) float [mm]
    dS, dN : (n,) float [N/mm]
        Lateral and vertical force per length (Eq. 5-25, 5-26).
    weights : (n,) float [mm]
        Quadrature weights along the wheel.
    lateral_force, patch_lateral_force, beyond_lateral_force : float [N]
    vertical_force : float [N]
    aligning_moment : float [N mm]
        ``integral s dS`` over the patch (about the vertical axis, + counter-clockwise
        seen from above); ``pneumatic_trail = -aligning_moment / patch_lateral_force``.
    relaxation_length : (float, float) [mm]
        Trailing and leading distance over which the lateral displacement beyond the
        patch falls to 1/e (Eq. 5-29).
    iterations : int
        Friction iterations used.
    friction_share : float
        Total over patch lateral force used by the final friction check: each patch
        section had to hold ``friction_share x`` its own force.
    """

    patch: ContactPatch = field(repr=False)
    s: np.ndarray = field(repr=False)
    in_patch: np.ndarray = field(repr=False)
    sliding: np.ndarray = field(repr=False)
    dv: np.ndarray = field(repr=False)
    dh: np.ndarray = field(repr=False)
    dS: np.ndarray = field(repr=False)
    dN: np.ndarray = field(repr=False)
    weights: np.ndarray = field(repr=False)
    lateral_force: float
    patch_lateral_force: float
    beyond_lateral_force: float
    vertical_force: float
    aligning_moment: float
    relaxation_length: tuple[float, float]
    iterations: int
    imposed_lateral: float = 0.0
    friction_share: float = 1.0

    @property
    def net_force_orientation(self) -> float:
        return float(math.atan2(self.lateral_force, self.vertical_force))

    @property
    def pneumatic_trail(self) -> float:
        """``-aligning_moment / patch_lateral_force`` [mm] (positive: force behind the centre)."""
        f = self.patch_lateral_force
        return float(-self.aligning_moment / f) if f else math.nan

    @property
    def friction_used(self) -> np.ndarray:
        """``|dS| / dN`` per patch section (Eq. 5-27); NaN beyond the patch."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.in_patch & (self.dN > 0), np.abs(self.dS) / self.dN, np.nan)


def _section_forces(patch: ContactPatch, dv, dh):
    """dS, dN per length [N/mm] and width of sections at (dv, dh)."""
    t = patch.tire
    sol, bad_h, bad_c = _solve_sections(
        t.tire_radius, t.rim_width, dv, dh, patch.camber, t.tire_radius * patch.camber
    )
    if np.any(bad_h) or np.any(bad_c):
        raise InvalidParameter(
            "lateral", patch.lateral, "a displacement within Rotta's construction"
        )
    p = patch.pressure
    return p * (sol.radius1 - sol.radius2), p * np.maximum(sol.width, 0.0)


def zero_force_displacement(patch: ContactPatch, dv) -> np.ndarray:
    """Lateral displacement at which a section at ``dv`` carries no lateral force
    (``r1 = r2``): 0 without camber, opposite to the lean with camber [mm]."""
    dv = np.asarray(dv, float)
    if patch.camber == 0:
        return np.zeros_like(dv)
    r0 = patch.tire.tire_radius
    h = 1e-6 * r0

    def fun(dh):
        f, _ = _section_forces(patch, dv, dh)
        fp, _ = _section_forces(patch, dv, dh + h)
        return f, (fp - f) / h

    span = 0.5 * r0
    return newton_bracketed(
        fun,
        np.zeros_like(dv),
        np.full_like(dv, -span),
        np.full_like(dv, span),
        xtol=tol.zero_force_xtol,
        what="zero-force section displacement",
    )


def _beyond(patch: ContactPatch, dv_end, dh_end, rate, n):
    """Sections beyond one patch end: s [mm] from the end, dv, dh, weights."""
    ell = Relaxation.decay_length(rate) if rate > 0 else 0.0
    span = min(8.0 * ell, 0.5 * math.pi * patch.tire.wheel_radius) if ell > 0 else 0.0
    if span <= 0:
        z = np.zeros(1)
        return z, z, z, z
    t, w = clenshaw_curtis(n)
    s = 0.5 * span * (t + 1.0)
    e = np.exp((rate - 1.0) * s)
    return s, dv_end * e, dh_end * e, 0.5 * span * w


def solve_lateral(
    tire: TireGeometry,
    *,
    pressure: float,
    load: float | None = None,
    deflection: float | None = None,
    camber: float = 0.0,
    slip: float = 0.0,
    lateral: float = 0.0,
    surface: Surface = Flat(),
    relaxation: Relaxation | float = Relaxation(),
    friction: float = math.inf,
    slip_anchor: str = "leading",
    n_sections: int = 201,
    n_beyond: int = 129,
) -> LateralResult:
    """Lateral forces of the tire with deflection beyond the patch and friction.

    Parameters
    ----------
    tire, pressure, load, deflection, camber, slip, lateral, surface
        As :func:`tiremesh.solve`.
    relaxation : Relaxation or float
        Relaxation rates [1/mm]; a float sets all four. 0 switches the beyond-patch
        deflection off.
    friction : float
        Friction coefficient (``inf``: no sliding).
    slip_anchor : {'leading', 'centre'}
        Where the slipping tread is undisplaced: the leading edge (brush model,
        default) or the patch centre (Appendix C).
    n_sections, n_beyond : int
        Sections in the patch and beyond each end.

    Returns
    -------
    LateralResult
    """
    relax = Relaxation.uniform(relaxation) if isinstance(relaxation, int | float) else relaxation
    if not isinstance(relax, Relaxation):
        raise InvalidParameter("relaxation", relaxation, "a Relaxation or a rate in [0, 1)")
    mu = float(friction)
    if math.isnan(mu) or mu < 0:
        raise InvalidParameter("friction", friction, ">= 0 (inf for no sliding)")
    nb = v.integer("n_beyond", n_beyond, 9, 20001)
    if slip_anchor not in ("leading", "centre"):
        raise InvalidParameter("slip_anchor", slip_anchor, "'leading' or 'centre'")
    kw = dict(
        pressure=pressure,
        load=load,
        deflection=deflection,
        camber=camber,
        slip=slip,
        surface=surface,
        n_sections=n_sections,
    )
    offset = 0.0
    for _ in range(tol.max_iter):
        patch = solve(tire, lateral=lateral + offset, **kw)
        if slip == 0 or slip_anchor == "centre":
            break
        new = -patch.x[-1] * math.tan(slip)  # dh = lateral at the leading edge
        if abs(new - offset) <= tol.disk_offset_atol:
            break
        offset = new
    else:
        raise NotConverged("leading-edge slip anchor", {"offset_mm": offset})
    x = patch.x
    dv = patch.sections.vert_deflection
    dh_imp = patch.sections.horz_deflection
    w_patch = patch.x_weights
    dh_free = zero_force_displacement(patch, dv) if math.isfinite(mu) else np.zeros_like(dv)
    front = x >= 0.0
    order_f = np.nonzero(front)[0]  # centre -> front
    order_r = np.nonzero(~front)[0][::-1]  # centre -> rear

    def beyond_forces(dh_patch):
        out = []
        for end, rate in ((0, relax.trail_out), (-1, relax.lead_out)):
            s, bdv, bdh, bw = _beyond(patch, dv[end], dh_patch[end], rate, nb)
            if bw.sum() == 0:
                out.append((s, bdv, bdh, np.zeros_like(s), np.zeros_like(s), bw))
                continue
            dS, _ = _section_forces(patch, bdv, bdh)
            out.append((s, bdv, bdh, dS, np.zeros_like(s), bw))
        return out

    dS, dN = _section_forces(patch, dv, dh_imp)
    dh = dh_imp
    sliding = np.zeros_like(front)
    iterations = 0
    ratio = 1.0
    beyond = None
    if math.isfinite(mu):
        history = []
        while iterations < tol.max_iter:
            iterations += 1
            demand = np.abs(dS * ratio)
            sliding = demand > mu * dN + 1e-12 * (1.0 + demand)
            u = dh_imp - dh_free
            u_new = u.copy()
            for order, rate in ((order_f, relax.lead_in), (order_r, relax.trail_in)):
                grip = ~sliding[order]
                pos = np.where(grip, np.arange(order.size), -1)
                anchor = np.maximum.accumulate(pos)  # nearest gripping section toward the centre
                has = anchor >= 0
                a_idx = order[np.where(has, anchor, 0)]
                decay = np.exp((rate - 1.0) * np.abs(x[order] - x[a_idx]))
                u_new[order] = np.where(grip, u[order], np.where(has, u[a_idx] * decay, 0.0))
            dh = dh_free + u_new
            dS, dN = _section_forces(patch, dv, dh)
            f_patch = float(np.sum(w_patch * dS))
            beyond = beyond_forces(dh)
            f_beyond = sum(float(np.sum(b[5] * b[3])) for b in beyond)
            total = f_patch + f_beyond
            history.append(total)
            if len(history) >= 2 and abs(history[-1] - history[-2]) <= tol.friction_rtol * (
                1.0 + abs(total)
            ):
                break
            if len(history) >= 3 and (history[-1] - history[-2]) * (history[-2] - history[-3]) < 0:
                total = 0.5 * (history[-1] + history[-2])  # oscillating: damp by averaging
            ratio = total / f_patch if f_patch else 1.0
            dS, dN = _section_forces(patch, dv, dh_imp)  # friction demand from the imposed state
        if len(history) < 2 or abs(history[-1] - history[-2]) > tol.friction_rtol * (
            1.0 + abs(history[-1])
        ):
            raise NotConverged(
                "friction iteration (section 5.6)",
                {"iterations": tol.max_iter, "last_totals_N": history[-3:]},
            )
        # on convergence dS, dN and beyond are those of the final displacement dh
    else:
        beyond = beyond_forces(dh)
    (s_t, dv_t, dh_t, dS_t, dN_t, w_t), (s_l, dv_l, dh_l, dS_l, dN_l, w_l) = beyond
    x_rear, x_front = x[0], x[-1]
    s_all = np.concatenate([x_rear - s_t[::-1], x, x_front + s_l])
    cat = lambda a, b, c: np.concatenate([a[::-1], b, c])
    f_patch = float(np.sum(w_patch * dS))
    f_beyond = float(np.sum(w_t * dS_t) + np.sum(w_l * dS_l))
    moment = float(np.sum(w_patch * dS * x))
    lengths = []
    for s_b, dh_b in ((s_t, dh_t), (s_l, dh_l)):
        if abs(dh_b[0]) > 0 and np.any(np.abs(dh_b) <= abs(dh_b[0]) / math.e):
            k = int(np.argmax(np.abs(dh_b) <= abs(dh_b[0]) / math.e))
            a, b = np.log(abs(dh_b[k - 1])), np.log(abs(dh_b[k]))
            lengths.append(
                float(
                    s_b[k - 1]
                    + (a - (np.log(abs(dh_b[0])) - 1.0)) / (a - b) * (s_b[k] - s_b[k - 1])
                )
            )
        else:
            lengths.append(math.nan)
    return LateralResult(
        patch=patch,
        s=s_all,
        in_patch=cat(np.zeros_like(s_t, bool), np.ones_like(x, bool), np.zeros_like(s_l, bool)),
        sliding=cat(np.zeros_like(s_t, bool), sliding, np.zeros_like(s_l, bool)),
        dv=cat(dv_t, dv, dv_l),
        dh=cat(dh_t, dh, dh_l),
        dS=cat(dS_t, dS, dS_l),
        dN=cat(dN_t, dN, dN_l),
        weights=cat(w_t, w_patch, w_l),
        lateral_force=f_patch + f_beyond,
        patch_lateral_force=f_patch,
        beyond_lateral_force=f_beyond,
        vertical_force=patch.vertical_force,
        aligning_moment=moment,
        relaxation_length=tuple(lengths),
        iterations=iterations,
        imposed_lateral=float(lateral),
        friction_share=float(ratio),
    )


def tangent_rule(camber_deg):
    """Normalized camber stiffness of the tangent rule, ``tan(theta) / theta`` [1/deg]
    (Eq. 2-5): the net ground reaction in the wheel plane. The dissertation's
    small-angle approximation ``tan(1 deg)`` = 0.017455 /deg is the value at 1 degree
    (the limit at 0 is pi/180 = 0.017453); the approximation is about 21 % too low
    at 45 degrees."""
    t = np.asarray(camber_deg, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.tan(np.radians(t)) / t
    return np.where(t == 0, np.pi / 180.0, out)


def stiffnesses(result) -> dict:
    """Secant stiffnesses of a solved case (Appendix C ``norm_*_stiffness``).

    Lateral ``Fy / lateral`` [N/mm], cornering ``Fy / slip`` [N/deg], camber
    ``Fy / camber`` [N/deg], each also normalized by the vertical load; for camber
    the tangent-rule value (Eq. 2-5), the agreement ratio and the camber-thrust
    deficiency ``1 - agreement`` (negative: a surplus, section 6.1.4).
    """
    p = result.patch if isinstance(result, LateralResult) else result
    fy, fz = result.lateral_force, result.vertical_force
    out = {}
    lateral = getattr(result, "imposed_lateral", p.lateral)
    if lateral:
        out["lateral_stiffness_N_mm"] = fy / lateral
        out["norm_lateral_stiffness_1_mm"] = fy / fz / lateral
    if p.slip:
        deg = math.degrees(p.slip)  # positive: the force opposes the turned tread line
        out["cornering_stiffness_N_deg"] = -fy / deg
        out["norm_cornering_stiffness_1_deg"] = -fy / fz / deg
    if p.camber:
        deg = math.degrees(p.camber)
        out["camber_stiffness_N_deg"] = fy / deg
        out["norm_camber_stiffness_1_deg"] = fy / fz / deg
        out["tangent_rule_1_deg"] = float(tangent_rule(deg))
        out["tangent_rule_agreement"] = (
            out["norm_camber_stiffness_1_deg"] / out["tangent_rule_1_deg"]
        )
        out["camber_thrust_deficiency"] = 1.0 - out["tangent_rule_agreement"]
    return out
