"""Analytical relationships extracted from the Rotta model (Dressel 2013, 8.2.2.1).

Closed-form fits of the patch length, width, area, sinkage, vertical stiffness and
camber thrust, generated from dense vectorized sweeps of the full model
(:func:`tiremesh.solve_many`) over the catalogue's domain, each with its
coefficients, its domain and its maximum and RMS relative error on held-out cases.

Every fitted relation uses the same three dimensionless groups::

    Pi   = Fz / (p r0 sqrt(r0 R))    load number (= A / (r0 sqrt(r0 R)), since A = Fz / p)
    beta = w / r0                    rim ratio
    cos(camber)

with ``r0`` the carcass radius, ``w`` the rim width, ``h = r0 + sqrt(r0^2 - w^2/4)``
the rim height (equation 5-3) and ``R = D_bead / 2 + h`` the wheel radius. Each
quantity is ``q = scale * exp(sum_k c_k t_k)`` with the terms ``t_k`` of its form:
``'power'`` (a plain power law, for use by hand) or ``'refined'`` (a full
second-order polynomial in the logs of the three groups). ``Fz`` and ``p`` enter only through ``Fz / p``: in
the Rotta model the deformed shape is pure geometry and ``Fz = p A`` exactly.

Exact identities (no fit): ``A = Fz / p`` (:data:`AREA_IDENTITY`, section 6.1.1) and,
for an uncambered tire on flat ground, ``L = 2 sqrt(delta (2 R - delta))``
(:func:`chord_length`: the patch ends where the wheel circle of radius ``R``
lowered by ``delta`` crosses the ground, equation 5-14).

References
----------
A. E. Dressel (2013), sections 6.1.1, 6.1.2, 6.1.4 and 8.2.2.1.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import validate as v
from .case import CaseTable
from .geometry import arc_length, rim_angle, rim_angle_from_arc_length
from .solver import solve_many

DOMAIN = {
    "arc_length": (45.0, 128.2),  # [mm] Table 3-2: Maxxis 22 mm .. Big Apple 55 mm
    "rim_width": (13.4, 18.7),  # [mm] Table 3-2
    "pressure": (0.2, 1.1),  # [N/mm^2] 2 .. 11 bar (chapter 3)
    "load": (304.0, 731.0),  # [N] (chapter 3)
    "camber": (0.0, math.radians(45.0)),  # [rad]
}
"""Sampled box of the sweeps: every catalogue tire size, rim, pressure and load the
dissertation measured, and camber up to 45 degrees (flat ground, 622 mm bead seat)."""

SINKAGE_MAX = 0.4
"""Largest model sinkage (deflection / rim height) inside the relations' domain."""
BEAD_SEAT_DIAMETER = 622.0  # [mm] every catalogue tire
ZERO_CAMBER_SHARE = 0.25  # share of sweep cases at exactly zero camber
STIFFNESS_STEP = 1e-4  # relative deflection step of the stiffness central difference
N_SECTIONS = 65  # sections per patch in the sweeps (tiremesh.sweep.VECTOR_SECTIONS)
QUANTITIES = ("sinkage", "length", "width", "vertical_stiffness", "camber_thrust")
FORMS = {
    "power": ("1", "ln Pi", "ln beta", "ln cos(camber)"),
    "refined": (
        "1",
        "ln Pi",
        "ln beta",
        "ln cos(camber)",
        "(ln Pi)^2",
        "(ln beta)^2",
        "(ln cos(camber))^2",
        "ln Pi * ln beta",
        "ln Pi * ln cos(camber)",
        "ln beta * ln cos(camber)",
    ),
}
"""Terms of each fitted form, in coefficient order."""
UNITS = {
    "sinkage": "-",
    "length": "mm",
    "width": "mm",
    "vertical_stiffness": "N/mm",
    "camber_thrust": "N",
    "area": "mm^2",
    "tire_radius": "mm",
}
SCALES = {
    "sinkage": "(r0/h)",
    "length": "sqrt(r0 R)",
    "width": "r0",
    "vertical_stiffness": "(Fz/r0)",
    "camber_thrust": "Fz tan(camber)",
}
"""Scale of each quantity: ``q = scale * exp(sum c_k t_k)``."""
AREA_IDENTITY = "A = Fz / p"


