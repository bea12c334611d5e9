"""The model's counterpart of each measured quantity (:mod:`.validate_points`).

How each quantity is measured and how the model is asked for it:

* static lateral stiffness (Appendix B; 3.9): the rim displaced sideways against the
  drum. Model: ``lateral`` = 1 mm (the force is linear in it, 6.1.3), force / 1 mm.
* normalized cornering and camber stiffness (4.1.4, 4.1.5): slopes of the lateral force
  near zero angle, divided by the load. Model: secants at 1 deg slip or camber.
* mean pneumatic trail (4.1.8): aligning torque over cornering force. Model: at 1 deg
  slip, ``-aligning_moment / patch_lateral_force`` of :class:`tiremesh.LateralResult`.
* normalized self-aligning torque stiffness (Table 4-4): torque per degree over the
  load, in m/deg; negative when it turns the wheel toward its direction of travel
  (the sign Table 4-4 prints with a positive trail). Model: ``|aligning_moment|``
  per degree over the load, with that sign when the trail is positive.
* ink prints (4.1.1): the ink area, load / ink area and the ellipse fitted to the
  print. Model: the patch area, load / area and the ellipse fitted to the patch edge
  as in Figure 5-15 (:func:`contactpatch.appendix_ellipse`).
* point-load decay (3.11.4): :func:`.validate_relax.point_load_decay` of the unloaded tire.
* tire radius and true size (Table 3-2): the radius solved from the arc length
  (Table 5-2).

Every lateral case runs with the decay length of the taut beam
(:class:`.validate_relax.BeamRelaxation`) as its relaxation rate on all four sides,
no friction limit (stiffnesses are slopes at zero angle, where nothing slides), on the
2.5 m drum of TU Delft (device 3) or on a flat plate, and the load case's default
slip kinematics (recorded in the outputs).
"""

from __future__ import annotations

from collections.abc import Callable

import tiremesh as tm
from tiremesh.units import MPA_PER_BAR

from ..errors import ContactPatchError
from ..ruler.model import appendix_ellipse
from .validate_points import Condition
from .validate_relax import BeamRelaxation, point_load_decay

#: TU Delft drum diameter [mm] (section 3.9)
DRUM_DIAMETER = 2500.0
#: imposed lateral displacement [mm], slip and camber angles [deg] of the secants
LATERAL_MM, SLIP_DEG, CAMBER_DEG = 1.0, 1.0, 1.0
#: the lateral cases: kind -> LoadCase fields
KINDS = {
    "lateral": {"lateral_mm": LATERAL_MM},
    "slip": {"slip_deg": SLIP_DEG},
    "camber": {"camber_deg": CAMBER_DEG},
}


def surface_of(cond: Condition):
    """The model surface of a condition (drum unless the row says flat plate).

    Parameters
    ----------
    cond : Condition

    Returns
    -------
    tiremesh.Flat or tiremesh.Drum
        A flat plate for ``surface == 'flat'``, else the drum of diameter
        :data:`DRUM_DIAMETER` [mm].
    """
    return tm.Flat() if cond.surface == "flat" else tm.Drum(DRUM_DIAMETER)


