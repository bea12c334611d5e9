"""Lateral mechanics: deflection beyond the patch, friction, stiffnesses
(sections 2.4, 5.5 to 5.8, 6.1; Appendix C).

Beyond the patch (5.7, 5.8, equations 5-28 and 5-29): a section beyond a patch end keeps the
end section's vertical and lateral displacement decayed as ``exp((i - 1) s)``, with
``s`` the distance along the wheel [mm] and ``i`` the relaxation rate (0.9 .. 0.999
per mm); it is solved as a Rotta section that no longer touches (zero contact
width, two distinct bulge radii, Figure 5-18) and carries ``dS = p (r1 - r2)`` but
no vertical load. The decay length is ``1 / (1 - i)``. Leading and trailing sides
have their own rates.

Friction (5.6, equation 5-27), Coulomb: each patch section's would-be ground reaction
is taken from the grip solution (its own lateral force plus a share of the force
beyond the patch in proportion to its normal load). Where it exceeds ``mu dN`` the
section slides and reacts exactly ``mu dN`` along the grip total; sliding sections'
displacement follows their gripping neighbour nearer the patch centre at the sliding
relaxation rate (Appendix C limits a section's slide by its neighbour's). The demand
does not depend on the sliding, so the result is monotone in ``mu`` without
iteration. Appendix C's iteration is kept as ``friction_model='appendix'``.

Slip: the kinematics are the load case's ``slip_kinematics`` (see
:mod:`tiremesh.case`), applied by :func:`tiremesh.solve` exactly as here.

Departures: the appendix slides toward ``dh = 0``; here toward each section's
zero-force displacement, so that zero friction gives zero lateral force also with
camber. It scales the beyond-patch share as ``dy * F / F_cp`` (a dimensional slip);
the Coulomb model here shares it in proportion to the normal load (a share in
proportion to the patch's own force is singular where that force nears zero, e.g.
camber against a lateral displacement).

References
----------
A. E. Dressel (2013), sections 5.5, 5.6, 5.7 and 5.8 (equations 5-25, 5-26, 5-27,
5-28 and 5-29) and 2.4 (equation 2-5). The index of equations is in
``docs/model.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._roots import newton_bracketed
from ._tol import tol
from .case import LoadCase, Relaxation
from .errors import InvalidParameter, NotConverged
from .geometry import TireGeometry
from .options import SolverOptions, active, using
from .section import section_arrays
from .solver import ContactPatch, clenshaw_curtis, solve
from .solver.api import as_case


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
        Lateral and vertical force per length (equations 5-25 and 5-26).
    weights : (n,) float [mm]
        Quadrature weights along the wheel.
    lateral_force, patch_lateral_force, beyond_lateral_force : float [N]
    vertical_force : float [N]
    aligning_moment : float [N mm]
        ``integral s dS`` over the patch (about the vertical axis, + counter-clockwise
        seen from above); ``pneumatic_trail = -aligning_moment / patch_lateral_force``.
    relaxation_length : (float, float) [mm]
        Trailing and leading distance over which the lateral displacement beyond the
        patch falls to 1/e (equation 5-29).
    iterations : int
        Friction iterations used.
    friction_share : float
        Total over patch lateral force used by the final friction check: each patch
        section had to hold ``friction_share x`` its own force.
    reaction : (n_patch,) float [N/mm]
        Lateral ground reaction per length on each patch section (its would-be grip
        demand, capped at ``mu dN`` where it slides); ``lateral_force`` is its
        integral.
    options : SolverOptions
        The judgement thresholds of the solve (they decide when the trail is NaN).
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
    friction_share: float = 1.0
    reaction: np.ndarray = field(default=None, repr=False)
    options: SolverOptions = field(default_factory=SolverOptions, repr=False)

    def __repr__(self) -> str:
        return (
            f"LateralResult(lateral_force={self.lateral_force:.4g} N, "
            f"patch {self.patch_lateral_force:.4g} N + beyond {self.beyond_lateral_force:.4g} N, "
            f"vertical_force={self.vertical_force:.4g} N, "
            f"pneumatic_trail={self.pneumatic_trail:.4g} mm, sliding={int(self.sliding.sum())})"
        )

    def _repr_html_(self) -> str:
        """A summary table for notebooks."""
        from .solver.patch import summary_html

        return summary_html(
            "LateralResult",
            {
                "lateral_force_N": self.lateral_force,
                "patch_lateral_force_N": self.patch_lateral_force,
                "beyond_lateral_force_N": self.beyond_lateral_force,
                "vertical_force_N": self.vertical_force,
                "aligning_moment_Nmm": self.aligning_moment,
                "pneumatic_trail_mm": self.pneumatic_trail,
                "sliding_sections": int(self.sliding.sum()),
                "friction_iterations": self.iterations,
                **{k: v for k, v in self.case.describe().items() if k != "tire"},
                "tire": self.case.tire.name,
            },
        )

    @property
    def case(self) -> LoadCase:
        """The load case solved."""
        return self.patch.case

    @property
    def imposed_lateral(self) -> float:
        """The case's imposed lateral displacement [mm]."""
        return self.patch.case.lateral

    @property
    def net_force_orientation(self) -> float:
        """Angle of the ground reaction from the vertical, ``atan2(Fy, Fz)`` [rad]."""
        return float(math.atan2(self.lateral_force, self.vertical_force))

    @property
    def pneumatic_trail(self) -> float:
        """``-aligning_moment / patch_lateral_force`` [mm] (positive: force behind the centre).

        NaN when the patch's own sections carry no net lateral force (below
        ``options.force_rtol`` of the vertical force), or less than
        ``options.trail_min_patch_share`` of the total (most of the force then comes from
        beyond the patch and the patch's own forces nearly cancel: their centroid, the
        trail, is meaningless; the validation found -660 mm there)."""
        f = self.patch_lateral_force
        if abs(f) <= self.options.force_rtol * abs(self.vertical_force):
            return math.nan
        if abs(f) < self.options.trail_min_patch_share * abs(self.lateral_force):
            return math.nan
        return float(-self.aligning_moment / f)

    @property
    def friction_used(self) -> np.ndarray:
        """``|dS| / dN`` per patch section, the minimum friction coefficient of
        equation 5-27; NaN beyond the patch."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.in_patch & (self.dN > 0), np.abs(self.dS) / self.dN, np.nan)


def section_forces(patch: ContactPatch, dv, dh):
    """Lateral and vertical force per length of Rotta sections at (dv, dh):
    ``dS = p (r1 - r2)`` (equation 5-25) and ``dN = p max(e2 - e1, 0)`` (equation 5-26).

    Parameters
    ----------
    patch : ContactPatch
        Gives the tire, the pressure [N/mm^2] and the camber [rad].
    dv, dh : (n,) float [mm]
        Vertical and lateral section displacement (any broadcastable shapes).

    Returns
    -------
    dS, dN : (n,) float [N/mm]

    Raises
    ------
    InvalidParameter
        A section leaves Rotta's construction (bead at the ground, or ``c <= 0``).
    """
    t = patch.tire
    sol, bad_h, bad_c = section_arrays(
        t.tire_radius, t.rim_width, dv, dh, camber=patch.camber, delta=t.tire_radius * patch.camber
    )
    if np.any(bad_h) or np.any(bad_c):
        raise InvalidParameter(
            "lateral", patch.lateral, "a displacement within Rotta's construction"
        )
    p = patch.pressure
    return p * (sol.radius1 - sol.radius2), p * np.maximum(sol.width, 0.0)


def zero_force_displacement(patch: ContactPatch, dv) -> np.ndarray:
    """Lateral displacement at which a section at ``dv`` carries no lateral force
    (``r1 = r2``): 0 without camber, opposite to the lean with camber. Solved per
    section by bracketed Newton within ``+-r0 / 2``.

    Parameters
    ----------
    patch : ContactPatch
    dv : (n,) float [mm]
        Vertical section displacement.

    Returns
    -------
    (n,) float [mm]
    """
    dv = np.asarray(dv, float)
    if patch.camber == 0:
        return np.zeros_like(dv)
    r0 = patch.tire.tire_radius
    h = 1e-6 * r0

    def fun(dh):
        f, _ = section_forces(patch, dv, dh)
        fp, _ = section_forces(patch, dv, dh + h)
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


@dataclass(frozen=True)
class BeyondSide:
    """Sections beyond one patch end (equation 5-28), from the end outward.

    Attributes
    ----------
    s : (k,) float [mm]
        Distance from the patch end along the wheel.
    dv, dh : (k,) float [mm]
        Vertical and lateral section displacement.
    dS : (k,) float [N/mm]
        Lateral force per length (equation 5-25).
    weights : (k,) float [mm]
        Quadrature weights over ``s``.
    """

    s: np.ndarray
    dv: np.ndarray
    dh: np.ndarray
    dS: np.ndarray
    weights: np.ndarray

    @property
    def force(self) -> float:
        """Lateral force beyond this end [N]."""
        return float(np.sum(self.weights * self.dS))


APPENDIX_LAST_SLICE = math.radians(15.0)
"""Appendix C's last slice angle (``rip.last_slice_angle = 15*pi/180``)."""


