"""The decay length beyond the patch from the taut beam of section 5.9.

Appendix C needs a relaxation rate ``i`` (section 5.8, equations 5-28 and 5-29) that
the dissertation does not derive: it uses 0.993 per mm for every tire and says the
question of "what rate to use" is left "unanswered" (5.8). Section 5.9 proposes the
taut beam on an elastic foundation (equation 5-30) to make the rate an output. Beyond
the patch there is no ground load, so equation 5-30 reads

``EI u'''' - T u'' + k u = 0``,

with the tension ``T = p pi r^2`` (equation 5-32; equation 5-33 as a variant), the
bending stiffness ``EI`` from equation 5-31 and the foundation ``k`` the lateral
stiffness of a Rotta section that no longer touches the ground (``d(dS)/d(dh)`` of
equation 5-25 at ``dv = 0``, the zero-width section of 5.7). The patch clamps the
tread line at its end (``u(0) = u0`` and, the tread in the patch being straight,
``u'(0) = 0``). With the decay rates ``a, b`` (roots of ``EI m^4 - T m^2 + k = 0``)
the solution is ``u = u0 (b e^{-ax} - a e^{-bx}) / (b - a)`` and its integral
``u0 (1/a + 1/b)``. An exponential ``u0 e^{-x/l}`` (equation 5-28 with
``lambda = 1 / l``, equation 5-29) carries the same total, and so to first order the
same force beyond the patch, when

``l = 1/a + 1/b = sqrt((T + 2 sqrt(k EI)) / k)``  (real or complex ``a, b``),

which is what :func:`decay_length` returns. ``EI = 0`` is the taut string,
``l = sqrt(T / k)``, Pacejka's ``sigma = sqrt(S / c_c)`` (equation 4-2).

``T`` and ``k`` both scale with the pressure, so the string's decay length does not
depend on it. The casing's E and thickness are not printed in the dissertation
(5.9.3.2 cites a literature value [47]); :func:`fit_modulus` fits E as the one global
parameter (thickness fixed), and :func:`leave_one_tire_out` reports how well it
predicts a tire it was not fitted on.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

import tiremesh as tm
from tiremesh.beam import bending_inertia, infinite_beam_point_load, tension_area, tension_hoop

#: casing thickness t [mm] used in equation 5-31 (tiremesh.beam's default; only E t is
#: identified by the fit since I ~ pi r^3 t for t << r)
THICKNESS_MM = 0.8
#: upper bound of the fitted modulus [N/mm^2]
MODULUS_MAX = 1.0e4
#: the rate the appendix uses for every tire (section 5.8, Appendix C)
APPENDIX_RATE = 0.993


def free_section_stiffness(tire: tm.TireGeometry, pressure: float) -> float:
    """Lateral stiffness of a Rotta section beyond the patch, ``d(dS)/d(dh)`` [N/mm^2].

    The section just touches the ground (``dv = 0``, zero contact width, section 5.7)
    and carries ``dS = p (r1 - r2)`` (equation 5-25); central difference at ``dh = 0``.

    Parameters
    ----------
    tire : TireGeometry
    pressure : float [N/mm^2]

    Returns
    -------
    float [N/mm per mm of circumference per mm of displacement]
    """
    h = 1e-4 * tire.tire_radius
    s = tm.solve_sections(tire.tire_radius, tire.rim_width, 0.0, np.array([h, -h]))
    d = s.radius1 - s.radius2
    return float(pressure * (d[0] - d[1]) / (2.0 * h))  # d/dh of the lateral force, equation 5-25


def tension(tire: tm.TireGeometry, pressure: float, kind: str = "area") -> float:
    """Circumferential tension [N]: equation 5-32 (``'area'``) or 5-33 (``'hoop'``).

    Parameters
    ----------
    tire : TireGeometry
    pressure : float [N/mm^2]
    kind : {'area', 'hoop'}

    Returns
    -------
    float [N]
    """
    if kind == "area":
        return float(tension_area(pressure, tire.tire_radius))
    if kind == "hoop":
        return float(tension_hoop(pressure, tire.wheel_radius, tire.tire_radius))
    raise ValueError(
        f"tension kind {kind!r}: use 'area' (tiremesh.beam.tension_area) "
        "or 'hoop' (tiremesh.beam.tension_hoop)"
    )


def decay_length(k, T, EI):
    """Decay length of the clamped taut beam, ``sqrt((T + 2 sqrt(k EI)) / k)`` [mm].

    Parameters
    ----------
    k : float or array [N/mm^2]
        Foundation stiffness.
    T : float or array [N]
        Tension.
    EI : float or array [N mm^2]
        Bending stiffness (0: the taut string).

    Returns
    -------
    float or ndarray [mm]
        The length ``l`` whose exponential ``exp(-x / l)`` has the integral of the
        beam's deflection beyond a clamped end (module docstring).
    """
    k, T, EI = np.asarray(k, float), np.asarray(T, float), np.asarray(EI, float)
    return np.sqrt((T + 2.0 * np.sqrt(k * EI)) / k)


def point_load_decay(k: float, T: float, EI: float) -> float:
    """Distance [mm] at which an infinite taut beam under a point load deflects 1/e of
    its deflection under the load (cf. the photographs of section 3.11.4).

    Parameters
    ----------
    k : float [N/mm^2]
    T : float [N]
    EI : float [N mm^2]

    Returns
    -------
    float [mm]
        ``sqrt(T / k)`` for ``EI = 0``; otherwise from
        :func:`tiremesh.beam.infinite_beam_point_load`.
    """
    if EI <= 0:
        return math.sqrt(T / k)
    scale = float(decay_length(k, T, EI))
    x = np.linspace(0.0, 20.0 * scale, 20001)
    u = infinite_beam_point_load(x, EI=EI, T=T, k=k, P=1.0)
    below = np.nonzero(np.abs(u) <= abs(u[0]) / math.e)[0]
    if below.size == 0:
        return math.nan
    j = int(below[0])
    return float(np.interp(abs(u[0]) / math.e, [abs(u[j]), abs(u[j - 1])], [x[j], x[j - 1]]))


def rate_of(length_mm: float) -> float:
    """Relaxation rate ``i = 1 - 1 / l`` (equations 5-28 and 5-29); 0 for ``l <= 1`` mm.

    Parameters
    ----------
    length_mm : float [mm]
        Decay length ``l`` (> 0).

    Returns
    -------
    float [per mm]
        ``max(0, 1 - 1 / l)``: the fraction of the displacement left after each mm.
    """
    return max(0.0, 1.0 - 1.0 / float(length_mm))


@dataclass(frozen=True)
class BeamRelaxation:
    """The decay length of a load case from the taut beam (module docstring).

    Attributes
    ----------
    modulus : float [N/mm^2]
        Casing E (0: the taut string).
    thickness : float [mm]
        Casing thickness of equation 5-31.
    tension : {'area', 'hoop'}
        Equation 5-32 or 5-33.
    """

    modulus: float = 0.0
    thickness: float = THICKNESS_MM
    tension: str = "area"

    def parts(self, tire: tm.TireGeometry, pressure: float) -> tuple[float, float, float]:
        """Foundation stiffness, tension and bending stiffness of the beam.

        Parameters
        ----------
        tire : TireGeometry
        pressure : float [N/mm^2]

        Returns
        -------
        k, T, EI : float [N/mm^2, N, N mm^2]
        """
        EI = self.modulus * float(bending_inertia(tire.tire_radius, self.thickness))
        return free_section_stiffness(tire, pressure), tension(tire, pressure, self.tension), EI

    def length(self, tire: tm.TireGeometry, pressure: float) -> float:
        """Decay length of the deflection beyond the patch (:func:`decay_length`).

        Parameters
        ----------
        tire : TireGeometry
        pressure : float [N/mm^2]

        Returns
        -------
        float [mm]
        """
        return float(decay_length(*self.parts(tire, pressure)))

    def rate(self, tire: tm.TireGeometry, pressure: float) -> float:
        """Relaxation rate for :class:`tiremesh.Relaxation` (all four sides).

        Parameters
        ----------
        tire : TireGeometry
        pressure : float [N/mm^2]

        Returns
        -------
        float [1/mm]
        """
        return rate_of(self.length(tire, pressure))

    def describe(self) -> str:
        """One line for tables.

        Returns
        -------
        str
            String or beam, E and t, and the tension's equation.
        """
        eq = "5-32" if self.tension == "area" else "5-33"
        if self.modulus == 0:
            return f"taut string (EI = 0), T by equation {eq}"
        return (
            f"taut beam, E = {self.modulus:.4g} N/mm², t = {self.thickness:g} mm, "
            f"T by equation {eq}"
        )


@dataclass(frozen=True)
class FitCase:
    """One measured point of the fit: the model's force as a function of the decay
    length (tabulated, :func:`tabulate_force`), its beam parts and the measurement.

    Attributes
    ----------
    tire_id : int
    k, T, I : float
        Foundation [N/mm^2], tension [N] and area moment (equation 5-31) [mm^4].
    lengths, values : (m,) float
        Decay lengths [mm] and the model quantity there (same unit as ``measured``).
    measured : float
    """

    tire_id: int
    k: float
    T: float
    I: float  # noqa: E741 (the symbol of equation 5-31)
    lengths: np.ndarray
    values: np.ndarray
    measured: float

    def model(self, modulus) -> np.ndarray:
        """Model value(s) at casing modulus/moduli ``modulus`` (interpolated).

        Parameters
        ----------
        modulus : (...) float [N/mm^2]
            Casing Young's modulus.

        Returns
        -------
        (...) float
            The model quantity, in the unit of ``measured``.
        """
        ell = decay_length(self.k, self.T, np.asarray(modulus, float) * self.I)
        return self.at_length(ell)

    def at_length(self, ell) -> np.ndarray:
        """Model value(s) at decay length(s) ``ell`` (interpolated in log-log, clipped
        to the tabulated lengths).

        Parameters
        ----------
        ell : (...) float [mm]

        Returns
        -------
        (...) float
            The model quantity, in the unit of ``measured``.
        """
        x = np.log(np.clip(np.asarray(ell, float), self.lengths[0], self.lengths[-1]))
        return np.exp(np.interp(x, np.log(self.lengths), np.log(self.values)))


#: decay lengths [mm] at which the fit tabulates the model
FIT_LENGTHS = np.geomspace(2.0, 400.0, 13)


def tabulate_force(value_at_rate: Callable[[float], float], lengths=FIT_LENGTHS) -> np.ndarray:
    """The model quantity at each decay length of ``lengths`` (rate ``1 - 1/l``).

    Parameters
    ----------
    value_at_rate : callable
        Relaxation rate -> model value (> 0).
    lengths : (m,) float [mm]

    Returns
    -------
    (m,) float
    """
    return np.array([value_at_rate(rate_of(ell)) for ell in lengths])


def _sse(cases: Sequence[FitCase], predict) -> np.ndarray:
    """Sum over ``cases`` of squared log errors of ``predict(case)`` (arrays broadcast)."""
    return sum((np.log(predict(c)) - math.log(c.measured)) ** 2 for c in cases)


def golden_min(f, lo: float, hi: float, xtol: float) -> tuple[float, float]:
    """Minimum of a unimodal ``f`` on ``[lo, hi]`` by golden-section search.

    Parameters
    ----------
    f : callable
        ``float -> float``, unimodal on ``[lo, hi]``.
    lo, hi : float
        The bracket (same unit as ``x``).
    xtol : float
        The search stops when the bracket is no wider than this.

    Returns
    -------
    (x, f(x)) : (float, float)
        The better of the last two interior points (the ends are never evaluated).
    """
    g = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = lo, hi
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    while b - a > xtol:
        if fc <= fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = f(d)
    return (c, fc) if fc <= fd else (d, fd)


def fit_scalar(cases: Sequence[FitCase], predict, grid: np.ndarray) -> float:
    """Minimize the squared log error over the parameter values of ``grid``, refined
    by a golden-section search between the neighbours of the best grid point.

    Parameters
    ----------
    cases : sequence of FitCase
    predict : callable
        ``(case, values) -> model values`` for an array of parameter values.
    grid : (g,) float, increasing

    Returns
    -------
    float
        The parameter value.
    """
    sse = _sse(cases, lambda c: predict(c, grid))
    j = int(np.argmin(sse))
    lo, hi = grid[max(j - 1, 0)], grid[min(j + 1, grid.size - 1)]
    if hi <= lo:
        return float(grid[j])
    f = lambda x: float(_sse(cases, lambda c: predict(c, np.array([x])))[0])
    x, fx = golden_min(f, float(lo), float(hi), 1e-6 * max(abs(hi), 1e-9))
    return float(x) if fx <= sse[j] else float(grid[j])


#: parameter grids: casing modulus [N/mm^2] (0 = string) and decay length [mm]
MODULUS_GRID = np.concatenate([[0.0], np.geomspace(1e-3, MODULUS_MAX, 281)])
LENGTH_GRID = np.geomspace(FIT_LENGTHS[0], FIT_LENGTHS[-1], 281)


def fit_modulus(cases: Sequence[FitCase]) -> float:
    """The casing modulus E [N/mm^2] (in ``[0, MODULUS_MAX]``) that minimizes the
    squared log error of ``cases``; NaN without cases.

    Parameters
    ----------
    cases : sequence of FitCase

    Returns
    -------
    float [N/mm^2]
        :func:`fit_scalar` over the modulus grid (0, then log-spaced from 1e-3 to
        :data:`MODULUS_MAX`); NaN if ``cases`` is empty.
    """
    if not cases:
        return math.nan
    return fit_scalar(cases, lambda c, e: c.model(e), MODULUS_GRID)


def fit_length(cases: Sequence[FitCase]) -> float:
    """One decay length [mm] for every case (a constant relaxation rate) that
    minimizes the squared log error of ``cases``; NaN without cases.

    Parameters
    ----------
    cases : sequence of FitCase

    Returns
    -------
    float [mm]
        :func:`fit_scalar` over lengths log-spaced across :data:`FIT_LENGTHS`
        (2 to 400 mm); NaN if ``cases`` is empty.
    """
    if not cases:
        return math.nan
    return fit_scalar(cases, lambda c, ell: c.at_length(ell), LENGTH_GRID)


def leave_one_tire_out(cases: Sequence[FitCase], fit) -> dict[int, float]:
    """The parameter fitted without each tire.

    Parameters
    ----------
    cases : sequence of FitCase
    fit : callable
        ``cases -> parameter`` (:func:`fit_modulus` or :func:`fit_length`).

    Returns
    -------
    dict
        Tire id -> the parameter fitted on every other tire's cases (NaN if there is
        no other tire).
    """
    tires = sorted({c.tire_id for c in cases})
    return {t: fit([c for c in cases if c.tire_id != t]) for t in tires}


__all__ = [
    "APPENDIX_RATE",
    "FIT_LENGTHS",
    "MODULUS_MAX",
    "THICKNESS_MM",
    "BeamRelaxation",
    "FitCase",
    "decay_length",
    "fit_length",
    "fit_modulus",
    "fit_scalar",
    "free_section_stiffness",
    "golden_min",
    "leave_one_tire_out",
    "point_load_decay",
    "rate_of",
    "tabulate_force",
    "tension",
]
