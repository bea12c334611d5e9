"""Support surfaces: flat ground, test drum, test disk (section 5.3).

Everything the model, the mesh, the patch extraction and the exports need from a
surface is the :class:`Surface` protocol below; no other module asks which kind of
surface it has. A new surface is one class here (or anywhere: subclass
:class:`SurfaceBase`, override what differs from flat ground) plus its tests; give it
``register_surface`` to make it parseable from the command line.

Frame: ground ``x`` forward (rolling direction), ``y`` lateral, ``z`` up, origin on
the surface below the wheel centre; the contact plane is ``z = 0``.

A drum (section 5.3.1) curves away from the tire in the rolling direction and lowers
each section's vertical deflection by its drop (equations 5-19, 5-20 and 5-21); a
disk (section 5.3.2) is flat but its circular track curves sideways, which shifts
each section's horizontal deflection (equations 5-22, 5-23 and 5-24). Drum and disk
share :func:`curvature_drop`: equations 5-19 and 5-22 are the same formula, and so
are equations 5-20 and 5-23.

References
----------
A. E. Dressel (2013), section 5.3. The index of equations is in ``docs/model.md``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Literal, Protocol, runtime_checkable

import numpy as np

from . import validate as v
from .errors import InvalidParameter

SURFACE_FORMS = "flat | drum:DIAMETER_MM | disk:DIAMETER_MM[:toward|away]"


@runtime_checkable
class Surface(Protocol):
    """What the model, mesh, patch extraction and export need from a support surface.

    All methods are vectorized (numpy broadcasting) and pure.
    """

    kind: ClassVar[str]

    @property
    def spec(self) -> str:
        """Command-line form that :func:`parse_surface` reads back (``drum:2500``)."""

    def describe(self) -> str:
        """Human-readable label for tables and titles.

        Returns
        -------
        str
            E.g. ``"drum 2500 mm"``.
        """

    def drop(self, phi, wheel_radius) -> tuple[np.ndarray, np.ndarray]:
        """Drop of the surface below the contact plane under the section at ``phi``
        (lowers the section's vertical deflection, equation 5-18).

        Parameters
        ----------
        phi : (...) float [rad]
            Section angle from bottom dead centre.
        wheel_radius : (...) float [mm]
            Axle height ``R`` of the unloaded wheel.

        Returns
        -------
        drop : (...) float [mm]
        ddrop_dphi : (...) float [mm/rad]
        """

    def shift(self, phi, wheel_radius, camber) -> tuple[np.ndarray, np.ndarray]:
        """Sideways shift of the track under the section at ``phi`` (adds to the
        section's horizontal deflection).

        Parameters
        ----------
        phi : (...) float [rad]
            Section angle from bottom dead centre.
        wheel_radius : (...) float [mm]
            Axle height ``R`` of the unloaded wheel.
        camber : (...) float [rad]
            Camber angle (its sign picks the side the track curves toward).

        Returns
        -------
        shift : (...) float [mm]
        dshift_dphi : (...) float [mm/rad]
        """

    def height(self, x) -> np.ndarray:
        """Height of the surface at ground position ``x``.

        Parameters
        ----------
        x : (...) float [mm]
            Ground coordinate along the rolling direction.

        Returns
        -------
        z : (...) float [mm]
            0 on flat ground, negative where the surface falls away.
        """

    def gap(self, points) -> np.ndarray:
        """Distance of ``points`` above the surface.

        Parameters
        ----------
        points : (n, 3) float [mm]
            Points in the ground frame.

        Returns
        -------
        gap : (n,) float [mm]
            Positive above the surface, negative below.
        """

    def unroll(self, x) -> np.ndarray:
        """Arc length along the surface of the surface point above ground ``x``
        (what paper wrapped on the surface records).

        Parameters
        ----------
        x : (...) float [mm]
            Ground coordinate along the rolling direction.

        Returns
        -------
        s : (...) float [mm]
        """

    def roll(self, s) -> np.ndarray:
        """Inverse of :meth:`unroll`: ground ``x`` of arc length ``s``.

        Parameters
        ----------
        s : (...) float [mm]
            Arc length along the surface.

        Returns
        -------
        x : (...) float [mm]
        """

    def stretch(self, x) -> np.ndarray:
        """``d unroll / dx``: surface length per unit of ground ``x``.

        Parameters
        ----------
        x : (...) float [mm]
            Ground coordinate along the rolling direction.

        Returns
        -------
        (...) float [-]
            1 on flat ground, >= 1 on a drum.
        """


def curvature_drop(phi, wheel_radius, curvature):
    """Drop of a curved surface under a wheel section (section 5.3) and its
    derivative with respect to ``phi``.

    ``D = R_s (1 - cos phi_s) / cos phi`` (equation 5-19 for a drum, 5-22 for a disk)
    with ``R_s sin phi_s = R sin phi`` (equation 5-20, 5-23), written as ``kappa R^2
    sin^2 phi / ((1 + sqrt(1 - (kappa R sin phi)^2)) cos phi)`` (the closed forms of
    equations 5-21 and 5-24) so a zero curvature ``kappa = 1 / R_s`` (flat) gives
    exactly 0 and a negative one flips the sign.

    Parameters
    ----------
    phi : (...) float [rad]
        Section angle from bottom dead centre.
    wheel_radius : (...) float [mm]
        Axle height ``R`` of the unloaded wheel.
    curvature : (...) float [1/mm]
        Signed ``1 / R_s``.

    Returns
    -------
    drop : (...) float [mm]
    ddrop_dphi : (...) float [mm/rad]

    Notes
    -----
    Dressel (2013), sections 5.3.1 and 5.3.2, equations 5-19, 5-20 (drum) and 5-22,
    5-23 (disk).
    """
    k = np.asarray(curvature, float)
    R = np.asarray(wheel_radius, float)
    sp, cp = np.sin(phi), np.cos(phi)
    u = k * R * sp  # Eq. 5-20, Eq. 5-23: sin(phi_s) = R sin(phi) / R_s
    root = np.sqrt(np.clip(1.0 - u * u, 0.0, None))
    num = k * R * R * sp * sp
    den = (1.0 + root) * cp
    with np.errstate(divide="ignore", invalid="ignore"):
        droot = np.where(root > 0, -u * k * R * cp / np.where(root > 0, root, 1.0), 0.0)
    dnum = 2.0 * k * R * R * sp * cp
    dden = droot * cp - (1.0 + root) * sp
    return num / den, (dnum * den - num * dden) / (den * den)  # Eq. 5-19, Eq. 5-22


class SurfaceBase(Surface):
    """Flat ground; subclass and override what a new surface changes.

    The methods are those of :class:`Surface` (documented there; the overrides
    inherit the docstrings).

    A subclass whose methods are plain numpy expressions of its fields can also
    stand for many cases at once (:meth:`stack`), so that cases on, say, drums of
    different diameters are solved in one vectorized group.
    """

    kind: ClassVar[str] = "flat"
    stack_fields: ClassVar[tuple[str, ...]] = ()

    def __init__(self) -> None:  # a plain class (Protocol would give it *args, **kwargs)
        pass

    @classmethod
    def stack(cls, surfaces) -> SurfaceBase | None:
        """One surface standing for ``surfaces`` (all of this class), one per case.

        Parameters
        ----------
        surfaces : sequence of SurfaceBase
            One per case, all ``type(s) is cls``.

        Returns
        -------
        SurfaceBase or None
            The common surface when all are equal; else, for classes listing
            ``stack_fields``, an instance whose fields are (m, 1) arrays (its methods
            then broadcast over cases); else None (the solver groups equal ones).
        """
        first = surfaces[0]
        if all(s == first for s in surfaces):
            return first
        if not cls.stack_fields:
            return None
        stacked = object.__new__(cls)
        for f in cls.stack_fields:
            object.__setattr__(stacked, f, np.array([getattr(s, f) for s in surfaces])[:, None])
        return stacked

    @property
    def spec(self) -> str:
        return self.kind

    @classmethod
    def from_spec(cls, args: list[str]) -> SurfaceBase:
        """The surface of a command-line form's arguments (see :func:`register_surface`).

        Parameters
        ----------
        args : list of str
            The ``:``-separated words after the keyword (``["2500"]`` of
            ``drum:2500``); this default takes none.

        Returns
        -------
        SurfaceBase
            An instance of ``cls``.
        """
        if args:
            raise ValueError(f"{cls.kind} takes no arguments")
        return cls()

    def describe(self) -> str:
        return self.kind

    def drop(self, phi, wheel_radius):
        z = np.zeros(np.broadcast(phi, wheel_radius).shape)
        return z, z

    def shift(self, phi, wheel_radius, camber):
        z = np.zeros(np.broadcast(phi, wheel_radius, camber).shape)
        return z, z

    def height(self, x):
        return np.zeros_like(np.asarray(x, float))

    def gap(self, points):
        p = np.asarray(points, float)
        return p[:, 2] - self.height(p[:, 0])

    def unroll(self, x):
        return np.asarray(x, float).copy()

    def roll(self, s):
        return np.asarray(s, float).copy()

    def stretch(self, x):
        return np.ones_like(np.asarray(x, float))


_REGISTRY: dict[str, type] = {}


def register_surface(name: str):
    """Class decorator: make ``name[:args]`` parseable by :func:`parse_surface`.

    Parameters
    ----------
    name : str
        Lower-case keyword of the command-line form (``"drum"``).

    Returns
    -------
    decorator : callable
        Registers the class and returns it unchanged. The class needs a classmethod
        ``from_spec(args: list[str])`` (``args`` the ``:``-separated rest).
    """

    def deco(cls):
        _REGISTRY[name] = cls
        return cls

    return deco


@register_surface("flat")
@dataclass(frozen=True)
class Flat(SurfaceBase):
    """Flat ground (UWM flat track, a plate)."""

    kind: ClassVar[str] = "flat"


@register_surface("drum")
@dataclass(frozen=True)
class Drum(SurfaceBase):
    """Outside of a cylindrical drum (TU Delft: 2.5 m diameter), section 5.3.1.

    Its :meth:`drop` is the drum term of equation 5-21 (equation 5-19 with equation
    5-20 substituted), which the solver subtracts as in equation 5-18.

    Parameters
    ----------
    diameter : float [mm]
        Must exceed the tire's wheel diameter's curvature limit: ``diameter > 100`` mm
        (a drum smaller than the wheel is outside the model's domain, 5.3.1).
    """

    diameter: float
    kind: ClassVar[str] = "drum"
    stack_fields: ClassVar[tuple[str, ...]] = ("diameter",)

    def __post_init__(self) -> None:
        d = float(v.positive("drum diameter", self.diameter, unit="mm"))
        if d <= 100.0:
            raise InvalidParameter("drum diameter", d, "> 100 mm (a test drum, not a roller)")
        object.__setattr__(self, "diameter", d)

    @property
    def curvature(self) -> float:
        """``1 / R_drum`` [1/mm]."""
        return 2.0 / self.diameter

    @property
    def spec(self) -> str:
        return f"drum:{self.diameter:g}"

    def describe(self) -> str:
        return f"drum {self.diameter:g} mm"

    @classmethod
    def from_spec(cls, args: list[str]) -> Drum:
        (d,) = args
        return cls(float(d))

    def drop(self, phi, wheel_radius):
        return curvature_drop(phi, wheel_radius, self.curvature)  # drop of equation 5-21

    def height(self, x):
        x = np.asarray(x, float)
        k = self.curvature
        return -k * x * x / (1.0 + np.sqrt(np.clip(1.0 - (k * x) ** 2, 0.0, None)))

    def gap(self, points):
        p = np.asarray(points, float)
        rd = 0.5 * self.diameter
        return np.hypot(p[:, 0], p[:, 2] + rd) - rd

    def unroll(self, x):
        k = self.curvature
        return np.arcsin(np.clip(k * np.asarray(x, float), -1.0, 1.0)) / k

    def roll(self, s):
        k = self.curvature
        return np.sin(k * np.asarray(s, float)) / k

    def stretch(self, x):
        k = self.curvature
        return 1.0 / np.sqrt(np.clip(1.0 - (k * np.asarray(x, float)) ** 2, 1e-300, None))


@register_surface("disk")
@dataclass(frozen=True)
class Disk(SurfaceBase):
    """Flat rotating disk whose circular track curves sideways (Padua: 3 m), 5.3.2.

    Its :meth:`shift` is equation 5-24 (equation 5-22 with equation 5-23
    substituted), added to each section's horizontal deflection.

    Parameters
    ----------
    diameter : float [mm]
        Diameter of the circular track, > 100 mm.
    curving : {'toward', 'away'}
        Whether the track's centre of curvature lies on the side toward which the
        wheel top leans (``'toward'`` the camber, as when cornering) or the other.
        With zero camber, ``'toward'`` puts the centre on ``+y``.
    """

    diameter: float
    curving: Literal["toward", "away"] = "toward"
    kind: ClassVar[str] = "disk"
    stack_fields: ClassVar[tuple[str, ...]] = ("diameter", "curving")

    def __post_init__(self) -> None:
        d = float(v.positive("disk diameter", self.diameter, unit="mm"))
        if d <= 100.0:
            raise InvalidParameter("disk diameter", d, "> 100 mm")
        object.__setattr__(self, "diameter", d)
        if self.curving not in ("toward", "away"):
            raise InvalidParameter("curving", self.curving, "'toward' or 'away'")

    @property
    def spec(self) -> str:
        return f"disk:{self.diameter:g}:{self.curving}"

    def describe(self) -> str:
        return f"disk {self.diameter:g} mm curving {self.curving} the camber"

    @classmethod
    def from_spec(cls, args: list[str]) -> Disk:
        if len(args) not in (1, 2):
            raise ValueError("disk takes DIAMETER[:toward|away]")
        return cls(float(args[0]), *args[1:])

    def center_side(self, camber):
        """Side of the track's centre of curvature, per camber.

        Parameters
        ----------
        camber : (...) float [rad]

        Returns
        -------
        (...) float
            +1 where the centre is on ``+y``, -1 where on ``-y``.
        """
        lean = np.where(np.asarray(camber, float) >= 0, 1.0, -1.0)
        return np.where(np.asarray(self.curving) == "toward", lean, -lean)

    def shift(self, phi, wheel_radius, camber):
        k = self.center_side(camber) * 2.0 / self.diameter
        return curvature_drop(phi, wheel_radius, k)  # Eq. 5-24


def parse_surface(text: str | Surface) -> Surface:
    """A surface from its command-line form.

    Parameters
    ----------
    text : str
        ``flat`` (or ``plate``, ``ground``), ``drum:2500``, ``disk:3000``,
        ``disk:3000:away`` (diameters in mm), or any registered form. A
        :class:`Surface` passes through.

    Returns
    -------
    Surface
    """
    if isinstance(text, SurfaceBase | Surface):  # SurfaceBase first: the fast check
        return text
    parts = [p.strip().lower() for p in str(text).split(":")]
    name = {"plate": "flat", "ground": "flat"}.get(parts[0], parts[0])
    cls = _REGISTRY.get(name)
    if cls is None:
        raise InvalidParameter("surface", text, SURFACE_FORMS)
    try:
        return cls.from_spec(parts[1:])
    except InvalidParameter:
        raise
    except (ValueError, TypeError) as exc:
        raise InvalidParameter("surface", text, SURFACE_FORMS) from exc


__all__ = [
    "SURFACE_FORMS",
    "Disk",
    "Drum",
    "Flat",
    "Surface",
    "SurfaceBase",
    "curvature_drop",
    "parse_surface",
    "register_surface",
]