def beyond_side(patch: ContactPatch, dv_end, dh_end, *, rate, n, end=None) -> BeyondSide:
    """Sections beyond one patch end, displaced as the end section decayed by
    ``exp((i - 1) s) = exp(-lambda s)``, ``lambda = 1 - i`` (equation 5-28).

    With ``force_convention='ground'`` the sections cover 8 decay lengths of arc
    along the carcass (equation 5-29; at most a quarter wheel) and the force is
    integrated over that arc length. With ``'appendix'`` they run from the patch end
    angle ``end`` to Appendix C's last slice angle (15 degrees) and the force is
    integrated over ``R d(sin phi)``, as the appendix's ``dy`` beyond the patch.

    Parameters
    ----------
    patch : ContactPatch
    dv_end, dh_end : float [mm]
        Vertical and lateral displacement of the end section.
    rate : float [1/mm]
        Relaxation rate ``i``, in [0, 1).
    n : int
        Clenshaw-Curtis nodes over the span.
    end : float [rad], optional
        Angle of the patch end (``'appendix'`` convention only; its sign says which end).

    Returns
    -------
    BeyondSide
        ``n`` sections; one zero section (zero weight) when there is no span.
    """
    zero = BeyondSide(*(np.zeros(1),) * 5)
    ell = Relaxation.decay_length(rate) if rate > 0 else 0.0
    R = patch.tire.wheel_radius
    t, w = clenshaw_curtis(n)
    if patch.case.force_convention == "appendix":
        a = abs(end)
        if ell <= 0 or a >= APPENDIX_LAST_SLICE:
            return zero
        phi = a + 0.5 * (APPENDIX_LAST_SLICE - a) * (t + 1.0)
        s = R * (phi - a)
        weights = 0.5 * (APPENDIX_LAST_SLICE - a) * w * R * np.cos(phi)
    else:
        span = min(8.0 * ell, 0.5 * math.pi * R) if ell > 0 else 0.0
        if span <= 0:
            return zero
        s = 0.5 * span * (t + 1.0)
        weights = 0.5 * span * w
    e = np.exp((rate - 1.0) * s)  # Eq. 5-28
    dv, dh = dv_end * e, dh_end * e
    dS, _ = section_forces(patch, dv, dh)
    return BeyondSide(s, dv, dh, dS, weights)


