"""Reading scans: PNG, JPEG, TIFF, BMP (8/16 bit; grey, RGB, RGBA, palette) and PDF pages.

The file is read once, into memory, and only if it is a regular file (a device, a
FIFO or a folder is refused before any byte is read: ``/dev/zero`` cannot hang the
reader). Raster images are decoded by OpenCV straight to 8-bit (or 16-bit) grey, the
format the analysis works in (no float copy of the sheet: a 1200 dpi letter page is
135 MB, not 540); RGBA, palette and unusual modes go through Pillow, transparent
pixels composited onto white paper (a naive grey conversion of RGBA with black
transparent pixels turns the sheet black).

The scale in mm per pixel comes from (in order) the caller (``dpi`` /
``mm_per_px``), the file's DPI metadata, or a PDF page's size. Metadata of 72 or 96
dpi is the default of cameras and screen software, not a scanner's resolution: it
is refused (:class:`ScaleUntrusted`, naming ``--dpi`` and ``--trust-dpi``) unless
``trust_dpi``. Without any scale, :class:`ScaleMissing`, unless ``allow_pixels``
(then 1 unit = 1 px).
"""

from __future__ import annotations

import io
import os
import stat
import warnings
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .coords import dots_per_cm_to_dpi, dpi_to_mm_per_px, mm_per_px_to_dpi, pdf_px_per_pt
from .errors import ImageTooLarge, InvalidInput, ScaleMissing, ScaleUntrusted, ScanReadError
from .options import AnalysisOptions, resolve_options

#: DPI values written by cameras and screen software when they know no resolution
DEFAULT_DPIS = (72.0, 96.0)
_WHITE = {np.dtype(np.uint8): 255.0, np.dtype(np.uint16): 65535.0, np.dtype(np.float32): 1.0}


