"""Load search: the wheel deflection that carries a vertical load (Appendix C
``find_sinkage``), vectorized over load cases.

The vertical force is ``p * A(dw)`` (equation 5-26, section 6.1.1), with ``A`` growing
monotonically with the wheel deflection ``dw``. The appendix takes up to 10 secant
steps to 0.1 %; here a joint Newton iteration on the deflection and both patch ends
(one section solve per step, analytic ``dA/ddw``) converges to ``tol.load_rtol``
(1e-10) in 3 to 6 steps, all load cases at once; a fully bracketed nested search
in ``log dw`` is the fallback.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._roots import newton_bracketed
from .._tol import tol
from ..errors import (
    LoadTooHigh,
    NoContact,
    NotConverged,
    PatchEndLimit,
    SlipLimit,
    SurfaceTooCurved,
    TireModelError,
)
from ..section import section_arrays
from ..units import MPA_PER_BAR
from .arrays import CaseArrays
from .ends import (
    driving_input,
    has_track_shift,
    patch_ends,
    touching_patch_ends,
    track_offset,
)
from .kinematics import (
    area_jacobian,
    displacements,
    djac_ddw,
    dw_sensitivities,
    limit_errors,
    raise_case_errors,
    sections_at,
)
from .quadrature import clenshaw_curtis


def area_and_slope(cs: CaseArrays, dw, n: int, guess=None):
    """Patch area A(dw) and its slope dA/ddw, with the patch ends; cases out of
    contact give A = 0 and dA/ddw = 0.

    Parameters
    ----------
    cs : CaseArrays
    dw : (m, 1) float [mm]
        Wheel deflection.
    n : int
        Clenshaw-Curtis sections per patch.
    guess : (rear, front) of (m, 1) float [rad], optional
        Warm start of the patch ends (straight track).

    Returns
    -------
    area : (m, 1) float [mm^2]
    slope : (m, 1) float [mm]
        dA/ddw.
    ends : (rear, front) of (m, 1) float [rad]
        0 for cases out of contact.
    """
    offset, ends = track_offset(dw, cs)
    if ends is None:
        rear, front, touching = touching_patch_ends(dw, cs, offset, guess)
    else:
        rear, front = ends
        touching = np.ones(dw.shape, bool)
    dwe = np.where(touching, dw, cs.max_deflection())
    t, wts = clenshaw_curtis(n)
    half = 0.5 * (front - rear)
    phi = 0.5 * (front + rear) + half * t
    sol, d = sections_at(phi, dwe, cs, offset)
    dv, ddv_dphi = d.dv, d.ddv
    jac = area_jacobian(sol, dv, ddv_dphi, phi, cs)
    ddv, ddh = dw_sensitivities(phi, cs)
    width = np.maximum(sol.width, 0.0)
    area = half * (wts * width * jac).sum(-1, keepdims=True)
    djac = djac_ddw(sol, phi, cs, dv=dv, ddv_dphi=ddv_dphi, jac=jac, dw=dwe)
    slope = half * (
        wts * ((sol.dwidth_ddv * ddv + sol.dwidth_ddh * ddh) * jac + width * djac)
    ).sum(-1, keepdims=True)
    area = np.where(touching, area, 0.0)
    slope = np.where(touching, slope, 0.0)
    return area, slope, (rear, front)


def max_load_arrays(cs: CaseArrays, n: int):
    """Largest load of each case: ``p A`` (equation 5-26) at the largest deflection
    (:meth:`CaseArrays.max_deflection`).

    Parameters
    ----------
    cs : CaseArrays
    n : int
        Clenshaw-Curtis sections per patch.

    Returns
    -------
    fmax : (m, 1) float [N]
    dmax : (m, 1) float [mm]
        The deflection at which ``fmax`` is carried.
    """
    dmax = cs.max_deflection()
    area, _, _ = area_and_slope(cs, dmax, n)
    return cs.pressure * area, dmax


@dataclass
class _NewtonState:
    """Per-case iterate of the joint Newton: deflection, end angles and step damping."""

    dw: np.ndarray
    rear: np.ndarray
    front: np.ndarray
    damp: np.ndarray

    def copy(self) -> _NewtonState:
        return _NewtonState(self.dw.copy(), self.rear.copy(), self.front.copy(), self.damp.copy())

    def take(self, index) -> _NewtonState:
        return _NewtonState(self.dw[index], self.rear[index], self.front[index], self.damp[index])

    def assign(self, index, other: _NewtonState) -> None:
        for f in ("dw", "rear", "front", "damp"):
            getattr(self, f)[index] = getattr(other, f)[index]


def surface_limit(cs: CaseArrays, i: int, dw: float, ends) -> SurfaceTooCurved | None:
    """:class:`SurfaceTooCurved` if a patch end of case ``i`` reaches the edge of the
    curved surface along the wheel, ``|kappa| R |sin(phi)| >= 1`` (equations 5-20 and
    5-23: there is no surface point under the section); else None.

    Parameters
    ----------
    cs : CaseArrays
    i : int
        Case index.
    dw : float [mm]
        Wheel deflection reached.
    ends : (rear, front) of float [rad]

    Returns
    -------
    SurfaceTooCurved or None
    """
    k = np.broadcast_to(np.asarray(getattr(cs.surface, "curvature", 0.0), float), cs.R.shape)
    reach = abs(float(k[i, 0])) * float(cs.R[i, 0]) * max(abs(np.sin(e)) for e in ends)
    if reach < 1.0:
        return None
    diameter = 2.0 / abs(float(k[i, 0]))
    return SurfaceTooCurved(
        f"{cs.surface.kind} diameter",
        diameter,
        f"> {2.0 * float(cs.R[i, 0]) * max(abs(np.sin(e)) for e in ends):.6g} mm (the patch "
        "must lie within the surface's cross-section along the wheel)",
        {"case": i, "deflection_mm": dw, "patch_half_length_over_surface_radius": reach},
    )


def _search_failure(cs: CaseArrays, st, i: int, offset) -> TireModelError:
    """The error of a load search that cannot step from its last valid iterate:
    the surface limit, the slip limit, no contact of the central section, or
    NotConverged."""
    dw, ends = float(st.dw[i, 0]), (float(st.rear[i, 0]), float(st.front[i, 0]))
    curved = surface_limit(cs, i, dw, ends)
    if curved is not None:
        return curved
    one = cs.take(np.array([i]))
    with np.errstate(all="ignore"):
        d = displacements(np.zeros((1, 1)), st.dw[i : i + 1], one, offset[i : i + 1])
        sol, _, _ = section_arrays(
            one.r0, one.w, d.dv, d.dh, camber=one.gamma, delta=one.r0 * one.gamma
        )
    slipped = slip_limit(one, (st.dw[i : i + 1], ends), offset[i : i + 1], i)
    if slipped is not None:
        return slipped
    if not float(sol.width[0, 0]) > 0:
        return NoContact(
            f"no contact: the central section does not touch at deflection {dw:.6g} mm "
            f"(case {i}); reduce the lateral displacement or increase the load"
        )
    return NotConverged(
        "load search (section 5.2): no valid step from the last iterate",
        {"case": i, "deflection_mm": dw, "end_angles_rad": ends},
    )


def slip_limit(one: CaseArrays, reached, offset, i: int) -> SlipLimit | None:
    """The slip limit of a case whose load search cannot step: with slip, sections
    inside the patch reached (the central one included: the slip anchor shifts it)
    are displaced sideways (``x tan(slip)``, equation 5-17) until their edges cross.

    Parameters
    ----------
    one : CaseArrays
        The case alone (m = 1).
    reached : (dw, (rear, front))
        Deflection (1, 1) [mm] and end angles [rad] the search reached.
    offset : (1, 1) float [mm]
        Track offset.
    i : int
        The case's index in its batch (for the state).

    Returns
    -------
    SlipLimit or None
        None without slip or when every section inside the patch keeps contact.
    """
    slip = float(one.slip[0, 0])
    if slip == 0:
        return None
    dw, (rear, front) = reached
    phi = rear + (front - rear) * np.linspace(0.0, 1.0, 33)[1:-1][None, :]
    with np.errstate(all="ignore"):
        d = displacements(phi, dw, one, offset)
        sol, bad_h, bad_c = section_arrays(
            one.r0, one.w, d.dv, d.dh, camber=one.gamma, delta=one.r0 * one.gamma
        )
    off = ~(sol.width[0] > 0) & ~bad_h[0] & ~bad_c[0]
    if not np.any(off):
        return None
    k = int(np.argmax(np.where(off, np.abs(d.dh[0]), -1.0)))
    return SlipLimit(
        "slip",
        slip,
        "a slip angle for which every section inside the patch keeps contact",
        {
            "case": i,
            "deflection_mm": float(dw[0, 0]),
            "section_x_mm": float(d.x[0, k]),
            "section_lateral_mm": float(d.dh[0, k]),
            "sections_off_ground": int(off.sum()),
        },
    )


def _contact_ends(cs: CaseArrays, dw, offset, steps: int = 40):
    """Angles where the section's vertical displacement falls to zero on each side
    (the surface leaves the tread), by bisection inside the flat-ground end.

    On a curved surface the patch is shorter than on flat ground: starting the load
    search at the flat-ground ends put its outer sections off a small drum (no
    contact, NaN width), and every damped step returned there.

    Parameters
    ----------
    cs : CaseArrays
    dw : (m, 1) float [mm]
    offset : (m, 1) float [mm]
    steps : int
        Bisection steps (2^-40 of the bracket).

    Returns
    -------
    rear, front : (m, 1) float [rad]
    """
    hi = np.arccos(np.clip((cs.R - dw) / cs.R, -1.0, 1.0))
    sign = np.array([[-1.0, 1.0]])  # both sides in one (m, 2) evaluation per step
    lo_, hi_ = np.zeros((hi.shape[0], 2)), hi * np.ones_like(sign)
    for _ in range(steps):
        mid = 0.5 * (lo_ + hi_)
        with np.errstate(all="ignore"):
            dv = displacements(sign * mid, dw, cs, offset).dv
        touch = dv > 0
        lo_, hi_ = np.where(touch, mid, lo_), np.where(touch, hi_, mid)
    out = sign * np.maximum(lo_, 1e-9)
    return out[:, :1], out[:, 1:]


def _start(cs: CaseArrays, load, dmax, start, offset) -> _NewtonState:
    if start is None:
        dw = np.clip(
            (load / (cs.pressure * 3.7 * np.sqrt(cs.R))) ** (2.0 / 3.0), 1e-3 * dmax, 0.9 * dmax
        )
        rear, front = _contact_ends(cs, dw, np.broadcast_to(offset, dw.shape))
        return _NewtonState(dw, rear, front, np.ones_like(dw))
    dw, (rear, front) = start[:2]
    return _NewtonState(dw.copy(), rear.copy(), front.copy(), np.ones_like(dw))


STALL_STEPS = 8
"""Joint Newton steps without a new smallest load residual after which a case is
handed to the bracketed :func:`nested_search` (it diverged: the search would only
run on to ``tol.max_iter``)."""


def _reach_failures(cs: CaseArrays, st, ids, failed: dict, dead) -> None:
    """Converged, but the surface still reaches sections beyond the ends: patch_ends
    would refuse this deflection (equation-free check, same probe). Names the cases
    ``ids`` in ``failed`` and marks them ``dead`` (in place)."""
    for i in ids:
        failed[int(i)] = PatchEndLimit(
            *driving_input(cs, i),
            "a value for which the patch ends where the surface leaves the tire",
            {"case": int(i), "deflection_mm": float(st.dw[i, 0])},
        )
        dead[i] = True


def joint_newton(cs: CaseArrays, load, n: int, offset=0.0, start=None):
    """Deflection and patch ends together: one section solve per Newton step.

    Unknowns per case: ``dw`` and both end angles; equations: zero width at both ends
    (section 5.2) and ``log(p A) = log(load)``. The nearly triangular 3 x 3 step is solved
    in closed form, each case independently. A step leaving Rotta's construction is halved
    from the last valid iterate; after five halvings the case has met a limit of the model.

    Parameters
    ----------
    cs : CaseArrays
    load : (m, 1) float [N]
    n : int
        Clenshaw-Curtis sections per patch.
    offset : (m, 1) float [mm], optional
        Fixed track offset (section 5.3.2; default 0).
    start : (dw, (rear, front)[, solved]) of (m, 1) float [mm, rad] (bool), optional
        Warm start; ``solved`` marks cases whose start is this search's own converged
        solution (the ``partial`` of a failed batch): they take no step again.

    Returns
    -------
    dw : (m, 1) float [mm]
    ends : (rear, front) of (m, 1) float [rad]
    converged : (m, 1) bool
    failed : dict of int -> TireModelError
        Cases that met a limit of the model, with the error naming it.
    """
    t, wts = clenshaw_curtis(n)
    dmax = cs.max_deflection()
    offset = np.broadcast_to(np.asarray(offset, float), cs.r0.shape)
    st = _start(cs, load, dmax, start, offset)
    good = st.copy()
    failed: dict[int, TireModelError] = {}
    dead = np.zeros(cs.m, bool)
    done = np.zeros(cs.m, bool) if start is None or len(start) < 3 else start[2][:, 0].copy()
    over, stall, best = np.zeros(cs.m, int), np.zeros(cs.m, int), np.full(cs.m, np.inf)
    for _ in range(tol.max_iter):
        act = np.nonzero(~done & ~dead)[0]  # only the cases still iterating cost a step
        if act.size == 0:
            break
        cs_a, s_a = cs.take(act), st.take(act)
        with np.errstate(all="ignore"):  # invalid cases compute garbage, masked below
            step = _newton_step(cs_a, s_a, offset[act], np.log(load[act]), (t, wts))
        if step.bad is not None:  # back to the last valid iterate, half the step
            bad = act[step.bad[:, 0]]
            st.damp[bad] *= 0.5
            newly = bad[st.damp[bad, 0] < 1 / 32]
            errs = limit_errors(cs_a, step.bad_h, step.bad_c, s_a.dw)
            for i in newly:
                j = int(np.nonzero(act == i)[0][0])
                err = errs.get(j) or _search_failure(cs, st, int(i), offset)
                if hasattr(err, "state"):
                    err.state["case"] = int(i)
                failed[int(i)] = err
            dead[newly] = True
            for f in ("dw", "rear", "front"):
                cur, prev = getattr(st, f), getattr(good, f)
                cur[bad] = prev[bad] + st.damp[bad] * (cur[bad] - prev[bad])
            keep = ~step.bad[:, 0]  # the valid cases step on in this iteration
            if not np.any(keep):
                continue
            act, s_a = act[keep], s_a.take(keep)
            step = step.take(keep)
        good.assign(act, st)
        _reach_failures(cs, st, act[(step.done & step.reach)[:, 0]], failed, dead)
        over[act] = np.where(((s_a.dw >= dmax[act]) & (step.f3 < 0))[:, 0], over[act] + 1, 0)
        dead[act] |= over[act] >= 3  # the load is beyond what the tire carries
        r3 = np.abs(step.f3[:, 0])  # diverging: the load residual stopped decreasing
        stall[act] = np.where(r3 < best[act], 0, stall[act] + 1)
        best[act] = np.minimum(best[act], r3)
        dead[act] |= stall[act] >= STALL_STEPS  # left to the bracketed search
        done[act] = step.done[:, 0]
        live = act[~step.done[:, 0] & step.finite[:, 0] & ~dead[act]]
        dead[act[~step.done[:, 0] & ~step.finite[:, 0]]] = True
        k = np.isin(act, live)
        dw_new = np.minimum(s_a.dw[k] + step.dw[k], dmax[live])
        outer = np.arccos(np.clip((cs.R[live] - dw_new) / cs.R[live], -1.0, 1.0)) * 1.05 + 1e-9
        st.rear[live] = np.clip(s_a.rear[k] + step.rear[k], -outer, -1e-9)
        st.front[live] = np.clip(s_a.front[k] + step.front[k], 1e-9, outer)
        st.dw[live] = dw_new
        st.damp[live] = np.minimum(1.0, 2.0 * st.damp[live])
    return st.dw, (st.rear, st.front), (done & ~dead)[:, None], failed


@dataclass(frozen=True)
class _Step:
    """One joint Newton step of the active cases (see :func:`joint_newton`)."""

    bad: np.ndarray | None
    bad_h: np.ndarray | None = None
    bad_c: np.ndarray | None = None
    dw: np.ndarray | None = None
    rear: np.ndarray | None = None
    front: np.ndarray | None = None
    f3: np.ndarray | None = None
    done: np.ndarray | None = None
    finite: np.ndarray | None = None
    reach: np.ndarray | None = None

    def take(self, keep) -> _Step:
        """The step of the cases ``keep`` (bool mask), all valid."""
        pick = lambda a: None if a is None else a[keep]
        return _Step(
            None,
            dw=pick(self.dw),
            rear=pick(self.rear),
            front=pick(self.front),
            f3=pick(self.f3),
            done=pick(self.done),
            finite=pick(self.finite),
            reach=pick(self.reach),
        )


def _newton_step(cs: CaseArrays, st: _NewtonState, offset, target, quad) -> _Step:
    t, wts = quad
    half = 0.5 * (st.front - st.rear)
    phi = 0.5 * (st.front + st.rear) + half * t
    d = displacements(phi, st.dw, cs, offset)
    sol, bad_h, bad_c = section_arrays(
        cs.r0, cs.w, d.dv, d.dh, camber=cs.gamma, delta=cs.r0 * cs.gamma, broadcast=True
    )
    jac = area_jacobian(sol, d.dv, d.ddv, phi, cs)
    width = sol.width
    area = half * (wts * width * jac).sum(-1, keepdims=True)
    bad = np.any(bad_h | bad_c, -1, keepdims=True) | ~(area > 0)
    dv_dw, dh_dw = dw_sensitivities(phi, cs)
    dwid_dw = sol.dwidth_ddv * dv_dw + sol.dwidth_ddh * dh_dw
    dwid_dphi = sol.dwidth_ddv * d.ddv + sol.dwidth_ddh * d.ddh
    djac = djac_ddw(sol, phi, cs, dv=d.dv, ddv_dphi=d.ddv, jac=jac, dw=st.dw)
    slope = half * (wts * (dwid_dw * jac + width * djac)).sum(-1, keepdims=True)
    f1, f2 = width[:, :1], width[:, -1:]
    a1, a2 = dwid_dphi[:, :1], dwid_dphi[:, -1:]
    b1, b2 = dwid_dw[:, :1], dwid_dw[:, -1:]
    with np.errstate(all="ignore"):
        c1, c2 = -f1 * jac[:, :1] / area, f2 * jac[:, -1:] / area
        f3 = np.log(cs.pressure * area) - target
        s = slope / area
        step_dw = (-f3 + c1 * f1 / a1 + c2 * f2 / a2) / (s - c1 * b1 / a1 - c2 * b2 / a2)
        step_dw = np.clip(step_dw, -0.5 * st.dw, st.dw) * st.damp  # damped: halve or double
        step_r = (-f1 - b1 * step_dw) / a1
        step_f = (-f2 - b2 * step_dw) / a2
    done = (
        (np.abs(f3) <= tol.load_rtol)
        & (np.abs(f1) <= tol.end_width_atol)
        & (np.abs(f2) <= tol.end_width_atol)
        & (np.abs(step_dw) <= tol.load_rtol * st.dw)
    )
    finite = np.isfinite(step_dw) & np.isfinite(step_r) & np.isfinite(step_f)
    reach = _reach(cs, st.dw, offset, done & ~bad)
    return _Step(
        bad if np.any(bad) else None,
        bad_h & bad,
        bad_c & bad,
        dw=step_dw,
        rear=step_r,
        front=step_f,
        f3=f3,
        done=done & ~bad,
        finite=finite,
        reach=reach,
    )


def _reach(cs: CaseArrays, dw, offset, which) -> np.ndarray:
    """Whether the surface still touches sections just beyond the flat-ground ends,
    probed only for the cases ``which`` (converged ones: the check costs a section
    solve).

    Parameters
    ----------
    cs : CaseArrays
    dw, offset : (m, 1) float [mm]
    which : (m, 1) bool

    Returns
    -------
    (m, 1) bool
        False for the cases not probed.
    """
    reach = np.zeros(dw.shape, bool)
    idx = np.nonzero(which[:, 0])[0]
    if idx.size == 0:
        return reach
    sub, dw_s = cs.take(idx), dw[idx]
    outer = np.minimum(1.05 * np.arccos(np.clip((sub.R - dw_s) / sub.R, -1, 1)) + 1e-9, 1.2)
    d_o = displacements(np.concatenate([-outer, outer], 1), dw_s, sub, offset[idx])
    sol_o, bh_o, bc_o = section_arrays(
        sub.r0, sub.w, d_o.dv, d_o.dh, camber=sub.gamma, delta=sub.r0 * sub.gamma
    )
    reach[idx] = np.any((sol_o.width > 0) & ~bh_o & ~bc_o, -1, keepdims=True)
    return reach


def _joint_with_offset(cs: CaseArrays, load, n: int, start=None):
    """Joint Newton inside a fixed point on the track offset (section 5.3.2): each
    outer step solves deflection and ends for a fixed offset, then moves the offset
    to the mean track shift at the new ends; only the cases whose offset still
    moves take another (warm-started) step."""
    if not has_track_shift(cs):
        dw, ends, done, failed = joint_newton(cs, load, n, start=start)
        return dw, ends, done, np.zeros_like(cs.r0), failed
    start = None if start is None else start[:2]  # solved at its final offset, not at 0
    dw, rear, front = np.zeros_like(cs.r0), np.zeros_like(cs.r0), np.zeros_like(cs.r0)
    offset, done, failed = np.zeros_like(cs.r0), np.zeros(cs.r0.shape, bool), {}
    active = np.arange(cs.m)
    for _ in range(tol.max_iter):
        sub = cs.take(active)
        dw_a, (r_a, f_a), ok_a, failed_a = joint_newton(
            sub, load[active], n, offset[active], start
        )
        failed.update({int(active[i]): err for i, err in failed_a.items()})
        dw[active], rear[active], front[active] = dw_a, r_a, f_a
        shift = lambda phi: sub.surface.shift(phi, sub.R, sub.gamma)[0]  # noqa: B023
        new = 0.5 * (shift(r_a) + shift(f_a))  # the offset that follows equation 5-24
        moved = np.abs(new - offset[active]) > tol.disk_offset_atol
        done[active] = ok_a & ~moved
        offset[active] = np.where(ok_a, new, offset[active])
        again = (ok_a & moved)[:, 0]
        active = active[again]
        if active.size == 0:
            break
        start = (dw_a[again], (r_a[again], f_a[again]))
    return dw, (rear, front), done, offset, failed


def _nested_each(sub: CaseArrays, load, n: int, idx) -> tuple[np.ndarray, dict]:
    """Nested search on a subset; if it fails as a whole, case by case."""
    try:
        return nested_search(sub, load, n)[0], {}
    except TireModelError as exc:
        if sub.m == 1:
            return np.full((1, 1), np.nan), {int(idx[0]): exc}
    dw, errors = np.full((sub.m, 1), np.nan), {}
    for j in range(sub.m):
        got, err = _nested_each(sub.take(np.array([j])), load[j : j + 1], n, idx[j : j + 1])
        dw[j], errors = got[0], {**errors, **err}
    return dw, errors


def find_deflection(cs: CaseArrays, load, n: int | None = None, *, start=None):
    """Wheel deflection carrying ``load``, with the patch ends and the track offset.

    :func:`joint_newton` solves every case it can; the cases it does not converge on
    (and only those) go to the fully bracketed :func:`nested_search`.

    Parameters
    ----------
    cs : CaseArrays
    load : (m, 1) float [N]
    n : int, optional
        Clenshaw-Curtis sections per patch (default ``tol.search_sections``).
    start : (dw, (rear, front)[, solved]) of (m, 1) float [mm, rad] (bool), optional
        Warm start (see :func:`joint_newton`).

    Returns
    -------
    dw : (m, 1) float [mm]
    ends : (rear, front) of (m, 1) float [rad]
    offset : (m, 1) float [mm]
        Track offset (section 5.3.2; 0 on a straight track).

    Raises
    ------
    TireModelError
        The first failed case's error, with every failed case's error in its
        ``case_errors`` (``{case index: error}``) and the solution in ``partial``
        (``(dw, ends, solved)``, valid for the other cases, ``solved`` (m, 1) bool).
    """
    n = tol.search_sections if n is None else n
    dw, ends, done, offset, failed = _joint_with_offset(cs, load, n, start)
    rest = ~done[:, 0] & ~np.isin(np.arange(cs.m), list(failed))
    if np.any(rest):
        idx = np.nonzero(rest)[0]
        sub = cs.take(idx)
        dw_s, errors = _nested_each(sub, load[idx], n, idx)
        failed.update(errors)
        ok = np.isfinite(dw_s[:, 0])
        if np.any(ok):
            sub_ok, dw_ok = sub.take(np.nonzero(ok)[0]), dw_s[ok]
            off_s, _ = track_offset(dw_ok, sub_ok)
            rear_s, front_s = patch_ends(dw_ok, sub_ok, off_s)
            dw, rear, front, offset = dw.copy(), ends[0].copy(), ends[1].copy(), offset.copy()
            k = idx[ok]
            dw[k], rear[k], front[k], offset[k] = dw_ok, rear_s, front_s, off_s
            ends = (rear, front)
    if failed:  # the good cases' solution travels with the error: a re-solve starts there
        solved = ~np.isin(np.arange(cs.m), list(failed))[:, None]
        failed[min(failed)].partial = (dw, ends, solved)
    raise_case_errors(failed)
    return dw, ends, offset


def nested_search(cs: CaseArrays, load, n: int):
    """Fully bracketed fallback: Newton in ``log dw`` on ``log(p A) = log(load)``, the
    patch ends solved at each step; all cases together.

    Parameters
    ----------
    cs : CaseArrays
    load : (m, 1) float [N]
    n : int
        Clenshaw-Curtis sections per patch.

    Returns
    -------
    dw : (m, 1) float [mm]
    ends : (rear, front) of (m, 1) float [rad]

    Raises
    ------
    LoadTooHigh
        A load exceeds ``p A`` at the largest deflection (the first such case).
    NotConverged
        The search fails otherwise.
    """
    target = np.log(load)
    dmax = cs.max_deflection()
    # power-law start, A ~ 3.7 sqrt(R) dw^1.5 (fits the catalogue tires to ~20 %)
    dw0 = np.clip(
        (load / (cs.pressure * 3.7 * np.sqrt(cs.R))) ** (2.0 / 3.0), 1e-3 * dmax, 0.9 * dmax
    )
    state = {"dw": None, "ends": None}

    def fun(u):
        dw = np.exp(u)
        guess = None
        if state["ends"] is not None:
            scale = np.sqrt(dw / state["dw"])
            guess = (state["ends"][0] * scale, state["ends"][1] * scale)
        area, slope, ends = area_and_slope(cs, dw, n, guess)
        state["dw"], state["ends"] = dw, ends
        force = cs.pressure * area
        with np.errstate(divide="ignore", invalid="ignore"):
            g = np.where(force > 0, np.log(force) - target, -np.inf * np.ones_like(force))
            dg = np.where(force > 0, slope * dw / area, 0.0)
        g = np.where(np.isfinite(g), g, -50.0)
        state["g"] = g
        return g, dg

    lo = np.log(1e-9 * dmax)
    hi = np.log(dmax)
    try:
        u = newton_bracketed(
            fun,
            np.log(dw0),
            lo,
            hi,
            xtol=tol.load_rtol * 1e-2,
            what="load search (find_sinkage)",
            sign_lo=-1.0,
            ftol=tol.load_rtol,
        )
    except NotConverged:
        u = None
    if u is not None and np.all(np.abs(state["g"]) <= 10 * tol.load_rtol):
        return np.exp(u), state["ends"]
    fmax, _ = max_load_arrays(cs, n)
    over = load > fmax
    if np.any(over):
        i = int(np.argmax(over.ravel()))
        raise LoadTooHigh(
            "load",
            float(load.flat[i]),
            float(fmax.flat[i]),
            f"at pressure {float(cs.pressure.flat[i]):.4g} N/mm^2 "
            f"({float(cs.pressure.flat[i]) / MPA_PER_BAR:.4g} bar)",
        )
    raise NotConverged("load search (find_sinkage)", {"load_N": load.ravel(), "u": u})
