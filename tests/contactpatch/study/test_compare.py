"""contactpatch.study.compare: prints paired with model load cases (section 6.2)."""

import math

import pytest
from numpy.testing import assert_allclose

import contactpatch as cp
import contactpatch.study.compare as cmp
import tiremesh as tm
from tiremesh.units import MPA_PER_BAR


def test_pairing_solves_each_case_once_and_records_failures(print_table, monkeypatch):
    rows, _ = print_table
    calls = []
    real = cmp.solve_case
    monkeypatch.setattr(cmp, "solve_case", lambda *a: calls.append(a) or real(*a))
    heavy = dict(rows[0], load_N="50000", print="9")
    odd = dict(rows[0], tire_id="", tire="no such tire", print="8")
    paired = cmp.pair_prints([*rows, *rows, heavy, heavy, odd])
    # one solve per distinct load case; the failing one too, and only once
    assert len(calls) == len({(r["pressure_bar"], r["load_N"], r["surface"]) for r in rows}) + 1
    assert all(isinstance(c[0], tm.LoadCase) for c in calls)
    by_print = {r["print"]: r for r in paired[-2:]}
    assert (
        by_print["9"]["model_status"] == "error" and "largest load" in by_print["9"]["model_error"]
    )
    assert by_print["8"]["model_status"] == "error" and "tire" in by_print["8"]["model_error"]
    assert paired[-2]["model_error"] == paired[-3]["model_error"]
    ok = [r for r in paired[: len(rows)]]
    assert all(r["model_status"] == "ok" for r in ok)
    for r in ok:
        assert_allclose(r["ratio_length"], float(r["length_mm"]) / r["model_length_mm"])
        # prints are shorter than the model's pointed patch (section 6.2.1)
        assert r["ratio_length"] < 1.0


ROW = {"tire_id": "6", "rim_width_mm": "13.4", "pressure_bar": "4.0", "load_N": "304"}


def test_case_of_a_row_is_one_load_case():
    case = cp.case_of({**ROW, "surface": "plate"})
    assert isinstance(case, tm.LoadCase)
    assert case.pressure == pytest.approx(4.0 * MPA_PER_BAR) and case.load == 304.0
    assert case.surface == tm.Flat() and case.tire.rim_width == 13.4
    # equal rows, equal (hashable) cases: the pairing cache key
    assert case == cp.case_of({**ROW, "surface": "flat", "drum_diameter_mm": "2000"})
    assert hash(case) == hash(cp.case_of(dict(ROW)))  # plate is the default


@pytest.mark.parametrize(
    ("columns", "surface"),
    [
        ({"surface": "drum"}, tm.Drum(2500.0)),  # TU Delft drum by default
        ({"surface": "drum", "drum_diameter_mm": "2000"}, tm.Drum(2000.0)),
        ({"surface": " Drum ", "drum_diameter_mm": ""}, tm.Drum(2500.0)),
        ({"surface": "disk"}, tm.Disk(3000.0)),
        ({"surface": "disk", "disk_diameter_mm": 1500}, tm.Disk(1500.0)),
        ({"surface": "drum:1800"}, tm.Drum(1800.0)),
        ({"surface": ""}, tm.Flat()),
    ],
)
def test_surface_of_a_row(columns, surface):
    assert cmp.surface_of(columns) == surface
    assert cp.case_of({**ROW, **columns}).surface == surface


@pytest.mark.parametrize(
    ("columns", "error", "match"),
    [
        ({"surface": "ice"}, tm.InvalidParameter, "surface"),
        ({"pressure_bar": ""}, cp.InvalidInput, "pressure_bar"),
        ({"load_N": "heavy"}, cp.InvalidInput, "load_N"),
        ({"tire_id": "", "tire": ""}, cp.InvalidInput, "tire"),
        ({"pressure_bar": "-1"}, tm.InvalidParameter, "pressure"),
    ],
)
def test_case_of_invalid_rows(columns, error, match):
    with pytest.raises(error, match=match):
        cp.case_of({**ROW, **columns})


def test_tire_of_explicit_dimensions():
    t = cmp.tire_of({"tire": "mine", "tire_radius_mm": "15", "rim_width_mm": "19"})
    assert (t.tire_radius, t.rim_width, t.bead_seat_diameter, t.name) == (15, 19, 622, "mine")
    a = cmp.tire_of({"arc_length_mm": "60", "rim_width_mm": "19", "bead_seat_diameter_mm": "584"})
    assert a.bead_seat_diameter == 584 and a.arc_length == pytest.approx(60)


def test_skipped_rows_and_ratios():
    skipped = cp.pair_prints([{**ROW, "status": "error"}])[0]
    assert skipped["model_status"] == "skipped" and math.isnan(skipped["ratio_length"])
    r = cmp.ratios({"length_mm": "80", "model_length_mm": 100.0, "width_mm": 5})
    assert r["ratio_length"] == 0.8 and math.isnan(r["ratio_width"])
    assert set(r) == set(cmp.RATIOS)