@dataclass(frozen=True, repr=False)
class Scan:
    """A scanned sheet (one page of a file).

    Attributes
    ----------
    pixels : (rows, cols) uint8, uint16 or float32
        Grey levels, larger is lighter: paper near :attr:`white`, ink near 0.
    mm_per_px : float [mm / px]
        Scale (1.0 with ``scale_source == 'pixels'``: units are pixels).
    scale_source : str
        'given', 'metadata', 'pdf', 'paper' (a photo rectified onto its paper) or
        'pixels'.
    path : str
        File the scan was read from ('' when made in memory).
    page : int
        Page of a PDF (0-based).
    n_pages : int
        Pages in the file.
    """

    pixels: np.ndarray
    mm_per_px: float
    scale_source: str
    path: str = ""
    page: int = 0
    n_pages: int = 1

    def __post_init__(self) -> None:
        a = self.pixels
        if not isinstance(a, np.ndarray) or a.ndim != 2 or a.dtype not in _WHITE or a.size == 0:
            raise InvalidInput(
                "pixels",
                getattr(a, "shape", type(a).__name__),
                "a non-empty 2-D uint8, uint16 or float32 array",
            )
        if not (np.isfinite(self.mm_per_px) and self.mm_per_px > 0):
            raise InvalidInput("mm_per_px", self.mm_per_px, "> 0 mm per pixel")

    def __repr__(self) -> str:
        rows, cols = self.shape
        where = f"{Path(self.path).name!r}" + (f" page {self.page}" if self.n_pages > 1 else "")
        return (
            f"Scan({where if self.path else 'in memory'}, {cols} x {rows} px, "
            f"{self.mm_per_px:.4g} mm/px ({self.dpi:.0f} dpi, {self.scale_source}))"
        )

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols) [px]."""
        return self.pixels.shape

    @property
    def white(self) -> float:
        """Grey level of white: 255, 65535 or 1.0 by dtype."""
        return _WHITE[self.pixels.dtype]

    @property
    def grey(self) -> np.ndarray:
        """The whole sheet as float32 in [0, 1] (a new full-size array)."""
        return self.crop(slice(None), slice(None))

    def crop(self, rows: slice, cols: slice) -> np.ndarray:
        """A box of the sheet as float32 grey in [0, 1].

        Parameters
        ----------
        rows, cols : slice [px]

        Returns
        -------
        (h, w) float32
        """
        a = self.pixels[rows, cols]
        return a.astype(np.float32) if a.dtype == np.float32 else a * np.float32(1 / self.white)

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


def read_file_bytes(path, *, max_bytes: int | None = None) -> bytes:
    """The content of a regular file, read once (devices, FIFOs, folders refused).

    The file is opened without blocking and checked on the open descriptor, so a
    FIFO or ``/dev/zero`` is refused at once and a file swapped after a check is
    not read by mistake.

    Parameters
    ----------
    path : str or PathLike
    max_bytes : int, optional
        Refuse larger files (:class:`ImageTooLarge`).

    Returns
    -------
    bytes

    Raises
    ------
    ScanReadError
        Missing, not a regular file, unreadable or empty.
    ImageTooLarge
        Larger than ``max_bytes``.
    """
    p = Path(path)
    try:
        fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    except FileNotFoundError as exc:
        raise ScanReadError(f"{p}: no such file (or a dangling link)") from exc
    except OSError as exc:
        raise ScanReadError(f"{p}: cannot open ({exc.strerror or exc})") from exc
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise ScanReadError(
                f"{p}: not a regular file ({_kind(st.st_mode)}); only files are read"
            )
        if max_bytes is not None and st.st_size > max_bytes:
            raise ImageTooLarge(f"{p}: {st.st_size:,} bytes exceeds {max_bytes:,}")
        if st.st_size == 0:
            raise ScanReadError(f"{p}: empty file")
        with os.fdopen(fd, "rb", closefd=False) as fh:
            return fh.read()
    except OSError as exc:
        raise ScanReadError(f"{p}: cannot read ({exc.strerror or exc})") from exc
    finally:
        os.close(fd)


def _kind(mode: int) -> str:
    for test, name in (
        (stat.S_ISDIR, "a folder"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISSOCK, "a socket"),
    ):
        if test(mode):
            return name
    return "not a regular file"


def _to_grey(im) -> np.ndarray:
    """Pillow image -> grey uint8 (uint16 for 16-bit), transparency composited on white."""
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
        a = np.asarray(im)
        if mode.startswith("I;16") or a.max() > 255:
            return np.clip(a, 0, 65535).astype(np.uint16)
        return np.clip(a, 0, 255).astype(np.uint8)
    if mode == "F":
        a = np.asarray(im, dtype=np.float32)
        return np.clip(a / (a.max() or 1.0), 0, 1).astype(np.float32)
    if mode != "L":
        im = im.convert("RGB").convert("L")  # ITU-R 601-2 luma, as OpenCV's
    return np.asarray(im, dtype=np.uint8)


def _metadata_dpi(info: dict) -> float | None:
    """DPI from the image's metadata (None if absent, unusable or anisotropic)."""
    dpi = info.get("dpi")
    if dpi is None and "jfif_density" in info and info.get("jfif_unit") in (1, 2):
        d = info["jfif_density"]
        if info["jfif_unit"] == 2:
            d = (dots_per_cm_to_dpi(d[0]), dots_per_cm_to_dpi(d[1]))
        dpi = d
    if dpi is None:
        return None
    try:
        dx, dy = (float(v) for v in (dpi if isinstance(dpi, tuple | list) else (dpi, dpi)))
    except (TypeError, ValueError):
        return None
    if not (np.isfinite(dx) and dx > 0) or abs(dx - dy) > 1e-3 * dx:
        return None  # unusable or anisotropic: do not guess
    return dx


