"""Reading scans (issue 4 item 1): formats, DPI, bad files."""

import struct
import zlib

import numpy as np
import pytest
from numpy.testing import assert_allclose
from PIL import Image

import inkprint as ip


def _sheet(mode="L"):
    a = np.full((60, 80), 240, np.uint8)
    a[20:40, 30:50] = 20
    return a


@pytest.mark.parametrize(
    ("mode", "suffix"),
    [
        ("L", ".png"),
        ("RGB", ".png"),
        ("P", ".png"),
        ("L", ".jpg"),
        ("RGB", ".tif"),
        ("I;16", ".tif"),
        ("L", ".pdf"),
    ],
)
def test_read_scan_formats_and_dpi(tmp_path, mode, suffix):
    a = _sheet()
    im = Image.fromarray(a)
    if mode == "RGB":
        im = im.convert("RGB")
    elif mode == "P":
        im = im.convert("P")
    elif mode == "I;16":
        im = Image.fromarray(a.astype(np.uint16) * 257)
    path = tmp_path / f"s{suffix}"
    if suffix == ".pdf":
        im.save(path, resolution=200.0)
    else:
        im.save(path, dpi=(200, 200))
    scan = ip.read_scan(path, dpi=200 if suffix == ".pdf" else None)
    assert scan.grey.dtype == np.float32 and 0 <= scan.grey.min() and scan.grey.max() <= 1
    assert_allclose(scan.mm_per_px, 25.4 / 200, rtol=1e-5)  # PNG stores pixels per metre
    assert abs(scan.grey.shape[0] - 60) <= 1 and scan.grey.shape[1] == 80  # PDF pages round up
    assert scan.grey[30, 40] < 0.2 < 0.8 < scan.grey[5, 5]


def test_read_scan_pdf_without_dpi_uses_page_size(tmp_path):
    # a page holding one scanned image is rendered at the image's own resolution
    Image.fromarray(_sheet()).save(tmp_path / "s.pdf", resolution=100.0)
    scan = ip.read_scan(tmp_path / "s.pdf")
    assert scan.scale_source == "pdf"
    assert abs(scan.grey.shape[0] - 60) <= 1 and scan.grey.shape[1] == 80  # pages round up
    assert_allclose(scan.mm_per_px, 25.4 / 100, rtol=1e-6)
    # a vector page (no single image) is rendered at AnalysisOptions.pdf_dpi
    import pypdfium2 as pdfium

    doc = pdfium.PdfDocument.new()
    doc.new_page(72.0, 36.0)  # 1 x 0.5 inch, blank
    doc.save(tmp_path / "v.pdf")
    assert ip.read_scan(tmp_path / "v.pdf").grey.shape == (150, 300)  # 300 dpi


def test_read_scan_rgba_transparent_black_is_paper(tmp_path):
    # field notes: RGBA whose transparent pixels are black must not turn all black
    rgba = np.zeros((60, 80, 4), np.uint8)
    rgba[20:40, 30:50] = (10, 10, 10, 255)
    Image.fromarray(rgba, "RGBA").save(tmp_path / "a.png", dpi=(150, 150))
    scan = ip.read_scan(tmp_path / "a.png")
    assert scan.grey[0, 0] == pytest.approx(1.0) and scan.grey[30, 40] < 0.1


def test_read_scan_scale_given_or_missing(tmp_path):
    Image.fromarray(_sheet()).save(tmp_path / "n.png")
    with pytest.raises(ip.ScaleMissing, match="--dpi"):
        ip.read_scan(tmp_path / "n.png")
    assert ip.read_scan(tmp_path / "n.png", allow_pixels=True).unit == "px"
    assert ip.read_scan(tmp_path / "n.png", mm_per_px=0.1726).mm_per_px == 0.1726
    with pytest.raises(ip.InvalidInput, match="dpi"):
        ip.read_scan(tmp_path / "n.png", dpi=-3)
    with pytest.raises(ip.InvalidInput, match="dpi/mm_per_px"):
        ip.read_scan(tmp_path / "n.png", dpi=150, mm_per_px=0.2)


