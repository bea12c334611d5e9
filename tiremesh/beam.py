"""Taut beam on an elastic foundation (section 5.9, equations 5-30, 5-31, 5-32 and 5-33).

``EI u'''' - T u'' + k(x) u = f(x)``: the tread centre line's lateral displacement
``u`` along the wheel, with the carcass's bending stiffness ``EI`` (equation 5-31), the
circumferential tension ``T`` from the inflation pressure (equation 5-32 or 5-33), and the
Rotta sections as the foundation ``k`` [N/mm^2] and load ``f`` [N/mm].

:func:`solve_beam` solves it by pentadiagonal finite differences (pinned ends far
from the patch); :func:`infinite_beam_point_load` is the closed form it is checked
against. :func:`beam_rotta` iterates beam and Rotta model (5.9.4) with two
linearizations:

* ``'consistent'``: the Rotta force at the imposed displacement and the sections'
  tangent stiffness as the foundation (a Newton step): a unique answer.
* ``'dissertation'``: force rate and stiffness rate both from the Rotta sections at
  the current displacement (secant). Because the Rotta section is nearly linear,
  ``f / k`` is then the current displacement itself, so every displacement is an
  equilibrium and the iteration stays near its start: the finding of section 7.3.4,
  reproduced (see the tests).

E and the casing thickness are inputs: the dissertation cites a literature value
for nylon-cord/rubber carcasses ([47]) without printing it; the defaults here
(E = 300 N/mm^2, t = 0.8 mm) are assumptions to change.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import validate as v
from .errors import InvalidParameter, NotConverged


def bending_inertia(tire_radius, thickness):
    """Area moment of the carcass for the taut beam, equation 5-31 (section 5.9).

    ``I = pi/4 (r^4 - (r - t)^4)`` (half the section, far from the rim).

    Parameters
    ----------
    tire_radius : (...) float [mm]
        Carcass radius ``r``.
    thickness : (...) float [mm]
        Casing thickness ``t``.

    Returns
    -------
    I : (...) float [mm^4]
    """
    r = np.asarray(tire_radius, float)
    return np.pi / 4.0 * (r**4 - (r - np.asarray(thickness, float)) ** 4)  # Eq. 5-31


def tension_area(pressure, tire_radius):
    """Tread tension from the pressure on the cross-section area, equation 5-32.

    ``T = p pi r^2`` (section 5.9.3.3).

    Parameters
    ----------
    pressure : (...) float [N/mm^2]
    tire_radius : (...) float [mm]
        Carcass radius ``r``.

    Returns
    -------
    T : (...) float [N]
    """
    return np.asarray(pressure) * np.pi * np.asarray(tire_radius) ** 2  # Eq. 5-32


def tension_hoop(pressure, wheel_radius, tire_radius):
    """Tread tension from the radial pressure over the circumference, equation 5-33.

    ``T = p (R + 2 r)``; about half of equation 5-32 for a 28-622 tire (section
    5.9.3.3).

    Parameters
    ----------
    pressure : (...) float [N/mm^2]
    wheel_radius : (...) float [mm]
        Unloaded wheel radius ``R``.
    tire_radius : (...) float [mm]
        Carcass radius ``r``.

    Returns
    -------
    T : (...) float [N/mm as printed; used as N by :func:`beam_rotta`]
    """
    R, r = np.asarray(wheel_radius), np.asarray(tire_radius)
    return np.asarray(pressure) * (R + 2 * r)  # Eq. 5-33


def solve_beam(x, *, EI: float, T: float, k, f) -> np.ndarray:
    """Finite-difference solution of equation 5-30 on a uniform grid, ends pinned
    (``u = u'' = 0``).

    Parameters
    ----------
    x : (n,) float [mm], uniform, n >= 5
    EI : float [N mm^2]
    T : float [N]
    k : float or (n,) float [N/mm^2]
    f : (n,) float [N/mm]

    Returns
    -------
    u : (n,) float [mm]
    """
    from scipy.linalg import solve_banded

    x = np.asarray(x, float)
    n = x.size
    if n < 5 or not np.allclose(np.diff(x), x[1] - x[0], rtol=1e-9, atol=0):
        raise InvalidParameter("x", f"array of {n}", "a uniform grid of >= 5 points")
    h = x[1] - x[0]
    EI = float(v.positive("EI", EI, unit="N mm^2"))
    T = float(v.finite("T", T, unit="N"))
    k = np.broadcast_to(np.asarray(k, float), (n,))
    f = np.broadcast_to(np.asarray(f, float), (n,))
    a, b = EI / h**4, T / h**2  # Eq. 5-30
    ab = np.zeros((5, n))
    ab[0, 2:] = a  # u_{i+2}
    ab[1, 1:] = -4 * a - b  # u_{i+1}
    ab[2, :] = 6 * a + 2 * b + k  # u_i
    ab[3, :-1] = -4 * a - b  # u_{i-1}
    ab[4, :-2] = a  # u_{i-2}
    # pinned ends: ghost u_{-1} = -u_1 (u'' = 0 at u_0 = 0); rows 0 and n-1 impose u = 0
    ab[2, 0] = ab[2, -1] = 1.0
    ab[1, 1] = ab[0, 2] = 0.0
    ab[3, -2] = ab[4, -3] = 0.0
    ab[2, 1] -= a  # row 1: u_{-1} = -u_1 folds into u_1
    ab[2, -2] -= a
    rhs = f.copy()
    rhs[0] = rhs[-1] = 0.0
    return solve_banded((2, 2), ab, rhs)


def infinite_beam_point_load(x, *, EI: float, T: float, k: float, P: float) -> np.ndarray:
    """Closed form: infinite taut beam on a uniform foundation, point load ``P`` at 0.

    ``EI m^4 - T m^2 + k = 0`` gives the decay rates ``a, b`` (real or complex
    conjugate); ``u = A e^{-a|x|} + B e^{-b|x|}`` with ``u'(0) = 0`` and the shear jump
    ``2 EI u'''(0+) - 2 T u'(0+) = P`` (only the EI term survives). Checks
    :func:`solve_beam` (equation 5-30).

    Parameters
    ----------
    x : (n,) float [mm]
        Positions along the beam (load at 0).
    EI : float [N mm^2]
        Bending stiffness.
    T : float [N]
        Tension.
    k : float [N/mm^2]
        Uniform foundation stiffness.
    P : float [N]
        Point load.

    Returns
    -------
    u : (n,) float [mm]
        Lateral displacement.
    """
    disc = np.sqrt(complex(T * T - 4 * EI * k))
    m2a, m2b = (T + disc) / (2 * EI), (T - disc) / (2 * EI)
    a, b = np.sqrt(m2a), np.sqrt(m2b)
    a = a if a.real > 0 else -a
    b = b if b.real > 0 else -b
    A = -P / (2 * EI * a * (a * a - b * b))
    B = -a * A / b
    ax = np.abs(np.asarray(x, float))
    return np.real(A * np.exp(-a * ax) + B * np.exp(-b * ax))


@dataclass(frozen=True)
class BeamResult:
    """Beam-Rotta iteration (section 5.9.4).

    Attributes
    ----------
    x : (n,) float [mm]
        Position along the wheel (0 at the patch centre).
    u : (n,) float [mm]
        Converged lateral displacement of the tread centre line.
    dS : (n,) float [N/mm]
    lateral_force, vertical_force : float [N]
    history : list of float
        Net force orientation [rad] after each iteration.
    EI, T : float
    """

    x: np.ndarray = field(repr=False)
    u: np.ndarray = field(repr=False)
    dS: np.ndarray = field(repr=False)
    lateral_force: float
    vertical_force: float
    history: list
    EI: float
    T: float

    @property
    def net_force_orientation(self) -> float:
        """Angle of the ground reaction from the vertical, ``atan2(Fy, Fz)`` [rad]."""
        return float(math.atan2(self.lateral_force, self.vertical_force))


def beam_rotta(
    patch,
    *,
    start: float = 0.0,
    method: str = "consistent",
    modulus: float = 300.0,
    thickness: float = 0.8,
    tension: str = "area",
    half_length: float | None = None,
    n: int = 801,
    max_iter: int = 60,
    rtol: float | None = None,
) -> BeamResult:
    """Iterate the taut beam with the Rotta sections (section 5.9.4).

    Parameters
    ----------
    patch : ContactPatch
        The solved patch (camber, lateral, slip and deflection come from it).
    start : float [mm]
        Initial uniform lateral displacement of the centre line.
    method : {'consistent', 'dissertation'}
        Linearization (module docstring).
    modulus : float [N/mm^2], thickness : float [mm], tension : {'area', 'hoop'}
        Carcass E and casing thickness (equation 5-31); tension by equation 5-32 or 5-33.
    half_length : float [mm], optional
        Beam half-length (default a quarter of the tire circumference).
    n, max_iter : int
        Beam grid points (21 .. 200001); iterations before NotConverged is raised.
    rtol : float, optional
        Relative change of the net force orientation to stop at: 1e-8 for 'consistent',
        1e-2 for 'dissertation' (the appendix's loose rule, 0.1 N or 10 %).

    Returns
    -------
    BeamResult
    """
    from .lateral import section_forces

    if method not in ("consistent", "dissertation"):
        raise InvalidParameter("method", method, "'consistent' or 'dissertation'")
    if tension not in ("area", "hoop"):
        raise InvalidParameter("tension", tension, "'area' or 'hoop'")
    t = patch.tire
    E = float(v.positive("modulus", modulus, unit="N/mm^2"))
    th = float(v.in_range("thickness", thickness, 0.0, t.tire_radius, unit="mm"))
    EI = float(E * bending_inertia(t.tire_radius, th))
    T = float(
        tension_area(patch.pressure, t.tire_radius)
        if tension == "area"
        else tension_hoop(patch.pressure, t.wheel_radius, t.tire_radius)
    )
    L = (
        0.5 * math.pi * t.wheel_radius
        if half_length is None
        else float(v.positive("half_length", half_length))
    )
    x = np.linspace(-L, L, v.integer("n", n, 21, 200_001))
    inside = (x >= patch.x[0]) & (x <= patch.x[-1])
    dv = np.where(inside, np.interp(x, patch.x, patch.sections.vert_deflection), 0.0)
    dh0 = np.where(inside, np.interp(x, patch.x, patch.sections.horz_deflection), patch.lateral)
    width = np.where(inside, np.interp(x, patch.x, patch.sections.width), 0.0)
    fz = float(np.trapezoid(patch.pressure * np.maximum(width, 0), x))
    rtol = (1e-8 if method == "consistent" else 1e-2) if rtol is None else float(rtol)
    h = 1e-4
    u = np.full_like(x, float(start))
    history = []
    for _ in range(max_iter):
        dS, _ = section_forces(patch, dv, dh0 + u)
        dSp, _ = section_forces(patch, dv, dh0 + u + h)
        if method == "consistent":
            f0, _ = section_forces(patch, dv, dh0)
            k = np.maximum((dSp - dS) / h, 0.0)
            rhs = f0
        else:  # force rate and stiffness rate both at the current displacement
            with np.errstate(divide="ignore", invalid="ignore"):
                k = np.where(np.abs(u) > 1e-12, dS / u, (dSp - dS) / h)
            k = np.where(k > 0, k, (dSp - dS) / h)
            rhs = dS
        k = np.where(inside | (k > 0), k, np.max(k[inside]) if inside.any() else 0.0)
        u = solve_beam(x, EI=EI, T=T, k=k, f=rhs)
        dS, _ = section_forces(patch, dv, dh0 + u)
        fy = float(np.trapezoid(dS, x))
        history.append(math.atan2(fy, fz))
        if len(history) >= 2 and abs(history[-1] - history[-2]) <= rtol * (1 + abs(history[-1])):
            return BeamResult(x, u, dS, fy, fz, history, EI, T)
    raise NotConverged(
        "beam-Rotta iteration (section 5.9.4)",
        {"iterations": max_iter, "orientation_rad": history[-3:]},
    )
