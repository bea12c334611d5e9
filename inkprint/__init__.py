"""inkprint: scanned ink prints of bicycle tire contact patches (sections 3.5, 4.1.1, 7.1.1).

Read a scan (PNG, JPEG, TIFF, PDF) with its scale, binarize it, group the tread
blobs into prints, set apart edge spots that bore no load, and measure each print
with :mod:`contactpatch`'s shared metrics, in mm. One scan or a batch of thousands.
The judgement thresholds are an :class:`AnalysisOptions` passed to each call (and
with the batch options to every worker); there is no global setting.

Public API
----------
Reading   : read_scan, Scan
Analysis  : analyze_scan, SheetResult, PrintResult, contact_pressure
Options   : AnalysisOptions
Steps     : binarize, group_blobs, edge_spots
Batch     : run_batch, BatchResult (options: inkprint.batch.Options)
Overlay   : draw_overlay
Pixels/mm : inkprint.coords
Synthetic : inkprint.synth (render_sheet, outline_law, make_sample_set)
Errors    : InkPrintError, InvalidInput, ScanReadError, ImageTooLarge, ScaleMissing,
            NoInk, AllInk
"""

from .analyze import analyze_scan
from .batch import BatchResult, run_batch
from .binarize import binarize
from .errors import (
    AllInk,
    ImageTooLarge,
    InkPrintError,
    InvalidInput,
    NoInk,
    OutputLocked,
    ScaleMissing,
    ScaleUntrusted,
    ScanReadError,
)
from .group import edge_spots, group_blobs
from .options import AnalysisOptions
from .overlay import draw_overlay
from .read import Scan, iter_scans, read_scan
from .results import PrintResult, SheetResult, contact_pressure

__all__ = [
    "AllInk",
    "AnalysisOptions",
    "BatchResult",
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
    "draw_overlay",
    "edge_spots",
    "group_blobs",
    "read_scan",
    "run_batch",
]
