"""Support surfaces: flat ground, test drum, test disk (section 5.3).

A drum (section 5.3.1, Eq. 5-18 to 5-21) curves away from the tire in the rolling
direction and lowers each section's vertical deflection; a disk (section 5.3.2,
Eq. 5-22 to 5-24) is flat but its circular track curves sideways, which shifts
each section's horizontal deflection.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from . import _validate as v
from .errors import InvalidParameter


@dataclass(frozen=True)
class Flat:
    """Flat ground (UWM flat track, a plate)."""

    kind = "flat"

    def describe(self) -> str:
        return "flat"


@dataclass(frozen=True)
class Drum:
    """Outside of a cylindrical drum (TU Delft: 2.5 m diameter).

    Parameters
    ----------
    diameter : float [mm]
    """

    diameter: float
    kind = "drum"

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "diameter", float(v.positive("drum diameter", self.diameter, unit="mm"))
        )

    def describe(self) -> str:
        return f"drum {self.diameter:g} mm"


@dataclass(frozen=True)
class Disk:
    """Flat rotating disk whose circular track curves sideways (Padua: 3 m).

    Parameters
    ----------
    diameter : float [mm]
        Diameter of the circular track.
    curving : {'toward', 'away'}
        Whether the track's centre of curvature lies on the side toward which the
        wheel top leans (``'toward'`` the camber, as when cornering) or the other.
        With zero camber, ``'toward'`` puts the centre on ``+y``.
    """

    diameter: float
    curving: Literal["toward", "away"] = "toward"
    kind = "disk"

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "diameter", float(v.positive("disk diameter", self.diameter, unit="mm"))
        )
        if self.curving not in ("toward", "away"):
            raise InvalidParameter("curving", self.curving, "'toward' or 'away'")

    def center_side(self, camber: float) -> float:
        """+1 if the track centre is on ``+y``, -1 if on ``-y``."""
        lean = 1.0 if camber >= 0 else -1.0
        return lean if self.curving == "toward" else -lean

    def describe(self) -> str:
        return f"disk {self.diameter:g} mm curving {self.curving} the camber"


Surface = Flat | Drum | Disk


def parse_surface(text: str) -> Surface:
    """'flat', 'drum:2500', 'disk:3000', 'disk:3000:away' (diameters in mm)."""
    parts = [p.strip().lower() for p in str(text).split(":")]
    try:
        if parts[0] in ("flat", "plate", "ground") and len(parts) == 1:
            return Flat()
        if parts[0] == "drum" and len(parts) == 2:
            return Drum(float(parts[1]))
        if parts[0] == "disk" and len(parts) in (2, 3):
            return Disk(float(parts[1]), parts[2] if len(parts) == 3 else "toward")
    except ValueError as exc:
        if isinstance(exc, InvalidParameter):
            raise
        raise InvalidParameter(
            "surface", text, "flat | drum:DIAMETER_MM | disk:DIAMETER_MM[:toward|away]"
        ) from exc
    raise InvalidParameter(
        "surface", text, "flat | drum:DIAMETER_MM | disk:DIAMETER_MM[:toward|away]"
    )


def curvature_drop(phi, wheel_radius, curvature):
    """Drop of a curved surface under a wheel section, Eq. 5-19/5-20 (and 5-22/5-23).

    ``D = R_s (1 - cos phi_s) / cos phi`` with ``R_s sin phi_s = R sin phi``, written
    as ``kappa R^2 sin^2 phi / ((1 + sqrt(1 - (kappa R sin phi)^2)) cos phi)`` so a
    zero curvature ``kappa = 1 / R_s`` (flat) gives exactly 0 and a negative one
    flips the sign.

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
    """
    k = np.asarray(curvature, float)
    R = np.asarray(wheel_radius, float)
    sp, cp = np.sin(phi), np.cos(phi)
    u = k * R * sp
    root = np.sqrt(1.0 - u * u)
    num = k * R * R * sp * sp
    den = (1.0 + root) * cp
    with np.errstate(divide="ignore", invalid="ignore"):
        droot = np.where(root > 0, -u * k * R * cp / root, 0.0)
    dnum = 2.0 * k * R * R * sp * cp
    dden = droot * cp - (1.0 + root) * sp
    return num / den, (dnum * den - num * dden) / (den * den)
