"""A load case: everything one solve of the Rotta model needs, as one validated value.

:class:`LoadCase` is the input of :func:`tiremesh.solve`, :func:`tiremesh.solve_lateral`,
meshes, renders, sweeps, pairing with prints and the command line. A batch of
cases is a :class:`CaseTable` (columns = fields, numpy arrays) that the vectorized
solver turns into arrays once.

Units inside: mm, N, N/mm^2, rad. :meth:`LoadCase.from_units` converts from the
unit-carrying names used at the edges (``pressure_bar``, ``camber_deg``...).

Slip kinematics (one definition for :func:`solve` and :func:`solve_lateral`):

``'leading'`` (default)
    The tread enters the patch undisplaced at the leading edge and the rim moves
    sideways at ``tan(slip)`` per mm rolled (brush-model kinematics):
    ``dh = lateral + (x - x_lead) tan(slip)``. Gives a cornering force and a positive
    pneumatic trail.
``'relaxation'``
    Stretched-string kinematics (Figure 4-15, sections 5.7, 5.8): the carcass ahead of
    the leading edge is already displaced, decaying as the relaxation beyond the patch
    (decay length ``l = 1 / (1 - i_lead)``, equation 5-29); continuity of the slope at
    the leading edge puts the undisplaced point ``l`` ahead of it:
    ``dh = lateral + (x - x_lead - l) tan(slip)``.
``'centre'``
    Appendix C: the patch centre line turns about the patch centre,
    ``dh = lateral + x tan(slip)``; a pure slip angle gives antisymmetric
    displacements and almost no net force.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from . import validate as v
from .errors import InvalidParameter
from .footprint import Footprint, parse_footprint
from .geometry import TireGeometry
from .surface import Flat, Surface, parse_surface
from .units import MPA_PER_BAR

SLIP_KINEMATICS = ("leading", "centre", "relaxation")
FRICTION_MODELS = ("coulomb", "appendix")
FORCE_CONVENTIONS = ("ground", "appendix")
MAX_SECTIONS = 20001


def one_of(names) -> str:
    """``"'a', 'b' or 'c'"``: the allowed values of an option, for error messages.

    Parameters
    ----------
    names : sequence of str

    Returns
    -------
    str
    """
    quoted = [repr(n) for n in names]
    return quoted[0] if len(quoted) == 1 else ", ".join(quoted[:-1]) + " or " + quoted[-1]


@dataclass(frozen=True)
class Relaxation:
    """Relaxation rates of Appendix C, per mm along the wheel (section 5.8).

    A displacement beyond the patch decays as ``exp(-lambda s)`` with the decay rate
    ``lambda = 1 - i`` of equation 5-28 and the decay length ``1 / lambda`` of
    equation 5-29 (:meth:`decay_length`).

    Attributes
    ----------
    lead_out : float [1/mm]
        Beyond the leading patch end (before the tread touches the ground).
    trail_out : float [1/mm]
        Beyond the trailing end (after it leaves the ground).
    lead_in, trail_in : float [1/mm]
        Sliding inside the front / rear half of the patch.

    All in [0, 1); 0 switches the deflection beyond the patch off.
    """

    lead_out: float = 0.993
    trail_out: float = 0.993
    lead_in: float = 0.993
    trail_in: float = 0.993

    def __post_init__(self) -> None:
        for name in ("lead_out", "trail_out", "lead_in", "trail_in"):
            val = getattr(self, name)
            if not (isinstance(val, int | float) and 0.0 <= val < 1.0):
                raise InvalidParameter(
                    f"relaxation.{name}", val, "[0, 1) per mm (0.9 .. 0.999 typical)"
                )

    @staticmethod
    def decay_length(rate: float) -> float:
        """``1 / (1 - i)`` [mm], the distance over which a displacement falls to 1/e
        (equation 5-29 with ``lambda = 1 - i``, equation 5-28).

        Parameters
        ----------
        rate : float [1/mm]
            A relaxation rate ``i`` in [0, 1).

        Returns
        -------
        float [mm]
        """
        return 1.0 / (1.0 - rate)  # Eq. 5-29

    @classmethod
    def uniform(cls, rate: float) -> Relaxation:
        """All four rates equal to ``rate``.

        Parameters
        ----------
        rate : float [1/mm]
            In [0, 1); 0 switches the deflection beyond the patch off.

        Returns
        -------
        Relaxation
        """
        return cls(rate, rate, rate, rate)


def slip_anchor(kinematics: str, relaxation: Relaxation) -> float:
    """Distance ahead of the leading edge [mm] where a slipping tread is undisplaced:
    0 for ``'leading'``, the leading decay length for ``'relaxation'``, NaN for
    ``'centre'`` (no anchor: the centre line turns about the patch centre).

    Parameters
    ----------
    kinematics : str
    relaxation : Relaxation

    Returns
    -------
    float [mm]
    """
    if kinematics == "centre":
        return math.nan
    if kinematics == "relaxation" and relaxation.lead_out > 0:
        return Relaxation.decay_length(relaxation.lead_out)
    return 0.0


def _relaxation(value) -> Relaxation:
    if isinstance(value, Relaxation):
        return value
    if isinstance(value, int | float) and not isinstance(value, bool):
        return Relaxation.uniform(float(value))
    raise InvalidParameter("relaxation", value, "a Relaxation or a rate in [0, 1) per mm")


@dataclass(frozen=True)
class LoadCase:
    """One load case of the Rotta model, validated at construction.

    Parameters
    ----------
    tire : TireGeometry
    pressure : float [N/mm^2]
        Inflation pressure, > 0 (0.4 N/mm^2 = 4 bar).
    load : float [N], optional
        Vertical load to carry; exactly one of ``load`` and ``deflection``.
    deflection : float [mm], optional
        Wheel displacement toward the surface in the wheel plane (``delta_w``).
    camber : float [rad]
        Positive leans the wheel top toward ``+y``; ``|camber| < pi/2``.
    slip : float [rad]
        Slip angle, ``|slip| < pi/2``; see ``slip_kinematics``.
    lateral : float [mm]
        Imposed lateral displacement of the patch relative to the rim (``+y``).
    surface : Surface
        :class:`Flat`, :class:`Drum`, :class:`Disk` or any :class:`Surface`; a string
        such as ``"drum:2500"`` is parsed.
    n_sections : int
        Sections between the exact patch ends (Clenshaw-Curtis nodes), 9 .. 20001.
    relaxation : Relaxation or float
        Relaxation rates beyond the patch and of sliding (equation 5-28), used by
        :func:`solve_lateral`; a float sets all four.
    friction : float
        Friction coefficient, >= 0 (``inf``: no sliding), used by :func:`solve_lateral`.
    slip_kinematics : {'leading', 'relaxation', 'centre'}
        How a slip angle displaces the tread (module docstring).
    n_beyond : int
        Sections beyond each patch end in :func:`solve_lateral`, 9 .. 20001.
    force_convention : {'ground', 'appendix'}
        Length element of the lateral-force integrals (equation 5-25). ``'ground'``
        (default): the true ground length of each slice (the path of the contact
        segment's midpoint on the surface) in the patch, and arc length along the
        carcass beyond it, to where the displacement has decayed. ``'appendix'``:
        Appendix C's ``dy`` = ``d[(R - dv) sin phi]`` in the patch and
        ``R d(sin phi)`` beyond it, up to its last slice angle of 15 degrees
        (``docs/model.md``: -1.8 % camber thrust at 45 degrees for ``'ground'``).
    friction_model : {'coulomb', 'appendix'}
        ``'coulomb'``: a sliding section's ground reaction is exactly ``mu dN``, so
        ``|Fy| <= mu Fz`` always; ``'appendix'``: Appendix C's iteration, where
        sliding sections keep the force of their relaxed displacement
        (:mod:`tiremesh.lateral`).
    footprint : Footprint or str
        What :attr:`ContactPatch.footprint` reports: ``'rotta'`` (default, the exact
        pointed patch) or ``'rounded[:SPREAD_MM:THRESHOLD]'``, the ink print's rounded
        ends (:mod:`tiremesh.footprint`, beyond the dissertation, 7.3.1).

    Examples
    --------
    >>> import tiremesh as tm
    >>> case = tm.LoadCase(tm.get_tire(1), pressure=0.4, load=400.0)
    >>> case.replace(camber=0.1).camber
    0.1
    """

    tire: TireGeometry
    pressure: float
    load: float | None = None
    deflection: float | None = None
    camber: float = 0.0
    slip: float = 0.0
    lateral: float = 0.0
    surface: Surface = field(default_factory=Flat)
    n_sections: int = 201
    relaxation: Relaxation = field(default_factory=Relaxation)
    friction: float = math.inf
    slip_kinematics: str = "leading"
    n_beyond: int = 129
    friction_model: str = "coulomb"
    force_convention: str = "ground"
    footprint: Footprint = field(default_factory=Footprint)

    def __post_init__(self) -> None:
        if not isinstance(self.tire, TireGeometry):
            raise InvalidParameter("tire", self.tire, "a TireGeometry (tiremesh.get_tire(...))")
        set_ = lambda name, val: object.__setattr__(self, name, val)
        set_("pressure", _scalar("pressure", self.pressure, v.positive, unit="N/mm^2"))
        if (self.load is None) == (self.deflection is None):
            raise InvalidParameter(
                "load/deflection", (self.load, self.deflection), "exactly one of the two"
            )
        if self.load is not None:
            set_("load", _scalar("load", self.load, v.positive, unit="N"))
        else:
            set_("deflection", _scalar("deflection", self.deflection, v.positive, unit="mm"))
        half = math.pi / 2
        set_("camber", _scalar("camber", self.camber, v.in_range, -half, half, unit="rad"))
        set_("slip", _scalar("slip", self.slip, v.in_range, -half, half, unit="rad"))
        set_("lateral", _scalar("lateral", self.lateral, v.finite, unit="mm"))
        set_("surface", parse_surface(self.surface))
        set_("n_sections", v.integer("n_sections", self.n_sections, 9, MAX_SECTIONS))
        set_("n_beyond", v.integer("n_beyond", self.n_beyond, 9, MAX_SECTIONS))
        set_("relaxation", _relaxation(self.relaxation))
        mu = _friction(self.friction)
        if math.isnan(mu) or mu < 0:
            raise InvalidParameter("friction", self.friction, ">= 0 (inf for no sliding)")
        set_("friction", mu)
        if self.slip_kinematics not in SLIP_KINEMATICS:
            raise InvalidParameter(
                "slip_kinematics", self.slip_kinematics, one_of(SLIP_KINEMATICS)
            )
        if self.force_convention not in FORCE_CONVENTIONS:
            raise InvalidParameter(
                "force_convention", self.force_convention, one_of(FORCE_CONVENTIONS)
            )
        if self.friction_model not in FRICTION_MODELS:
            raise InvalidParameter("friction_model", self.friction_model, one_of(FRICTION_MODELS))
        set_("footprint", parse_footprint(self.footprint))

    def replace(self, **changes) -> LoadCase:
        """A copy with ``changes`` applied (validated again). Giving ``load`` clears
        ``deflection`` and vice versa.

        Parameters
        ----------
        **changes
            Field values by name (units as the fields: mm, N, N/mm^2, rad).

        Returns
        -------
        LoadCase
            The copy; ``self`` is unchanged (frozen).

        Raises
        ------
        InvalidParameter
            A changed value is out of range (the error names the field).

        Examples
        --------
        >>> import tiremesh as tm
        >>> c = tm.LoadCase(tm.get_tire(1), pressure=0.4, load=400.0)
        >>> c.replace(deflection=5.0).load is None
        True
        """
        if "load" in changes and "deflection" not in changes:
            changes["deflection"] = None
        if "deflection" in changes and "load" not in changes:
            changes["load"] = None
        return dataclasses.replace(self, **changes)

    @classmethod
    def from_units(
        cls,
        tire: TireGeometry,
        *,
        pressure_bar: float,
        load_N: float | None = None,
        deflection_mm: float | None = None,
        camber_deg: float = 0.0,
        slip_deg: float = 0.0,
        lateral_mm: float = 0.0,
        surface: Surface | str = "flat",
        **options,
    ) -> LoadCase:
        """A load case from unit-carrying values (bar, N, mm, degrees); ``options``
        are the other fields (``n_sections``, ``friction``, ``relaxation``...).

        Parameters
        ----------
        tire : TireGeometry
        pressure_bar : float [bar]
        load_N : float [N], optional
        deflection_mm : float [mm], optional
            Exactly one of ``load_N`` and ``deflection_mm``.
        camber_deg, slip_deg : float [deg]
        lateral_mm : float [mm]
        surface : Surface or str
            A surface or its CLI form (``flat | drum:D | disk:D[:toward|away]``).
        **options
            Further :class:`LoadCase` fields by name.

        Returns
        -------
        LoadCase
            In the model's units (N/mm^2, rad).
        """
        return cls(
            tire,
            pressure=_scalar("pressure_bar", pressure_bar, v.positive, unit="bar") * MPA_PER_BAR,
            load=load_N,
            deflection=deflection_mm,
            camber=math.radians(_scalar("camber_deg", camber_deg, v.finite, unit="deg")),
            slip=math.radians(_scalar("slip_deg", slip_deg, v.finite, unit="deg")),
            lateral=lateral_mm,
            surface=surface,
            **options,
        )

    def describe(self) -> dict[str, float | str]:
        """The case with unit-carrying names (for tables, titles, file metadata).

        Returns
        -------
        dict of str to float or str
            The tire's :meth:`TireGeometry.describe` plus ``pressure_bar``, ``load_N``,
            ``deflection_mm`` (NaN where not given), ``camber_deg``, ``slip_deg``,
            ``lateral_mm``, ``surface`` (its CLI form), ``friction``,
            ``slip_kinematics`` and ``force_convention``.
        """
        return {
            **self.tire.describe(),
            "pressure_bar": self.pressure / MPA_PER_BAR,
            "load_N": math.nan if self.load is None else self.load,
            "deflection_mm": math.nan if self.deflection is None else self.deflection,
            "camber_deg": math.degrees(self.camber),
            "slip_deg": math.degrees(self.slip),
            "lateral_mm": self.lateral,
            "surface": self.surface.spec,
            "friction": self.friction,
            "slip_kinematics": self.slip_kinematics,
            "force_convention": self.force_convention,
        }


def _friction(value) -> float:
    if isinstance(value, bool) or np.ndim(value) != 0:
        raise InvalidParameter("friction", value, "a scalar >= 0 (inf for no sliding)")
    try:
        return float(value)
    except (TypeError, ValueError) as exc:
        raise InvalidParameter("friction", value, "a number >= 0 (inf for no sliding)") from exc


def _scalar(name, value, check, *args, **kw) -> float:
    """A validated float scalar: plain Python for Python and numpy numbers (a load case
    is built per sweep row, so this is hot), the shared array validator otherwise."""
    if isinstance(value, int | float | np.floating | np.integer) and not isinstance(value, bool):
        x = float(value)
        if check is v.positive and math.isfinite(x) and x > 0:
            return x
        if check is v.finite and math.isfinite(x):
            return x
        if check is v.in_range and args[0] < x < args[1]:
            return x
    if np.ndim(value) != 0:
        raise InvalidParameter(name, value, "a scalar (use a CaseTable for many cases)")
    return float(check(name, value, *args, **kw))


@dataclass(frozen=True)
class CaseTable:
    """Many load cases as columns (numpy arrays of one length ``m``).

    Built from a list of :class:`LoadCase` (:meth:`from_cases`) or from broadcastable
    columns (:meth:`from_columns`); the vectorized solver reads its arrays once.

    Attributes
    ----------
    tire_radius, rim_width, bead_seat_diameter : (m,) float [mm]
    pressure : (m,) float [N/mm^2]
    load : (m,) float [N]
        NaN where the case gives a deflection.
    deflection : (m,) float [mm]
        NaN where the case gives a load.
    camber, slip : (m,) float [rad]
    lateral : (m,) float [mm]
    surface : tuple of Surface, length m
    slip_kinematics : tuple of str, length m
    force_convention : tuple of str, length m
    slip_anchor : (m,) float [mm]
        Distance ahead of the leading edge where a slipping tread is undisplaced
        (:func:`slip_anchor`; NaN: the appendix's centre-line turn).
    """

    tire_radius: np.ndarray
    rim_width: np.ndarray
    bead_seat_diameter: np.ndarray
    pressure: np.ndarray
    load: np.ndarray
    deflection: np.ndarray
    camber: np.ndarray
    slip: np.ndarray
    lateral: np.ndarray
    surface: tuple
    slip_kinematics: tuple
    force_convention: tuple = ()
    slip_anchor: np.ndarray | None = None

    def __len__(self) -> int:
        return self.pressure.shape[0]

    @classmethod
    def from_cases(cls, cases: Sequence[LoadCase]) -> CaseTable:
        """Stack validated load cases into columns.

        Parameters
        ----------
        cases : sequence of LoadCase, length m

        Returns
        -------
        CaseTable
            ``m`` rows.

        Raises
        ------
        InvalidParameter
            An item is not a :class:`LoadCase` (named ``cases[i]``).
        """
        for i, c in enumerate(cases):
            if not isinstance(c, LoadCase):
                raise InvalidParameter(f"cases[{i}]", c, "a LoadCase")
        col = lambda f: np.array([f(c) for c in cases], float)
        nan = math.nan
        return cls(
            tire_radius=col(lambda c: c.tire.tire_radius),
            rim_width=col(lambda c: c.tire.rim_width),
            bead_seat_diameter=col(lambda c: c.tire.bead_seat_diameter),
            pressure=col(lambda c: c.pressure),
            load=col(lambda c: nan if c.load is None else c.load),
            deflection=col(lambda c: nan if c.deflection is None else c.deflection),
            camber=col(lambda c: c.camber),
            slip=col(lambda c: c.slip),
            lateral=col(lambda c: c.lateral),
            surface=tuple(c.surface for c in cases),
            slip_kinematics=tuple(c.slip_kinematics for c in cases),
            force_convention=tuple(c.force_convention for c in cases),
            slip_anchor=col(lambda c: slip_anchor(c.slip_kinematics, c.relaxation)),
        )

    @classmethod
    def from_columns(
        cls,
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
        surface: Surface | Sequence[Surface] = Flat(),
        slip_kinematics: str = "leading",
        force_convention: str = "ground",
    ) -> CaseTable:
        """Columns broadcast together like numpy (scalars repeat), validated per column.

        Exactly one of ``load`` [N] and ``deflection`` [mm] is given; ``surface`` is
        one surface for all cases or one per case.

        Parameters
        ----------
        tire_radius, rim_width : array_like [mm]
        pressure : array_like [N/mm^2]
        load : array_like [N], optional
        deflection : array_like [mm], optional
        camber, slip : array_like [rad]
            In (-pi/2, pi/2).
        lateral : array_like [mm]
        bead_seat_diameter : array_like [mm]
        surface : Surface or str, or a sequence of them (length m)
        slip_kinematics : str
            ``'leading'``, ``'relaxation'`` or ``'centre'`` (:func:`slip_anchor`).
        force_convention : str
            ``'ground'`` or ``'appendix'`` (``FORCE_CONVENTIONS``).

        Returns
        -------
        CaseTable
            ``m`` rows, ``m`` the size of the broadcast columns.

        Raises
        ------
        InvalidParameter
            A column out of range or not broadcastable (named), both or neither of
            ``load`` and ``deflection``.
        """
        if (load is None) == (deflection is None):
            raise InvalidParameter("load/deflection", (load, deflection), "exactly one of the two")
        r0 = v.positive("tire_radius", tire_radius, unit="mm")
        w = v.positive("rim_width", rim_width, unit="mm")
        d = v.positive("bead_seat_diameter", bead_seat_diameter, unit="mm")
        p = v.positive("pressure", pressure, unit="N/mm^2")
        half = np.pi / 2
        g = v.in_range("camber", camber, -half, half, unit="rad")
        a = v.in_range("slip", slip, -half, half, unit="rad")
        lat = v.finite("lateral", lateral, unit="mm")
        if load is not None:
            f = v.positive("load", load, unit="N")
            dw = np.full(np.shape(f), np.nan)
        else:
            dw = v.positive("deflection", deflection, unit="mm")
            f = np.full(np.shape(dw), np.nan)
        if slip_kinematics not in SLIP_KINEMATICS:
            raise InvalidParameter("slip_kinematics", slip_kinematics, one_of(SLIP_KINEMATICS))
        if force_convention not in FORCE_CONVENTIONS:
            raise InvalidParameter("force_convention", force_convention, one_of(FORCE_CONVENTIONS))
        many = isinstance(surface, list | tuple)
        n_surf = len(surface) if many else 1
        try:
            cols = np.broadcast_arrays(r0, w, d, p, f, dw, g, a, lat, np.empty(n_surf))
        except ValueError as exc:
            shapes = [np.shape(x) for x in (r0, w, d, p, f, dw, g, a, lat)]
            raise InvalidParameter("columns", shapes, "shapes that broadcast together") from exc
        cols = [np.atleast_1d(c).ravel().astype(float) for c in cols[:-1]]
        m = cols[0].shape[0]
        surfaces = [parse_surface(s) for s in surface] if many else [parse_surface(surface)]
        if len(surfaces) not in (1, m):
            raise InvalidParameter("surface", len(surfaces), f"one surface or {m}")
        if np.any(cols[1] >= 2 * cols[0]):
            raise InvalidParameter("rim_width", float(np.max(cols[1])), "< 2 x tire_radius [mm]")
        return cls(
            *cols,
            tuple(surfaces * (m if len(surfaces) == 1 else 1)),
            (slip_kinematics,) * m,
            (force_convention,) * m,
            np.full(m, slip_anchor(slip_kinematics, Relaxation())),
        )

    def take(self, index) -> CaseTable:
        """The rows ``index`` (int array or boolean mask) as a new table.

        Parameters
        ----------
        index : int array, slice or (m,) bool array

        Returns
        -------
        CaseTable
        """
        idx = np.arange(len(self))[index]
        arr = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        return CaseTable(
            **{
                k: (
                    val
                    if val is None or (isinstance(val, tuple) and not val)
                    else tuple(val[i] for i in idx)
                    if isinstance(val, tuple)
                    else val[idx]
                )
                for k, val in arr.items()
            }
        )


__all__ = [
    "FORCE_CONVENTIONS",
    "FRICTION_MODELS",
    "SLIP_KINEMATICS",
    "CaseTable",
    "LoadCase",
    "Relaxation",
]
