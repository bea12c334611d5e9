"""inkprint: scanned ink prints of bicycle tire contact patches (sections 3.5, 4.1.1, 7.1.1).

Read a scan (PNG, JPEG, TIFF, PDF) with its scale, binarize it, group the tread
blobs into prints, set apart edge spots that bore no load, and measure each print
with :mod:`contactpatch`'s shared metrics, in mm. One scan or a batch of thousands.

Public API
----------
Reading   : read_scan, Scan
Analysis  : analyze_scan, SheetResult, PrintResult, contact_pressure
Steps     : binarize, group_blobs, edge_spots
Batch     : run_batch, BatchResult
Overlay   : draw_overlay
Synthetic : inkprint.synth (render_sheet, outline_law, make_sample_set)
Errors    : InkPrintError, InvalidInput, ScanReadError, ImageTooLarge, ScaleMissing,
            NoInk, AllInk
Settings  : tol
"""

from ._tol import tol
from .analyze import PrintResult, SheetResult, analyze_scan, contact_pressure
from .binarize import binarize
from .errors import (
    AllInk,
    ImageTooLarge,
    InkPrintError,
    InvalidInput,
    NoInk,
    ScaleMissing,
    ScanReadError,
)
from .group import edge_spots, group_blobs
from .read import Scan, read_scan

__all__ = [
    "AllInk",
    "ImageTooLarge",
    "InkPrintError",
    "InvalidInput",
    "NoInk",
    "PrintResult",
    "ScaleMissing",
    "Scan",
    "ScanReadError",
    "SheetResult",
    "analyze_scan",
    "binarize",
    "contact_pressure",
    "edge_spots",
    "group_blobs",
    "read_scan",
    "tol",
]