def _file_scale(p: Path, dpi: float | None, *, trust_dpi: bool, opts: AnalysisOptions):
    """Scale [mm / px] from a file's own DPI, or None if it has none usable."""
    if dpi is None or not (opts.min_dpi <= dpi <= opts.max_dpi):
        return None
    if not trust_dpi and any(abs(dpi - d) < 0.5 for d in DEFAULT_DPIS):
        raise ScaleUntrusted(
            f"{p}: the file says {dpi:g} dpi, the default of cameras and screen software, "
            f"not a scanner's resolution; give the real one with --dpi N (or --mm-per-px), "
            f"or --trust-dpi if {dpi:g} dpi is right"
        )
    return dpi_to_mm_per_px(dpi)


def read_scan(
    path,
    *,
    dpi: float | None = None,
    mm_per_px: float | None = None,
    allow_pixels: bool = False,
    trust_dpi: bool = False,
    page: int = 0,
    options: AnalysisOptions | None = None,
    data: bytes | None = None,
    paper=None,
) -> Scan:
    """Read a scan (one page) and its scale.

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
    trust_dpi : bool
        Accept 72 or 96 dpi metadata (camera and screen defaults, refused otherwise).
    page : int
        Page of a PDF (0-based).
    options : AnalysisOptions, optional
        Uses ``max_pixels``, ``min_dpi``, ``max_dpi`` and ``pdf_dpi`` (defaults when
        None).
    data : bytes, optional
        The file's content, already read (:func:`read_file_bytes`); ``path`` then
        only names it.
    paper : str or (2,) float, optional
        The sheet's paper ('A4', 'letter', 'WxH' in mm: :func:`inkprint.paper.paper_size`)
        in a photo taken at a tilt: the page is rectified from its four corners and
        its scale comes from the paper (:func:`inkprint.paper.rectify_page`); not with
        ``dpi`` or ``mm_per_px``.

    Returns
    -------
    Scan

    Raises
    ------
    ScanReadError, ImageTooLarge, ScaleMissing, ScaleUntrusted, InvalidInput
    """
    return next(
        iter_scans(
            path,
            dpi=dpi,
            mm_per_px=mm_per_px,
            allow_pixels=allow_pixels,
            trust_dpi=trust_dpi,
            pages=[page],
            options=options,
            data=data,
            paper=paper,
        )
    )


def iter_scans(
    path,
    *,
    dpi: float | None = None,
    mm_per_px: float | None = None,
    allow_pixels: bool = False,
    trust_dpi: bool = False,
    pages=None,
    options: AnalysisOptions | None = None,
    data: bytes | None = None,
    paper=None,
):
    """Every page of a file as a :class:`Scan` (a raster image has one).

    Parameters
    ----------
    path : str or PathLike
    dpi, mm_per_px, allow_pixels, trust_dpi, options, data, paper
        As for :func:`read_scan`.
    pages : sequence of int, optional
        Pages to read (0-based); default all. Only page 0 exists in a raster image.

    Yields
    ------
    Scan

    Raises
    ------
    ScanReadError, ImageTooLarge, ScaleMissing, ScaleUntrusted, InvalidInput
        (``InvalidInput`` for a page the file does not have).
    """
    opts = resolve_options(options)
    p = Path(path)
    given = _check_scale(dpi, mm_per_px, opts)
    if paper is not None:
        yield from _rectified(path, paper, given, pages=pages, options=opts, data=data)
        return
    buf = data if data is not None else read_file_bytes(p)
    if buf.startswith(b"%PDF"):
        yield from _read_pdf(p, buf, given, pages=pages, trust_dpi=trust_dpi, opts=opts)
        return
    if pages is not None and any(int(k) != 0 for k in pages):
        raise InvalidInput("page", list(pages), "0 (a raster image has one page)")
    yield _read_raster(p, buf, given, allow_pixels=allow_pixels, trust_dpi=trust_dpi, opts=opts)