@dataclass(frozen=True)
class Relation:
    """One closed-form relation and its accuracy against the full model.

    Attributes
    ----------
    name : str
        Quantity: one of :data:`QUANTITIES`, ``'area'`` or ``'tire_radius'``.
    form : str
        ``'power'``, ``'refined'`` (:data:`FORMS`), ``'identity'`` (area) or
        ``'polynomial'`` (tire radius from arc length).
    unit : str
        Unit of the quantity.
    formula : str
        The relation as text, with its coefficients.
    terms : tuple of str
        Names of the terms, in coefficient order.
    coefficients : tuple of float
    domain : tuple of (str, float, float)
        Range of each input and group over the cases it was fitted on (units in
        the names; ``camber_rad`` is ``|camber|``).
    max_error, rms_error : float [-]
        Largest and RMS relative error on the held-out cases.
    max_error_zero_camber : float [-]
        Largest relative error on the held-out cases at zero camber (NaN if none).
    n_fit, n_test : int
        Cases fitted and held out.
    """

    name: str
    form: str
    unit: str
    formula: str
    terms: tuple
    coefficients: tuple
    domain: tuple
    max_error: float
    rms_error: float
    max_error_zero_camber: float
    n_fit: int
    n_test: int

    def as_dict(self) -> dict:
        """The relation as plain values (for JSON).

        Returns
        -------
        dict
            The attributes; ``terms`` and ``coefficients`` as lists, ``domain`` as
            ``{name: [lo, hi]}``.
        """
        d = dataclasses.asdict(self)
        d["terms"], d["coefficients"] = list(self.terms), list(self.coefficients)
        d["domain"] = {k: [lo, hi] for k, lo, hi in self.domain}
        return d


def tire_radius_from_arc_length(arc_length_mm, rim_width):
    """Carcass radius from the bead-to-bead arc length, exactly (equations 5-6, 5-5).

    Parameters
    ----------
    arc_length_mm : (...) float [mm]
    rim_width : (...) float [mm]

    Returns
    -------
    r0 : (...) float [mm]
    """
    theta0 = rim_angle_from_arc_length(rim_width, arc_length_mm)
    return np.asarray(rim_width, float) / (2.0 * np.sin(0.5 * theta0))


def chord_length(deflection, wheel_radius):
    """Patch length of an uncambered tire on flat ground, ``2 sqrt(delta (2 R - delta))``.

    The patch ends where the deflected section depth ``R - (R - delta) / cos(phi)``
    (equation 5-14) falls to zero: the chord of the wheel circle at depth ``delta``.

    Parameters
    ----------
    deflection : (...) float [mm]
        Wheel deflection ``delta``.
    wheel_radius : (...) float [mm]
        ``R = D_bead / 2 + h``.

    Returns
    -------
    length : (...) float [mm]
    """
    d = np.asarray(deflection, float)
    return 2.0 * np.sqrt(d * (2.0 * np.asarray(wheel_radius, float) - d))


def _column(obj, key, default=None):
    if isinstance(obj, Mapping):
        val = obj.get(key, default)
    else:
        val = getattr(obj, key, default)
    return None if val is None else np.asarray(val, float)


def case_inputs(cases) -> dict[str, np.ndarray]:
    """The inputs of the relations as arrays, from a CaseTable or a mapping.

    Parameters
    ----------
    cases : CaseTable or mapping
        A mapping gives ``rim_width`` [mm], ``pressure`` [N/mm^2], ``load`` [N],
        optionally ``camber`` [rad] (0) and ``bead_seat_diameter`` [mm] (622), and
        ``tire_radius`` [mm] or ``arc_length`` [mm] (converted exactly, equation 5-6).
        Arrays broadcast together.

    Returns
    -------
    dict of (m,) float arrays
        ``tire_radius, rim_width, pressure, load, camber, bead_seat_diameter`` and
        ``arc_length`` [mm, N/mm^2, N, rad].
    """
    w = _column(cases, "rim_width")
    r0 = _column(cases, "tire_radius")
    if r0 is None:
        r0 = tire_radius_from_arc_length(_column(cases, "arc_length"), w)
    cols = {
        "tire_radius": r0,
        "rim_width": w,
        "pressure": _column(cases, "pressure"),
        "load": _column(cases, "load"),
        "camber": _column(cases, "camber", 0.0),
        "bead_seat_diameter": _column(cases, "bead_seat_diameter", BEAD_SEAT_DIAMETER),
    }
    out = dict(zip(cols, np.broadcast_arrays(*cols.values()), strict=True))
    out = {k: np.atleast_1d(a).astype(float).ravel() for k, a in out.items()}
    r0 = out["tire_radius"]
    out["arc_length"] = arc_length(r0, rim_angle(out["rim_width"], r0))
    return out


