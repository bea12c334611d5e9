"""Issue 12, the gaps closed last: ``--scheduler-timeout`` and top-level ``-q`` / ``-v``
on ``inkprint``, batch tables in the format of their extension, the shortest name of
a file reached through symlinks."""

import dataclasses
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from inkprint.cli import main
from tests.inkprint.test_safety import small_sheet


def closed_loopback_port() -> int:
    """A 127.0.0.1 port nothing listens on (bound, then closed)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def one_scan(tmp_path):
    d = tmp_path / "scans"
    d.mkdir()
    small_sheet(d / "a.png")
    return d


def test_batch_scheduler_timeout_refused_loopback_exit_2(one_scan, tmp_path, capsys):
    address = f"tcp://127.0.0.1:{closed_loopback_port()}"
    out = tmp_path / "r.csv"
    args = ["batch", str(one_scan), "-o", str(out), "--scheduler", address]
    code = main([*args, "--scheduler-timeout", "3", "--no-band"])
    err = capsys.readouterr().err
    assert code == 2
    assert address in err and "refused" in err
    assert "Traceback" not in err
    assert not out.exists()  # refused before any work


def test_batch_scheduler_timeout_reaches_the_scheduler_check(one_scan, tmp_path, monkeypatch):
    import inkprint.batch as batch

    seen = {}

    def fake_check(address, *, timeout):
        seen["address"], seen["timeout"] = address, timeout
        raise batch.InvalidInput("scheduler", address, "stop here")

    monkeypatch.setattr(batch, "check_scheduler", fake_check)
    args = ["batch", str(one_scan), "-o", str(tmp_path / "r.csv"), "--no-band"]
    assert main([*args, "--scheduler", "tcp://127.0.0.1:1", "--scheduler-timeout", "2.5"]) == 2
    assert seen == {"address": "tcp://127.0.0.1:1", "timeout": 2.5}


@pytest.mark.parametrize("value", ["0", "-1", "inf", "soon"])
def test_batch_scheduler_timeout_bad_value_usage_error(one_scan, tmp_path, value, capsys):
    with pytest.raises(SystemExit) as e:
        main(["batch", str(one_scan), "-o", str(tmp_path / "r.csv"), "--scheduler-timeout", value])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert "--scheduler-timeout" in err and "seconds > 0" in err


def test_main_quiet_and_verbose_at_top_level(one_scan, tmp_path, capsys):
    out = tmp_path / "r.csv"
    assert main(["-q", "batch", str(one_scan), "-o", str(out), "--workers", "1", "--no-band"]) == 0
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err == ""
    out2 = tmp_path / "r2.csv"
    assert main(["batch", str(one_scan), "-o", str(out2), "--workers", "1", "--no-band"]) == 0
    assert "wrote" in capsys.readouterr().out  # without -q the summary is printed
    scan = str(one_scan / "a.png")
    assert main(["-v", "analyze", scan, "--no-band"]) == 0
    assert "a.png" in capsys.readouterr().out
    assert main(["-q", "synth", "-o", str(tmp_path / "syn"), "--mixed", "2"]) == 0
    assert capsys.readouterr().out == ""


def test_analyze_leaves_the_garbage_collector_as_it_was(one_scan, capsys):
    # `inkprint analyze` pauses the collector while it imports and analyses the
    # first file, and freezes it at exit only (an exit handler): a caller's
    # collector is left as it was, enabled or not, and nothing is frozen now
    import atexit
    import gc

    scan = str(one_scan / "a.png")
    frozen = gc.get_freeze_count()
    try:
        for enabled in (True, False):
            (gc.enable if enabled else gc.disable)()
            assert main(["analyze", scan, scan, "--no-band"]) == 0
            assert gc.isenabled() == enabled
            assert main(["analyze", str(one_scan / "missing.png")]) == 1
            assert gc.isenabled() == enabled
    finally:
        gc.enable()
    assert gc.get_freeze_count() == frozen
    atexit.unregister(gc.freeze)  # this test process keeps its last collection
    capsys.readouterr()


def test_main_quiet_and_verbose_together_refused(one_scan, capsys):
    assert main(["-q", "analyze", str(one_scan / "a.png"), "-v"]) == 2
    assert "-q and -v" in capsys.readouterr().err


# -- what one `inkprint analyze` loads (issue 11 item 7: <= 0.35 s a file) -----------------


def _modules_after(code: str) -> set:
    """The modules a fresh interpreter holds once it has run ``code``."""
    run = subprocess.run(
        [sys.executable, "-c", f"{code}\nimport sys\nprint(' '.join(sorted(sys.modules)))"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 0, run.stderr
    return set(run.stdout.splitlines()[-1].split())


def test_analyze_command_line_parsed_without_numpy_or_the_batch():
    # the command line is parsed before numpy loads (one OpenBLAS thread is set
    # first) and builds the analyze command's options only: no batch scheduler
    mods = _modules_after(
        "from inkprint.cli import build_parser\n"
        "build_parser('analyze').parse_args(['analyze', 'a.png', '--group-mm', '3'])"
    )
    assert "inkprint.options" in mods  # the thresholds' defaults, in the help
    loaded = {"numpy", "cv2", "inkprint.batch", "tiremesh.parallel", "concurrent.futures"} & mods
    assert not loaded


def test_analyze_run_loads_no_module_it_does_not_use(one_scan):
    # a PNG is decoded without Pillow; no table is written (tempfile), nothing is
    # drawn, no Sauvola (scikit-image, scipy), no notebook HTML (html.entities)
    scan = str(one_scan / "a.png")
    mods = _modules_after(f"from inkprint.cli import main\nmain(['-q', 'analyze', {scan!r}])")
    assert {"inkprint.analyze", "shapely", "contactpatch"} <= mods
    unused = {"PIL", "scipy", "skimage", "tempfile", "html.entities", "inkprint.overlay"}
    assert not unused & mods


def test_parser_for_one_command_and_for_all():
    from inkprint.cli import build_parser

    batch = ["batch", "src", "-o", "r.csv", "--workers", "2"]
    assert build_parser().parse_args(batch).workers == 2
    assert build_parser("batch").parse_args(batch).workers == 2
    assert build_parser("no such command").parse_args(batch).workers == 2
    with pytest.raises(SystemExit):  # the analyze command's parser has no batch options
        build_parser("analyze").parse_args(batch)
    a = build_parser("analyze").parse_args(["-q", "analyze", "a.png", "--band", "0.2"])
    assert (a.scans, a.sensitivity, a.quiet) == (["a.png"], 0.2, True)


# -- batch tables in the format of their extension ------------------------------------------


@pytest.fixture
def two_scans(tmp_path):
    d = tmp_path / "two"
    d.mkdir()
    small_sheet(d / "a.png", seed=1, length=55.0)
    small_sheet(d / "b.png", seed=2, length=60.0)
    return d


def test_run_batch_parquet_output_read_back_with_pyarrow_and_resumed(two_scans, tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    from inkprint.batch import run_batch
    from tests.inkprint.test_safety import FAST

    out = tmp_path / "r.parquet"
    first = run_batch(two_scans, out, options=FAST, workers=1, progress=False)
    assert first.outputs == [out]
    assert not out.with_suffix(".csv").exists() and not out.with_suffix(".json").exists()
    table = pq.read_table(out)
    assert table.num_rows == 2
    names = [Path(f).name for f in table.column("file").to_pylist()]
    assert sorted(names) == ["a.png", "b.png"]
    assert str(table.schema.field("length_mm").type) == "double"  # typed, not text
    lengths = dict(zip(names, table.column("length_mm").to_pylist(), strict=True))
    assert lengths["b.png"] > lengths["a.png"]  # 60 mm vs 55 mm prints
    again = run_batch(two_scans, out, options=FAST, workers=1, progress=False)
    assert again.n_skipped == 2  # resumed from the Parquet table itself
    assert pq.read_table(out).num_rows == 2  # no duplicate rows
    other = dataclasses.replace(FAST, method="sauvola")
    changed = run_batch(two_scans, out, options=other, workers=1, progress=False)
    assert changed.n_skipped == 0  # other options: the work is redone, not kept stale
    assert pq.read_table(out).num_rows == 2


def test_cli_batch_json_output_resumes(two_scans, tmp_path, capsys):
    import json

    out = tmp_path / "r.json"
    args = ["batch", str(two_scans), "-o", str(out), "--workers", "1", "--no-band"]
    assert main(args) == 0
    assert len(json.loads(out.read_text())) == 2
    assert main(args) == 0
    assert "(2 already done)" in capsys.readouterr().out
    assert len(json.loads(out.read_text())) == 2


@pytest.mark.parametrize("name", ["r.xlsx", "r.txt", "r"])
def test_cli_batch_unknown_extension_refused_before_work(two_scans, tmp_path, name, capsys):
    out = tmp_path / "o" / name
    assert main(["batch", str(two_scans), "-o", str(out), "--workers", "1", "--no-band"]) == 2
    err = capsys.readouterr().err
    assert ".csv" in err and ".parquet" in err and name in err
    assert not (tmp_path / "o").exists()  # nothing written, not even the lock


# -- the shortest name of a file reached through links -----------------------------------------


def test_collect_jobs_symlink_dedup_keeps_shortest_name(tmp_path):
    # issue 12: a recursive glob through `self -> .` showed ln/self/self/.../tire.png
    from inkprint.jobs import collect_jobs

    d = tmp_path / "ln"
    d.mkdir()
    small_sheet(d / "tire.png")  # 't' sorts after 's': the glob lists self/... first
    (d / "self").symlink_to(d)
    (d / "alias.png").symlink_to(d / "tire.png")  # same depth, a link's name
    jobs = collect_jobs(str(d / "**" / "*.png"))
    assert [Path(j.display) for j in jobs] == [d / "tire.png"]
    assert jobs[0].path == str((d / "tire.png").resolve())


def test_collect_jobs_broken_link_reported_under_shortest_name(tmp_path):
    from inkprint.jobs import collect_jobs

    d = tmp_path / "ln"
    d.mkdir()
    (d / "x_gone.png").symlink_to(d / "missing.png")
    (d / "self").symlink_to(d)
    jobs = collect_jobs(str(d / "**" / "*.png"))
    assert [Path(j.display) for j in jobs] == [d / "x_gone.png"]
    assert "dangling" in jobs[0].error


def test_run_batch_symlink_rows_carry_the_shortest_name(tmp_path):
    from inkprint.batch import run_batch
    from tests.inkprint.test_safety import FAST

    d = tmp_path / "ln"
    d.mkdir()
    small_sheet(d / "tire.png")
    (d / "self").symlink_to(d)
    res = run_batch(
        str(d / "**" / "*.png"), tmp_path / "r.csv", options=FAST, workers=1, progress=False
    )
    assert [r["file"] for r in res.rows] == [str(d / "tire.png")]