def beyond_both(patch: ContactPatch, dv, dh, *, relax: Relaxation, n: int):
    """(trailing, leading) :class:`BeyondSide` continuing the patch's end sections.

    Parameters
    ----------
    patch : ContactPatch
    dv, dh : (n,) float [mm]
        Patch section displacements, trailing to leading (the end values are used).
    relax : Relaxation
        Its ``trail_out`` and ``lead_out`` rates [1/mm] apply.
    n : int
        Clenshaw-Curtis nodes per side.

    Returns
    -------
    (BeyondSide, BeyondSide)
    """
    return (
        beyond_side(patch, dv[0], dh[0], rate=relax.trail_out, n=n, end=patch.phi_ends[0]),
        beyond_side(patch, dv[-1], dh[-1], rate=relax.lead_out, n=n, end=patch.phi_ends[1]),
    )


def slide(u, sliding, x, relax: Relaxation) -> np.ndarray:
    """Sliding step of section 5.6: a sliding section follows its nearest gripping
    neighbour toward the patch centre, decayed at the inner relaxation rate
    (Appendix C limits a section's slide by its neighbour's).

    Parameters
    ----------
    u : (n,) float [mm]
        Section displacement relative to the zero-force displacement.
    sliding : (n,) bool
    x : (n,) float [mm]
        Forward section position: ``x >= 0`` slides at ``lead_in``, the rest at
        ``trail_in``.
    relax : Relaxation

    Returns
    -------
    (n,) float [mm]
        ``u`` where gripping; where sliding, the gripping neighbour's ``u`` times
        ``exp((i - 1) |x - x_neighbour|)``, or 0 if no section toward the centre grips.
    """
    front = x >= 0.0
    u_new = u.copy()
    orders = (np.nonzero(front)[0], np.nonzero(~front)[0][::-1])  # centre -> out
    for order, rate in zip(orders, (relax.lead_in, relax.trail_in), strict=True):
        grip = ~sliding[order]
        pos = np.where(grip, np.arange(order.size), -1)
        anchor = np.maximum.accumulate(pos)  # nearest gripping section toward the centre
        has = anchor >= 0
        a_idx = order[np.where(has, anchor, 0)]
        decay = np.exp((rate - 1.0) * np.abs(x[order] - x[a_idx]))  # as equation 5-28
        u_new[order] = np.where(grip, u[order], np.where(has, u[a_idx] * decay, 0.0))
    return u_new