def dimensionless_groups(inputs: Mapping) -> dict[str, np.ndarray]:
    """The groups every fitted relation uses, and the lengths they are built from.

    Parameters
    ----------
    inputs : mapping
        :func:`case_inputs` output.

    Returns
    -------
    dict of (m,) float arrays
        ``Pi`` [-] = Fz / (p r0 sqrt(r0 R)), ``beta`` [-] = w / r0, ``cos_camber`` [-],
        ``rim_height`` h [mm] (equation 5-3), ``wheel_radius`` R [mm].
    """
    r0, w = inputs["tire_radius"], inputs["rim_width"]
    h = r0 + np.sqrt(r0**2 - 0.25 * w**2)  # equation 5-3 with cos(theta0/2) from 5-2
    big_r = 0.5 * inputs["bead_seat_diameter"] + h
    return {
        "Pi": inputs["load"] / (inputs["pressure"] * r0 * np.sqrt(r0 * big_r)),
        "beta": w / r0,
        "cos_camber": np.cos(inputs["camber"]),
        "rim_height": h,
        "wheel_radius": big_r,
    }


def design_matrix(groups: Mapping, form: str) -> np.ndarray:
    """The terms of a fitted form (:data:`FORMS`) evaluated for m cases.

    Parameters
    ----------
    groups : mapping
        :func:`dimensionless_groups` output.
    form : {'power', 'refined'}

    Returns
    -------
    (m, k) float array [-]
    """
    lp, lb, lc = np.log(groups["Pi"]), np.log(groups["beta"]), np.log(groups["cos_camber"])
    cols = [np.ones_like(lp), lp, lb, lc]
    if form == "refined":
        cols += [lp * lp, lb * lb, lc * lc, lp * lb, lp * lc, lb * lc]
    return np.stack(cols, axis=-1)


def quantity_scale(name: str, inputs: Mapping, groups: Mapping) -> np.ndarray:
    """The scale of a fitted quantity (:data:`SCALES`), in its unit.

    Parameters
    ----------
    name : str
        One of :data:`QUANTITIES`.
    inputs, groups : mapping
        :func:`case_inputs` and :func:`dimensionless_groups` outputs.

    Returns
    -------
    (m,) float array [unit of the quantity]
    """
    r0, fz = inputs["tire_radius"], inputs["load"]
    scales = {
        "sinkage": lambda: r0 / groups["rim_height"],
        "length": lambda: np.sqrt(r0 * groups["wheel_radius"]),
        "width": lambda: r0,
        "vertical_stiffness": lambda: fz / r0,
        "camber_thrust": lambda: fz * np.tan(inputs["camber"]),
    }
    return scales[name]()


def evaluate_relation(relation: Relation, cases) -> np.ndarray:
    """The value of ``relation`` for many cases, vectorized.

    Parameters
    ----------
    relation : Relation
    cases : CaseTable or mapping
        See :func:`case_inputs` (``arc_length`` may replace ``tire_radius``).

    Returns
    -------
    (m,) float array [``relation.unit``]
        Sinkage [-], length [mm], width [mm], vertical stiffness [N/mm], camber
        thrust [N] (signed as the camber), area [mm^2] or tire radius [mm].
    """
    inputs = case_inputs(cases)
    c = np.asarray(relation.coefficients, float)
    if relation.form == "identity":
        return inputs["load"] / inputs["pressure"]
    if relation.form == "polynomial":
        s0 = inputs["arc_length"]
        return s0 * np.polyval(c[::-1], inputs["rim_width"] / s0)
    groups = dimensionless_groups(inputs)
    x = design_matrix(groups, relation.form)
    return quantity_scale(relation.name, inputs, groups) * np.exp(x @ c)


def sweep_cases(n_cases: int, *, seed: int = 0) -> CaseTable:
    """Random cases over :data:`DOMAIN` (uniform in each input; a
    :data:`ZERO_CAMBER_SHARE` of them at zero camber), flat ground.

    Parameters
    ----------
    n_cases : int
    seed : int
        Seed of ``numpy.random.default_rng``.

    Returns
    -------
    CaseTable
        With ``load`` given (load-searched cases).
    """
    m = v.integer("n_cases", n_cases, 2, 10**8)
    rng = np.random.default_rng(seed)
    draw = {k: rng.uniform(lo, hi, m) for k, (lo, hi) in DOMAIN.items()}
    draw["camber"][rng.random(m) < ZERO_CAMBER_SHARE] = 0.0
    r0 = tire_radius_from_arc_length(draw["arc_length"], draw["rim_width"])
    return CaseTable.from_columns(
        tire_radius=r0,
        rim_width=draw["rim_width"],
        pressure=draw["pressure"],
        load=draw["load"],
        camber=draw["camber"],
        bead_seat_diameter=BEAD_SEAT_DIAMETER,
    )


