"""Thresholds and tolerances of :mod:`inkprint`, in one documented place.

Sizes are physical (mm, mm^2) and converted to pixels with the scan's scale, so
the same settings work at 150 and 600 dpi.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class Tolerances:
    """Attributes
    ----------
    max_pixels : int
        Largest image accepted (width x height); larger files raise ImageTooLarge
        before decoding (decompression-bomb guard). 2.5e8 is a letter sheet at 1800 dpi.
    min_dpi, max_dpi : float
        Plausible range of DPI metadata; outside it the metadata is ignored.
    pdf_dpi : float
        Resolution at which PDF pages are rendered when no --dpi is given.
    min_ink_fraction, max_ink_fraction : float
        A sheet with less ink than this is blank (NoInk); with more, all ink (AllInk).
    speck_area_mm2 : float
        Ink blobs smaller than this are paper grain / specks and removed.
    group_distance_mm : float
        Blobs closer than this belong to the same print (joins tread knobs and ribs;
        two prints on a sheet are further apart).
    min_patch_area_mm2 : float
        A group with less ink is a label, dust or a mark, not a print.
    min_patch_width_mm : float
        A group narrower than this across its axis is a line or handwriting (ruler,
        pen stroke, a label's text line); bicycle prints are >= ~7 mm wide (4.1.1).
    min_net_to_gross : float
        A group whose ink covers less of its hull than this is writing, not a print.
    max_patch_aspect : float
        A group longer than this many widths is a line, not a contact patch.
    edge_spot_area_mm2 : float
        Section 7.1.1 rule: blobs at least this large (and dark) form the print's core.
    edge_spot_faintness : float
        A blob outside the core whose peak darkness is below this fraction of the
        core's was not pressed: it bore no load.
    edge_spot_distance_mm : float
        A small blob outside the core farther than this from it bore no load.
    edge_window_mm : float
        Window of the local paper / ink levels whose mean defines the print's edge
        (half contrast) for the outline.
    sensitivity : float
        Relative threshold change of the sensitivity band (+-10 %).
    """

    max_pixels: int = 250_000_000
    min_dpi: float = 30.0
    max_dpi: float = 10_000.0
    pdf_dpi: float = 300.0
    min_ink_fraction: float = 1e-5
    max_ink_fraction: float = 0.6
    speck_area_mm2: float = 0.05
    group_distance_mm: float = 3.0
    min_patch_area_mm2: float = 100.0
    min_patch_width_mm: float = 4.5
    min_net_to_gross: float = 0.15
    max_patch_aspect: float = 30.0
    edge_spot_area_mm2: float = 1.5
    edge_spot_faintness: float = 0.6
    edge_spot_distance_mm: float = 2.0
    edge_window_mm: float = 0.6
    sensitivity: float = 0.10


tol = Tolerances()
