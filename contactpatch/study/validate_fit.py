"""The one fitted parameter and its leave-one-tire-out check.

The casing modulus E of the taut beam (section 5.9.3.2; :mod:`.validate_relax`) is
fitted once across all tires to the static lateral stiffnesses of Appendix B (the
measurement that depends most directly on the deflection beyond the patch, 4.1.10
item 9), minimizing the squared log error. Every model value reported for a tire in
the fit uses E fitted *without* that tire (leave one tire out), so each is a
prediction; tires outside the fit use E from all fitted tires.

:func:`variants` sets the fitted beam beside the choices that need no fit (Appendix
C's fixed rate, no deflection beyond the patch, the taut string with either tension)
and beside the other single global parameter one could fit (one decay length for all
tires), each with its in-sample and leave-one-tire-out errors.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from tiremesh.beam import bending_inertia
from tiremesh.units import MPA_PER_BAR

from .validate_model import ModelRunner
from .validate_points import Condition, Point
from .validate_relax import (
    APPENDIX_RATE,
    FIT_LENGTHS,
    BeamRelaxation,
    FitCase,
    fit_length,
    fit_modulus,
    leave_one_tire_out,
    rate_of,
    tabulate_force,
)
from .validate_stats import ratio_stats

#: the quantity the parameter is fitted to
FIT_QUANTITY = "lateral_stiffness"


@dataclass
class RelaxationFit:
    """Fitted casing modulus and decay length, all tires and leave-one-tire-out.

    Attributes
    ----------
    modulus : float [N/mm^2]
        E fitted to every tire (t = :data:`.validate_relax.THICKNESS_MM`).
    loto_modulus : dict
        Tire id -> E fitted without that tire.
    length : float [mm]
        The single decay length (constant rate) fitted to every tire (a variant).
    loto_length : dict
        Tire id -> that length fitted without the tire.
    cases : list of FitCase
    """

    modulus: float
    loto_modulus: dict
    length: float
    loto_length: dict
    cases: list = field(repr=False)

    def modulus_for(self, tire_id: int) -> float:
        """E for a tire: fitted without it if it is in the fit, else fitted to all;
        0 (the taut string) where no other tire was there to fit E to.

        Parameters
        ----------
        tire_id : int

        Returns
        -------
        float [N/mm^2]
        """
        e = self.loto_modulus.get(tire_id, self.modulus)
        return 0.0 if math.isnan(e) else e

    def relaxation_for(self, tire_id: int) -> BeamRelaxation:
        """The beam for a tire (:meth:`modulus_for`).

        Parameters
        ----------
        tire_id : int

        Returns
        -------
        BeamRelaxation
        """
        return BeamRelaxation(self.modulus_for(tire_id))


def fit_points(points: list[Point]) -> list[Point]:
    """The compared points the parameter is fitted to.

    Parameters
    ----------
    points : list of Point

    Returns
    -------
    list of Point
        The points of :data:`FIT_QUANTITY` with status ``compared``, in input order.
    """
    return [p for p in points if p.quantity == FIT_QUANTITY and p.status == "compared"]


def fit_case(runner: ModelRunner, p: Point) -> FitCase:
    """The :class:`FitCase` of one measured lateral stiffness (model tabulated over
    decay lengths with exact solves).

    Parameters
    ----------
    runner : ModelRunner
        Any runner (only its tires and its solves at given rates are used).
    p : Point
        A compared point of :data:`FIT_QUANTITY`.

    Returns
    -------
    FitCase
        The foundation stiffness [N/mm^2] and tension [N] (equation 5-32) at the
        point's pressure, the area moment [mm^4] at the default thickness, the model's
        lateral stiffness [N/mm] at each of :data:`.validate_relax.FIT_LENGTHS` and
        the measured value [N/mm].
    """
    tire = runner.tire(p.condition)
    k, T, _ = BeamRelaxation().parts(tire, p.condition.pressure_bar * MPA_PER_BAR)
    values = tabulate_force(lambda rate: runner.value(FIT_QUANTITY, p.condition, rate))
    inertia = float(bending_inertia(tire.tire_radius, BeamRelaxation().thickness))
    return FitCase(p.condition.tire_id, k, T, inertia, FIT_LENGTHS, values, p.measured)


def fit_relaxation(runner: ModelRunner, points: list[Point]) -> RelaxationFit:
    """Fit E (and, as a variant, one decay length) with leave-one-tire-out refits.

    Parameters
    ----------
    runner : ModelRunner
        Any runner (only its solves at given rates are used).
    points : list of Point

    Returns
    -------
    RelaxationFit
    """
    cases = [fit_case(runner, p) for p in fit_points(points)]
    return RelaxationFit(
        modulus=fit_modulus(cases),
        loto_modulus=leave_one_tire_out(cases, fit_modulus),
        length=fit_length(cases),
        loto_length=leave_one_tire_out(cases, fit_length),
        cases=cases,
    )


def _or(x: float, default: float) -> float:
    return default if math.isnan(x) else x


def _variant(name, params, fitted, ratios, note="") -> dict:
    row = {"variant": name, "parameters": params, "fitted_parameters": fitted, "note": note}
    row.update(ratio_stats(ratios))
    return row


def variants(runner: ModelRunner, points: list[Point], fit: RelaxationFit) -> list[dict]:
    """Errors of the lateral stiffness under each way of setting the decay length.

    Parameters
    ----------
    runner : ModelRunner
    points : list of Point
        The fit points among them are used (:func:`fit_points`).
    fit : RelaxationFit

    Returns
    -------
    list of dict
        ``variant``, ``parameters``, ``fitted_parameters`` (0 or 1), ``note`` and
        :func:`.validate_stats.ratio_stats` of model / measured over the fit points;
        fitted variants appear twice, in sample and leave-one-tire-out.
    """
    pts = fit_points(points)
    rel = lambda c, relax: relax.rate(runner.tire(c), c.pressure_bar * MPA_PER_BAR)
    choices: list[tuple[str, str, int, Callable[[Condition, int], float], str]] = [
        (
            "Appendix C rate",
            f"i = {APPENDIX_RATE} per mm for every tire (5.8)",
            0,
            lambda c, t: APPENDIX_RATE,
            "",
        ),
        ("no deflection beyond the patch", "i = 0", 0, lambda c, t: 0.0, "the plain patch"),
        (
            "taut string, T = tiremesh.beam.tension_area (equation 5-32)",
            "EI = 0, T = p pi r^2",
            0,
            lambda c, t: rel(c, BeamRelaxation(0.0)),
            "",
        ),
        (
            "taut string, T = tiremesh.beam.tension_hoop (equation 5-33)",
            "EI = 0, T = p (R + 2 r)",
            0,
            lambda c, t: rel(c, BeamRelaxation(0.0, tension="hoop")),
            "",
        ),
        (
            "taut beam, E fitted (in sample)",
            f"E = {fit.modulus:.4g} N/mm²",
            1,
            lambda c, t: rel(c, BeamRelaxation(_or(fit.modulus, 0.0))),
            "fitted to these points",
        ),
        (
            "taut beam, E fitted (leave one tire out)",
            "E refitted without each tire",
            1,
            lambda c, t: rel(c, fit.relaxation_for(t)),
            "the validation's choice",
        ),
        (
            "one decay length (in sample)",
            f"l = {fit.length:.4g} mm",
            1,
            lambda c, t: rate_of(_or(fit.length, 0.0)),
            "fitted to these points",
        ),
        (
            "one decay length (leave one tire out)",
            "l refitted without each tire",
            1,
            lambda c, t: rate_of(_or(fit.loto_length[t], 0.0)),
            "no decay where no other tire",
        ),
    ]
    out = []
    for name, params, n_fit, rate, note in choices:
        ratios = [
            runner.value(FIT_QUANTITY, p.condition, rate(p.condition, p.condition.tire_id))
            / p.measured
            for p in pts
        ]
        out.append(_variant(name, params, n_fit, ratios, note))
    return out


#: the rolling decay length measured in 4.1.9.1, in patch lengths ("~3 times")
ROLLING_DECAY_PATCHES = 3.0


def cornering_variants(runner: ModelRunner, points: list[Point]) -> list[dict]:
    """The cornering stiffness under three decay lengths: the taut beam's (the reported
    values), Appendix C's 0.993 per mm (5.8) and the rolling decay measured in 4.1.9.1
    (about 3 patch lengths; the model's ellipse length). None is fitted. (The trail,
    ``-aligning_moment / patch_lateral_force``, does not depend on the decay length.)

    Parameters
    ----------
    runner : ModelRunner
        Runner with the fitted decay length (its default rate is the taut beam's).
    points : list of Point
        The compared cornering-stiffness points are used.

    Returns
    -------
    list of dict
        ``variant``, ``quantity`` and :func:`.validate_stats.ratio_stats`.
    """
    rolling = lambda c: rate_of(ROLLING_DECAY_PATCHES * runner.value("ellipse_length", c))
    choices = [
        ("taut beam (reported)", lambda c: None),
        (f"Appendix C rate {APPENDIX_RATE} per mm (143 mm)", lambda c: APPENDIX_RATE),
        (f"measured rolling decay, {ROLLING_DECAY_PATCHES:g} patch lengths (4.1.9.1)", rolling),
    ]
    q = "cornering_stiffness"
    pts = [p for p in points if p.quantity == q and p.status == "compared"]
    out = []
    for name, rate in choices:
        ratios = [runner.value(q, p.condition, rate(p.condition)) / p.measured for p in pts]
        out.append({"variant": name, "quantity": q, **ratio_stats(ratios)})
    return out


#: the mean trail over the patch length, all tires and configurations (4.1.8) [%]
MEASURED_TRAIL_PCT = 12.76


def trail_kinematics(runner: ModelRunner, points: list[Point]) -> list[dict]:
    """The pneumatic trail (4.1.8) under each slip kinematics of the load case: the
    tread anchored at the leading edge (the default), turned about the centre
    (Appendix C) and displaced ahead of the patch along the relaxation (Figure 4-15,
    5.7: the dissertation's measured kinematics). None is fitted; the decay length is
    the taut beam's.

    Parameters
    ----------
    runner : ModelRunner
        Runner with the fitted decay length.
    points : list of Point
        The compared pneumatic-trail points are used.

    Returns
    -------
    list of dict
        Per kinematics: ``variant``, ``quantity`` (``pneumatic_trail``),
        :func:`.validate_stats.ratio_stats` of model / measured trail,
        ``trail_pct_of_length`` (median model trail over patch length [%], measured
        mean 12.76 %) and ``undefined`` (cases where the patch carries too little of
        the force for a trail, :func:`.validate_model.trail`).
    """
    import tiremesh as tm
    from tiremesh.case import SLIP_KINEMATICS

    from .validate_model import Undefined, trail

    pts = [p for p in points if p.quantity == "pneumatic_trail" and p.status == "compared"]
    out = []
    for kin in SLIP_KINEMATICS:
        ratios, pct, undefined = [], [], 0
        for p in pts:
            case = runner.case(p.condition, "slip", runner.rate(p.condition))
            r = tm.solve_lateral(case.replace(slip_kinematics=kin))
            try:
                t = trail(r)
            except Undefined:
                undefined += 1
                continue
            ratios.append(t / p.measured)
            pct.append(100.0 * t / r.patch.length)
        med = float(np.median(pct)) if pct else math.nan
        row = {"variant": kin, "quantity": "pneumatic_trail", **ratio_stats(ratios)}
        out.append({**row, "trail_pct_of_length": med, "undefined": undefined})
    return out


def loto_table(points: list[Point], fit: RelaxationFit) -> list[dict]:
    """Per fitted tire: E and decay length fitted without it, and its points' ratios
    under the leave-one-tire-out E (the reported model values).

    Parameters
    ----------
    points : list of Point
        With ``model`` set (:func:`.validate.evaluate_points`).
    fit : RelaxationFit

    Returns
    -------
    list of dict
        Per tire id in the fit, in order: ``tire_id``, ``tire``, ``n`` (its fit
        points), ``modulus_without_tire`` and ``modulus_used`` [N/mm^2],
        ``length_without_tire`` [mm], ``ratios`` (model / measured, as text) and
        ``rms_log_error`` (NaN without points).
    """
    out = []
    for tid in sorted(fit.loto_modulus):
        pts = [p for p in fit_points(points) if p.condition.tire_id == tid]
        ratios = [p.ratio for p in pts]
        out.append(
            {
                "tire_id": tid,
                "tire": pts[0].condition.tire if pts else "",
                "n": len(pts),
                "modulus_without_tire": fit.loto_modulus[tid],
                "modulus_used": fit.modulus_for(tid),
                "length_without_tire": fit.loto_length[tid],
                "ratios": " ".join(f"{r:.3f}" for r in ratios),
                "rms_log_error": math.sqrt(sum(math.log(r) ** 2 for r in ratios) / len(ratios))
                if ratios
                else math.nan,
            }
        )
    return out


def error_curve(fit: RelaxationFit, n: int = 121) -> dict:
    """RMS log error of the fit points vs E (from the tabulated model), for the figure.

    Parameters
    ----------
    fit : RelaxationFit
        Its ``cases`` give the tabulated model.
    n : int
        Number of log-spaced moduli from 0.01 N/mm^2 (E = 0 is added in front).

    Returns
    -------
    dict
        ``modulus`` [N/mm^2] (E = 0, then log-spaced to
        :data:`.validate_relax.MODULUS_MAX`; ``n + 1`` values), ``rms_log_error`` at
        each, ``fitted`` and ``loto`` (sorted E without each tire) [N/mm^2].
    """
    from .validate_relax import MODULUS_MAX

    grid = np.concatenate([[0.0], np.geomspace(1e-2, MODULUS_MAX, n)])
    err = sum((np.log(c.model(grid)) - math.log(c.measured)) ** 2 for c in fit.cases)
    return {
        "modulus": grid.tolist(),
        "rms_log_error": np.sqrt(err / len(fit.cases)).tolist(),
        "fitted": fit.modulus,
        "loto": sorted(fit.loto_modulus.values()),
    }


__all__ = [
    "FIT_QUANTITY",
    "ROLLING_DECAY_PATCHES",
    "RelaxationFit",
    "cornering_variants",
    "error_curve",
    "fit_case",
    "fit_points",
    "fit_relaxation",
    "loto_table",
    "trail_kinematics",
    "variants",
]