def vertical_stiffness(cases: CaseTable, deflection, *, n_sections: int = N_SECTIONS):
    """``dFz / d(deflection)`` at fixed pressure and camber, by a central difference
    of two deflection solves (step :data:`STIFFNESS_STEP` of the deflection).

    Parameters
    ----------
    cases : CaseTable
        m cases (their load column is ignored).
    deflection : (m,) float [mm]
        Wheel deflection at which to differentiate; NaN skips a case.
    n_sections : int

    Returns
    -------
    (m,) float [N/mm]
        NaN where ``deflection`` is NaN or a shifted solve fails.
    """
    dw = np.asarray(deflection, float)
    idx = np.nonzero(np.isfinite(dw) & (dw > 0))[0]
    k = np.full(dw.shape, np.nan)
    if idx.size == 0:
        return k
    d = dw[idx]
    steps = np.concatenate([d * (1.0 + STIFFNESS_STEP), d * (1.0 - STIFFNESS_STEP)])
    both = cases.take(np.concatenate([idx, idx]))
    both = dataclasses.replace(both, load=np.full(steps.shape, np.nan), deflection=steps)
    f = solve_many(both, n_sections=n_sections, errors="flag")["vertical_force"]
    k[idx] = (f[: idx.size] - f[idx.size :]) / (2.0 * STIFFNESS_STEP * d)
    return k


def solve_sweep(cases: CaseTable, *, n_sections: int = N_SECTIONS) -> dict[str, np.ndarray]:
    """The full model for every case: :func:`tiremesh.solve_many` (``errors='flag'``)
    plus ``vertical_stiffness`` [N/mm] (:func:`vertical_stiffness`).

    Parameters
    ----------
    cases : CaseTable
        Load-searched cases.
    n_sections : int

    Returns
    -------
    dict of (m,) arrays
        The keys of :func:`tiremesh.solve_many` and ``vertical_stiffness``; failed
        cases have ``ok = False`` and NaN values.
    """
    out = solve_many(cases, n_sections=n_sections, errors="flag")
    dw = np.where(out["ok"], out["deflection"], np.nan)
    out["vertical_stiffness"] = vertical_stiffness(cases, dw, n_sections=n_sections)
    return out


def model_values(name: str, inputs: Mapping, results: Mapping) -> np.ndarray:
    """The full model's value of a quantity, from :func:`solve_sweep` results.

    Parameters
    ----------
    name : str
        One of :data:`QUANTITIES`, ``'area'`` or ``'tire_radius'``.
    inputs : mapping
        :func:`case_inputs` output.
    results : mapping
        :func:`solve_sweep` (or :func:`tiremesh.solve_many`) output.

    Returns
    -------
    (m,) float array [unit of the quantity]
        ``camber_thrust`` is the patch lateral force (equation 5-25 summed over the patch).
    """
    if name == "tire_radius":
        return inputs["tire_radius"]
    key = {"camber_thrust": "lateral_force"}.get(name, name)
    if key not in results:
        return np.full(inputs["load"].shape, np.nan)
    return np.asarray(results[key], float)


def in_domain(name: str, inputs: Mapping, results: Mapping, *, sinkage_max: float = SINKAGE_MAX):
    """Cases a relation covers: solved, finite, sinkage <= ``sinkage_max`` (the
    geometric ``tire_radius`` relation covers every case), nonzero camber for
    ``camber_thrust``.

    Parameters
    ----------
    name : str
    inputs, results : mapping
        :func:`case_inputs` and :func:`solve_sweep` outputs.
    sinkage_max : float [-]

    Returns
    -------
    (m,) bool array
    """
    if name == "tire_radius":
        return np.ones(inputs["load"].shape, bool)
    ok = np.asarray(results.get("ok", np.isfinite(results["sinkage"])), bool)
    with np.errstate(invalid="ignore"):
        mask = ok & np.isfinite(model_values(name, inputs, results))
        mask &= np.asarray(results["sinkage"]) <= sinkage_max
    if name == "camber_thrust":
        mask &= inputs["camber"] != 0
    return mask


def relative_errors(relation: Relation, cases, results, *, rows=None) -> np.ndarray:
    """``relation / model - 1`` on the cases of its domain (or on ``rows``).

    Parameters
    ----------
    relation : Relation
    cases : CaseTable or mapping
    results : mapping
        :func:`solve_sweep` output for ``cases``.
    rows : (m,) bool array, optional
        Cases to use (default: :func:`in_domain`).

    Returns
    -------
    (n,) float array [-]
        One per used case, in case order.
    """
    inputs = case_inputs(cases)
    if rows is None:
        rows = in_domain(relation.name, inputs, results)
    sub = {k: a[rows] for k, a in inputs.items()}
    model = model_values(relation.name, inputs, results)[rows]
    return evaluate_relation(relation, sub) / model - 1.0


def _domain(inputs: Mapping, groups: Mapping, results: Mapping, rows) -> tuple:
    vals = {
        "arc_length_mm": inputs["arc_length"],
        "rim_width_mm": inputs["rim_width"],
        "pressure_N_mm2": inputs["pressure"],
        "load_N": inputs["load"],
        "camber_rad": np.abs(inputs["camber"]),
        "bead_seat_diameter_mm": inputs["bead_seat_diameter"],
        "Pi": groups["Pi"],
        "beta": groups["beta"],
        "sinkage": np.asarray(results["sinkage"], float),
    }
    if not np.any(rows):
        return tuple((k, math.nan, math.nan) for k in vals)
    return tuple((k, float(np.min(a[rows])), float(np.max(a[rows]))) for k, a in vals.items())