def _rectified(path, paper, given, *, pages, options: AnalysisOptions, data):
    """The pages of a photo rectified onto their paper (their scale from it: the
    file's own, or a camera's default DPI, is not used)."""
    from .paper import paper_size, rectify_page

    paper_size(paper)  # (a bad name refused before the file is read)
    if given is not None:
        raise InvalidInput("paper", paper, "no scale given with it (--dpi, --mm-per-px)")
    for scan in iter_scans(
        path, allow_pixels=True, trust_dpi=True, pages=pages, options=options, data=data
    ):
        yield rectify_page(scan, paper)


def _open_header(p: Path, buf: bytes, opts: AnalysisOptions):
    """Pillow image opened lazily (header only), its size checked."""
    from PIL import Image, UnidentifiedImageError

    try:
        im = Image.open(io.BytesIO(buf))
    except (Image.DecompressionBombError, Image.DecompressionBombWarning) as exc:
        raise ImageTooLarge(f"{p}: {exc}") from exc
    except UnidentifiedImageError as exc:
        raise ScanReadError(f"{p}: not an image Pillow or OpenCV can read") from exc
    except (OSError, SyntaxError, ValueError) as exc:
        raise ScanReadError(f"{p}: cannot decode ({exc})") from exc
    w, h = im.size
    if w * h > opts.max_pixels:
        raise ImageTooLarge(f"{p}: {w} x {h} px exceeds {opts.max_pixels:,} px")
    return im


def _complete(buf: bytes, fmt: str) -> bool:
    """Whether a PNG or JPEG stream has its end marker (OpenCV may decode a truncated
    file into a partly grey image without an error)."""
    if fmt == "PNG":
        return buf.rstrip(b"\0")[-12:].startswith(b"\0\0\0\0IEND")
    if fmt == "JPEG":
        return buf.rstrip(b"\0")[-2:] == b"\xff\xd9"
    return True


def _imdecode(buf: bytes, shape: tuple[int, int], sixteen_bit: bool) -> np.ndarray | None:
    """OpenCV decode to grey, 16-bit kept with ``sixteen_bit`` (None unless ``shape``)."""
    import cv2

    flags = cv2.IMREAD_GRAYSCALE | (cv2.IMREAD_ANYDEPTH if sixteen_bit else 0)
    a = cv2.imdecode(np.frombuffer(buf, np.uint8), flags)
    return a if a is not None and a.shape == shape else None


def _decode_cv2(buf: bytes, im) -> np.ndarray | None:
    """OpenCV decode to grey for the plain modes (None: leave it to Pillow)."""
    plain = im.mode in ("L", "RGB", "I;16", "I;16B", "CMYK", "1") and "transparency" not in im.info
    if im.format not in ("PNG", "JPEG", "BMP") or not plain:
        return None
    return _imdecode(buf, (im.size[1], im.size[0]), im.mode.startswith("I;16"))


_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: (bit depth, colour type) of the grey and RGB PNGs: Pillow's modes 1, L, I;16, RGB
_PNG_PLAIN = {(1, 0), (2, 0), (4, 0), (8, 0), (16, 0), (8, 2), (16, 2)}
#: chunks that change nothing :func:`_decode` uses, with their least length (Pillow
#: refuses a shorter one)
_PNG_INERT = {b"gAMA": 4, b"cHRM": 32, b"sRGB": 1, b"tIME": 0}