@dataclass(frozen=True)
class FrictionState:
    """State of the patch after the friction iteration (section 5.6).

    Attributes
    ----------
    dh, dS, dN : (n,) float [mm, N/mm, N/mm]
        Section displacement and the carcass's lateral and vertical force per length.
    reaction : (n,) float [N/mm]
        Lateral ground reaction per length on each patch section: its would-be (grip)
        demand (:func:`_demand`), capped at ``mu dN`` where it slides.
    sliding : (n,) bool
    beyond : (BeyondSide, BeyondSide)
        Trailing and leading side.
    iterations : int
    share : float
        Total over patch lateral force of the final friction check.
    """

    dh: np.ndarray
    dS: np.ndarray
    dN: np.ndarray
    reaction: np.ndarray
    sliding: np.ndarray
    beyond: tuple
    iterations: int
    share: float


def grip_state(patch: ContactPatch, case: LoadCase) -> FrictionState:
    """No sliding: every section keeps its imposed displacement (``friction = inf``).

    Parameters
    ----------
    patch : ContactPatch
    case : LoadCase

    Returns
    -------
    FrictionState
    """
    dv, dh = patch.sections.vert_deflection, patch.sections.horz_deflection
    dS, dN = section_forces(patch, dv, dh)
    beyond = beyond_both(patch, dv, dh, relax=case.relaxation, n=case.n_beyond)
    own = float(np.sum(patch.x_weights * dS))
    f_beyond = sum(b.force for b in beyond)
    q = (own + f_beyond) / own if own else 1.0
    sign, demand = _demand(patch, dS, _normal_load(patch, dN), f_beyond)
    return FrictionState(dh, dS, dN, sign * demand, np.zeros(dS.shape, bool), beyond, 0, q)


def _normal_load(patch: ContactPatch, dN) -> np.ndarray:
    """Normal load per length [N/mm] that integrates exactly to the vertical force."""
    total = float(np.sum(patch.x_weights * dN))
    return dN * (patch.vertical_force / total) if total > 0 else dN


MIN_UTILIZATION = 0.1
"""Smallest friction utilization ``demand / dN`` of a loaded patch section, as a
fraction of the patch's mean ``|Fy| / Fz``, in the Coulomb demand (:func:`_demand`)."""


