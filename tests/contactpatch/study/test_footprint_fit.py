"""The global fit of the rounded footprint (contactpatch.study.footprint_fit) and the
rounded columns of the pairing (compare.solve_case)."""

from __future__ import annotations

import numpy as np
from numpy.testing import assert_allclose

import tiremesh as tm
from contactpatch.study import compare
from contactpatch.study import footprint_fit as ff


def test_print_ellipse_of_an_ellipse_is_itself():
    t = np.linspace(0, 2 * np.pi, 4001)
    ring = np.column_stack([40 * np.cos(t) + 3, 4 * np.sin(t) - 1])
    length, width = ff.print_ellipse(ring)
    assert_allclose([length, width], [80.0, 8.0], rtol=1e-5)


def test_best_fit_finds_the_grid_point_and_leave_one_out_refits():
    s, t = np.meshgrid(ff.SPREADS, ff.THRESHOLDS, indexing="ij")
    # synthetic model: every target equals its measurement at spread 2, threshold 0.45
    values = {
        n: m * np.exp((s - 2.0) * (k + 1) / 10 + (t - 0.45) * (k - 5))
        for k, (n, (m, _)) in enumerate(ff.TARGETS.items())
    }
    i, j, cost = ff.best_fit(values, list(ff.TARGETS))
    assert (ff.SPREADS[i], ff.THRESHOLDS[j]) == (2.0, 0.45)
    assert cost < 1e-20
    loo = ff.leave_one_out(values, by="group")
    assert {r["name"] for r in loo} == set(ff.TARGETS)
    assert_allclose([r["ratio"] for r in loo], 1.0, atol=1e-12)


def test_fit_conditions_take_540_N_for_the_big_apple():
    conds = ff.fit_conditions()
    assert conds["big_apple"].load_N == 540.0
    assert all(d.surface == "drum" and f.surface == "flat" for d, f in conds["pairs"])
    assert 20 <= len(conds["pairs"]) <= 40


def test_solve_case_pairs_rounded_next_to_plain():
    case = tm.LoadCase.from_units(
        tm.TireGeometry.from_arc_length(45.0, 13.4), pressure_bar=6.895, load_N=304.0
    )
    cols = compare.solve_case(case)
    assert cols["model_rounded_length_mm"] < cols["model_length_mm"]
    assert_allclose(cols["model_rounded_area_mm2"], cols["model_area_mm2"], rtol=0.05)
