"""Load search: the wheel deflection that carries a vertical load (Appendix C
``find_sinkage``), vectorized over load cases.

The vertical force is ``p * A(dw)`` (Eq. 5-26, section 6.1.1), with ``A`` growing
monotonically with the wheel deflection ``dw``. The appendix takes up to 10 secant
steps to 0.1 %; here a bracketed Newton iteration in ``log dw`` (``A`` is close to
a power law in ``dw``) with the analytic ``dA/ddw`` converges to ``tol.load_rtol``
(1e-10) in 3 to 5 steps, all load cases at once.
"""

from __future__ import annotations

import numpy as np

from . import _validate as v
from ._roots import newton_bracketed
from ._tol import tol
from .errors import LoadTooHigh, NotConverged, TireModelError
from .geometry import TireGeometry
from .patch import (
    ContactPatch,
    _build,
    _Cases,
    _cases,
    _check_deflection,
    _disk_offset,
    _evaluate,
    _patch_ends,
    _sections_at,
    _single_cases,
    area_jacobian,
    clenshaw_curtis,
    solve_patch,
)
from .surface import Flat, Surface

# relative step of the directional difference in _djac_ddw (~sqrt(eps) of the smooth,
# O(1)-curvature Jacobian: ~1e-8 relative accuracy, enough for a Newton derivative)
_DIFF_STEP = 1e-7


def _dw_sensitivities(phi, cs: _Cases):
    """d dv / d dw and d dh / d dw of each section (Eq. 5-17, 5-13 and the slip term,
    ``x = (R - dv) sin phi``; the disk offset held fixed)."""
    cg = np.cos(cs.gamma)
    ddv_ddw = cg / np.cos(phi)
    return ddv_ddw, np.tan(cs.gamma) * ddv_ddw - np.tan(cs.slip) * cg * np.tan(phi)


def _djac_ddw(sol, dv, ddv_dphi, phi, cs: _Cases, jac, dw):
    """d(area Jacobian)/d(wheel deflection): a directional difference along the exact
    d dv/d dw = cos(camber)/cos(phi) (Eq. 5-17), moving the section midpoints by
    their analytic sensitivities."""
    h = _DIFF_STEP * dw
    cg, cp = np.cos(cs.gamma), np.cos(phi)
    ddv_ddw, ddh_ddw = _dw_sensitivities(phi, cs)
    xm = 0.5 * (sol.edge1 + sol.edge2) + h * (sol.dmid_ddv * ddv_ddw + sol.dmid_ddh * ddh_ddw)
    dv2 = dv + h * ddv_ddw
    ddv2 = ddv_dphi + h * cg * np.sin(phi) / (cp * cp)
    return (area_jacobian(sol, dv2, ddv2, phi, cs, xm) - jac) / h


def _area_and_slope(cs: _Cases, dw, n: int, guess=None):
    """Patch area A(dw) and dA/ddw (m, 1); cases out of contact give A = 0."""
    offset, ends = _disk_offset(dw, cs)
    if ends is None:
        rear, front, touching = _patch_ends(dw, cs, offset, guess, touching_only=True)
    else:
        rear, front = ends
        touching = np.ones(dw.shape, bool)
    dwe = np.where(touching, dw, cs.max_deflection())
    t, wts = clenshaw_curtis(n)
    half = 0.5 * (front - rear)
    phi = 0.5 * (front + rear) + half * t
    sol, (dv, ddv_dphi, _, _, _, _) = _sections_at(phi, dwe, cs, offset)
    jac = area_jacobian(sol, dv, ddv_dphi, phi, cs)
    ddv, ddh = _dw_sensitivities(phi, cs)
    width = np.maximum(sol.width, 0.0)
    area = half * (wts * width * jac).sum(-1, keepdims=True)
    djac = _djac_ddw(sol, dv, ddv_dphi, phi, cs, jac, dwe)
    slope = half * (
        wts * ((sol.dwidth_ddv * ddv + sol.dwidth_ddh * ddh) * jac + width * djac)
    ).sum(-1, keepdims=True)
    area = np.where(touching, area, 0.0)
    slope = np.where(touching, slope, 0.0)
    return area, slope, (rear, front)


