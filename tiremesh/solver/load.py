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

import numpy as np

from .._roots import newton_bracketed
from .._tol import tol
from ..errors import LoadTooHigh, NotConverged, TireModelError
from ..units import MPA_PER_BAR
from .arrays import CaseArrays
from .ends import has_track_shift, patch_ends, touching_patch_ends, track_offset
from .kinematics import area_jacobian, djac_ddw, dw_sensitivities, sections_at
from .quadrature import clenshaw_curtis


def area_and_slope(cs: CaseArrays, dw, n: int, guess=None):
    """Patch area A(dw) and dA/ddw (m, 1); cases out of contact give A = 0."""
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
    djac = djac_ddw(sol, dv, ddv_dphi, phi, cs, jac, dwe)
    slope = half * (
        wts * ((sol.dwidth_ddv * ddv + sol.dwidth_ddh * ddh) * jac + width * djac)
    ).sum(-1, keepdims=True)
    area = np.where(touching, area, 0.0)
    slope = np.where(touching, slope, 0.0)
    return area, slope, (rear, front)


def max_load_arrays(cs: CaseArrays, n: int):
    dmax = cs.max_deflection()
    area, _, _ = area_and_slope(cs, dmax, n)
    return cs.pressure * area, dmax


def joint_newton(cs: CaseArrays, load, n: int, offset=0.0, start=None):
    """Deflection and patch ends together: one section solve per Newton step.

    Unknowns per case: wheel deflection ``dw`` and the end angles ``phi_r, phi_f``.
    Equations: zero width at both ends (section 5.2) and ``log(p A) = log(load)``.
    The Clenshaw-Curtis nodes span [phi_r, phi_f], so every step evaluates the end
    widths and the area in one call. The Jacobian is nearly triangular
    (``dA/dphi_end = +-width_end * dx/dphi``, which vanishes at the solution), so the
    3 x 3 step is solved in closed form.

    ``offset`` is a fixed track offset (m, 1) [mm]; ``start`` an optional warm start
    ``(dw, (rear, front))``. Returns ``(dw, (rear, front), converged)`` with a
    per-case mask of converged cases (the caller solves the others by the nested,
    fully bracketed search), or ``None`` if a step left the model's domain.
    """
    t, wts = clenshaw_curtis(n)
    dmax = cs.max_deflection()
    if start is None:
        dw = np.clip(
            (load / (cs.pressure * 3.7 * np.sqrt(cs.R))) ** (2.0 / 3.0), 1e-3 * dmax, 0.9 * dmax
        )
        phi_f = np.arccos((cs.R - dw) / cs.R)
        phi_r = -phi_f
    else:
        dw, (phi_r, phi_f) = start
    target = np.log(load)
    at_limit = 0
    for _ in range(tol.max_iter):
        half = 0.5 * (phi_f - phi_r)
        phi = 0.5 * (phi_f + phi_r) + half * t
        try:
            sol, d = sections_at(phi, dw, cs, offset)
        except TireModelError:
            return None
        dv, ddv, ddh = d.dv, d.ddv, d.ddh
        jac = area_jacobian(sol, dv, ddv, phi, cs)
        width = sol.width
        dv_dw, dh_dw = dw_sensitivities(phi, cs)
        dwid_dw = sol.dwidth_ddv * dv_dw + sol.dwidth_ddh * dh_dw
        dwid_dphi = sol.dwidth_ddv * ddv + sol.dwidth_ddh * ddh
        area = half * (wts * width * jac).sum(-1, keepdims=True)
        if np.any(area <= 0):
            return None
        djac = djac_ddw(sol, dv, ddv, phi, cs, jac, dw)
        slope = half * (wts * (dwid_dw * jac + width * djac)).sum(-1, keepdims=True)
        f1, f2 = width[:, :1], width[:, -1:]
        a1, a2 = dwid_dphi[:, :1], dwid_dphi[:, -1:]
        b1, b2 = dwid_dw[:, :1], dwid_dw[:, -1:]
        c1, c2 = -f1 * jac[:, :1] / area, f2 * jac[:, -1:] / area
        f3 = np.log(cs.pressure * area) - target
        s = slope / area
        step_dw = (-f3 + c1 * f1 / a1 + c2 * f2 / a2) / (s - c1 * b1 / a1 - c2 * b2 / a2)
        step_dw = np.clip(step_dw, -0.5 * dw, dw)  # damped: at most halve or double
        step_r = (-f1 - b1 * step_dw) / a1
        step_f = (-f2 - b2 * step_dw) / a2
        dw_new = np.minimum(dw + step_dw, dmax)
        at_limit = at_limit + 1 if np.any((dw >= dmax) & (f3 < 0)) else 0
        if at_limit >= 3:  # the load is beyond what the tire carries: let the caller say so
            return None
        outer = np.arccos(np.clip((cs.R - dw_new) / cs.R, -1.0, 1.0)) * 1.05 + 1e-9
        phi_r = np.clip(phi_r + step_r, -outer, -1e-9)
        phi_f = np.clip(phi_f + step_f, 1e-9, outer)
        dw = dw_new
        if not np.all(np.isfinite(dw)):
            return None
        done = (
            (np.abs(f3) <= tol.load_rtol)
            & (np.abs(f1) <= tol.end_width_atol)
            & (np.abs(f2) <= tol.end_width_atol)
            & (np.abs(step_dw) <= tol.load_rtol * dw)
        )
        if np.all(done):
            break
    return dw, (phi_r, phi_f), done


