"""One look across the report: a colour per tire, a marker per surface.

The colours (Okabe & Ito's colour-blind safe set, then Tableau's) follow the tire's
name (a hash of it, :func:`tire_colour_slot`), not the order in which tires appear,
and are used by every figure, table chip and print overlay of the report and by
the validation's figures, so a tire keeps its colour everywhere and from one report
to the next.
"""

from __future__ import annotations

import zlib

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
#: the first PRIMARY colours of PALETTE (Okabe & Ito without yellow) are used first
PRIMARY = 7
#: matplotlib marker per surface kind
SURFACE_MARKERS = {"plate": "o", "flat": "o", "drum": "s", "disk": "D"}


def tire_colour_slot(name) -> int:
    """The palette index a tire's name hashes to (CRC-32, stable across runs).

    Parameters
    ----------
    name : str

    Returns
    -------
    int
        In ``0 .. PRIMARY - 1`` (the colour-blind safe colours).
    """
    return zlib.crc32(str(name).encode("utf-8")) % PRIMARY


def tire_colours(tires) -> dict[str, str]:
    """A colour (hex) per tire, chosen by its name, in sorted order of the names.

    Parameters
    ----------
    tires : iterable of str

    Returns
    -------
    dict of str to str
        Each tire gets the colour of :func:`tire_colour_slot`; when two tires of
        one set hash to the same colour, the later name (in sorted order) takes the
        next free one (the other safe colours first, then Tableau's). Beyond 12
        tires colours repeat.
    """
    names = sorted({str(t) for t in tires})
    used: set[int] = set()
    out = {}
    for t in names:
        s = tire_colour_slot(t)
        order = [(s + i) % PRIMARY for i in range(PRIMARY)] + list(range(PRIMARY, len(PALETTE)))
        k = next((i for i in order if i not in used), s)
        used.add(k)
        out[t] = PALETTE[k]
    return out


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


__all__ = [
    "PALETTE",
    "PRIMARY",
    "SURFACE_MARKERS",
    "surface_marker",
    "tire_colour_slot",
    "tire_colours",
]
