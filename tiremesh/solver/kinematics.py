"""Section kinematics around the wheel (sections 5.2, 5.3 and 5.4).

Each radial section at angle ``phi`` from bottom dead centre is pressed into the
support surface by (equations 5-14 and 5-15, less the drum drop as in equations 5-18
and 5-21)::

    dv(phi) = (R - (R - dw) / cos phi) cos(camber) - drop(phi)

and displaced sideways by (equation 5-17, plus the imposed lateral displacement, the
slip term and the disk shift of equation 5-24)::

    dh(phi) = lateral + dv tan(camber) + x(phi) tan(slip) + shift(phi) - offset

where ``x = (R - dv) sin phi`` is the section's forward position along the ground,
``drop`` / ``shift`` come from the :class:`~tiremesh.surface.Surface` (a drum lowers
sections, a disk track shifts them) and ``offset`` puts the patch ends of a curved
track where they would be on a straight one (section 5.3.2).

Ground frame: ``x`` forward (rolling direction), ``y`` lateral toward section side 2
(the side the wheel top leans to for positive camber), ``z`` up; origin on the
ground below the centre of the central section.

References
----------
A. E. Dressel (2013), sections 5.2 and 5.3. The index of equations is in
``docs/model.md``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import BulgeLimit, RimBottoms, TireModelError
from ..section import SectionSolution, section_arrays
from .arrays import CaseArrays

# relative step of the directional difference in djac_ddw (~sqrt(eps) of the smooth,
# O(1)-curvature Jacobian: ~1e-8 relative accuracy, enough for a Newton derivative)
_DIFF_STEP = 1e-7


@dataclass(frozen=True)
class Displacements:
    """Per-section displacements and their derivatives along the wheel.

    Attributes
    ----------
    dv, dh : (m, n) float [mm]
        Vertical and horizontal deflection of each section.
    ddv, ddh : (m, n) float [mm/rad]
        Their derivatives with respect to ``phi``.
    x, dx : (m, n) float [mm, mm/rad]
        Forward position ``(R - dv) sin phi`` and its derivative.
    """

    dv: np.ndarray
    ddv: np.ndarray
    dh: np.ndarray
    ddh: np.ndarray
    x: np.ndarray
    dx: np.ndarray


def displacements(phi, dw, cs: CaseArrays, offset) -> Displacements:
    """Section displacements around the wheel.

    Parameters
    ----------
    phi : (m, n) or (k, m, n) float [rad]
        Section angles from bottom dead centre.
    dw : (m, 1) float [mm]
        Wheel deflection in the wheel plane.
    cs : CaseArrays
    offset : (m, 1) float [mm]
        Track offset (section 5.3.2; 0 on a straight track).

    Returns
    -------
    Displacements
        ``dv``, ``dh``, ``x`` and their ``phi`` derivatives, shaped like ``phi``.

    Notes
    -----
    Dressel (2013), sections 5.2 and 5.3: ``dv`` by equations 5-14 and 5-15, less
    the surface drop (equations 5-18 and 5-21); ``dh`` by equation 5-17 plus the
    lateral, slip and track-shift terms (module docstring).
    """
    cg, tg, ta = np.cos(cs.gamma), np.tan(cs.gamma), np.tan(cs.slip)
    sp, cp = np.sin(phi), np.cos(phi)
    dv = cg * (cs.R - (cs.R - dw) / cp)  # Eq. 5-14, Eq. 5-15
    ddv = -cg * (cs.R - dw) * sp / (cp * cp)
    drop, ddrop = cs.surface.drop(phi, cs.R)
    dv, ddv = dv - drop, ddv - ddrop  # Eq. 5-18, Eq. 5-21
    x = (cs.R - dv) * sp
    dx = -ddv * sp + (cs.R - dv) * cp
    shift, dshift = cs.surface.shift(phi, cs.R, cs.gamma)
    dh = cs.lateral + dv * tg + x * ta + (shift - offset)  # Eq. 5-17
    ddh = ddv * tg + dx * ta + dshift
    return Displacements(dv, ddv, dh, ddh, x, dx)


def first_bad_case(bad, m: int) -> int:
    """Index of the first case with a True entry (for error messages).

    Parameters
    ----------
    bad : (m, n) or (k, m, n) bool
        Flags per section; axis -2 is the case.
    m : int
        Number of cases.

    Returns
    -------
    int
        The first flagged case, 0 if none.
    """
    rows = np.any(
        np.reshape(np.broadcast_to(bad, np.shape(bad)), (-1, m, np.shape(bad)[-1])), (0, 2)
    )
    return int(np.argmax(rows)) if rows.any() else 0


def sections_at(phi, dw, cs: CaseArrays, offset, broadcast=False):
    """Rotta sections (section 5.1) at angles around the wheel (sections 5.2, 5.3).

    Parameters
    ----------
    phi : (m, n) or (k, m, n) float [rad]
        Section angles from bottom dead centre.
    dw : (m, 1) float [mm]
        Wheel deflection.
    cs : CaseArrays
    offset : (m, 1) float [mm]
        Track offset (section 5.3.2).
    broadcast : bool
        Broadcast every field of the solution to the shape of ``phi``.

    Returns
    -------
    sol : SectionSolution
        Arrays shaped like ``phi`` (or broadcastable to it).
    d : Displacements
        The section displacements (:func:`displacements`).

    Raises
    ------
    RimBottoms, BulgeLimit
        A bead reaches the surface, or a side bulge would need more carcass than it
        has (the displacement ``dh`` is beyond Rotta's construction); the message
        names the input that drives ``dh``; ``.case_errors`` holds every failed case.
    """
    d = displacements(phi, dw, cs, offset)
    sol, bad_h, bad_c = section_arrays(
        cs.r0, cs.w, d.dv, d.dh, camber=cs.gamma, delta=cs.r0 * cs.gamma, broadcast=broadcast
    )
    if np.any(bad_h) or np.any(bad_c):
        raise_case_errors(limit_errors(cs, _per_case(bad_h, cs.m), _per_case(bad_c, cs.m), dw))
    return sol, d


def _per_case(bad, m: int) -> np.ndarray:
    """(m, 1) bool: any True of ``bad`` (..., m, n) for each case."""
    b = np.broadcast_to(bad, np.shape(bad))
    return np.any(b.reshape(-1, m, b.shape[-1]), axis=(0, 2))[:, None]


def limit_errors(cs: CaseArrays, bad_h, bad_c, dw) -> dict[int, TireModelError]:
    """The limit of Rotta's construction each failed case ran into.

    Parameters
    ----------
    cs : CaseArrays
    bad_h, bad_c : (m, k) bool
        Sections whose bead reaches the surface / whose bulge runs out of carcass.
    dw : (m, 1) float [mm]
        Wheel deflection reached.

    Returns
    -------
    dict of int -> TireModelError
        :class:`RimBottoms` or :class:`BulgeLimit` per failed case, with its state.
    """
    out: dict[int, TireModelError] = {}
    dw = np.broadcast_to(dw, cs.r0.shape)
    for i in np.nonzero(np.any(bad_h, -1) | np.any(bad_c, -1))[0]:
        state = {"case": int(i), "deflection_mm": float(dw[i, 0])}
        if np.any(bad_h[i]):
            out[int(i)] = RimBottoms(
                "deflection",
                float(dw[i, 0]),
                "small enough that no bead reaches the support surface",
                state,
            )
            continue
        name = "slip" if cs.slip[i, 0] else "lateral" if cs.lateral[i, 0] else "camber"
        value = float({"slip": cs.slip, "lateral": cs.lateral, "camber": cs.gamma}[name][i, 0])
        out[int(i)] = BulgeLimit(
            name,
            value,
            "a value for which every side bulge keeps more carcass than its chord",
            state,
        )
    return out


def raise_case_errors(errors: dict[int, TireModelError]) -> None:
    """Raise the first case's error carrying all of them as ``.case_errors``
    (``{case index: error}``), so a batch can set exactly those cases aside.

    Parameters
    ----------
    errors : dict of int -> TireModelError

    Returns
    -------
    None
        Returns only when ``errors`` is empty.
    """
    if errors:
        exc = errors[min(errors)]
        exc.case_errors = dict(errors)
        raise exc


def dw_sensitivities(phi, cs: CaseArrays):
    """d dv / d dw and d dh / d dw of each section (equation 5-15 and equation 5-17
    with the slip term, ``x = (R - dv) sin phi``; the track offset held fixed).

    Parameters
    ----------
    phi : (m, n) float [rad]
        Section angles.
    cs : CaseArrays

    Returns
    -------
    ddv_ddw, ddh_ddw : (m, n) float [-]
    """
    cg = np.cos(cs.gamma)
    ddv_ddw = cg / np.cos(phi)
    return ddv_ddw, np.tan(cs.gamma) * ddv_ddw - np.tan(cs.slip) * cg * np.tan(phi)


def section_to_ground(xs, zs, phi, *, tire_radius, wheel_radius, camber, ground_z):
    """Map section-frame points to the ground frame (Appendix C's R3x, R3y rotations).

    Parameters
    ----------
    xs, zs : (...) float [mm]
        Points in the (cambered, ground-aligned) section frame of :mod:`tiremesh.section`.
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


def area_jacobian(sol: SectionSolution, dv, ddv, phi, cs: CaseArrays, *, xm=None):
    """Ground area per unit section width and per radian of ``phi`` [mm/rad].

    The contact segment ``[e1, e2]`` of the section at ``phi`` maps to the ground by
    :func:`section_to_ground`, which is linear in the section coordinate, so the
    patch area is exactly ``integral (e2 - e1) |J(x_mid, phi)| dphi`` with ``J`` the
    Jacobian determinant of ``(x_s, phi) -> (x, y)`` at the segment midpoint. For an
    uncambered tire ``|J| = dx/dphi`` (equation 5-26's ``dy``); a cambered section plane is
    tilted, which makes its ground footprint slightly smaller (the appendix, which
    takes ``polyarea`` of the projected outline, includes this too). On a curved
    surface the area is measured along the surface (unrolled), as an ink print is.

    Parameters
    ----------
    sol : SectionSolution
        Sections at ``phi``, arrays (m, n).
    dv : (m, n) float [mm]
        Vertical deflection of each section.
    ddv : (m, n) float [mm/rad]
        ``d dv / d phi``.
    phi : (m, n) float [rad]
    cs : CaseArrays
    xm : (m, n) float [mm], optional
        Section-frame ``x`` where ``J`` is taken (default the contact midpoint).

    Returns
    -------
    jac : (m, n) float [mm/rad]
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
    return jac * cs.surface.stretch(rho * sp)


def djac_ddw(sol: SectionSolution, phi, cs: CaseArrays, *, dv, ddv_dphi, jac, dw):
    """d(area Jacobian)/d(wheel deflection): a directional difference along the exact
    d dv/d dw = cos(camber)/cos(phi), moving the section midpoints by their analytic
    sensitivities (for the load search's ``dA/ddw``).

    Parameters
    ----------
    sol : SectionSolution
        Sections at ``phi``, arrays (m, n).
    dv : (m, n) float [mm]
    ddv_dphi : (m, n) float [mm/rad]
    phi : (m, n) float [rad]
    cs : CaseArrays
    jac : (m, n) float [mm/rad]
        :func:`area_jacobian` at ``dw``.
    dw : (m, 1) float [mm]
        Wheel deflection (sets the step).

    Returns
    -------
    djac : (m, n) float [1/rad]
    """
    h = _DIFF_STEP * dw
    cg, cp = np.cos(cs.gamma), np.cos(phi)
    ddv_ddw, ddh_ddw = dw_sensitivities(phi, cs)
    xm = 0.5 * (sol.edge1 + sol.edge2) + h * (sol.dmid_ddv * ddv_ddw + sol.dmid_ddh * ddh_ddw)
    dv2 = dv + h * ddv_ddw
    ddv2 = ddv_dphi + h * cg * np.sin(phi) / (cp * cp)
    return (area_jacobian(sol, dv2, ddv2, phi, cs, xm=xm) - jac) / h
