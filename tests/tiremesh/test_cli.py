"""`tiremesh` command line, run in a subprocess as a user would."""

import csv
import json
import subprocess
import sys

import pytest
from numpy.testing import assert_allclose


def run(*args, check=True):
    proc = subprocess.run(
        [sys.executable, "-m", "tiremesh.cli", *args], capture_output=True, text=True, timeout=120
    )
    if check and proc.returncode != 0:
        raise AssertionError(proc.stderr)
    return proc


def test_cli_solve_catalogue_tire_human():
    out = run("solve", "--tire", "big apple", "--pressure", "4bar", "--deflection", "5").stdout
    assert "Schwalbe Big Apple 55-622" in out
    assert "length 118.9" in out and "width 9.917" in out


def test_cli_solve_json_load_search():
    out = run(
        "solve",
        "--size",
        "37",
        "--rim-width",
        "18.7",
        "--pressure",
        "58psi",
        "--load",
        "40.8kg",
        "--camber",
        "45",
        "--surface",
        "drum:2500",
        "--json",
    ).stdout
    data = json.loads(out)
    assert_allclose(data["vertical_force_N"], 40.8 * 9.81, rtol=1e-6)
    assert data["surface"] == "drum 2500 mm"
    assert data["lateral_force_N"] > 0


def test_cli_solve_csv_and_files(tmp_path):
    sec, outline = tmp_path / "sections.csv", tmp_path / "outline.csv"
    out = run(
        "solve",
        "--tire",
        "5",
        "--pressure",
        "400kPa",
        "--load",
        "400N",
        "--csv",
        "--sections-csv",
        str(sec),
        "--outline-csv",
        str(outline),
        "--sections",
        "51",
    ).stdout
    rows = list(csv.DictReader(out.splitlines()))
    assert len(rows) == 1 and float(rows[0]["vertical_force_N"]) == pytest.approx(400, rel=1e-6)
    assert len(list(csv.DictReader(sec.open()))) == 51
    assert len(list(csv.DictReader(outline.open()))) == 103


@pytest.mark.parametrize(
    ("args", "match"),
    [
        (["--tire", "5", "--pressure=-1bar", "--load", "400N"], "pressure"),
        (["--tire", "5", "--pressure", "1bar", "--load", "900kg"], "largest load"),
        (["--tire", "99", "--pressure", "4bar", "--load", "400N"], "tire"),
        (["--tire", "5", "--pressure", "4bar", "--load", "400N", "--camber", "95"], "camber"),
        (["--tire", "5", "--pressure", "4bar", "--load", "400N", "--surface", "moon"], "surface"),
        (["--tire", "5", "--size", "30", "--pressure", "4bar", "--load", "400N"], "exactly one"),
        (["--size", "30", "--pressure", "4bar", "--load", "400N"], "--rim-width"),
    ],
)
def test_cli_solve_errors_are_clear(args, match):
    proc = run("solve", *args, check=False)
    assert proc.returncode == 2
    assert match in proc.stderr and "Traceback" not in proc.stderr


def test_cli_solve_slip_points_to_lateral_mechanics():
    out = run("solve", "--tire", "5", "--pressure", "4bar", "--load", "400N", "--slip", "1").stdout
    assert "note: a slip angle" in out
    lat = run(
        "solve",
        "--tire",
        "5",
        "--pressure",
        "4bar",
        "--load",
        "400N",
        "--slip",
        "1",
        "--relaxation",
        "0.993",
        "--json",
    ).stdout
    data = json.loads(lat)
    assert data["norm_cornering_stiffness_1_deg"] > 0 and data["pneumatic_trail_mm"] > 0


def test_cli_slip_kinematics_option():
    common = ["solve", "--tire", "5", "--pressure", "4bar", "--load", "400N", "--slip", "1"]
    lead = json.loads(run(*common, "--json").stdout)
    centre = json.loads(run(*common, "--slip-kinematics", "centre", "--json").stdout)
    # leading edge anchored: the patch carries a cornering force; centred turn: none
    assert lead["lateral_force_N"] < -1.0
    assert abs(centre["lateral_force_N"]) < 1e-6
    assert "Appendix C" in run(*common, "--slip-kinematics", "centre").stdout


