"""Patch ends (section 5.2) and the track offset of a sideways-curved track (5.3.2).

The patch ends are the roots of the section width ``e2 - e1`` along the wheel,
found by a bracketed Newton iteration with analytic derivatives (not quantized to
the section spacing, as in Appendix C).
"""

from __future__ import annotations

import numpy as np

from .._roots import newton_bracketed
from .._tol import tol
from ..errors import NoContact, NotConverged, PatchEndLimit, TireModelError
from .arrays import CaseArrays
from .kinematics import raise_case_errors, sections_at


def flat_end_angle(dw, cs: CaseArrays) -> np.ndarray:
    """End angle of the patch on flat ground without camber, ``acos((R - dw) / R)``
    (where equation 5-14 gives zero deflection).

    Parameters
    ----------
    dw : (m, 1) float [mm]
        Wheel deflection.
    cs : CaseArrays

    Returns
    -------
    phi : (m, 1) float [rad]
    """
    return np.arccos(np.clip((cs.R - dw) / cs.R, -1.0, 1.0))


def patch_ends(dw, cs: CaseArrays, offset, guess=None):
    """Angles of the patch ends: the roots of the section width ``e2 - e1`` along the
    wheel (section 5.2).

    Bracketed by the central section (in contact) and 1.05 x the flat-ground end,
    where the surface no longer reaches the tire.

    Parameters
    ----------
    dw : (m, 1) float [mm]
        Wheel deflection.
    cs : CaseArrays
    offset : (m, 1) float [mm]
        Track offset (section 5.3.2; 0 on a straight track).
    guess : (rear, front) of (m, 1) float [rad], optional
        Warm start (default the flat-ground ends).

    Returns
    -------
    rear, front : (m, 1) float [rad]

    Raises
    ------
    NoContact
        The central section of a case does not touch.
    PatchEndLimit
        A section beyond the flat-ground end still touches (end not bracketed).

    """
    phi_flat = flat_end_angle(dw, cs)
    outer = np.minimum(1.05 * phi_flat + 1e-9, 1.2)
    zero = np.zeros_like(outer)
    probe, _ = sections_at(np.stack([zero, outer, -outer]), dw, cs, offset)
    width0 = probe.width[0]
    dwb = np.broadcast_to(dw, cs.r0.shape)
    errors: dict[int, TireModelError] = {}
    for i in np.nonzero(width0[:, 0] <= 0)[0]:
        errors[int(i)] = NoContact(
            f"no contact: the central section's edges cross (width {width0[i, 0]:.4g} mm) "
            f"at deflection {dwb[i, 0]:.6g} mm (case {int(i)}); increase the deflection or "
            "load, or reduce the lateral displacement"
        )
    beyond = np.any(probe.width[1:] > 0, axis=0)[:, 0]
    for i in np.nonzero(beyond & (width0[:, 0] > 0))[0]:
        errors[int(i)] = PatchEndLimit(
            *driving_input(cs, i),
            "a value for which the patch ends where the surface leaves the tire",
            {"case": int(i), "deflection_mm": float(dwb[i, 0])},
        )
    raise_case_errors(errors)

    def fun(phi):
        sol, d = sections_at(phi, dw, cs, offset)
        return sol.width, sol.dwidth_ddv * d.ddv + sol.dwidth_ddh * d.ddh

    lo = np.stack([-outer, zero])
    hi = np.stack([zero, outer])
    x0 = np.stack([-phi_flat, phi_flat]) if guess is None else np.stack(guess)
    sign_lo = np.stack([-np.ones_like(zero), np.ones_like(zero)])
    ends = newton_bracketed(
        fun, x0, lo, hi, xtol=tol.end_xtol, what="contact patch end (section 5.2)", sign_lo=sign_lo
    )
    return ends[0], ends[1]


def driving_input(cs: CaseArrays, i: int) -> tuple[str, float]:
    """The input that displaces case ``i``'s sections sideways (named in errors).

    Parameters
    ----------
    cs : CaseArrays
    i : int
        Case index.

    Returns
    -------
    name : str
        ``'slip'``, ``'lateral'`` or ``'camber'``.
    value : float [rad or mm]
    """
    name = "slip" if cs.slip[i, 0] else "lateral" if cs.lateral[i, 0] else "camber"
    return name, float({"slip": cs.slip, "lateral": cs.lateral, "camber": cs.gamma}[name][i, 0])


def touching_patch_ends(dw, cs: CaseArrays, offset, guess=None):
    """Like :func:`patch_ends`, but cases whose central section is out of contact do
    not raise: their ends are 0.

    Parameters
    ----------
    dw : (m, 1) float [mm]
        Wheel deflection.
    cs : CaseArrays
    offset : (m, 1) float [mm]
        Track offset (section 5.3.2).
    guess : (rear, front) of (m, 1) float [rad], optional
        Warm start, used when every case touches.

    Returns
    -------
    rear, front : (m, 1) float [rad]
    touching : (m, 1) bool
        Whether the central section is in contact.
    """
    zero = np.zeros_like(np.broadcast_to(dw, cs.r0.shape))
    probe, _ = sections_at(zero, dw, cs, offset)
    touching = probe.width > 0
    if np.all(touching):
        rear, front = patch_ends(dw, cs, offset, guess)
        return rear, front, touching
    dw_t = np.where(touching, dw, cs.max_deflection())
    rear, front = patch_ends(dw_t, cs, offset)
    return np.where(touching, rear, 0.0), np.where(touching, front, 0.0), touching


def has_track_shift(cs: CaseArrays) -> bool:
    """Whether the surface shifts sections sideways (a curved track, section 5.3.2).

    Parameters
    ----------
    cs : CaseArrays

    Returns
    -------
    bool
    """
    probe = np.array([[0.1, -0.1]])
    return bool(np.any(cs.surface.shift(probe, cs.R, cs.gamma)[0]))


def track_offset(dw, cs: CaseArrays):
    """Offset of section 5.3.2: the track shift at the patch ends (mean of both ends),
    iterated to convergence (the appendix hard-codes 1.4 mm for its 3 m disk).

    The offset has no equation number: it is the text after equation 5-24 ("the
    entire contact patch needs to be offset ... so that the ends of the contact
    patches are located where they would be if there were not a disk curvature").

    Parameters
    ----------
    dw : (m, 1) float [mm]
        Wheel deflection.
    cs : CaseArrays

    Returns
    -------
    offset : (m, 1) float [mm]
    ends : (rear, front) of (m, 1) float [rad], or None when the track is straight

    Raises
    ------
    NotConverged
        The offset still moves after ``tol.max_iter`` iterations.
    """
    if not has_track_shift(cs):
        return np.zeros_like(cs.r0), None
    shift = lambda phi: cs.surface.shift(phi, cs.R, cs.gamma)[0]
    offset = shift(flat_end_angle(dw, cs))
    for _ in range(tol.max_iter):
        rear, front = patch_ends(dw, cs, offset)
        new = 0.5 * (shift(rear) + shift(front))  # 5.3.2 offset (text after equation 5-24)
        if np.all(np.abs(new - offset) <= tol.disk_offset_atol):
            return new, (rear, front)
        offset = new
    raise NotConverged(
        "track offset (section 5.3.2)", {"iterations": tol.max_iter, "offset_mm": offset.ravel()}
    )
