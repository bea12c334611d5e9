"""Reading scans: PNG, JPEG, TIFF (8/16 bit; grey, RGB, RGBA, palette) and PDF pages.

The result is a grey image in [0, 1] (1 = white paper, 0 = black ink) and a scale
in mm per pixel, taken from (in order) the caller (``dpi`` / ``mm_per_px``), the
file's DPI metadata, or the PDF's page size. Without any scale, a
:class:`ScaleMissing` error, unless ``allow_pixels`` (then 1 unit = 1 px).
Transparent pixels are composited onto white paper (a naive grey conversion of
RGBA with black transparent pixels turns the sheet black).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .coords import dots_per_cm_to_dpi, dpi_to_mm_per_px, mm_per_px_to_dpi, pdf_px_per_pt
from .errors import ImageTooLarge, InvalidInput, ScaleMissing, ScanReadError
from .options import AnalysisOptions, resolve_options

RASTER = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp"}


@dataclass(frozen=True)
class Scan:
    """A scanned sheet.

    Attributes
    ----------
    grey : (rows, cols) float32 in [0, 1]
        1 = white paper, 0 = black ink.
    mm_per_px : float [mm / px]
        Scale (1.0 with ``scale_source == 'pixels'``: units are pixels).
    scale_source : str
        'given', 'metadata', 'pdf' or 'pixels'.
    path : str
        File the scan was read from ('' when made in memory).
    page : int
        Page of a PDF (0-based).
    """

    grey: np.ndarray
    mm_per_px: float
    scale_source: str
    path: str = ""
    page: int = 0

    @property
    def dpi(self) -> float:
        """Resolution [dots per inch]."""
        return mm_per_px_to_dpi(self.mm_per_px)

    @property
    def unit(self) -> str:
        """Unit of lengths measured on this scan: 'mm', or 'px' without a scale."""
        return "px" if self.scale_source == "pixels" else "mm"


def _check_scale(dpi, mm_per_px, opts: AnalysisOptions) -> float | None:
    """The scale given by the caller [mm / px], or None."""
    if dpi is not None and mm_per_px is not None:
        raise InvalidInput("dpi/mm_per_px", (dpi, mm_per_px), "at most one of the two")
    if dpi is not None:
        dpi = float(dpi)
        if not (np.isfinite(dpi) and opts.min_dpi <= dpi <= opts.max_dpi):
            raise InvalidInput("dpi", dpi, f"[{opts.min_dpi:g}, {opts.max_dpi:g}]")
        return dpi_to_mm_per_px(dpi)
    if mm_per_px is not None:
        s = float(mm_per_px)
        lo, hi = dpi_to_mm_per_px(opts.max_dpi), dpi_to_mm_per_px(opts.min_dpi)
        if not (np.isfinite(s) and lo <= s <= hi):
            raise InvalidInput("mm_per_px", s, f"[{lo:.4g}, {hi:.4g}] mm per pixel")
        return s
    return None


def _to_grey(im) -> np.ndarray:
    """Pillow image -> float32 grey in [0, 1], transparency composited on white."""
    from PIL import Image

    mode = im.mode
    if mode == "P":
        im = im.convert("RGBA" if "transparency" in im.info else "RGB")
        mode = im.mode
    if mode in ("RGBA", "LA", "PA") or (mode == "RGB" and "transparency" in im.info):
        rgba = im.convert("RGBA")
        white = Image.new("RGBA", rgba.size, (255, 255, 255, 255))
        im = Image.alpha_composite(white, rgba).convert("RGB")
        mode = "RGB"
    if mode in ("I;16", "I;16B", "I;16L", "I;16N", "I"):
        a = np.asarray(im, dtype=np.float64)
        top = 65535.0 if mode.startswith("I;16") or a.max() > 255 else 255.0
        return np.clip(a / top, 0, 1).astype(np.float32)
    if mode == "F":
        a = np.asarray(im, dtype=np.float64)
        return np.clip(a / (a.max() or 1.0), 0, 1).astype(np.float32)
    if mode == "1":
        return np.asarray(im, dtype=np.float32)
    if mode == "CMYK":
        im = im.convert("RGB")
    if mode in ("RGB", "YCbCr", "CMYK", "LAB", "HSV"):
        im = im.convert("RGB")
        a = np.asarray(im, dtype=np.float32) / 255.0
        return (0.299 * a[..., 0] + 0.587 * a[..., 1] + 0.114 * a[..., 2]).astype(np.float32)
    return (np.asarray(im.convert("L"), dtype=np.float32) / 255.0).astype(np.float32)


def _metadata_mm_per_px(im, opts: AnalysisOptions) -> float | None:
    """Scale from the image's DPI metadata [mm / px], or None if absent or implausible."""
    dpi = im.info.get("dpi")
    if dpi is None and "jfif_density" in im.info and im.info.get("jfif_unit") in (1, 2):
        d = im.info["jfif_density"]
        if im.info["jfif_unit"] == 2:
            d = (dots_per_cm_to_dpi(d[0]), dots_per_cm_to_dpi(d[1]))
        dpi = d
    if dpi is None:
        return None
    try:
        dx, dy = (float(v) for v in (dpi if isinstance(dpi, tuple | list) else (dpi, dpi)))
    except (TypeError, ValueError):
        return None
    if not (opts.min_dpi <= dx <= opts.max_dpi) or abs(dx - dy) > 1e-3 * dx:
        return None  # implausible or anisotropic: do not guess
    return dpi_to_mm_per_px(dx)