def _joint_with_offset(cs: CaseArrays, load, n: int):
    """Joint Newton inside a fixed point on the track offset (section 5.3.2): each
    outer step solves deflection and ends for a fixed offset, then moves the offset
    to the mean track shift at the new ends (a few outer steps; warm-started)."""
    if not has_track_shift(cs):
        found = joint_newton(cs, load, n)
        return None if found is None else (*found, np.zeros_like(cs.r0))
    shift = lambda phi: cs.surface.shift(phi, cs.R, cs.gamma)[0]
    offset, start = np.zeros_like(cs.r0), None
    for _ in range(tol.max_iter):
        found = joint_newton(cs, load, n, offset, start)
        if found is None:
            return None
        dw, (rear, front), done = found
        new = 0.5 * (shift(rear) + shift(front))  # the offset that follows equation 5-24
        moved = np.abs(new - offset) > tol.disk_offset_atol
        if not np.any(moved & done):
            return dw, (rear, front), done, offset
        offset, start = np.where(done, new, offset), (dw, (rear, front))
    return None


def find_deflection(cs: CaseArrays, load, n: int | None = None):
    """Wheel deflection (m, 1) [mm] carrying ``load`` (m, 1) [N], the patch ends
    (rear, front) and the track offset (m, 1) [mm].

    The joint Newton solves every case it can; the cases it does not converge on
    (and only those) go to the nested, fully bracketed search.
    """
    n = tol.search_sections if n is None else n
    found = _joint_with_offset(cs, load, n)
    if found is None:
        done = np.zeros(cs.r0.shape, bool)
        dw, ends, offset = np.zeros_like(cs.r0), (cs.r0 * 0, cs.r0 * 0), np.zeros_like(cs.r0)
    else:
        dw, ends, done, offset = found
    if np.all(done):
        return dw, ends, offset
    idx = np.nonzero(~done[:, 0])[0]
    sub = cs.take(idx)
    dw_s, _ = nested_search(sub, load[idx], n)
    off_s, _ = track_offset(dw_s, sub)
    rear_s, front_s = patch_ends(dw_s, sub, off_s)
    dw, rear, front, offset = dw.copy(), ends[0].copy(), ends[1].copy(), offset.copy()
    dw[idx], rear[idx], front[idx], offset[idx] = dw_s, rear_s, front_s, off_s
    return dw, (rear, front), offset


def nested_search(cs: CaseArrays, load, n: int):
    """Fully bracketed fallback: Newton in log(dw), patch ends solved at each step."""
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