def _error_stats(err: np.ndarray, zero: np.ndarray) -> tuple[float, float, float]:
    if err.size == 0:
        return math.nan, math.nan, math.nan
    a = np.abs(err)
    mz = float(np.max(a[zero])) if np.any(zero) else math.nan
    return float(np.max(a)), float(np.sqrt(np.mean(err**2))), mz


def _signed(x: float, digits: int = 4) -> str:
    return f"{'-' if x < 0 else '+'} {abs(x):.{digits}g}"


def _formula(name: str, form: str, c) -> str:
    """The relation as text with its coefficients (4 significant digits)."""
    if form == "identity":
        return AREA_IDENTITY
    if form == "polynomial":
        powers = ("", " x", " x^2", " x^3")
        poly = " ".join(_signed(x, 5) + t for x, t in zip(c[1:], powers[1:], strict=True))
        return f"r0 = s0 ({c[0]:.5g} {poly}), x = w / s0"
    if form == "power":
        groups = ("Pi", "beta", "cos(camber)")
        powers = " ".join(f"{g}^{x:.4g}" for g, x in zip(groups, c[1:], strict=True))
        return f"{name} = {math.exp(c[0]):.4g} {SCALES[name]} {powers}"
    terms = " ".join(f"{_signed(x)} {t}" for t, x in zip(FORMS[form][1:], c[1:], strict=True))
    return f"{name} = {SCALES[name]} exp({c[0]:.4g} {terms})"


def _fit_log(name, form, fit, test) -> Relation:
    """Least-squares fit of ``ln(q / scale)`` on ``fit``; errors on ``test``.
    ``fit`` and ``test`` are ``(inputs, groups, results, rows)``."""
    inputs, groups, results, rows = fit
    x = design_matrix(groups, form)[rows]
    scale = quantity_scale(name, inputs, groups)[rows]
    y = np.log(model_values(name, inputs, results)[rows] / scale)
    coef = np.linalg.lstsq(x, y, rcond=None)[0]
    return _relation(name, form, coef, fit, test)


def _relation(name, form, coef, fit, test) -> Relation:
    terms = FORMS.get(form, ("Fz/p",) if form == "identity" else ())
    coef = tuple(float(c) for c in coef)
    rel = Relation(
        name, form, UNITS[name], _formula(name, form, coef), terms, coef, (), *[math.nan] * 3, 0, 0
    )
    t_in, _, t_res, t_rows = test
    err = relative_errors(rel, t_in, t_res, rows=t_rows)
    mx, rms, mz = _error_stats(err, t_in["camber"][t_rows] == 0)
    return dataclasses.replace(
        rel,
        domain=_domain(fit[0], fit[1], fit[2], fit[3]),
        max_error=mx,
        rms_error=rms,
        max_error_zero_camber=mz,
        n_fit=int(np.count_nonzero(fit[3])),
        n_test=int(np.count_nonzero(t_rows)),
    )


def _fit_radius(fit, test) -> Relation:
    """``r0 / s0`` as a cubic in ``w / s0`` (the exact inverse of equation 5-6 is a root)."""
    inputs, _, _, rows = fit
    x = inputs["rim_width"][rows] / inputs["arc_length"][rows]
    coef = np.polynomial.polynomial.polyfit(
        x, inputs["tire_radius"][rows] / inputs["arc_length"][rows], 3
    )
    rel = _relation("tire_radius", "polynomial", coef, fit, test)
    return dataclasses.replace(rel, terms=("1", "x", "x^2", "x^3"))