def _max_load(cs: _Cases, n: int):
    dmax = cs.max_deflection()
    area, _, _ = _area_and_slope(cs, dmax, n)
    return cs.pressure * area, dmax


def _joint_newton(cs: _Cases, load, n: int):
    """Deflection and patch ends together: one section solve per Newton step.

    Unknowns per case: wheel deflection ``dw`` and the end angles ``phi_r, phi_f``.
    Equations: zero width at both ends (section 5.2) and ``log(p A) = log(load)``.
    The Clenshaw-Curtis nodes span [phi_r, phi_f], so every step evaluates the end
    widths and the area in one call. The Jacobian is nearly triangular
    (``dA/dphi_end = +-width_end * dx/dphi``, which vanishes at the solution), so the
    3 x 3 step is solved in closed form. Returns ``None`` where it does not converge
    (the caller falls back to the nested, fully bracketed search).
    """
    t, wts = clenshaw_curtis(n)
    dmax = cs.max_deflection()
    dw = np.clip(
        (load / (cs.pressure * 3.7 * np.sqrt(cs.R))) ** (2.0 / 3.0), 1e-3 * dmax, 0.9 * dmax
    )
    phi_f = np.arccos((cs.R - dw) / cs.R)
    phi_r = -phi_f
    target = np.log(load)
    at_limit = 0
    for _ in range(tol.max_iter):
        half = 0.5 * (phi_f - phi_r)
        phi = 0.5 * (phi_f + phi_r) + half * t
        try:
            sol, (dv, ddv, _, ddh, _, _) = _sections_at(phi, dw, cs, 0.0)
        except TireModelError:
            return None
        jac = area_jacobian(sol, dv, ddv, phi, cs)
        width = sol.width
        dv_dw, dh_dw = _dw_sensitivities(phi, cs)
        dwid_dw = sol.dwidth_ddv * dv_dw + sol.dwidth_ddh * dh_dw
        dwid_dphi = sol.dwidth_ddv * ddv + sol.dwidth_ddh * ddh
        area = half * (wts * width * jac).sum(-1, keepdims=True)
        if np.any(area <= 0):
            return None
        djac = _djac_ddw(sol, dv, ddv, phi, cs, jac, dw)
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
            return dw, (phi_r, phi_f)
    return None


def _find_deflection(cs: _Cases, load, n: int | None = None):
    """Wheel deflection (m, 1) [mm] carrying ``load`` (m, 1) [N], and the patch ends."""
    n = tol.search_sections if n is None else n
    if not np.any(cs.k_disk):  # the disk offset couples the ends: use the nested search
        found = _joint_newton(cs, load, n)
        if found is not None:
            return found
    return _nested_search(cs, load, n)


def _nested_search(cs: _Cases, load, n: int):
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
        area, slope, ends = _area_and_slope(cs, dw, n, guess)
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
    fmax, _ = _max_load(cs, n)
    over = load > fmax
    if np.any(over):
        i = int(np.argmax(over.ravel()))
        raise LoadTooHigh(
            "load",
            float(load.flat[i]),
            float(fmax.flat[i]),
            f"at pressure {float(cs.pressure.flat[i]):.4g} N/mm^2 "
            f"({float(cs.pressure.flat[i]) / 0.1:.4g} bar)",
        )
    raise NotConverged("load search (find_sinkage)", {"load_N": load.ravel(), "u": u})


def find_sinkage(
    tire: TireGeometry,
    load: float,
    *,
    pressure: float,
    camber: float = 0.0,
    slip: float = 0.0,
    lateral: float = 0.0,
    surface: Surface = Flat(),
) -> float:
    """Wheel deflection [mm] at which the tire carries ``load`` (Appendix C ``find_sinkage``).

    Parameters
    ----------
    tire : TireGeometry
    load : float [N]
        Target vertical force, > 0.
    pressure : float [N/mm^2]
    camber, slip, lateral, surface
        As in :func:`tiremesh.solve_patch`.

    Returns
    -------
    deflection : float [mm]

    Raises
    ------
    LoadTooHigh
        The load exceeds what the tire carries before a bead reaches the surface;
        ``.max_load`` holds that largest load [N].
    """
    cs = _single_cases(tire, pressure, camber, slip, lateral, surface)
    f = v.positive("load", np.array([[load]], float), unit="N")
    return float(_find_deflection(cs, f)[0][0, 0])