class ModelRunner:
    """Solves the model for conditions, caching every solve.

    Parameters
    ----------
    relaxation : callable
        ``tire_id -> BeamRelaxation``: the decay-length model for a tire (the
        leave-one-tire-out modulus for tires in the fit).
    """

    def __init__(self, relaxation: Callable[[int], BeamRelaxation]):
        self.relaxation = relaxation
        self._cache: dict = {}

    def tire(self, cond: Condition) -> tm.TireGeometry:
        """The tire from the row's arc length and rim width (Table 3-2, Table 5-2).

        Parameters
        ----------
        cond : Condition
            One measured condition (tire, pressure, load, surface).

        Returns
        -------
        TireGeometry
        """
        key = ("tire", cond.arc_length, cond.rim_width, cond.tire)
        if key not in self._cache:
            self._cache[key] = tm.TireGeometry.from_arc_length(
                cond.arc_length, cond.rim_width, name=cond.tire
            )
        return self._cache[key]

    def rate(self, cond: Condition, relax: BeamRelaxation | None = None) -> float:
        """Relaxation rate of the condition's tire at its pressure.

        Parameters
        ----------
        cond : Condition
            One measured condition (tire, pressure, load, surface).
        relax : BeamRelaxation, optional
            Decay-length model; default: the runner's for this tire.

        Returns
        -------
        float [1/mm]
        """
        relax = relax or self.relaxation(cond.tire_id)
        return relax.rate(self.tire(cond), cond.pressure_bar * MPA_PER_BAR)

    def case(self, cond: Condition, kind: str = "", rate: float = 0.0) -> tm.LoadCase:
        """The load case of ``cond``.

        Parameters
        ----------
        cond : Condition
            One measured condition (tire, pressure, load, surface).
        kind : str, optional
            A key of :data:`KINDS` (the displacement applied), or '' for the patch.
        rate : float [1/mm], optional
            Relaxation rate.

        Returns
        -------
        tiremesh.LoadCase
        """
        return tm.LoadCase.from_units(
            self.tire(cond),
            pressure_bar=cond.pressure_bar,
            load_N=cond.load_N,
            surface=surface_of(cond),
            relaxation=rate,
            **KINDS.get(kind, {}),
        )

    def lateral(self, cond: Condition, kind: str, rate: float | None = None):
        """:func:`tiremesh.solve_lateral` of one kind (default rate: :meth:`rate`).

        The first solve of a condition and kind searches the deflection that carries
        the load; solves at other rates reuse that deflection (the patch does not
        depend on the rate, and the load search is most of the cost).

        Parameters
        ----------
        cond : Condition
            One measured condition (tire, pressure, load, surface).
        kind : str
            A key of :data:`KINDS`.
        rate : float [1/mm], optional
            Relaxation rate; default :meth:`rate`.

        Returns
        -------
        tiremesh.LateralResult
        """
        rate = self.rate(cond) if rate is None else float(rate)
        key = ("lateral", cond, kind, rate)
        if key not in self._cache:
            dkey = ("deflection", cond, kind)
            case = self.case(cond, kind, rate)
            if dkey in self._cache:
                case = case.replace(deflection=self._cache[dkey])
            result = tm.solve_lateral(case)
            self._cache.setdefault(dkey, result.patch.deflection)
            self._cache[key] = result
        return self._cache[key]

    def patch(self, cond: Condition):
        """The patch without lateral displacement (:func:`tiremesh.solve`).

        Parameters
        ----------
        cond : Condition
            One measured condition (tire, pressure, load, surface).

        Returns
        -------
        tiremesh.ContactPatch
        """
        key = ("patch", cond)
        if key not in self._cache:
            self._cache[key] = tm.solve(self.case(cond))
        return self._cache[key]

    def ellipse(self, cond: Condition):
        """Figure 5-15's ellipse of the patch (:func:`contactpatch.appendix_ellipse`).

        Parameters
        ----------
        cond : Condition
            One measured condition (tire, pressure, load, surface).

        Returns
        -------
        EllipseFit
            Raises :class:`ContactPatchError` when the fit fails.
        """
        key = ("ellipse", cond)
        if key not in self._cache:
            e = appendix_ellipse(self.patch(cond))
            if not e:
                raise ContactPatchError(f"ellipse fit of the model patch failed: {e.reason}")
            self._cache[key] = e
        return self._cache[key]

    def value(self, quantity: str, cond: Condition, rate: float | None = None) -> float:
        """The model's value of ``quantity`` at ``cond``.

        Parameters
        ----------
        quantity : str
            A key of :data:`EVALUATORS`.
        cond : Condition
            One measured condition.
        rate : float [1/mm], optional
            Relaxation rate; default :meth:`rate`.

        Returns
        -------
        float
            In the unit of :data:`.validate_points.QUANTITIES`.
        """
        return EVALUATORS[quantity](self, cond, rate)


def _stiffness(key: str, kind: str):
    def get(m: ModelRunner, c: Condition, rate) -> float:
        return tm.stiffnesses(m.lateral(c, kind, rate))[key]

    return get


