"""inkprint: scanned ink prints of bicycle tire contact patches (sections 3.5, 4.1.1, 7.1.1).

Read a scan (PNG, JPEG, TIFF, PDF) with its scale, binarize it, group the tread
blobs into prints, set apart edge spots that bore no load, and measure each print
with :mod:`contactpatch`'s shared metrics, in mm. One scan or a batch of thousands.
The judgement thresholds are an :class:`AnalysisOptions` passed to each call (and
with the batch options to every worker); there is no global setting.

Public API
----------
Reading   : read_scan, iter_scans (every PDF page), Scan; rectify_page, paper_size
            (a photo taken at a tilt, its scale from its paper: ``paper=``)
Analysis  : analyze_scan, SheetResult, PrintResult, contact_pressure
Options   : AnalysisOptions
Steps     : prepare_page (light, photo page), binarize, sort_ink (marks that are not
            prints), group_blobs (whole footprints), edge_spots (section 7.1.1),
            find_scales (a ruler's scale among the marks: its strip and pitch)
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

import sys
import types

from tiremesh.lazy import lazy_attributes

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
    "find_scales",
    "group_blobs",
    "iter_scans",
    "paper_size",
    "prepare_page",
    "read_scan",
    "rectify_page",
    "run_batch",
    "sort_ink",
]

# Everything but the errors loads on first use (PEP 562): importing the package
# (``inkprint.cli`` does) does not import numpy, so the command line can set up the
# process first (one OpenBLAS thread for ``inkprint analyze``), and one ``inkprint
# analyze`` does not load the batch's scheduler, tables and progress bar.
_LAZY = {
    "AnalysisOptions": ".options",
    "BatchOptions": (".batch", "Options"),
    "BatchResult": ".batch",
    "PrintResult": ".results",
    "Scan": ".read",
    "SheetResult": ".results",
    "analyze_scan": ".analyze",
    "binarize": ".binarize",
    "contact_pressure": ".results",
    "draw_overlay": ".overlay",
    "edge_spots": ".group",
    "find_scales": ".ruler",
    "group_blobs": ".group",
    "iter_scans": ".read",
    "paper_size": ".paper",
    "prepare_page": ".light",
    "read_scan": ".read",
    "rectify_page": ".paper",
    "run_batch": ".batch",
    "sort_ink": ".marks",
}

__getattr__, __dir__ = lazy_attributes(__name__, globals(), _LAZY)


class _Package(types.ModuleType):
    """The package's module: ``inkprint.binarize`` stays the function when its
    submodule :mod:`inkprint.binarize` is imported (the import system then sets the
    submodule as the package's attribute; the eager imports used to set it back)."""

    def __setattr__(self, name: str, value) -> None:
        if (
            isinstance(value, types.ModuleType)
            and _LAZY.get(name) == f".{name}"
            and value.__name__ == f"{__name__}.{name}"
        ):
            value = getattr(value, name)
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