def max_load(
    tire: TireGeometry,
    *,
    pressure: float,
    camber: float = 0.0,
    slip: float = 0.0,
    lateral: float = 0.0,
    surface: Surface = Flat(),
) -> float:
    """Largest vertical load [N] the model carries at this pressure (deflection at
    ``tol.rim_clearance`` of the point where a bead reaches the surface)."""
    cs = _single_cases(tire, pressure, camber, slip, lateral, surface)
    return float(_max_load(cs, tol.search_sections)[0][0, 0])


def _one_of(load, deflection) -> None:
    if (load is None) == (deflection is None):
        from .errors import InvalidParameter

        raise InvalidParameter("load/deflection", (load, deflection), "exactly one of the two")


def solve(
    tire: TireGeometry,
    *,
    pressure: float,
    load: float | None = None,
    deflection: float | None = None,
    camber: float = 0.0,
    slip: float = 0.0,
    lateral: float = 0.0,
    surface: Surface = Flat(),
    n_sections: int = 201,
) -> ContactPatch:
    """Solve the Rotta tire for a vertical ``load`` [N] or a wheel ``deflection`` [mm].

    Exactly one of ``load`` and ``deflection`` must be given. See
    :func:`tiremesh.solve_patch` for the other parameters.
    """
    _one_of(load, deflection)
    if deflection is None:
        n = v.integer("n_sections", n_sections, 9, 20001)
        cs = _single_cases(tire, pressure, camber, slip, lateral, surface)
        f = v.positive("load", np.array([[load]], float), unit="N")
        dw, ends = _find_deflection(cs, f)
        out = _evaluate(cs, dw, n, ends=ends)
        return _build(tire, cs, float(dw[0, 0]), out, surface, pressure, camber, slip, lateral)
    return solve_patch(
        tire,
        deflection,
        pressure=pressure,
        camber=camber,
        slip=slip,
        lateral=lateral,
        surface=surface,
        n_sections=n_sections,
    )


def solve_many(
    *,
    tire_radius,
    rim_width,
    pressure,
    load=None,
    deflection=None,
    camber=0.0,
    slip=0.0,
    lateral=0.0,
    bead_seat_diameter=622.0,
    drum_diameter=np.inf,
    disk_diameter=np.inf,
    disk_side=1.0,
    n_sections: int = 65,
) -> dict[str, np.ndarray]:
    """Solve many load cases at once, as arrays (broadcast together).

    All parameters are arrays in the package units (mm, N/mm^2, N, rad);
    ``drum_diameter`` / ``disk_diameter`` are ``inf`` for flat ground / a straight
    track, ``disk_side`` is +1 when the disk track's centre lies on ``+y``.

    Returns
    -------
    dict of (m,) float arrays
        ``deflection, length, width, area, vertical_force, lateral_force,
        net_force_orientation, sinkage``.
    """
    _one_of(load, deflection)
    n = v.integer("n_sections", n_sections, 9, 20001)
    cs = _cases(
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
    )
    if deflection is None:
        f = v.positive("load", np.broadcast_to(load, (cs.m,)).reshape(-1, 1), unit="N")
        dw, ends = _find_deflection(cs, f)
    else:
        dw, ends = _check_deflection(np.broadcast_to(deflection, (cs.m,)).reshape(-1, 1), cs), None
    out = _evaluate(cs, dw, n, ends=ends)
    h = cs.rim_height[:, 0]
    return {
        "deflection": dw[:, 0],
        "length": out["length"],
        "width": out["width"],
        "area": out["area"],
        "vertical_force": out["vertical_force"],
        "lateral_force": out["lateral_force"],
        "net_force_orientation": np.arctan2(out["lateral_force"], out["vertical_force"]),
        "sinkage": dw[:, 0] / h,
    }


__all__ = ["find_sinkage", "max_load", "solve", "solve_many"]