def _plain_png(buf: bytes) -> tuple[int, int, bool, dict] | None:
    """Size, depth and DPI metadata of a plain PNG, read from its chunks as Pillow
    reads them (its ``info['dpi']`` from the pHYs chunk).

    Plain: grey or RGB, and before the image data only the header, pHYs and the
    chunks of :data:`_PNG_INERT`, each whole with its checksum right. Any other PNG
    (transparency, a palette, text, a colour profile, animation, a damaged chunk)
    or another format: None, for Pillow to read.

    Returns
    -------
    (width, height, sixteen_bit, info) or None
    """
    if not buf.startswith(_PNG_SIGNATURE):
        return None
    pos, head, info = len(_PNG_SIGNATURE), None, {}
    while pos + 12 <= len(buf):
        n, cid = int.from_bytes(buf[pos : pos + 4], "big"), buf[pos + 4 : pos + 8]
        if cid == b"IDAT" and head is not None:
            w, h = int.from_bytes(head[:4], "big"), int.from_bytes(head[4:8], "big")
            if (head[8], head[9]) not in _PNG_PLAIN or head[11] or not (w and h):
                return None
            return w, h, head[8:10] == b"\x10\x00", info  # 16-bit grey stays 16-bit
        data, crc = buf[pos + 8 : pos + 8 + n], buf[pos + 8 + n : pos + 12 + n]
        if len(crc) < 4 or zlib.crc32(data, zlib.crc32(cid)) != int.from_bytes(crc, "big"):
            return None
        if head is None:
            if cid != b"IHDR" or n < 13:
                return None
            head = data
        elif cid == b"pHYs" and n >= 9:
            if data[8] == 1:  # pixels per metre
                px, py = int.from_bytes(data[:4], "big"), int.from_bytes(data[4:8], "big")
                info["dpi"] = (px * 0.0254, py * 0.0254)
        elif n < _PNG_INERT.get(cid, n + 1):
            return None
        pos += 12 + n
    return None


def _decode_plain_png(buf: bytes, opts: AnalysisOptions):
    """Grey pixels and the metadata DPI of a plain PNG (:func:`_plain_png`), without
    Pillow (25 ms of imports in a 0.4 s ``inkprint analyze``); None for any other
    file, or one too large or truncated (:func:`_decode` says why)."""
    png = _plain_png(buf)
    if png is None:
        return None
    w, h, sixteen_bit, info = png
    if w * h > opts.max_pixels or not _complete(buf, "PNG"):
        return None
    grey = _imdecode(buf, (h, w), sixteen_bit)
    return None if grey is None else (grey, _metadata_dpi(info))


def _decode(p: Path, buf: bytes, opts: AnalysisOptions):
    """Grey pixels and the metadata DPI of a raster file."""
    from PIL import Image

    im = _open_header(p, buf, opts)
    meta = _metadata_dpi(im.info)
    if not _complete(buf, im.format):
        raise ScanReadError(f"{p}: truncated {im.format} file (no end marker)")
    grey = _decode_cv2(buf, im)
    if grey is not None:
        return grey, meta
    try:
        im.load()
        return _to_grey(im), meta
    except (Image.DecompressionBombError, Image.DecompressionBombWarning) as exc:
        raise ImageTooLarge(f"{p}: {exc}") from exc
    except (OSError, SyntaxError, ValueError) as exc:
        raise ScanReadError(f"{p}: cannot decode ({exc})") from exc


def _decode_with_pillow(p: Path, buf: bytes, opts: AnalysisOptions):
    """:func:`_decode` with Pillow's pixel limit at ``opts.max_pixels``, an error."""
    from PIL import Image

    old = Image.MAX_IMAGE_PIXELS
    Image.MAX_IMAGE_PIXELS = opts.max_pixels
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", Image.DecompressionBombWarning)
            return _decode(p, buf, opts)
    finally:
        Image.MAX_IMAGE_PIXELS = old


def _read_raster(
    p: Path, buf: bytes, given, *, allow_pixels: bool, trust_dpi: bool, opts: AnalysisOptions
) -> Scan:
    """A raster image with the given, metadata or no scale."""
    decoded = _decode_plain_png(buf, opts)  # the common scan, without Pillow
    grey, meta = decoded if decoded is not None else _decode_with_pillow(p, buf, opts)
    if given is not None:
        return Scan(grey, given, "given", str(p))
    scale = _file_scale(p, meta, trust_dpi=trust_dpi, opts=opts)
    if scale is not None:
        return Scan(grey, scale, "metadata", str(p))
    if allow_pixels:
        return Scan(grey, 1.0, "pixels", str(p))
    why = "no DPI in the file" if meta is None else f"its {meta:g} dpi is implausible"
    raise ScaleMissing(f"{p}: {why}; give --dpi or --mm-per-px (or --pixels)")


