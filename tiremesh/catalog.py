"""The 14 tires of Table 3-2 (Dressel 2013), shipped in ``assets/tires.csv``.

Each entry's geometry is built from its measured carcass arc length and rim
width (equation 5-6), as the dissertation does for its model runs.
"""

from __future__ import annotations

import csv
import functools
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from .errors import InvalidParameter
from .geometry import TireGeometry


def asset_path(name: str) -> Path:
    """Path of a bundled asset: inside the installed package (``tiremesh/data``) or,
    for a source checkout / editable install, the repository's ``assets/``.

    Parameters
    ----------
    name : str
        File name of the asset (``"tires.csv"``).

    Returns
    -------
    Path

    Raises
    ------
    FileNotFoundError
        The asset is in neither place.
    """
    packaged = resources.files("tiremesh").joinpath("data", name)
    if packaged.is_file():
        return Path(str(packaged))
    repo = Path(__file__).resolve().parent.parent / "assets" / name
    if repo.is_file():
        return repo
    raise FileNotFoundError(f"bundled asset {name!r} not found in {packaged} or {repo}")


@dataclass(frozen=True)
class CatalogTire:
    """One row of Table 3-2.

    Attributes
    ----------
    id : int
    brand, model : str
    size : float [mm]
        Nominal size printed on the tire (ISO width).
    arc_length : float [mm]
        Measured carcass arc length bead to bead.
    tire_radius : float [mm]
        As printed in Table 3-2 (one decimal).
    rim_width : float [mm]
    bead_seat_diameter : float [mm]
    """

    id: int
    brand: str
    model: str
    size: float
    arc_length: float
    tire_radius: float
    rim_width: float
    bead_seat_diameter: float

    @property
    def name(self) -> str:
        return f"{self.brand} {self.model} {self.size:g}-{self.bead_seat_diameter:g}"

    def geometry(self, *, rim_width: float | None = None) -> TireGeometry:
        """Tire geometry from the measured arc length (optionally on another rim).

        Parameters
        ----------
        rim_width : float [mm], optional
            Mount on another rim (default the Table 3-2 rim); equation 5-6.

        Returns
        -------
        TireGeometry
        """
        return TireGeometry.from_arc_length(
            self.arc_length,
            self.rim_width if rim_width is None else rim_width,
            bead_seat_diameter=self.bead_seat_diameter,
            name=self.name,
        )


@functools.lru_cache(maxsize=1)
def load_catalog() -> tuple[CatalogTire, ...]:
    """All catalogue tires, in Table 3-2 order.

    Returns
    -------
    tuple of CatalogTire
    """
    with asset_path("tires.csv").open(newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    return tuple(
        CatalogTire(
            id=int(r["id"]),
            brand=r["brand"],
            model=r["model"],
            size=float(r["size_mm"]),
            arc_length=float(r["arc_length_mm"]),
            tire_radius=float(r["tire_radius_mm"]),
            rim_width=float(r["rim_width_mm"]),
            bead_seat_diameter=float(r["bead_seat_diameter_mm"]),
        )
        for r in rows
    )


def find_tire(key: int | str) -> CatalogTire:
    """A catalogue tire by id (``8``, ``"8"``) or by a case-insensitive part of its
    name (``"big apple"``).

    Parameters
    ----------
    key : int or str
        Catalogue id (1-based) or a unique part of the name.

    Returns
    -------
    CatalogTire

    Raises
    ------
    InvalidParameter
        An unknown id, or a name that matches no tire or several (the message lists
        the candidates).
    """
    tires = load_catalog()
    text = str(key).strip()
    if text.isdigit():
        for t in tires:
            if t.id == int(text):
                return t
        raise InvalidParameter("tire", key, f"an id 1..{len(tires)} or a name from the catalogue")
    hits = [t for t in tires if text.lower() in t.name.lower()]
    if len(hits) == 1:
        return hits[0]
    names = "; ".join(f"{t.id}: {t.name}" for t in (hits or tires))
    raise InvalidParameter(
        "tire",
        key,
        f"one catalogue tire ({'ambiguous' if hits else 'unknown'}; candidates: {names})",
    )


def get_tire(key: int | str, *, rim_width: float | None = None) -> TireGeometry:
    """Geometry of a catalogue tire by id or name (see :func:`find_tire`).

    Parameters
    ----------
    key : int or str
        Catalogue id (1-based) or a unique part of the name.
    rim_width : float [mm], optional
        Mount on another rim (the measured carcass arc length is kept, equation 5-6).

    Returns
    -------
    TireGeometry
    """
    return _geometry(key, rim_width)


@functools.lru_cache(maxsize=512)
def _geometry(key, rim_width) -> TireGeometry:
    return find_tire(key).geometry(rim_width=rim_width)  # frozen: safe to share
