"""One look across the report: a colour per tire, a marker per surface.

The colours (Okabe & Ito's colour-blind safe set, then Tableau's) are assigned to
the tires in sorted order once per report, and used by every figure, table chip
and print overlay, so a tire keeps its colour everywhere.
"""

from __future__ import annotations

PALETTE = (
    "#0072B2",
    "#D55E00",
    "#009E73",
    "#CC79A7",
    "#E69F00",
    "#56B4E9",
    "#000000",
    "#F0E442",
    "#8c564b",
    "#7f7f7f",
    "#bcbd22",
    "#17becf",
)
#: matplotlib marker per surface kind
SURFACE_MARKERS = {"plate": "o", "flat": "o", "drum": "s", "disk": "D"}


def tire_colours(tires) -> dict[str, str]:
    """A colour (hex) per tire, in sorted order of the names.

    Parameters
    ----------
    tires : iterable of str

    Returns
    -------
    dict of str to str
        Beyond 12 tires the palette repeats (each colour then marks several tires).
    """
    names = sorted({str(t) for t in tires})
    return {t: PALETTE[k % len(PALETTE)] for k, t in enumerate(names)}


def surface_marker(surface) -> str:
    """The matplotlib marker of a surface (``o`` plate, ``s`` drum, ``D`` disk).

    Parameters
    ----------
    surface : str

    Returns
    -------
    str
    """
    kind = str(surface).split(":", 1)[0].strip().lower()
    return SURFACE_MARKERS.get(kind, "^")


__all__ = ["PALETTE", "SURFACE_MARKERS", "surface_marker", "tire_colours"]