def _pdf_page_dpi(pg) -> float | None:
    """Resolution of a page that is one scanned image (None otherwise)."""
    import pypdfium2.raw as pdfium_c

    w_pt, _ = pg.get_size()
    images = [o for o in pg.get_objects() if o.type == pdfium_c.FPDF_PAGEOBJ_IMAGE]
    if len(images) != 1:
        return None
    left, _, right, _ = images[0].get_bounds()
    if right - left < 0.9 * w_pt:
        return None
    return images[0].get_px_size()[0] / ((right - left) / 72.0)


def _read_pdf(p: Path, buf: bytes, given, *, pages, trust_dpi: bool, opts: AnalysisOptions):
    """PDF pages rendered at the given scale, else at the embedded scan's own."""
    import pypdfium2 as pdfium

    try:
        doc = pdfium.PdfDocument(buf)
    except Exception as exc:  # pdfium raises its own PdfiumError
        raise ScanReadError(f"{p}: cannot open PDF ({exc})") from exc
    try:
        n = len(doc)
        wanted = range(n) if pages is None else [int(k) for k in pages]
        bad = [k for k in wanted if not 0 <= k < n]
        if bad:
            raise InvalidInput("page", bad[0], f"0 .. {n - 1} (the file has {n} pages)")
        for k in wanted:
            yield _render_page(p, doc[k], k, n, given, trust_dpi=trust_dpi, opts=opts)
    finally:
        doc.close()


def _render_page(p: Path, pg, k: int, n: int, given, *, trust_dpi: bool, opts: AnalysisOptions):
    """One PDF page as a Scan."""
    w_pt, h_pt = pg.get_size()
    native = _pdf_page_dpi(pg)
    if given is None and native is not None:
        _file_scale(p, native, trust_dpi=trust_dpi, opts=opts)  # refuses 72/96 dpi scans
    dpi = native if native is not None and opts.min_dpi <= native <= opts.max_dpi else opts.pdf_dpi
    mm = given if given is not None else dpi_to_mm_per_px(dpi)
    scale = pdf_px_per_pt(mm)
    if w_pt * h_pt * scale * scale > opts.max_pixels:
        raise ImageTooLarge(
            f"{p}: page {k} at {mm_per_px_to_dpi(mm):.0f} dpi exceeds {opts.max_pixels:,} px"
        )
    try:
        grey = pg.render(scale=scale, grayscale=True).to_numpy()
    except Exception as exc:
        raise ScanReadError(f"{p}: cannot render PDF page {k} ({exc})") from exc
    grey = np.ascontiguousarray(grey.reshape(grey.shape[:2]) if grey.ndim == 3 else grey)
    return Scan(grey.astype(np.uint8, copy=False), mm, "given" if given else "pdf", str(p), k, n)


def page_count(path, *, data: bytes | None = None) -> int:
    """Pages in a file (1 for a raster image).

    Parameters
    ----------
    path : str or PathLike
    data : bytes, optional
        The content, already read.

    Returns
    -------
    int
    """
    buf = data if data is not None else read_file_bytes(path)
    if not buf.startswith(b"%PDF"):
        return 1
    import pypdfium2 as pdfium

    try:
        doc = pdfium.PdfDocument(buf)
    except Exception as exc:
        raise ScanReadError(f"{path}: cannot open PDF ({exc})") from exc
    try:
        return len(doc)
    finally:
        doc.close()


__all__ = ["DEFAULT_DPIS", "Scan", "iter_scans", "page_count", "read_file_bytes", "read_scan"]