def fit_relations(cases, results, *, test=None) -> list[Relation]:
    """Fit every relation to a sweep and measure it on held-out cases.

    Parameters
    ----------
    cases : CaseTable or sequence of LoadCase
        The sweep (load-searched cases; see :func:`sweep_cases`).
    results : mapping
        :func:`solve_sweep` output for ``cases`` (without ``vertical_stiffness``,
        as from :func:`tiremesh.solve_many`, the stiffness relations are left out).
    test : (cases, results), optional
        An independent held-out sweep. Default: the even rows of ``cases`` are
        fitted and the odd rows held out.

    Returns
    -------
    list of Relation
        ``area`` (identity), ``tire_radius`` (geometry), then each of
        :data:`QUANTITIES` in each of :data:`FORMS`.
    """
    if not isinstance(cases, CaseTable):
        cases = CaseTable.from_cases(list(cases))
    inputs = case_inputs(cases)
    m = inputs["load"].shape[0]
    if test is None:
        fit_rows, test_rows = np.arange(m) % 2 == 0, np.arange(m) % 2 == 1
        test_cases, test_results = cases, results
    else:
        test_cases, test_results = test
        if not isinstance(test_cases, CaseTable):
            test_cases = CaseTable.from_cases(list(test_cases))
        fit_rows, test_rows = np.ones(m, bool), np.ones(len(test_cases), bool)
    t_inputs = case_inputs(test_cases)
    groups, t_groups = dimensionless_groups(inputs), dimensionless_groups(t_inputs)
    out = []
    for name in ("area", "tire_radius", *QUANTITIES):  # a loop over quantities, not cases
        f_rows = fit_rows & in_domain(name, inputs, results)
        f = (inputs, groups, results, f_rows)
        t_rows = test_rows & in_domain(name, t_inputs, test_results)
        t = (t_inputs, t_groups, test_results, t_rows)
        if name == "area":
            out.append(_relation("area", "identity", (1.0,), f, t))
        elif name == "tire_radius":
            out.append(_fit_radius(f, t))
        elif np.count_nonzero(f[3]) > len(FORMS["refined"]) and np.any(t[3]):
            out += [_fit_log(name, form, f, t) for form in FORMS]
    return out


def _pct(x: float) -> str:
    """An error as text: percent (3 significant digits below 1 %, else 2 decimals), or
    scientific below 1e-4 (NaN: a dash)."""
    if not math.isfinite(x):
        return "-"
    if x < 1e-4:
        return f"{x:.1e}"
    return f"{100 * x:.3g} %" if x < 0.01 else f"{100 * x:.2f} %"


def error_rows(relations) -> list[dict]:
    """One table row per relation (for :func:`tiremesh.io.write_table`).

    Parameters
    ----------
    relations : list of Relation

    Returns
    -------
    list of dict
        ``quantity, form, unit, max_rel_error [-], rms_rel_error [-],
        max_rel_error_zero_camber [-], n_fit, n_test, formula``.
    """
    return [
        {
            "quantity": r.name,
            "form": r.form,
            "unit": r.unit,
            "max_rel_error": r.max_error,
            "rms_rel_error": r.rms_error,
            "max_rel_error_zero_camber": r.max_error_zero_camber,
            "n_fit": r.n_fit,
            "n_test": r.n_test,
            "formula": r.formula,
        }
        for r in relations
    ]


def coefficient_rows(relations) -> list[dict]:
    """The coefficients in long form (for :func:`tiremesh.io.write_table`).

    Parameters
    ----------
    relations : list of Relation

    Returns
    -------
    list of dict
        One row per relation and term: ``quantity, form, term, coefficient``.
    """
    return [
        {"quantity": r.name, "form": r.form, "term": t, "coefficient": c}
        for r in relations
        for t, c in zip(r.terms, r.coefficients, strict=True)
    ]


def outside_errors(relations, cases, results) -> list[dict]:
    """Errors of the fitted relations on held-out (odd) rows beyond :data:`SINKAGE_MAX`:
    how the relations degrade outside their domain.

    Parameters
    ----------
    relations : list of Relation
    cases : CaseTable
    results : mapping
        :func:`solve_sweep` output.

    Returns
    -------
    list of dict
        ``quantity, form, max_rel_error, rms_rel_error, n`` for each fitted relation.
    """
    inputs = case_inputs(cases)
    odd = np.arange(inputs["load"].shape[0]) % 2 == 1
    rows = []
    for r in relations:
        if r.form not in FORMS:
            continue
        everything = in_domain(r.name, inputs, results, sinkage_max=np.inf)
        beyond = odd & everything & ~in_domain(r.name, inputs, results)
        err = relative_errors(r, cases, results, rows=beyond)
        mx, rms, _ = _error_stats(err, np.zeros(err.shape, bool))
        rows.append(
            {
                "quantity": r.name,
                "form": r.form,
                "max_rel_error": mx,
                "rms_rel_error": rms,
                "n": int(err.size),
            }
        )
    return rows


def error_table_markdown(relations) -> str:
    """The Markdown error table of ``relations`` (held-out cases).

    Parameters
    ----------
    relations : list of Relation

    Returns
    -------
    str
        Columns: quantity, form, max and RMS relative error, max at zero camber,
        held-out cases.
    """
    lines = [
        "| quantity | form | max rel. error | RMS rel. error | max at zero camber | held-out cases |",
        "| --- | --- | ---: | ---: | ---: | ---: |",
    ]
    for r in relations:
        lines.append(
            f"| {r.name} | {r.form} | {_pct(r.max_error)} | {_pct(r.rms_error)} "
            f"| {_pct(r.max_error_zero_camber)} | {r.n_test:,} |"
        )
    return "\n".join(lines) + "\n"