def _demand(patch: ContactPatch, dS, dN, f_beyond):
    """Would-be (grip) lateral ground reaction per patch section, along the total.

    Each section reacts its own force plus a share of the force beyond the patch in
    proportion to its normal load (the beyond-patch force reaches the ground through
    the contact pressure). Where a loaded section's demand opposes the total or
    nearly vanishes (camber against a lateral displacement), the tread band passes
    it on: the demand is blended with a uniform utilization ``|F| / Fz`` just enough
    that every loaded section uses at least :data:`MIN_UTILIZATION` of the mean.
    The total is unchanged, so a fully sliding patch reacts ``mu Fz``.

    Parameters
    ----------
    patch : ContactPatch
    dS, dN : (n,) float [N/mm]
        Grip lateral force and normal load per length of the patch sections.
    f_beyond : float [N]
        Lateral force beyond both patch ends.

    Returns
    -------
    sign : float
        Sign of the grip total (0 if it is zero).
    demand : (n,) float [N/mm]
        Non-negative demand along ``sign``; ``sum(w demand) = |total|``.
    """
    w = patch.x_weights
    fz = float(np.sum(w * dN))
    d = dS + (f_beyond / fz) * dN if fz > 0 else dS.copy()
    total = float(np.sum(w * d))
    sign = float(np.sign(total))
    loaded = dN > 0
    if sign == 0 or not np.any(loaded):
        return sign, np.zeros_like(d)
    mean = abs(total) / fz
    u_min = float(np.min(sign * d[loaded] / dN[loaded]))
    theta = max(0.0, (MIN_UTILIZATION * mean - u_min) / (mean - u_min))
    demand = np.maximum((1.0 - theta) * sign * d + theta * mean * dN, 0.0)
    return sign, demand * (abs(total) / float(np.sum(w * demand)))


def coulomb_friction(patch: ContactPatch, case: LoadCase) -> FrictionState:
    """Coulomb friction on the patch (section 5.6), the default ``friction_model``.

    The would-be ground reaction of each patch section is taken from the grip
    solution (:func:`_demand`: its own force plus its normal-load share of the
    force beyond the patch, along the grip total). Where it exceeds ``mu dN`` the
    section slides (equation 5-27) and reacts exactly ``mu dN`` in the direction of
    the grip total; elsewhere it reacts its demand. The demand is fixed, so the set
    of sliding sections shrinks as ``mu`` grows and no iteration is needed. The
    sliding sections' carcass displacement follows the nearest gripping neighbour
    toward the patch centre (:func:`slide`), which gives the reported ``dh``,
    ``dS`` and the force beyond the patch; it does not feed back into the demand.

    Guarantees: ``|Fy| <= min(mu Fz, |Fy_grip|)``; ``Fy`` has the sign of the grip
    solution and ``|Fy|`` is nondecreasing in ``mu``; ``mu = 0`` gives 0; full sliding
    gives ``mu Fz``.

    Parameters
    ----------
    patch : ContactPatch
    case : LoadCase
        ``friction`` (mu), ``relaxation`` and ``n_beyond`` are used.

    Returns
    -------
    FrictionState
    """
    mu, relax, nb = case.friction, case.relaxation, case.n_beyond
    x, dv = patch.x, patch.sections.vert_deflection
    grip = grip_state(patch, case)
    normal = _normal_load(patch, grip.dN)  # the vertical load stays where the patch put it
    f_beyond = sum(b.force for b in grip.beyond)
    sign, demand = _demand(patch, grip.dS, normal, f_beyond)
    cap = mu * normal
    sliding = demand > cap  # Eq. 5-27
    reaction = sign * np.minimum(demand, cap)
    if not np.any(sliding):  # nothing slides: the carcass keeps its grip state
        return FrictionState(
            grip.dh, grip.dS, normal, reaction, sliding, grip.beyond, 1, grip.share
        )
    dh_free = zero_force_displacement(patch, dv)
    dh = dh_free + slide(grip.dh - dh_free, sliding, x, relax)
    dS, _ = section_forces(patch, dv, dh)
    beyond = beyond_both(patch, dv, dh, relax=relax, n=nb)
    return FrictionState(dh, dS, normal, reaction, sliding, beyond, 1, grip.share)


