"""Batch runs (issue 4 item 7): broken files, resume, atomic outputs, Dask."""

import csv
import json
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from inkprint.batch import Options, run_batch
from inkprint.synth import drum_and_plate_sheet, render_sheet, save_scan

SAMPLES = Path(__file__).resolve().parents[2] / "assets" / "prints"


def read_rows(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


@pytest.fixture
def folder(tmp_path):
    d = tmp_path / "scans"
    d.mkdir()
    for i in range(3):
        img, _ = render_sheet(
            drum_and_plate_sheet(tire_radius=12.0, load=300 + 50 * i, pressure=0.5, seed=i)
        )
        save_scan(img, d / f"ok{i}.png", dpi=150)
    (d / "empty.png").write_bytes(b"")
    (d / "text.jpg").write_text("hello")
    good = (d / "ok0.png").read_bytes()
    (d / "trunc.png").write_bytes(good[: len(good) // 3])
    img, _ = render_sheet(drum_and_plate_sheet(tire_radius=12.0, load=300, pressure=0.5))
    save_scan(img, d / "noscale.png", dpi=150)
    from PIL import Image

    Image.open(d / "noscale.png").save(d / "noscale.png")  # drop the DPI
    Image.new("L", (400, 500), 250).save(d / "blank.png", dpi=(150, 150))
    Image.new("L", (400, 500), 5).save(d / "black.png", dpi=(150, 150))
    return d


def test_batch_broken_files_become_error_rows_and_resume(folder, tmp_path):
    out = tmp_path / "res.csv"
    res = run_batch(folder, out, options=Options(sensitivity=False), workers=2, progress=False)
    rows = read_rows(out)
    by_file = {}
    for r in rows:
        by_file.setdefault(Path(r["file"]).name, []).append(r)
    assert {r["status"] for r in by_file["ok1.png"]} == {"ok"} and len(by_file["ok1.png"]) == 2
    for bad, what in [
        ("empty.png", "ScanReadError"),
        ("text.jpg", "ScanReadError"),
        ("trunc.png", "ScanReadError"),
        ("noscale.png", "ScaleMissing"),
        ("blank.png", "NoInk"),
        ("black.png", "NoInk"),
    ]:
        (row,) = by_file[bad]
        assert row["status"] == "error" and row["error"].startswith(what), row
    assert res.n_errors == 6 and res.n_files == 9
    assert json.loads(out.with_suffix(".json").read_text()) and len(
        json.loads(out.with_suffix(".json").read_text())
    ) == len(rows)
    # a second run skips everything already done (same run key) and keeps the rows;
    # a file that could not be read at all (empty.png) is tried again
    again = run_batch(folder, out, options=Options(sensitivity=False), workers=1, progress=False)
    assert again.n_skipped == 8 and read_rows(out) == rows
    # a renamed copy reuses the rows of its content; a changed file is analysed again
    shutil.copy(folder / "ok2.png", folder / "copy.png")
    img, _ = render_sheet(drum_and_plate_sheet(tire_radius=14.0, load=500, pressure=0.4, seed=9))
    save_scan(img, folder / "ok0.png", dpi=150)
    third = run_batch(folder, out, options=Options(sensitivity=False), workers=1, progress=False)
    assert third.n_skipped == 8 and third.n_files == 10
    new = read_rows(out)
    copy = [r for r in new if r["file"].endswith("copy.png")]
    orig = [r for r in new if r["file"].endswith("ok2.png")]
    assert [r["length_mm"] for r in copy] == [r["length_mm"] for r in orig]
    ok0 = [r for r in new if r["file"].endswith("ok0.png")]
    assert len(ok0) == 2 and ok0[0]["sha256"] != by_file["ok0.png"][0]["sha256"]


def test_batch_manifest_columns_carried_through(tmp_path):
    out = tmp_path / "res.csv"
    run_batch(
        None,
        out,
        manifest=SAMPLES / "manifest.csv",
        options=Options(sensitivity=False),
        workers=2,
        progress=False,
    )
    rows = read_rows(out)
    manifest = read_rows(SAMPLES / "manifest.csv")
    assert len(rows) == len(manifest)
    for r in rows:
        m = next(m for m in manifest if m["file"] == r["file"] and m["print"] == r["print"])
        for k in ("tire", "pressure_bar", "load_N", "surface"):
            assert r[k] == m[k]
        # a label next to a print may flag it (a judgement, section 7.1.1)
        assert r["status"] == "ok" or (r["status"] == "flagged" and r["flags"] == "mark_on_edge")
        assert 90 < float(r["load_per_hull_area_pct"]) < 120  # Figure 4-3: close to 100 %


def test_bundled_samples_measure_within_the_bar_or_are_flagged(tmp_path):
    # issue 11: tire08_4bar_500N #0 read 2.4 % short (a tip block dropped as an edge
    # spot) and the tire06 prints up to 1.3 % wide (the images were drawn 0.4 px wider
    # than their truth; redrawn with centre-sampled edges, truth.csv unchanged)
    out = tmp_path / "res.csv"
    opts = Options(sensitivity=False)
    run_batch(None, out, manifest=SAMPLES / "manifest.csv", options=opts, progress=False)
    truth = read_rows(SAMPLES / "truth.csv")
    for r in read_rows(out):
        if r["status"] != "ok":
            continue
        t = next(t for t in truth if t["file"] == r["file"] and t["print"] == r["print"])
        for k in ("length_mm", "width_mm"):
            assert abs(float(r[k]) / float(t[k]) - 1) < 0.01, (r["file"], r["print"], k)


def test_batch_killed_midway_leaves_complete_outputs(tmp_path):
    src = tmp_path / "many"
    src.mkdir()
    img, _ = render_sheet(drum_and_plate_sheet(tire_radius=12.0, load=400, pressure=0.5))
    for i in range(14):
        save_scan(img[i:], src / f"s{i:02d}.png", dpi=150)  # distinct content
    out = tmp_path / "res.csv"
    code = (
        f"from inkprint.batch import run_batch, Options; "
        f"run_batch({str(src)!r}, {str(out)!r}, options=Options(), workers=1, progress=False, "
        f"checkpoint_seconds=0.0)"
    )
    proc = subprocess.Popen([sys.executable, "-c", code])
    deadline = time.time() + 120
    while not out.exists() and time.time() < deadline and proc.poll() is None:
        time.sleep(0.02)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    rows = read_rows(out)  # parses: never half-written
    assert 0 < len(rows) < 28
    assert json.loads(out.with_suffix(".json").read_text()) is not None
    assert all(r["status"] in ("ok", "flagged") for r in rows)  # complete rows, no errors
    # the lock died with the process: a new batch with the same options resumes
    res = run_batch(src, out, options=Options(), workers=2, progress=False)
    assert res.n_skipped == len({r["sha256"] for r in rows}) and len(read_rows(out)) == 28


def test_batch_on_dask_local_cluster_equals_local(tmp_path):
    from dask.distributed import LocalCluster

    files = sorted(SAMPLES.glob("*.jpg"))[:3]
    src = tmp_path / "src"
    src.mkdir()
    for f in files:
        shutil.copy(f, src / f.name)
    local = run_batch(
        src, tmp_path / "local.csv", options=Options(sensitivity=False), workers=1, progress=False
    )
    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster:
        remote = run_batch(
            src,
            tmp_path / "dask.csv",
            options=Options(sensitivity=False),
            scheduler=cluster.scheduler_address,
            progress=False,
        )
    assert read_rows(tmp_path / "local.csv") == read_rows(tmp_path / "dask.csv")
    assert len(remote.rows) == len(local.rows) == 6


def test_cli_analyze_and_batch(folder, tmp_path):
    ok = folder / "ok1.png"
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "inkprint.cli",
            "analyze",
            str(ok),
            "--load",
            "350N",
            "--pressure",
            "5bar",
            "--overlay",
            str(tmp_path / "ov"),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.count("#") == 2 and "% of inflation" in proc.stdout
    assert len(list((tmp_path / "ov").glob("ok1_png_*_p0_overlay.png"))) == 1
    bad = subprocess.run(
        [sys.executable, "-m", "inkprint.cli", "analyze", str(folder / "empty.png")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert bad.returncode == 1 and "empty file" in bad.stderr and "Traceback" not in bad.stderr
    assert "1 of 1 file(s)" in bad.stderr and not bad.stdout
    csv_out = subprocess.run(
        [sys.executable, "-m", "inkprint.cli", "analyze", str(ok), "--csv", "--no-band"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert len(list(csv.DictReader(csv_out.stdout.splitlines()))) == 2
    b = subprocess.run(
        [
            sys.executable,
            "-m",
            "inkprint.cli",
            "batch",
            str(folder),
            "-o",
            str(tmp_path / "b.csv"),
            "--workers",
            "2",
            "--quiet",
            "--no-band",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert b.returncode == 1, b.stderr  # some files failed
    assert "6 error row(s)" in b.stderr and not b.stdout and (tmp_path / "b.json").is_file()


def test_run_batch_records_an_unexpected_failure_and_goes_on(tmp_path, monkeypatch):
    # a bug on one file (an OverflowError in the line sorting once) aborted the whole
    # batch; now that file's row says so and the other files are analysed
    import inkprint.analyze

    src = tmp_path / "src"
    src.mkdir()
    files = sorted(SAMPLES.glob("*.jpg"))[:2]
    for f in files:
        shutil.copy(f, src / f.name)
    real = inkprint.analyze.analyze_scan

    def flaky(scan, **kw):
        if str(scan.path).endswith(files[0].name):
            raise OverflowError("cannot convert float infinity to integer")
        return real(scan, **kw)

    monkeypatch.setattr(inkprint.analyze, "analyze_scan", flaky)
    res = run_batch(src, tmp_path / "out.csv", options=Options(sensitivity=False), workers=1)
    bad = [r for r in res.rows if r["status"] == "error"]
    assert [Path(r["file"]).name for r in bad] == [files[0].name]
    assert bad[0]["error"].startswith("internal error (OverflowError: cannot convert")
    good = [r for r in res.rows if Path(r["file"]).name == files[1].name]
    assert good and all(r["status"] in ("ok", "flagged") for r in good)


def test_batch_manifest_page_rows_set_each_pages_rolling_axis(tmp_path):
    # a PDF of two tires: page 0 rolls along x, page 1 along y (a print 20 x 50 mm on
    # the sheet: 50 mm long). The manifest's per-page rows give each page's axis;
    # the first row's axis was used for every page: page 1's length and width swapped
    from inkprint.synth import PrintSpec, SheetSpec

    pages, truths = [], []
    for angle in (0.0, 90.0):
        img, (t,) = render_sheet(
            SheetSpec((PrintSpec(50.0, 20.0, (100.0, 130.0), angle, "slick"),), dpi=150.0)
        )
        pages.append(img)
        truths.append(t)
    save_scan(pages, tmp_path / "two.pdf", dpi=150.0)
    (tmp_path / "manifest.csv").write_text(
        "file,page,rolling_axis,load_N\ntwo.pdf,0,x,300\ntwo.pdf,1,y,400\n"
    )
    out = tmp_path / "res.csv"
    run_batch(
        None,
        out,
        manifest=tmp_path / "manifest.csv",
        options=Options(sensitivity=False),
        workers=1,
        progress=False,
    )
    rows = sorted(read_rows(out), key=lambda r: r["page"])
    assert [r["page"] for r in rows] == ["0", "1"]
    assert [r["rolling_axis"] for r in rows] == ["x", "y"]
    assert [r["load_N"] for r in rows] == ["300", "400"]
    for r, t in zip(rows, truths, strict=True):
        assert r["status"] == "ok", r
        assert abs(float(r["length_mm"]) / t.length - 1) < 0.01
        assert abs(float(r["width_mm"]) / t.width - 1) < 0.01