def _domain_markdown(relations) -> str:
    ref = next(r for r in relations if r.name == "sinkage")
    lines = ["| input | min | max |", "| --- | ---: | ---: |"]
    lines += [f"| {k} | {lo:.4g} | {hi:.4g} |" for k, lo, hi in ref.domain]
    return "\n".join(lines) + "\n"


def relations_markdown(relations, *, summary: Mapping, outside=()) -> str:
    """The generated report: sweep summary, error table, formulas, domain and the
    errors beyond the domain.

    Parameters
    ----------
    relations : list of Relation
    summary : mapping
        Sweep facts printed as a list (``{"cases": 100000, ...}``).
    outside : list of dict
        :func:`outside_errors` rows.

    Returns
    -------
    str
    """
    parts = ["# Analytical relationships of the Rotta model (generated)\n"]
    parts.append("\n".join(f"- {k}: {val}" for k, val in summary.items()) + "\n")
    parts.append("## Errors against the full model (held-out cases)\n")
    parts.append(error_table_markdown(relations))
    parts.append("## Formulas\n")
    parts.append(
        "Pi = Fz / (p r0 sqrt(r0 R)), beta = w / r0, h = r0 + sqrt(r0^2 - w^2/4), "
        "R = D_bead / 2 + h.\n"
    )
    parts.append("| quantity | form | formula |\n| --- | --- | --- |")
    parts.append("\n".join(f"| {r.name} | {r.form} | `{r.formula}` |" for r in relations) + "\n")
    parts.append(f"## Domain (fitted cases, sinkage <= {SINKAGE_MAX})\n")
    parts.append(_domain_markdown(relations))
    if outside:
        parts.append(f"## Beyond the domain: held-out cases with sinkage > {SINKAGE_MAX}\n")
        parts.append("| quantity | form | max rel. error | RMS rel. error | cases |")
        parts.append("| --- | --- | ---: | ---: | ---: |")
        parts.append(
            "\n".join(
                f"| {o['quantity']} | {o['form']} | {_pct(o['max_rel_error'])} "
                f"| {_pct(o['rms_rel_error'])} | {o['n']:,} |"
                for o in outside
            )
            + "\n"
        )
    return "\n".join(parts)


def sweep_summary(cases, results) -> dict:
    """Facts of a sweep for the report.

    Parameters
    ----------
    cases : CaseTable
    results : mapping
        :func:`solve_sweep` output.

    Returns
    -------
    dict of str
        Case counts, failures by error type, cases beyond :data:`SINKAGE_MAX`,
        zero-camber cases, sections, stiffness method.
    """
    ok = np.asarray(results["ok"], bool)
    kinds: dict[str, int] = {}
    for msg in np.asarray(results["error"])[~ok]:  # failed cases only (a few)
        kinds[str(msg).split(":")[0]] = kinds.get(str(msg).split(":")[0], 0) + 1
    with np.errstate(invalid="ignore"):
        beyond = int(np.count_nonzero(ok & (np.asarray(results["sinkage"]) > SINKAGE_MAX)))
    camber = np.asarray(case_inputs(cases)["camber"])
    return {
        "cases": f"{ok.size:,} (even rows fitted, odd rows held out)",
        "solved": f"{int(ok.sum()):,}",
        "not solvable (model limits)": ", ".join(f"{k} {n}" for k, n in kinds.items()) or "none",
        f"solved with sinkage > {SINKAGE_MAX} (outside the domain)": f"{beyond:,}",
        "zero-camber cases": f"{int(np.count_nonzero(camber == 0)):,}",
        "sections per patch": N_SECTIONS,
        "stiffness": f"central difference, deflection step {STIFFNESS_STEP:g} (relative)",
    }


LABELS = {
    "sinkage": "sinkage (deflection / rim height) [-]",
    "length": "patch length [mm]",
    "width": "patch width [mm]",
    "vertical_stiffness": "vertical stiffness [N/mm]",
    "camber_thrust": "camber thrust (patch lateral force) [N]",
}