def _lateral_stiffness(m: ModelRunner, c: Condition, rate) -> float:
    return m.lateral(c, "lateral", rate).lateral_force / LATERAL_MM


def _aligning(m: ModelRunner, c: Condition, rate) -> float:
    r = m.lateral(c, "slip", rate)
    sign = -1.0 if trail(r) > 0 else 1.0
    return sign * abs(r.aligning_moment) / (r.vertical_force * SLIP_DEG) / 1000.0


class Undefined(ContactPatchError):
    """The model's value exists but is not meaningful here (reason in the message)."""


#: a trail needs the patch to carry at least this share of the lateral force
PATCH_SHARE_MIN = 0.1


def trail(r) -> float:
    """Pneumatic trail of a slip result [mm], or :class:`Undefined` when the patch
    carries under :data:`PATCH_SHARE_MIN` of the lateral force: the model spreads the
    force beyond the patch over the patch in proportion to each section's own force, so
    ``-M / F_patch`` has no meaning when ``F_patch`` is near zero.

    Parameters
    ----------
    r : tiremesh.LateralResult
        A slip solve (:meth:`ModelRunner.lateral` of kind ``'slip'``).

    Returns
    -------
    float [mm]
        ``r.pneumatic_trail``.

    Raises
    ------
    Undefined
        When ``|patch_lateral_force| / |lateral_force|`` is below
        :data:`PATCH_SHARE_MIN` (or the lateral force is zero).
    """
    share = abs(r.patch_lateral_force) / abs(r.lateral_force) if r.lateral_force else 0.0
    if share < PATCH_SHARE_MIN:
        raise Undefined(
            f"trail undefined: the patch carries {share:.1%} of the lateral force "
            f"(< {PATCH_SHARE_MIN:.0%})"
        )
    return r.pneumatic_trail


def _decay(m: ModelRunner, c: Condition, rate) -> float:
    relax = m.relaxation(c.tire_id)
    return point_load_decay(*relax.parts(m.tire(c), c.pressure_bar * MPA_PER_BAR))


#: quantity -> (runner, condition, rate or None) -> model value
EVALUATORS = {
    "lateral_stiffness": _lateral_stiffness,
    "lateral_stiffness_extreme": lambda m, c, r: _lateral_stiffness(m, c, r) / c.load_N,
    "cornering_stiffness": _stiffness("norm_cornering_stiffness_1_deg", "slip"),
    "camber_stiffness": _stiffness("norm_camber_stiffness_1_deg", "camber"),
    "pneumatic_trail": lambda m, c, r: trail(m.lateral(c, "slip", r)),
    "aligning_stiffness": _aligning,
    "ink_area": lambda m, c, r: m.patch(c).area,
    "load_per_area": lambda m, c, r: c.load_N / m.patch(c).area,
    "ellipse_length": lambda m, c, r: m.ellipse(c).length,
    "ellipse_width": lambda m, c, r: m.ellipse(c).width,
    "ellipse_area": lambda m, c, r: m.ellipse(c).area,
    "decay_length": _decay,
    "tire_radius": lambda m, c, r: m.tire(c).tire_radius,
    "true_size": lambda m, c, r: 2.0 * m.tire(c).tire_radius,
}

#: quantities whose model value depends on the relaxation rate
RATE_DEPENDENT = (
    "lateral_stiffness",
    "lateral_stiffness_extreme",
    "cornering_stiffness",
    "camber_stiffness",
    "pneumatic_trail",
    "aligning_stiffness",
    "decay_length",
)


def slip_kinematics() -> str:
    """The slip kinematics every lateral case uses (the load case's default).

    Returns
    -------
    str
        ``slip_kinematics`` of a default :class:`tiremesh.LoadCase`.
    """
    return tm.LoadCase(tm.get_tire(1), pressure=0.4, load=100.0).slip_kinematics


__all__ = [
    "CAMBER_DEG",
    "DRUM_DIAMETER",
    "EVALUATORS",
    "KINDS",
    "LATERAL_MM",
    "PATCH_SHARE_MIN",
    "RATE_DEPENDENT",
    "SLIP_DEG",
    "ModelRunner",
    "Undefined",
    "slip_kinematics",
    "surface_of",
    "trail",
]