def test_cli_case_matches_library():
    import tiremesh as tm

    out = run(
        "solve",
        "--tire",
        "8",
        "--pressure",
        "4.5bar",
        "--load",
        "400N",
        "--camber",
        "20",
        "--lateral",
        "0.5",
        "--surface",
        "disk:3000:away",
        "--sections",
        "101",
        "--json",
    ).stdout
    case = tm.LoadCase.from_units(
        tm.get_tire(8),
        pressure_bar=4.5,
        load_N=400.0,
        camber_deg=20.0,
        lateral_mm=0.5,
        surface="disk:3000:away",
        n_sections=101,
    )
    p = tm.solve(case)
    data = json.loads(out)
    assert_allclose(
        [data["deflection_mm"], data["lateral_force_N"], data["area_mm2"]],
        [p.deflection, p.lateral_force, p.area],
        rtol=1e-12,
    )


def test_cli_sweep_json_and_errors(tmp_path):
    out = tmp_path / "s.json"
    run("sweep", "--grid", "tire=5 pressure_bar=3,5 load_N=400 camber_deg=5", "-o", str(out))
    rows = json.loads(out.read_text())
    assert len(rows) == 2 and all(r["status"] == "ok" for r in rows)
    bad = run(
        "sweep", "--grid", "tire=5 pressure_bar=3 load_N=400 camber=5", "-o", str(out), check=False
    )
    assert bad.returncode == 2 and "camber" in bad.stderr and "Traceback" not in bad.stderr
    bad = run(
        "sweep",
        "--grid",
        "tire=5 pressure_bar=3 load_N=400",
        "-o",
        str(tmp_path / "s.txt"),
        check=False,
    )
    assert bad.returncode == 2 and "--output" in bad.stderr


def test_cli_section_rejects_unknown_figure_format(tmp_path):
    proc = run(
        "section",
        "--tire",
        "5",
        "--pressure",
        "4bar",
        "--load",
        "400N",
        "-o",
        str(tmp_path / "s.xyz"),
        check=False,
    )
    assert proc.returncode == 2 and "--output" in proc.stderr


# --- issue 12: units, formats, clear errors, conventions -------------------------------

CASE = ["--tire", "5", "--pressure", "4bar", "--load", "400N"]


def _clean_failure(proc, *needles, code=2):
    """Exit ``code``, a one-line ``error:`` on stderr with every needle, no traceback."""
    assert proc.returncode == code, (proc.returncode, proc.stdout, proc.stderr)
    assert "Traceback" not in proc.stderr and "Traceback" not in proc.stdout
    assert "error" in proc.stderr
    for needle in needles:
        assert needle in proc.stderr, (needle, proc.stderr)


@pytest.mark.parametrize(
    ("option", "value", "forms"),
    [
        ("--pressure", "60", "4bar, 60psi, 400kPa, 0.4MPa"),
        ("--pressure", "0.4", "4bar, 60psi, 400kPa, 0.4MPa"),
        ("--load", "400", "400N, 40kg"),
    ],
)
def test_cli_solve_bare_number_is_refused_with_the_accepted_forms(option, value, forms):
    # before: --pressure 60 ran at 60 bar, --pressure 0.4 (the library's MPa) at 0.4 bar
    args = {"--pressure": "4bar", "--load": "400N", option: value}
    proc = run("solve", "--tire", "5", *(x for kv in args.items() for x in kv), check=False)
    _clean_failure(proc, option, forms)
    assert proc.stdout == ""


@pytest.mark.parametrize(
    "args",
    [
        ["--pressure", "0bar", "--load", "400N"],
        ["--pressure", "4bar", "--load=-5N"],
        ["--pressure", "4bar", "--load", "0kg"],
        ["--pressure", "4bar", "--deflection", "0"],
    ],
)
def test_cli_solve_impossible_values_are_refused(args):
    proc = run("solve", "--tire", "5", *args, check=False)
    _clean_failure(proc, "> 0")


def test_cli_version():
    import tiremesh as tm

    proc = run("--version")
    assert proc.stdout.strip() == f"tiremesh {tm.__version__}"


@pytest.mark.parametrize("command", ["solve", "sweep", "mesh", "render", "section"])
def test_cli_every_command_takes_quiet_and_verbose(command):
    text = run(command, "--help").stdout
    assert "-q, --quiet" in text and "-v, --verbose" in text


