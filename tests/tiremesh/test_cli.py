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
        "400",
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
        (["--tire", "5", "--pressure=-1bar", "--load", "400"], "pressure"),
        (["--tire", "5", "--pressure", "1bar", "--load", "900kg"], "largest load"),
        (["--tire", "99", "--pressure", "4bar", "--load", "400"], "tire"),
        (["--tire", "5", "--pressure", "4bar", "--load", "400", "--camber", "95"], "camber"),
        (["--tire", "5", "--pressure", "4bar", "--load", "400", "--surface", "moon"], "surface"),
    ],
)
def test_cli_solve_errors_are_clear(args, match):
    proc = run("solve", *args, check=False)
    assert proc.returncode == 2
    assert match in proc.stderr and "Traceback" not in proc.stderr


def test_cli_solve_slip_points_to_lateral_mechanics():
    out = run("solve", "--tire", "5", "--pressure", "4bar", "--load", "400", "--slip", "1").stdout
    assert "note: a slip angle" in out
    lat = run(
        "solve",
        "--tire",
        "5",
        "--pressure",
        "4bar",
        "--load",
        "400",
        "--slip",
        "1",
        "--relaxation",
        "0.993",
        "--json",
    ).stdout
    data = json.loads(lat)
    assert data["norm_cornering_stiffness_1_deg"] > 0 and data["pneumatic_trail_mm"] > 0


def test_cli_slip_kinematics_option():
    common = ["solve", "--tire", "5", "--pressure", "4bar", "--load", "400", "--slip", "1"]
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
        "400",
        "-o",
        str(tmp_path / "s.xyz"),
        check=False,
    )
    assert proc.returncode == 2 and "--output" in proc.stderr