def _every(mask, n: int = 3000) -> np.ndarray:
    idx = np.nonzero(mask)[0]
    return idx[:: max(1, idx.size // n)]


def relation_figure(name: str, relations, cases, results, *, stem):
    """Model vs relation (left) and relative error vs model sinkage (right) for one
    quantity, both forms, held-out (odd) rows; rows beyond :data:`SINKAGE_MAX` in
    light colours on the right.

    Parameters
    ----------
    name : str
        One of :data:`QUANTITIES`.
    relations : list of Relation
    cases : CaseTable
    results : mapping
        :func:`solve_sweep` output.
    stem : str or PathLike
        Output path without suffix (PNG written).

    Returns
    -------
    list of Path
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .io import save_figure

    inputs = case_inputs(cases)
    odd = np.arange(inputs["load"].shape[0]) % 2 == 1
    inside = odd & in_domain(name, inputs, results)
    beyond = odd & in_domain(name, inputs, results, sinkage_max=np.inf) & ~inside
    model, sink = model_values(name, inputs, results), np.asarray(results["sinkage"])
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10, 4.2))
    for r, colour in zip((r for r in relations if r.name == name), ("0.55", "C0"), strict=False):
        for rows, alpha, tag in (
            (_every(inside), 0.5, ""),
            (_every(beyond, 800), 0.15, ", beyond"),
        ):
            val = evaluate_relation(r, {k: a[rows] for k, a in inputs.items()})
            kw = {"s": 3, "color": colour, "alpha": alpha, "lw": 0}
            if not tag:
                ax0.scatter(model[rows], val, label=f"{r.form}", **kw)
            ax1.scatter(sink[rows], 100 * (val / model[rows] - 1), label=r.form + tag, **kw)
    lim = [np.nanmin(model[inside]), np.nanmax(model[inside])]
    ax0.plot(lim, lim, "k-", lw=0.8)
    ax0.set(xlabel=f"full model: {LABELS[name]}", ylabel="relation", title=name.replace("_", " "))
    ax1.axvline(SINKAGE_MAX, color="k", lw=0.6, ls="--")
    ax1.set(xlabel="model sinkage [-]", ylabel="relation / model - 1 [%]", title="held-out error")
    for ax in (ax0, ax1):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, markerscale=3)
    fig.tight_layout()
    return save_figure(fig, stem, formats=(".png",), dpi=120)


def _json_ready(obj):
    """``obj`` with NaN/inf floats as None and numpy scalars as Python numbers."""
    if isinstance(obj, Mapping):
        return {str(k): _json_ready(x) for k, x in obj.items()}
    if isinstance(obj, list | tuple):
        return [_json_ready(x) for x in obj]
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def read_relations(path) -> list[Relation]:
    """The relations of a ``relations.json`` written by :func:`write_relations`.

    Parameters
    ----------
    path : str or PathLike

    Returns
    -------
    list of Relation
    """
    doc = json.loads(Path(path).read_text(encoding="utf-8"))
    out = []
    for d in doc["relations"]:
        d = {k: (math.nan if x is None else x) for k, x in d.items()}
        d["terms"], d["coefficients"] = tuple(d["terms"]), tuple(d["coefficients"])
        nan = lambda x: math.nan if x is None else float(x)
        d["domain"] = tuple((k, nan(lo), nan(hi)) for k, (lo, hi) in d["domain"].items())
        out.append(Relation(**d))
    return out


def write_relations(out_dir, *, n_cases: int = 100_000, seed: int = 0) -> list[Path]:
    """Sweep the model, fit the relations and write them with their errors.

    Parameters
    ----------
    out_dir : str or PathLike
        Folder (created if missing).
    n_cases : int
        Cases in the sweep (half fitted, half held out); >= 100,000 for the docs.
    seed : int
        Seed of the sweep (:func:`sweep_cases`).

    Returns
    -------
    list of Path
        ``relations.json`` (relations with coefficients, domain and errors),
        ``relations_coefficients.csv``, ``relations_errors.csv``, ``relations.md``
        (report with the error table) and one PNG figure per quantity.
    """
    from .io import write_table, write_text_atomic

    out = Path(out_dir)
    cases = sweep_cases(n_cases, seed=seed)
    results = solve_sweep(cases)
    rels = fit_relations(cases, results)
    outside = outside_errors(rels, cases, results)
    summary = {"seed": seed, **sweep_summary(cases, results)}
    doc = {"summary": summary, "relations": [r.as_dict() for r in rels], "beyond_domain": outside}
    text = json.dumps(_json_ready(doc), indent=1, allow_nan=False)
    paths = [
        write_text_atomic(out / "relations.json", text),
        write_table(coefficient_rows(rels), out / "relations_coefficients.csv"),
        write_table(error_rows(rels), out / "relations_errors.csv"),
        write_text_atomic(
            out / "relations.md", relations_markdown(rels, summary=summary, outside=outside)
        ),
    ]
    for name in QUANTITIES:
        if any(r.name == name for r in rels):
            paths += relation_figure(name, rels, cases, results, stem=out / f"relation_{name}")
    return paths


__all__ = [
    "AREA_IDENTITY",
    "DOMAIN",
    "FORMS",
    "QUANTITIES",
    "SINKAGE_MAX",
    "Relation",
    "case_inputs",
    "chord_length",
    "dimensionless_groups",
    "evaluate_relation",
    "fit_relations",
    "read_relations",
    "relative_errors",
    "solve_sweep",
    "sweep_cases",
    "tire_radius_from_arc_length",
    "vertical_stiffness",
    "write_relations",
]