def test_cli_quiet_silences_info_lines(tmp_path):
    out = tmp_path / "m.vtp"
    loud = run("mesh", *CASE, "--around", "60", "-o", str(out)).stdout
    assert "wrote" in loud
    assert run("mesh", "-q", *CASE, "--around", "60", "-o", str(out)).stdout == ""
    # -q before the command works too
    assert run("-q", "mesh", *CASE, "--around", "60", "-o", str(out)).stdout == ""


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["solve", *CASE, "--sections-csv", "/proc/x.csv"], "--sections-csv"),
        (["solve", *CASE, "--outline-csv", "/proc/x.csv"], "--outline-csv"),
        (["mesh", *CASE, "-o", "/proc/x.vtp"], "--output"),
        (["render", *CASE, "-o", "/proc/x.png"], "--output"),
        (["section", *CASE, "-o", "/proc/x.png"], "--output"),
        (["sweep", "--grid", "tire=5 pressure_bar=3 load_N=400", "-o", "/proc/x.csv"], "--output"),
    ],
)
def test_cli_unwritable_output_names_the_path_and_the_reason(args, option):
    proc = run(*args, check=False)
    path = next(a for a in args if a.startswith("/proc/"))
    _clean_failure(proc, f"cannot write {path}", option, "No such file or directory")


@pytest.mark.parametrize("command", ["solve", "mesh", "sweep"])
def test_cli_folder_given_as_output_file_is_refused(command, tmp_path):
    folder = tmp_path / {"solve": "s.csv", "mesh": "m.vtp", "sweep": "w.csv"}[command]
    folder.mkdir()
    args = {
        "solve": ["solve", *CASE, "--sections-csv", str(folder)],
        "mesh": ["mesh", *CASE, "-o", str(folder)],
        "sweep": ["sweep", "--grid", "tire=5 pressure_bar=3 load_N=400", "-o", str(folder)],
    }[command]
    _clean_failure(run(*args, check=False), str(folder), "folder")


def test_cli_mesh_size_is_refused_before_any_work(tmp_path):
    import time

    t0 = time.monotonic()
    proc = run(
        "mesh",
        *CASE,
        "--around",
        "100000",
        "--bulge-points",
        "10000",
        "-o",
        str(tmp_path / "big.vtp"),
        check=False,
    )
    _clean_failure(proc, "2,000,499,996 vertices", "5,000,000", "--max-vertices")
    assert time.monotonic() - t0 < 30 and not (tmp_path / "big.vtp").exists()
    proc = run("mesh", *CASE, "--around", "10", "-o", str(tmp_path / "m.vtp"), check=False)
    _clean_failure(proc, "--around")


def test_cli_render_dpi_and_unknown_format_are_refused(tmp_path):
    _clean_failure(run("render", *CASE, "--dpi", "0", "-o", str(tmp_path / "r.png"), check=False))
    proc = run("render", *CASE, "-o", str(tmp_path / "r.bmp"), check=False)
    _clean_failure(proc, "--output", ".png")
    for flag, value in (("--camera", "30,95,1"), ("--image-size", "0x10"), ("--scalars", "heat")):
        proc = run("render", *CASE, flag, value, "-o", str(tmp_path / "r.png"), check=False)
        _clean_failure(proc, flag)


def test_cli_section_dpi_zero_is_refused(tmp_path):
    proc = run("section", *CASE, "--dpi", "0", "-o", str(tmp_path / "s.png"), check=False)
    _clean_failure(proc, "--dpi", "10 .. 1200")
    assert not (tmp_path / "s.png").exists()


def test_cli_render_passes_camera_background_title_and_size(monkeypatch, tmp_path, capsys):
    import functools

    from tiremesh import cli, render

    seen = {}

    @functools.wraps(render.render)
    def fake(tire_mesh, path, **kw):
        seen.update(kw, path=path)

    monkeypatch.setattr(render, "render", fake)
    args = ["render", *CASE, "--around", "60", "-o", str(tmp_path / "r.png")]
    assert cli.main([*args, "--camera", "30,20,1.5", "--background", "black", "--no-title"]) == 0
    # the colour is parsed at the edge (an error names --background), passed as RGB
    assert seen["camera"] == (30.0, 20.0, 1.5) and seen["background"] == (0.0, 0.0, 0.0)
    assert seen["title"] is False and seen["size"] == (1200, 900)
    seen.clear()
    assert cli.main([*args, "--image-size", "320x240"]) == 0
    # options not given are not passed: render() keeps its own defaults
    assert seen["size"] == (320, 240) and not {"camera", "background", "title"} & set(seen)


