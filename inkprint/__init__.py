"""inkprint: scanned ink prints of bicycle tire contact patches (sections 3.5, 4.1.1, 7.1.1).

Read a scan (PNG, JPEG, TIFF, PDF) with its scale, binarize it, group the tread
blobs into prints, set apart edge spots that bore no load, and measure each print
with :mod:`contactpatch`'s shared metrics, in mm. One scan or a batch of thousands.
The judgement thresholds are an :class:`AnalysisOptions` passed to each call (and
with the batch options to every worker); there is no global setting.

Public API
----------
Reading   : read_scan, iter_scans (every PDF page), Scan
Analysis  : analyze_scan, SheetResult, PrintResult, contact_pressure
Options   : AnalysisOptions
Steps     : prepare_page (light, photo page), binarize, sort_ink (marks that are not
            prints), group_blobs (whole footprints), edge_spots (section 7.1.1)
Batch     : run_batch, BatchResult, BatchOptions (= inkprint.batch.Options)
Overlay   : draw_overlay
Pixels/mm : inkprint.coords
Synthetic : inkprint.synth (render_sheet, outline_law, make_sample_set),
            inkprint.synth_cases (the failure classes, make_mixed_set),
            inkprint.accuracy (python -m inkprint.accuracy)
Errors    : InkPrintError, InvalidInput, ScanReadError, ImageTooLarge, ScaleMissing,
            ScaleUntrusted, NoInk, AllInk, OutputLocked
"""

__version__ = "0.2.0"

from .analyze import analyze_scan
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
from .light import prepare_page
from .marks import sort_ink
from .options import AnalysisOptions
from .overlay import draw_overlay
from .read import Scan, iter_scans, read_scan
from .results import PrintResult, SheetResult, contact_pressure

__all__ = [
    "AllInk",
    "AnalysisOptions",
    "BatchOptions",
    "BatchResult",
    "ImageTooLarge",
    "InkPrintError",
    "InvalidInput",
    "NoInk",
    "OutputLocked",
    "PrintResult",
    "ScaleMissing",
    "ScaleUntrusted",
    "Scan",
    "ScanReadError",
    "SheetResult",
    "analyze_scan",
    "binarize",
    "contact_pressure",
    "draw_overlay",
    "edge_spots",
    "group_blobs",
    "iter_scans",
    "prepare_page",
    "read_scan",
    "run_batch",
    "sort_ink",
]

# The batch (scheduler, tables, progress bar) loads on first use (PEP 562): one
# ``inkprint analyze`` does not need it.
_LAZY = {"BatchResult": "BatchResult", "run_batch": "run_batch", "BatchOptions": "Options"}


def __getattr__(name: str):
    """A batch name, imported on first use (PEP 562)."""
    if name not in _LAZY:
        raise AttributeError(f"module 'inkprint' has no attribute {name!r}")
    from . import batch

    value = getattr(batch, _LAZY[name])
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