def test_read_scan_bad_files(tmp_path, monkeypatch):
    (tmp_path / "empty.png").write_bytes(b"")
    with pytest.raises(ip.ScanReadError, match="empty"):
        ip.read_scan(tmp_path / "empty.png", dpi=150)
    (tmp_path / "text.png").write_text("not an image at all")
    with pytest.raises(ip.ScanReadError, match="not an image"):
        ip.read_scan(tmp_path / "text.png", dpi=150)
    Image.fromarray(_sheet()).save(tmp_path / "ok.png")
    data = (tmp_path / "ok.png").read_bytes()
    (tmp_path / "trunc.png").write_bytes(data[: len(data) // 2])
    with pytest.raises(ip.ScanReadError):
        ip.read_scan(tmp_path / "trunc.png", dpi=150)
    with pytest.raises(ip.ScanReadError, match="no such file"):
        ip.read_scan(tmp_path / "missing.png", dpi=150)
    (tmp_path / "bad.pdf").write_bytes(b"%PDF-1.4 garbage")
    with pytest.raises(ip.ScanReadError, match="PDF"):
        ip.read_scan(tmp_path / "bad.pdf", dpi=150)


def test_read_scan_huge_dimensions_is_refused_before_decoding(tmp_path):
    # a PNG whose header claims 100000 x 100000 pixels (a decompression bomb)
    def chunk(kind, body):
        return (
            struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
        )

    png = b"\x89PNG\r\n\x1a\n" + chunk(
        b"IHDR", struct.pack(">IIBBBBB", 100000, 100000, 8, 0, 0, 0, 0)
    )
    png += chunk(b"IDAT", zlib.compress(b"\x00" * 1000)) + chunk(b"IEND", b"")
    (tmp_path / "bomb.png").write_bytes(png)
    with pytest.raises(ip.ImageTooLarge, match="exceeds"):
        ip.read_scan(tmp_path / "bomb.png", dpi=150)


def test_coords_pixel_to_mm_conversions_only_in_coords():
    # issue 9 item 6: pixel <-> mm conversion lives in inkprint.coords only; a scale
    # multiplied or divided inline elsewhere is a second definition that can drift
    import re
    from pathlib import Path

    from inkprint.coords import binned_mm_per_px, mm_to_px_length, px_to_mm_length

    pat = re.compile(r"[*/]\s*\(?\s*(?:\w+\.)*(?:px_mm|mm_per_px)\b(?!\s*=)")
    pkg = Path(ip.__file__).parent
    hits = [
        f"{p.name}:{i}: {line.strip()}"
        for p in sorted(pkg.glob("*.py"))
        if p.name != "coords.py"
        for i, line in enumerate(p.read_text().splitlines(), 1)
        if pat.search(re.sub(r"\"[^\"]*\"", '""', line.split("#")[0]))
    ]
    assert not hits, hits
    assert binned_mm_per_px(0.1, 4) == pytest.approx(0.4, rel=1e-12)
    assert px_to_mm_length(mm_to_px_length(3.0, 0.0847), 0.0847) == pytest.approx(3.0, rel=1e-12)


def _png_chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def _png_bytes(tmp_path, mode="L", extra=(), **save):
    """A PNG saved by Pillow, ``extra`` chunks put right after its header."""
    a = _sheet()
    im = {
        "L": lambda: Image.fromarray(a),
        "RGB": lambda: Image.fromarray(a).convert("RGB"),
        "P": lambda: Image.fromarray(a).convert("P"),
        "1": lambda: Image.fromarray(a).convert("1"),
        "I;16": lambda: Image.fromarray(a.astype(np.uint16) * 257),
    }[mode]()
    im.save(tmp_path / "s.png", **save)
    data = (tmp_path / "s.png").read_bytes()
    return data[:33] + b"".join(extra) + data[33:]  # signature 8 + IHDR 25 bytes


GAMA = _png_chunk(b"gAMA", struct.pack(">I", 45455))
ASPECT = _png_chunk(b"pHYs", struct.pack(">IIB", 3, 2, 0))
NOTES = (GAMA, _png_chunk(b"sRGB", b"\0"), _png_chunk(b"tIME", bytes(7)), ASPECT)


@pytest.mark.parametrize(
    ("mode", "extra", "save", "plain"),
    [
        ("L", (), {"dpi": (300, 300)}, True),
        ("L", (), {}, True),
        ("RGB", (), {"dpi": (200, 200)}, True),
        ("I;16", (), {"dpi": (600, 600)}, True),
        ("1", (), {"dpi": (150, 150)}, True),
        ("L", NOTES, {"dpi": (300, 300)}, True),
        ("L", (ASPECT,), {}, True),
        ("L", (), {"dpi": (300, 300), "transparency": 0}, False),
        ("P", (), {"dpi": (300, 300)}, False),
        ("L", (_png_chunk(b"tEXt", b"dpi\x0072"),), {}, False),
        ("L", (_png_chunk(b"iCCP", b"p\0\0" + zlib.compress(b"x")),), {}, False),
    ],
)
def test_plain_png_is_read_as_pillow_reads_it(tmp_path, mode, extra, save, plain):
    # a plain PNG (grey or RGB, no transparency, text or profile) is read without
    # Pillow: the same pixels and DPI metadata as through Pillow; any other goes to it
    from inkprint import read
    from inkprint.options import resolve_options

    opts = resolve_options(None)
    buf = _png_bytes(tmp_path, mode, extra, **save)
    fast = read._decode_plain_png(buf, opts)
    grey, meta = read._decode_with_pillow(tmp_path / "s.png", buf, opts)
    assert (fast is not None) == plain
    if plain:
        assert fast[0].dtype == grey.dtype and np.array_equal(fast[0], grey)
        assert fast[1] == meta


@pytest.mark.parametrize(
    "extra",
    [
        (GAMA[:-1] + bytes([GAMA[-1] ^ 1]),),  # a wrong checksum
        (_png_chunk(b"gAMA", b"\0\0"),),  # too short
        (_png_chunk(b"pHYs", b"\0\0\0\1"),),  # too short
        (_png_chunk(b"IHDR", bytes(13)),),  # a second header
    ],
)
def test_damaged_plain_png_is_left_to_pillow(tmp_path, extra):
    from inkprint import read
    from inkprint.options import resolve_options

    opts = resolve_options(None)
    buf = _png_bytes(tmp_path, "L", extra, dpi=(300, 300))
    assert read._decode_plain_png(buf, opts) is None
    assert read._decode_plain_png(buf[:-12], opts) is None  # no IEND
    assert read._decode_plain_png(buf[:40], opts) is None


def test_plain_png_needs_no_pillow(tmp_path):
    # the speed of one `inkprint analyze` on a PNG scan: Pillow's imports are 25 ms
    import subprocess
    import sys

    (tmp_path / "s.png").write_bytes(_png_bytes(tmp_path, "L", dpi=(300, 300)))
    code = (
        "import sys, inkprint as ip; s = ip.read_scan(sys.argv[1]); "
        "assert round(s.dpi) == 300 and 'PIL' not in sys.modules, sorted(sys.modules)"
    )
    subprocess.run([sys.executable, "-c", code, str(tmp_path / "s.png")], check=True)