def test_cli_mesh_with_surface_and_lossy_format_warning(tmp_path):
    proc = run("mesh", *CASE, "--around", "60", "--with-surface", "-o", str(tmp_path / "m.ply"))
    assert (tmp_path / "m.ply").is_file() and (tmp_path / "m_surface.ply").is_file()
    assert "warning" not in proc.stderr
    proc = run("mesh", *CASE, "--around", "60", "-o", str(tmp_path / "m.stl"))
    assert "warning: .stl keeps geometry" in proc.stderr and ".vtp, .ply or .glb" in proc.stderr


def test_cli_sweep_parquet_is_parquet(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    out = tmp_path / "s.parquet"
    run("sweep", "--grid", "tire=5 pressure_bar=3,5 load_N=400", "-o", str(out))
    assert out.read_bytes()[:4] == b"PAR1"  # before: CSV text under a .parquet name
    table = pq.read_table(out)
    assert table.num_rows == 2 and table.column("status").to_pylist() == ["ok", "ok"]
    assert str(table.schema.field("vertical_force_N").type) == "double"


def test_cli_sweep_unknown_extension_refused_before_any_work(tmp_path):
    out = tmp_path / "s.xlsx"
    proc = run("sweep", "--grid", "tire=5 pressure_bar=3 load_N=400", "-o", str(out), check=False)
    _clean_failure(proc, "--output", ".csv, .json, .parquet")
    assert list(tmp_path.iterdir()) == []


def test_cli_sweep_exit_1_when_some_cases_fail(tmp_path):
    out = tmp_path / "s.csv"
    proc = run(
        "sweep", "--grid", "tire=5 pressure_bar=1 load_N=400,9000", "-o", str(out), check=False
    )
    assert proc.returncode == 1 and "1 of 2 cases failed" in proc.stderr
    assert "Traceback" not in proc.stderr
    rows = list(csv.DictReader(out.open()))
    assert [r["status"] for r in rows] == ["ok", "error"]


def test_cli_sweep_workers_and_timeout_are_checked(tmp_path):
    grid = ["sweep", "--grid", "tire=5 pressure_bar=3 load_N=400", "-o", str(tmp_path / "s.csv")]
    _clean_failure(run(*grid, "--workers", "0", check=False), "--workers")
    _clean_failure(run(*grid, "--scheduler-timeout", "0", check=False), "--scheduler-timeout")


def test_cli_sweep_refused_scheduler_is_clear_and_fast(tmp_path):
    import socket
    import time

    with socket.socket() as s:  # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    address = f"tcp://127.0.0.1:{port}"
    t0 = time.monotonic()
    grid = ["sweep", "--grid", "tire=5 pressure_bar=3 load_N=400", "-o", str(tmp_path / "s.csv")]
    proc = run(*grid, "--scheduler", address, check=False)
    _clean_failure(proc, address, "refused")
    assert time.monotonic() - t0 < 30 and not (tmp_path / "s.csv").exists()


def test_cli_sweep_silent_scheduler_times_out(tmp_path):
    import socket
    import time

    with socket.socket() as srv:  # accepts connections (backlog), never answers
        srv.bind(("127.0.0.1", 0))
        srv.listen(4)
        address = f"127.0.0.1:{srv.getsockname()[1]}"
        t0 = time.monotonic()
        grid = ["sweep", "--grid", "tire=5 pressure_bar=3 load_N=400"]
        proc = run(
            *grid,
            "-o",
            str(tmp_path / "s.csv"),
            "--scheduler",
            address,
            "--scheduler-timeout",
            "0.5",
            check=False,
        )
    _clean_failure(proc, address, "0.5 s")
    assert time.monotonic() - t0 < 30


def test_cli_internal_error_is_one_line_and_verbose_shows_traceback(monkeypatch, capsys):
    from tiremesh import cli

    def boom(a):
        raise RuntimeError("boom")

    monkeypatch.setattr(cli, "_cmd_solve", boom)
    assert cli.main(["solve", *CASE]) == 3
    err = capsys.readouterr().err
    assert "internal error RuntimeError: boom" in err and "Traceback" not in err
    assert cli.main(["solve", "-v", *CASE]) == 3
    assert "Traceback" in capsys.readouterr().err


def test_cli_usage_error_exit_2():
    proc = run("solve", "--tire", "5", check=False)
    assert proc.returncode == 2 and "--pressure" in proc.stderr
