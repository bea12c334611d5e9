"""Issue 12, inkprint's part: batch resume never stale, safe files, explicit units,
CLI conventions, notebook-friendly results. Each reproducer of the issue is a test."""

import csv
import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time
import uuid
from pathlib import Path

import pytest

import inkprint as ip
from inkprint.batch import Job, Options, overlay_name, process_file, run_batch
from inkprint.cli import main
from inkprint.csvsafe import escape_cell, read_csv, unescape_cell, write_csv
from inkprint.synth import PrintSpec, SheetSpec, render_sheet, save_scan

FAST = Options(sensitivity=False)


def small_sheet(path, *, seed=0, length=60.0, dpi=150):
    spec = SheetSpec(
        (PrintSpec(length, 10.0, (50.0, 40.0), tread="slick"),),
        dpi=dpi,
        size=(100.0, 80.0),
        seed=seed,
        specks=5,
    )
    img, _ = render_sheet(spec)
    return save_scan(img, path, dpi=dpi)


@pytest.fixture
def folder(tmp_path):
    d = tmp_path / "scans"
    d.mkdir()
    for i in range(3):
        small_sheet(d / f"s{i}.png", seed=i, length=50.0 + 5 * i)
    return d


def rows_of(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


# -- resume that is never stale ---------------------------------------------------------


def test_run_batch_resume_redoes_the_work_when_options_change(folder, tmp_path):
    out = tmp_path / "r.csv"
    first = run_batch(folder, out, options=FAST, workers=1, progress=False)
    same = run_batch(folder, out, options=FAST, workers=1, progress=False)
    assert first.n_skipped == 0 and same.n_skipped == 3
    # a new scale, method or threshold changes the numbers: nothing is kept
    for changed in (
        Options(sensitivity=False, dpi=300),
        Options(sensitivity=False, method="fixed", threshold=0.5),
        Options(sensitivity=False, analysis=ip.AnalysisOptions(edge_spot_area_mm2=2.0)),
    ):
        res = run_batch(folder, out, options=changed, workers=1, progress=False)
        assert res.n_skipped == 0
    rows = rows_of(out)
    assert len(rows) == 3 and {round(float(r["dpi"])) for r in rows} == {150}  # the last run
    assert len({r["run_key"] for r in rows}) == 3


def test_run_batch_resume_redoes_a_file_whose_manifest_row_changed(folder, tmp_path):
    man = folder / "manifest.csv"
    write_csv([{"file": f"s{i}.png", "load_N": 300, "pressure_bar": 4} for i in range(3)], man)
    out = tmp_path / "r.csv"
    run_batch(None, out, manifest=man, options=FAST, workers=1, progress=False)
    write_csv(
        [
            {"file": f"s{i}.png", "load_N": 300 + 100 * (i == 1), "pressure_bar": 4}
            for i in range(3)
        ],
        man,
    )
    res = run_batch(None, out, manifest=man, options=FAST, workers=1, progress=False)
    assert res.n_skipped == 2
    assert {r["file"]: r["load_N"] for r in rows_of(out)}["s1.png"] == "400"


def test_run_batch_identical_files_get_their_rows_once(folder, tmp_path):
    # the c.jpg with 4 rows: copies reuse the rows, each file keeps its own
    for name in ("c.png", "d.png"):
        shutil.copy(folder / "s0.png", folder / name)
    out = tmp_path / "r.csv"
    run_batch(folder, out, options=FAST, workers=1, progress=False)
    again = run_batch(folder, out, options=FAST, workers=1, progress=False)
    rows = rows_of(out)
    assert again.n_skipped == 5
    names = [Path(r["file"]).name for r in rows]
    assert sorted(names) == sorted(set(names)) and len(rows) == 5


def test_run_batch_second_batch_on_the_same_output_refuses(folder, tmp_path):
    from inkprint.batch import _Lock

    out = tmp_path / "r.csv"
    with _Lock(out):  # a first batch holds the output
        with pytest.raises(ip.OutputLocked, match="another inkprint batch"):
            run_batch(folder, out, options=FAST, workers=1, progress=False)
        assert main(["batch", str(folder), "-o", str(out), "-q"]) == 2
    run_batch(folder, out, options=FAST, workers=1, progress=False)  # released


def _marked(marker: str) -> list[int]:
    pids = []
    for p in Path("/proc").iterdir():
        if p.name.isdigit():
            try:
                if marker.encode() in (p / "environ").read_bytes():
                    pids.append(int(p.name))
            except OSError:
                pass
    return pids


@pytest.mark.skipif(not Path("/proc/self/environ").exists(), reason="needs /proc")
def test_run_batch_workers_die_with_their_parent(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for i in range(12):
        small_sheet(src / f"s{i:02d}.png", seed=i, length=40.0 + i, dpi=300)
    out = tmp_path / "r.csv"
    marker = f"INKPRINT_TEST_{uuid.uuid4().hex}"
    code = (
        f"from inkprint.batch import run_batch, Options; run_batch({str(src)!r}, "
        f"{str(out)!r}, options=Options(), workers=2, progress=False)"
    )
    env = {**os.environ, marker: "1"}
    proc = subprocess.Popen([sys.executable, "-c", code], env=env)
    deadline = time.time() + 60
    while len(_marked(marker)) < 3 and time.time() < deadline:
        time.sleep(0.05)
    assert len(_marked(marker)) >= 3  # the batch and its workers
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    deadline = time.time() + 10
    while _marked(marker) and time.time() < deadline:
        time.sleep(0.1)
    assert not _marked(marker), "worker processes outlived the killed batch"


# -- only regular files; links resolved once --------------------------------------------


def test_process_file_devices_and_fifos_become_error_rows(tmp_path):
    rows = process_file(Job("/dev/zero", {}, "/dev/zero"), options=FAST)
    assert rows[0]["status"] == "error" and "not a regular file" in rows[0]["error"]
    fifo = tmp_path / "pipe.png"
    os.mkfifo(fifo)
    box = {}
    t = threading.Thread(
        target=lambda: box.update(rows=process_file(Job(str(fifo)), options=FAST))
    )
    t.start()
    t.join(10)
    assert not t.is_alive(), "reading a FIFO hung"
    assert "FIFO" in box["rows"][0]["error"]


def test_cli_analyze_dev_zero_does_not_hang(capsys):
    assert main(["analyze", "/dev/zero"]) == 1
    assert "not a regular file" in capsys.readouterr().err


def test_collect_jobs_symlinks_resolved_once(folder, tmp_path):
    (folder / "loop.png").symlink_to(folder / "loop.png")
    (folder / "gone.png").symlink_to(folder / "missing.png")
    (folder / "again.png").symlink_to(folder / "s1.png")
    (folder / "self").symlink_to(folder)
    out = tmp_path / "r.csv"
    res = run_batch(str(folder / "**" / "*.png"), out, options=FAST, workers=1, progress=False)
    rows = rows_of(out)
    errors = {Path(r["file"]).name: r["error"] for r in rows if r["status"] == "error"}
    assert "symlink loop" in errors["loop.png"] and "dangling" in errors["gone.png"]
    ok = [r for r in rows if r["status"] == "ok"]
    assert len(ok) == 3  # s0, s1, s2 once each, however many names lead to them
    assert res.n_errors == 2


def test_overlay_names_are_unique_per_file_and_page(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir(), b.mkdir()
    small_sheet(a / "x.png", seed=1)
    small_sheet(b / "x.png", seed=2)
    small_sheet(a / "x.jpg", seed=3)
    ov = tmp_path / "ov"
    opts = Options(sensitivity=False, overlay_dir=str(ov))
    rows = []
    for p in (a / "x.png", b / "x.png", a / "x.jpg"):
        rows += process_file(Job(str(p), {}, str(p)), options=opts)
    names = {r["overlay"] for r in rows}
    assert len(names) == 3 and all(Path(n).is_file() for n in names)
    assert overlay_name(Job(str(a / "x.png")), 0) != overlay_name(Job(str(a / "x.png")), 1)


# -- manifest confinement, report without a manifest --------------------------------------


def test_read_manifest_paths_stay_in_its_folder(folder, tmp_path):
    secret = tmp_path / "secret.png"
    small_sheet(secret, seed=7)
    man = folder / "manifest.csv"
    write_csv([{"file": "s0.png"}, {"file": "../secret.png"}, {"file": str(secret)}], man)
    out = tmp_path / "r.csv"
    run_batch(None, out, manifest=man, options=FAST, workers=1, progress=False)
    rows = rows_of(out)
    outside = [r for r in rows if r["status"] == "error"]
    assert len(outside) == 2 and all("--allow-outside" in r["error"] for r in outside)
    assert all(r["sha256"] == "" for r in outside)  # never read
    run_batch(None, out, manifest=man, options=FAST, workers=1, progress=False, allow_outside=True)
    assert all(r["status"] == "ok" for r in rows_of(out))


def test_cli_report_without_a_manifest_is_a_clear_usage_error(folder, tmp_path, capsys):
    code = main(
        ["batch", str(folder), "-o", str(tmp_path / "r.csv"), "--report", str(tmp_path / "rep")]
    )
    err = capsys.readouterr().err
    assert code == 2 and "--manifest" in err and "Traceback" not in err
    assert not (tmp_path / "r.csv").exists()  # refused before any work


def test_cli_report_with_a_partial_manifest_says_what_is_left_out(tmp_path, capsys):
    from inkprint.synth import drum_and_plate_sheet

    d = tmp_path / "two"
    d.mkdir()
    img, _ = render_sheet(drum_and_plate_sheet(tire_radius=12.0, load=400.0, pressure=0.5))
    save_scan(img, d / "sheet.png", dpi=150)
    man = d / "manifest.csv"
    row = {"file": "sheet.png", "print": 0, "tire": "big apple", "pressure_bar": 5, "load_N": 400}
    write_csv([row, {"file": "sheet.png", "print": 1}], man)
    code = main(
        [
            "batch",
            "-o",
            str(tmp_path / "r.csv"),
            "--manifest",
            str(man),
            "--report",
            str(tmp_path / "rep"),
            "--no-renders",
            "--no-band",
            "-q",
        ]
    )
    err = capsys.readouterr().err
    assert code == 0, err
    assert "left out: sheet.png#1" in err and "KeyError" not in err
    assert (tmp_path / "rep" / "index.html").is_file()


# -- CSV formula injection --------------------------------------------------------------------


@pytest.mark.parametrize(
    ("cell", "written"),
    [
        ('=HYPERLINK("http://x")', '\'=HYPERLINK("http://x")'),
        ("+cmd|' /C calc'!A0", "'+cmd|' /C calc'!A0"),
        ("@SUM(A1:A9)", "'@SUM(A1:A9)"),
        ("-2+3", "'-2+3"),
        ("\tx", "'\tx"),
        ("\rx", "'\rx"),
        ("-3.5", "-3.5"),
        ("+2", "+2"),
        (-3.5, -3.5),
        ("plain", "plain"),
        ("'=x", "''=x"),
    ],
)
def test_escape_cell_owasp(cell, written):
    assert escape_cell(cell) == written
    assert unescape_cell(escape_cell(cell)) == cell


def test_run_batch_outputs_are_spreadsheet_safe(folder, tmp_path):
    man = folder / "manifest.csv"
    evil = '=HYPERLINK("http://evil","x")'
    write_csv([{"file": "s0.png", "tire": evil, "note": "@SUM(1)", "load_N": "-3.5"}], man)
    out = tmp_path / "r.csv"
    run_batch(None, out, manifest=man, options=FAST, workers=1, progress=False)
    raw = out.read_text()
    assert "'=HYPERLINK" in raw and "'@SUM" in raw and ",=HYPERLINK" not in raw
    (row,) = read_csv(out)
    assert row["tire"] == evil  # read back exactly
    assert row["status"] == "error" and "load_N" in row["error"]  # -3.5 N: refused
    assert json.loads(out.with_suffix(".json").read_text())[0]["tire"] == evil
    # and a resume reads its own escaped table back without doubling the quotes
    run_batch(None, out, manifest=man, options=FAST, workers=1, progress=False)
    assert read_csv(out)[0]["tire"] == evil


def test_cli_analyze_csv_is_spreadsheet_safe(tmp_path, capsys):
    path = small_sheet(tmp_path / "=evil.png")
    assert main(["analyze", str(path), "--csv", "--no-band"]) == 0
    text = capsys.readouterr().out
    assert "'" + str(path) in text or "'=evil" not in text.split(",")[0]
    assert next(iter(csv.DictReader(text.splitlines())))["status"] == "ok"


# -- units at the CLI edge ---------------------------------------------------------------------


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--pressure", "60"], "4bar, 60psi, 400kPa or 0.4MPa"),
        (["--pressure", "0.4"], "a bare number is ambiguous"),
        (["--load", "400"], "400N or 40kg"),
        (["--load=-5N"], "> 0"),
        (["--pressure", "0bar"], "> 0"),
        (["--pressure", "4parsecs"], "with its unit"),
    ],
)
def test_cli_units_are_explicit(tmp_path, capsys, args, message):
    path = small_sheet(tmp_path / "s.png")
    assert main(["analyze", str(path), "--no-band", *args]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


def test_cli_units_accepted_forms(tmp_path, capsys):
    from inkprint.cli import quantity

    assert quantity("4bar", kind="pressure", flag="--pressure") == pytest.approx(0.4)
    assert quantity("60psi", kind="pressure", flag="--pressure") == pytest.approx(
        0.41369, rel=1e-4
    )
    assert quantity("400kPa", kind="pressure", flag="--pressure") == pytest.approx(0.4)
    assert quantity("0.4MPa", kind="pressure", flag="--pressure") == pytest.approx(0.4)
    assert quantity("40kg", kind="load", flag="--load") == pytest.approx(392.4)
    path = small_sheet(tmp_path / "s.png")
    assert main(["analyze", str(path), "--no-band", "--load", "400N", "--pressure", "4bar"]) == 0
    assert "% of inflation" in capsys.readouterr().out


# -- CLI conventions -----------------------------------------------------------------------------


def test_cli_version_and_exit_codes(folder, tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        main(["--version"])
    assert e.value.code == 0 and capsys.readouterr().out.startswith("inkprint ")
    with pytest.raises(SystemExit) as e:
        main(["analyze"])  # usage error
    assert e.value.code == 2
    (folder / "bad.png").write_bytes(b"not a png")
    out = tmp_path / "r.csv"
    assert main(["batch", str(folder), "-o", str(out), "--workers", "1", "-q", "--no-band"]) == 1
    cap = capsys.readouterr()
    assert cap.out == "" and "1 error row(s)" in cap.err and "bad.png" in cap.err
    (folder / "bad.png").unlink()
    assert main(["batch", str(folder), "-o", str(out), "-q", "--no-band"]) == 0


def test_cli_verbose_tells_warnings_and_marks(tmp_path, capsys):
    from inkprint.synth import drum_and_plate_sheet

    img, _ = render_sheet(drum_and_plate_sheet(tire_radius=12.0, load=400.0, pressure=0.5))
    path = save_scan(img, tmp_path / "s.png", dpi=150)
    assert main(["analyze", str(path), "--no-band", "-v"]) == 0
    assert "set aside" in capsys.readouterr().err
    assert main(["analyze", str(path), "--no-band", "-q"]) == 0
    assert capsys.readouterr().err == ""


def test_cli_unwritable_output_names_the_path_without_a_traceback(folder, capsys):
    code = main(["batch", str(folder), "-o", "/proc/nope/r.csv", "-q", "--no-band"])
    err = capsys.readouterr().err
    assert code == 2 and "/proc/nope" in err and "Traceback" not in err


# -- notebooks -------------------------------------------------------------------------------------


def test_sheet_result_repr_and_html_are_short(tmp_path):
    path = small_sheet(tmp_path / "s.png")
    r = ip.analyze_scan(path, sensitivity=False)
    assert len(repr(r)) < 300 and "1 print(s)" in repr(r)
    assert len(repr(r.prints[0])) < 200 and "length" in repr(r.prints[0])
    html = r._repr_html_()
    assert "<table>" in html and "length" in html and len(html) < 3000
    assert "<table>" in r.prints[0]._repr_html_()
    assert "Scan(" in repr(ip.read_scan(path)) and len(repr(ip.read_scan(path))) < 200


def test_to_dataframe_needs_pandas_or_says_so(folder, tmp_path):
    res = run_batch(folder, tmp_path / "r.csv", options=FAST, workers=1, progress=False)
    try:
        import pandas  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pip install pandas"):
            res.to_dataframe()
    else:
        assert len(res.to_dataframe()) == 3
    assert "3 files" in repr(res)
