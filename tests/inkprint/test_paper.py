"""A photographed page rectified from its corners (inkprint.paper): exact truth from
synthetic photos of a letter page on a table, its far side shortened (keystone)."""

import csv

import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.paper import page_corners, paper_size, rectify_page
from inkprint.synth import LETTER, PrintSpec, SheetSpec, render_sheet, save_scan
from inkprint.synth_effects import Photo

DPI = 150.0  # (a letter page is 1275 x 1650 px: its size in mm exact)


def _tilted(tilt: float, *, seed: int = 3, border: float = 25.0):
    """A letter page with two prints photographed on a table, its far (top) corners
    moved in by ``tilt`` mm each (keystone 2 x tilt / 215.9); the photo (uint8) and
    the prints' truth."""
    prints = (
        PrintSpec(90.0, 30.0, (70.0, 200.0), 0.0, "ribbed"),
        PrintSpec(60.0, 45.0, (150.0, 80.0), 90.0, "mtb"),
    )
    spec = SheetSpec(prints, dpi=DPI, photo=Photo(border=border, tilt=tilt), seed=seed)
    return render_sheet(spec)


def _extents(prints) -> list:
    """Each print's (shorter, longer) extent [mm], in order (a print's rolling axis
    along y is measured with the sheet's x axis here)."""
    m = [getattr(p, "metrics", p) for p in prints]
    return sorted(sorted((q.length, q.width)) for q in m)


@pytest.mark.parametrize("tilt", [5.0, 10.0])
def test_rectify_page_keystone_photo_measures_within_half_a_percent(tilt):
    # held-out generator 6's tilted photos (keystone 4-10 %) read 6-13 % short at the
    # file's DPI and are flagged perspective; with the paper given, the page is
    # mapped back from its corners: here keystone 4.6 and 9.3 %
    img, truth = _tilted(tilt)
    scan = rectify_page(ip.Scan(img, 25.4 / DPI, "metadata"), "letter")
    assert scan.scale_source == "paper"
    rows, cols = scan.shape
    assert_allclose([cols * scan.mm_per_px, rows * scan.mm_per_px], LETTER, rtol=2e-3)
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert "perspective" not in r.flags
    assert_allclose(_extents(r.prints), _extents(truth), rtol=5e-3)


def test_analyze_scan_keystone_photo_without_paper_is_flagged_with_the_fix():
    img, _ = _tilted(10.0)
    r = ip.analyze_scan(ip.Scan(img, 25.4 / DPI, "metadata"), sensitivity=False)
    assert "perspective" in r.flags
    assert any("--paper" in w for w in r.warnings)


def test_page_corners_of_a_keystone_photo():
    img, _ = _tilted(10.0, border=25.0)
    q = page_corners(img)
    b, t = 25.0 / 25.4 * DPI, 10.0 / 25.4 * DPI
    w, h = LETTER[0] / 25.4 * DPI, LETTER[1] / 25.4 * DPI
    want = [[b + t, b], [b + w - t, b], [b + w, b + h], [b, b + h]]  # (x, y) from top-left
    assert_allclose(q, np.array(want) - 0.5, atol=1.5)


def test_rectify_page_wrong_paper_is_refused_naming_the_shapes():
    img, _ = _tilted(5.0)
    with pytest.raises(ip.InvalidInput, match=r"paper.*1\.3\d:1 in the photo, legal is 1\.65:1"):
        rectify_page(ip.Scan(img, 25.4 / DPI, "metadata"), "legal")


def test_rectify_page_scan_without_a_surround_raises_scale_missing():
    spec = SheetSpec((PrintSpec(90.0, 30.0, (100.0, 140.0)),), dpi=DPI)
    img, _ = render_sheet(spec)
    with pytest.raises(ip.ScaleMissing, match=r"no page with four corners.*--dpi"):
        rectify_page(ip.Scan(img, 25.4 / DPI, "metadata"), "letter")


@pytest.mark.parametrize(
    ("paper", "size"),
    [("A4", (210.0, 297.0)), ("letter", (215.9, 279.4)), ("297 x 210", (210.0, 297.0))],
)
def test_paper_size_names_and_dimensions(paper, size):
    assert paper_size(paper) == size


@pytest.mark.parametrize("paper", ["B7", "0x297", "wide", (210.0, -1.0)])
def test_paper_size_unknown_is_refused(paper):
    with pytest.raises(ip.InvalidInput, match="paper"):
        paper_size(paper)


def test_read_scan_paper_with_a_given_scale_is_refused(tmp_path):
    img, _ = _tilted(5.0)
    path = save_scan(img, tmp_path / "photo.png", dpi=72.0)
    with pytest.raises(ip.InvalidInput, match="paper"):
        ip.read_scan(path, paper="letter", dpi=300.0)
    # a camera's 72 dpi is no obstacle: the scale comes from the paper
    assert ip.read_scan(path, paper="letter").scale_source == "paper"


def test_cli_paper_and_manifest_column(tmp_path, capsys):
    from inkprint.cli import main

    img, truth = _tilted(8.0)
    save_scan(img, tmp_path / "photo.png", dpi=72.0)
    assert main(["analyze", str(tmp_path / "photo.png"), "--no-band", "--paper", "letter"]) == 0
    assert "perspective" not in capsys.readouterr().out
    with open(tmp_path / "manifest.csv", "w", newline="") as fh:
        csv.writer(fh).writerows([["file", "paper", "rolling_axis"], ["photo.png", "letter", "x"]])
    out = tmp_path / "rows.csv"
    args = [str(tmp_path), "--manifest", str(tmp_path / "manifest.csv"), "-o", str(out)]
    assert main(["batch", *args, "--no-band", "-q"]) == 0
    with open(out, newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["scale_source"] for r in rows] == ["paper", "paper"]
    got = sorted(sorted((float(r["length_mm"]), float(r["width_mm"]))) for r in rows)
    assert_allclose(got, _extents(truth), rtol=5e-3)


def test_batch_options_bad_paper_refused_before_any_file(tmp_path, capsys):
    from inkprint.batch import Options
    from inkprint.cli import main

    with pytest.raises(ip.InvalidInput, match="paper = 'B9'"):
        Options(paper="B9")
    # a batch-wide --paper is checked before a file is read: no table, exit 2 (a
    # manifest's bad paper is an error row of its file)
    out = tmp_path / "rows.csv"
    assert main(["batch", str(tmp_path), "-o", str(out), "--paper", "B9", "-q"]) == 2
    assert "paper = 'B9' is invalid" in capsys.readouterr().err
    assert not out.exists()
