"""Undeformed tire cross-section geometry (section 5.1, equations 5-1, 5-2, 5-3, 5-4,
5-5 and 5-6).

A bicycle tire's cross section is a circular arc of radius ``r0`` from bead to bead;
the beads sit on a rim of inner width ``w``. Everything here is closed form except
the rim angle from a measured arc length (equation 5-6), which is a root.
Equation 5-1, ``w = 2 r0 sin(theta0 / 2)``, defines the rim angle; it is used
through its inversions, equation 5-2 (:func:`rim_angle`) and equation 5-5
(:meth:`TireGeometry.from_arc_length`).

References
----------
A. E. Dressel (2013), chapter 5, section 5.1; the index of equations is in
``docs/model.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import validate as v
from ._roots import newton_bracketed
from ._tol import tol
from .errors import InvalidParameter

DEFAULT_BEAD_SEAT_DIAMETER = 622.0  # 700C / 29er, ISO 622 [mm]


def rim_angle(rim_width, tire_radius):
    """Angle swept by the missing part of the carcass circle between the beads.

    ``theta0 = 2 asin(w / (2 r0))``, equation 5-2.

    Parameters
    ----------
    rim_width : (...) float [mm]
    tire_radius : (...) float [mm]

    Returns
    -------
    theta0 : (...) float [rad]

    Notes
    -----
    Dressel (2013), section 5.1, equation 5-2 (the inverse of equation 5-1).
    """
    return 2.0 * np.arcsin(np.asarray(rim_width) / (2.0 * np.asarray(tire_radius)))  # Eq. 5-2


def rim_height(tire_radius, rim_angle):
    """Height of the rim bead line above the lowest point of the tire.

    ``h = r0 (1 + cos(theta0 / 2))``, equation 5-3.

    Parameters
    ----------
    tire_radius : (...) float [mm]
        Carcass radius ``r0``.
    rim_angle : (...) float [rad]
        Rim angle ``theta0`` (equation 5-2).

    Returns
    -------
    h : (...) float [mm]

    Notes
    -----
    Dressel (2013), section 5.1, equation 5-3.
    """
    return np.asarray(tire_radius) * (1.0 + np.cos(0.5 * np.asarray(rim_angle)))  # Eq. 5-3


def arc_length(tire_radius, rim_angle):
    """Carcass arc length from bead to bead, ``s0 = r0 (2 pi - theta0)``.

    Parameters
    ----------
    tire_radius : (...) float [mm]
        Carcass radius ``r0``.
    rim_angle : (...) float [rad]
        Rim angle ``theta0`` (equation 5-2).

    Returns
    -------
    s0 : (...) float [mm]

    Notes
    -----
    Dressel (2013), section 5.1, equation 5-4.
    """
    return np.asarray(tire_radius) * (2.0 * np.pi - np.asarray(rim_angle))  # Eq. 5-4


def rim_angle_from_arc_length(rim_width, arc_length):
    """Solve ``w / s0 = 2 sin(theta0 / 2) / (2 pi - theta0)`` (equation 5-6) for theta0.

    The right-hand side increases monotonically from 0 to 2/pi on (0, pi], so the
    root is unique; it is found by a bracketed Newton iteration to machine
    precision (the dissertation uses MATLAB's ``fzero`` from pi/4).

    Parameters
    ----------
    rim_width, arc_length : (...) float [mm]

    Returns
    -------
    theta0 : (...) float [rad]

    Raises
    ------
    InvalidParameter
        If ``rim_width >= 2 arc_length / pi`` (the tire cannot sit on the rim).

    Notes
    -----
    Dressel (2013), section 5.1, equation 5-6 (equations 5-4 and 5-5 with ``r0``
    eliminated); Table 5-2 is the worked example.
    """
    w = v.positive("rim_width", rim_width, unit="mm")
    s0 = v.positive("arc_length", arc_length, unit="mm")
    ratio = w / s0
    if np.any(ratio >= 2.0 / np.pi):
        raise InvalidParameter(
            "rim_width",
            float(np.max(w)),
            f"< 2/pi x arc_length = {float(np.min(2 * s0 / np.pi)):.6g} mm",
            "the rim is wider than the carcass can span",
        )

    def fun(t):
        den = 2.0 * np.pi - t
        f = 2.0 * np.sin(0.5 * t) / den - ratio  # Eq. 5-6
        df = np.cos(0.5 * t) / den + 2.0 * np.sin(0.5 * t) / den**2
        return f, df

    # small-angle start: 2 sin(t/2)/(2 pi - t) ~ t / (2 pi)
    x0 = np.minimum(2.0 * np.pi * ratio, 0.5 * np.pi)
    return newton_bracketed(
        fun,
        x0,
        np.zeros_like(ratio),
        np.full_like(ratio, np.pi),
        xtol=tol.geometry_xtol,
        what="rim angle from arc length (equation 5-6)",
    )


@dataclass(frozen=True)
class TireGeometry:
    """An undeformed tire on its rim.

    Parameters
    ----------
    tire_radius : float [mm]
        Radius ``r0`` of the carcass circle (Figure 5-2).
    rim_width : float [mm]
        Inner rim width ``w``, bead to bead.
    bead_seat_diameter : float [mm]
        ISO bead seat diameter of the rim (622 for 700C).
    name : str
        Free label (catalogue name).
    """

    tire_radius: float
    rim_width: float
    bead_seat_diameter: float = DEFAULT_BEAD_SEAT_DIAMETER
    name: str = ""

    def __post_init__(self) -> None:
        r0 = float(v.positive("tire_radius", self.tire_radius, unit="mm"))
        w = float(v.positive("rim_width", self.rim_width, unit="mm"))
        d = float(v.positive("bead_seat_diameter", self.bead_seat_diameter, unit="mm"))
        if w >= 2.0 * r0:
            raise InvalidParameter(
                "rim_width",
                w,
                f"< 2 x tire_radius = {2 * r0:.6g} mm",
                "the rim is wider than the carcass circle",
            )
        object.__setattr__(self, "tire_radius", r0)
        object.__setattr__(self, "rim_width", w)
        object.__setattr__(self, "bead_seat_diameter", d)

    @classmethod
    def from_size(
        cls, size: float, rim_width: float, *, bead_seat_diameter: float = 622.0, name: str = ""
    ) -> TireGeometry:
        """Tire from its nominal size, taken as the carcass diameter (Table 5-1).

        Parameters
        ----------
        size : float [mm]
            Nominal (ETRTO) width, read as the carcass diameter ``2 r0``.
        rim_width : float [mm]
            Inner rim width ``w`` (bead to bead).
        bead_seat_diameter : float [mm], optional
            Rim bead-seat diameter (622 for 700C / 29er).
        name : str, optional
            Label for tables.

        Returns
        -------
        TireGeometry
        """
        size = float(v.positive("size", size, unit="mm"))
        return cls(0.5 * size, rim_width, bead_seat_diameter, name)

    @classmethod
    def from_arc_length(
        cls,
        arc_length: float,
        rim_width: float,
        *,
        bead_seat_diameter: float = 622.0,
        name: str = "",
    ) -> TireGeometry:
        """Tire from a measured bead-to-bead carcass arc length (Table 5-2).

        The rim angle solves equation 5-6; the radius is then ``r0 = w / (2 sin(theta0 /
        2))``, equation 5-5 (Dressel 2013, section 5.1).

        Parameters
        ----------
        arc_length : float [mm]
            Measured carcass arc length from bead to bead ``s0``.
        rim_width : float [mm]
            Inner rim width ``w``; ``w < s0``.
        bead_seat_diameter : float [mm], optional
            Rim bead-seat diameter.
        name : str, optional
            Label for tables.

        Returns
        -------
        TireGeometry
        """
        theta0 = float(rim_angle_from_arc_length(rim_width, arc_length))
        r0 = float(rim_width) / (2.0 * math.sin(0.5 * theta0))  # Eq. 5-5
        return cls(r0, rim_width, bead_seat_diameter, name)

    @property
    def rim_angle(self) -> float:
        """theta0 [rad], equation 5-2."""
        return float(rim_angle(self.rim_width, self.tire_radius))

    @property
    def rim_height(self) -> float:
        """h [mm], equation 5-3."""
        return float(rim_height(self.tire_radius, self.rim_angle))

    @property
    def arc_length(self) -> float:
        """s0 [mm], bead to bead (equation 5-4)."""
        return float(arc_length(self.tire_radius, self.rim_angle))

    @property
    def size(self) -> float:
        """Carcass diameter 2 r0 [mm] (the 'size' of Table 5-1)."""
        return 2.0 * self.tire_radius

    @property
    def wheel_radius(self) -> float:
        """Unloaded wheel radius (axle to tread), ``D_bead / 2 + h`` [mm] (Appendix C)."""
        return 0.5 * self.bead_seat_diameter + self.rim_height

    def describe(self) -> dict[str, float | str]:
        """The geometry with unit-carrying names (for tables and file metadata).

        Returns
        -------
        dict
            ``tire, tire_radius_mm, arc_length_mm, rim_width_mm,
            bead_seat_diameter_mm, rim_height_mm``.
        """
        return {
            "tire": self.name or f"r0={self.tire_radius:.4g}mm",
            "tire_radius_mm": self.tire_radius,
            "arc_length_mm": self.arc_length,
            "rim_width_mm": self.rim_width,
            "bead_seat_diameter_mm": self.bead_seat_diameter,
            "rim_height_mm": self.rim_height,
        }