def read_scan(
    path,
    *,
    dpi: float | None = None,
    mm_per_px: float | None = None,
    allow_pixels: bool = False,
    page: int = 0,
    options: AnalysisOptions | None = None,
) -> Scan:
    """Read a scan and its scale.

    Parameters
    ----------
    path : str or PathLike
        PNG, JPEG, TIFF, BMP or PDF file.
    dpi : float, optional [dots per inch]
        Scale given explicitly (overrides the file's metadata).
    mm_per_px : float, optional [mm / px]
        Scale given explicitly; at most one of ``dpi`` and ``mm_per_px``.
    allow_pixels : bool
        Without any scale, measure in pixels instead of raising ScaleMissing.
    page : int
        Page of a PDF (0-based).
    options : AnalysisOptions, optional
        Uses ``max_pixels``, ``min_dpi``, ``max_dpi`` and ``pdf_dpi`` (defaults when
        None).

    Returns
    -------
    Scan
        ``grey`` is (rows, cols) float32 in [0, 1]; ``mm_per_px`` [mm / px].

    Raises
    ------
    ScanReadError, ImageTooLarge, ScaleMissing, InvalidInput
    """
    opts = resolve_options(options)
    p = Path(path)
    given = _check_scale(dpi, mm_per_px, opts)
    if not p.is_file():
        raise ScanReadError(f"{p}: no such file")
    if p.stat().st_size == 0:
        raise ScanReadError(f"{p}: empty file")
    with p.open("rb") as fh:
        head = fh.read(8)
    if head.startswith(b"%PDF"):
        return _read_pdf(p, given, page=page, opts=opts)
    return _read_raster(p, given, allow_pixels=allow_pixels, opts=opts)


def _read_raster(p: Path, given, *, allow_pixels: bool, opts: AnalysisOptions) -> Scan:
    """A raster image (Pillow) with the given, metadata or no scale."""
    from PIL import Image, UnidentifiedImageError

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", Image.DecompressionBombWarning)
            old = Image.MAX_IMAGE_PIXELS
            Image.MAX_IMAGE_PIXELS = opts.max_pixels
            try:
                with Image.open(p) as im:
                    w, h = im.size
                    if w * h > opts.max_pixels:
                        raise ImageTooLarge(f"{p}: {w} x {h} px exceeds {opts.max_pixels:,} px")
                    im.load()
                    meta = _metadata_mm_per_px(im, opts)
                    grey = _to_grey(im)
            finally:
                Image.MAX_IMAGE_PIXELS = old
    except (Image.DecompressionBombError, Image.DecompressionBombWarning) as exc:
        raise ImageTooLarge(f"{p}: {exc}") from exc
    except UnidentifiedImageError as exc:
        raise ScanReadError(f"{p}: not an image Pillow can read") from exc
    except (OSError, SyntaxError, ValueError) as exc:
        if isinstance(exc, ImageTooLarge):
            raise
        raise ScanReadError(f"{p}: cannot decode ({exc})") from exc
    if given is not None:
        return Scan(grey, given, "given", str(p))
    if meta is not None:
        return Scan(grey, meta, "metadata", str(p))
    if allow_pixels:
        return Scan(grey, 1.0, "pixels", str(p))
    raise ScaleMissing(f"{p}: no DPI in the file; give --dpi or --mm-per-px (or --pixels)")


def _read_pdf(p: Path, given, *, page: int, opts: AnalysisOptions) -> Scan:
    """One PDF page rendered at the given scale, else at ``opts.pdf_dpi``."""
    import pypdfium2 as pdfium

    try:
        doc = pdfium.PdfDocument(str(p))
    except Exception as exc:  # pdfium raises its own PdfiumError
        raise ScanReadError(f"{p}: cannot open PDF ({exc})") from exc
    try:
        if not 0 <= page < len(doc):
            raise InvalidInput("page", page, f"0 .. {len(doc) - 1}")
        pg = doc[page]
        w_pt, h_pt = pg.get_size()
        mm = given if given is not None else dpi_to_mm_per_px(opts.pdf_dpi)
        scale = pdf_px_per_pt(mm)
        if w_pt * h_pt * scale * scale > opts.max_pixels:
            raise ImageTooLarge(
                f"{p}: page {page} at {mm_per_px_to_dpi(mm):.0f} dpi exceeds {opts.max_pixels:,} px"
            )
        im = pg.render(scale=scale, grayscale=True).to_pil()
        grey = _to_grey(im)
    except (InvalidInput, ImageTooLarge):
        raise
    except Exception as exc:
        raise ScanReadError(f"{p}: cannot render PDF page {page} ({exc})") from exc
    finally:
        doc.close()
    return Scan(grey, mm, "given" if given is not None else "pdf", str(p), page)