def appendix_friction(patch: ContactPatch, case: LoadCase) -> FrictionState:
    """Appendix C's friction iteration (``friction_model='appendix'``): sections whose
    own force times the share exceeds ``mu dN`` (equation 5-27) relax toward their
    gripping neighbour, until the total carcass force converges; oscillation is
    damped by averaging. Unlike :func:`coulomb_friction` the sliding sections keep
    the force of their displacement, so ``|Fy|`` can exceed ``mu Fz``
    (``docs/model.md``).

    Parameters
    ----------
    patch : ContactPatch
    case : LoadCase

    Returns
    -------
    FrictionState
    """
    relax, mu, nb = case.relaxation, case.friction, case.n_beyond
    opts = active()
    x, dv = patch.x, patch.sections.vert_deflection
    dh_imp, w_patch = patch.sections.horz_deflection, patch.x_weights
    dh_free = zero_force_displacement(patch, dv)
    dS, dN = section_forces(patch, dv, dh_imp)
    ratio, history = 1.0, []
    for it in range(1, opts.friction_max_iter + 1):
        demand = np.abs(dS * ratio)
        sliding = demand > mu * dN + 1e-12 * (1.0 + demand)
        dh = dh_free + slide(dh_imp - dh_free, sliding, x, relax)
        dS, dN = section_forces(patch, dv, dh)
        f_patch = float(np.sum(w_patch * dS))
        beyond = beyond_both(patch, dv, dh, relax=relax, n=nb)
        total = f_patch + sum(b.force for b in beyond)
        history.append(total)
        if len(history) >= 2 and abs(history[-1] - history[-2]) <= opts.friction_rtol * (
            1.0 + abs(total)
        ):
            share = total / f_patch if f_patch else 1.0
            return FrictionState(dh, dS, dN, share * dS, sliding, beyond, it, float(ratio))
        if len(history) >= 3 and (history[-1] - history[-2]) * (history[-2] - history[-3]) < 0:
            total = 0.5 * (history[-1] + history[-2])  # oscillating: damp by averaging
        ratio = total / f_patch if f_patch else 1.0
        dS, dN = section_forces(patch, dv, dh_imp)  # friction demand from the imposed state
    raise NotConverged(
        "friction iteration (section 5.6)",
        {"iterations": opts.friction_max_iter, "last_totals_N": history[-3:]},
    )


def relaxation_length(side: BeyondSide) -> float:
    """Distance over which the lateral displacement beyond an end falls to 1/e of its
    value at the end (the decay length of equation 5-29, measured), interpolated in log.

    Parameters
    ----------
    side : BeyondSide

    Returns
    -------
    float [mm]
        NaN if it never falls to 1/e (or is 0 at the end).
    """
    s_b, dh_b = side.s, side.dh
    if not (abs(dh_b[0]) > 0 and np.any(np.abs(dh_b) <= abs(dh_b[0]) / math.e)):
        return math.nan
    k = int(np.argmax(np.abs(dh_b) <= abs(dh_b[0]) / math.e))
    a, b = np.log(abs(dh_b[k - 1])), np.log(abs(dh_b[k]))
    return float(s_b[k - 1] + (a - (np.log(abs(dh_b[0])) - 1.0)) / (a - b) * (s_b[k] - s_b[k - 1]))


def solve_lateral(
    case: LoadCase | TireGeometry, /, *, options: SolverOptions | None = None, **fields
) -> LateralResult:
    """Lateral forces of the tire with deflection beyond the patch and friction
    (sections 5.5 to 5.8).

    Parameters
    ----------
    case : LoadCase or TireGeometry
        The load case (its ``relaxation``, ``friction``, ``slip_kinematics`` and
        ``n_beyond`` apply here); or a tire with the fields as keywords.
    options : SolverOptions, optional
        Judgement thresholds (:class:`tiremesh.SolverOptions`); default: those of the
        enclosing call, or the defaults.
    **fields
        Load-case fields, as for :func:`tiremesh.solve`.

    Returns
    -------
    LateralResult
    """
    case = as_case(case, fields)
    with using(options) as opts:
        patch = solve(case)
        if not math.isfinite(case.friction):
            return _assemble(patch, grip_state(patch, case), opts)
        model = {"coulomb": coulomb_friction, "appendix": appendix_friction}[case.friction_model]
        return _assemble(patch, model(patch, case), opts)


def _assemble(patch: ContactPatch, st: FrictionState, opts: SolverOptions) -> LateralResult:
    """Concatenate trailing side, patch and leading side into one LateralResult."""
    x, dv = patch.x, patch.sections.vert_deflection
    trail, lead = st.beyond
    cat = lambda a, b, c: np.concatenate([a[::-1], b, c])
    no = lambda side: np.zeros(side.s.shape, bool)
    w_patch = patch.x_weights
    f_patch = float(np.sum(w_patch * st.dS))
    f_beyond = trail.force + lead.force
    fy = float(np.sum(w_patch * st.reaction))  # the ground reaction: own + beyond in grip
    return LateralResult(
        patch=patch,
        s=np.concatenate([x[0] - trail.s[::-1], x, x[-1] + lead.s]),
        in_patch=cat(no(trail), np.ones(x.shape, bool), no(lead)),
        sliding=cat(no(trail), st.sliding, no(lead)),
        dv=cat(trail.dv, dv, lead.dv),
        dh=cat(trail.dh, st.dh, lead.dh),
        dS=cat(trail.dS, st.dS, lead.dS),
        dN=cat(np.zeros_like(trail.s), st.dN, np.zeros_like(lead.s)),
        weights=cat(trail.weights, w_patch, lead.weights),
        lateral_force=fy,
        patch_lateral_force=f_patch,
        beyond_lateral_force=f_beyond,
        vertical_force=patch.vertical_force,
        aligning_moment=float(np.sum(w_patch * st.dS * x)),
        relaxation_length=(relaxation_length(trail), relaxation_length(lead)),
        iterations=st.iterations,
        friction_share=st.share,
        reaction=st.reaction,
        options=opts,
    )


def tangent_rule(camber_deg):
    """Normalized camber stiffness of the tangent rule, ``tan(theta) / theta``
    (equation 2-5): the net ground reaction in the wheel plane. The dissertation's
    small-angle approximation ``tan(1 deg)`` = 0.017455 /deg is the value at 1 degree
    (the limit at 0 is pi/180 = 0.017453); the approximation is about 21 % too low
    at 45 degrees.

    Parameters
    ----------
    camber_deg : float or (...) float [deg]

    Returns
    -------
    (...) float [1/deg]
        ``pi / 180`` where the camber is 0.
    """
    t = np.asarray(camber_deg, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.tan(np.radians(t)) / t
    return np.where(t == 0, np.pi / 180.0, out)


def stiffnesses(result) -> dict:
    """Secant stiffnesses of a solved case (Appendix C ``norm_*_stiffness``).

    Lateral ``Fy / lateral`` [N/mm], cornering ``-Fy / slip`` [N/deg], camber
    ``Fy / camber`` [N/deg], each also normalized by the vertical load; for camber
    the tangent-rule value (equation 2-5), the agreement ratio and the camber-thrust
    deficiency ``1 - agreement`` (negative: a surplus, section 6.1.4).

    Parameters
    ----------
    result : LateralResult or ContactPatch
        Its ``lateral_force`` and ``vertical_force`` [N] are used.

    Returns
    -------
    dict of str -> float
        Only for the non-zero inputs: ``lateral_stiffness_N_mm``,
        ``norm_lateral_stiffness_1_mm`` (lateral); ``cornering_stiffness_N_deg``,
        ``norm_cornering_stiffness_1_deg`` (slip); ``camber_stiffness_N_deg``,
        ``norm_camber_stiffness_1_deg``, ``tangent_rule_1_deg``,
        ``tangent_rule_agreement``, ``camber_thrust_deficiency`` (camber).
    """
    p = result.patch if isinstance(result, LateralResult) else result
    fy, fz = result.lateral_force, result.vertical_force
    out = {}
    lateral = p.lateral
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
