"""contactpatch.study.trends: exponents, sign counts (6.2.4), drum / plate (Table 4-1)."""

import math

import numpy as np
from numpy.testing import assert_allclose

from contactpatch import drum_plate_ratios, sign_agreement, trend_table
from contactpatch.study.trends import power_law_fit


def test_power_law_slopes_recovered_on_synthetic_tables():
    rng = np.random.default_rng(0)
    rows = []
    for tire, (b, c) in {"A": (-0.7, 1.0), "B": (-0.45, 0.55)}.items():
        for p in (2.0, 4.0, 6.9, 9.0):
            for f in (304.0, 450.0, 731.0):
                y = 3.0 * p**b * f**c * (1 + 1e-6 * rng.standard_normal())
                rows.append(
                    {
                        "tire": tire,
                        "surface": "plate",
                        "status": "ok",
                        "model_status": "ok",
                        "pressure_bar": p,
                        "load_N": f,
                        "length_mm": y,
                        "model_length_mm": 2 * p**-0.4 * f**0.4,
                        "width_mm": y / 10,
                        "model_width_mm": y / 11,
                        "hull_area_mm2": y * y,
                        "model_area_mm2": y * y,
                    }
                )
    t = {(r["tire"], r["quantity"]): r for r in trend_table(rows)}
    assert_allclose(
        [t["A", "length"]["print_pressure_exp"], t["A", "length"]["print_load_exp"]],
        [-0.7, 1.0],
        rtol=0.01,
    )
    assert_allclose(
        [t["B", "area"]["print_pressure_exp"], t["B", "area"]["print_load_exp"]],
        [-0.9, 1.1],
        rtol=0.01,
    )
    assert_allclose(t["A", "length"]["model_pressure_exp"], -0.4, rtol=0.01)
    fit = power_law_fit([1, 2, 3], [5, 5, 5], [1, 2**0.5, 3**0.5])
    assert_allclose(fit["b"], 0.5) and math.isnan(fit["c"])
    agree = {(a["quantity"], a["variable"]): a for a in sign_agreement(trend_table(rows))}
    assert (
        agree["length", "pressure"]["agree"] == 2
        and agree["length", "pressure"]["print_increases"] == 0
    )


def test_drum_plate_summary_like_table_4_1(print_table):
    rows, _ = print_table
    pairs, summary = drum_plate_ratios(rows)
    assert len(pairs) == 4
    s = {r["quantity"]: r for r in summary}
    # the sample scans follow Table 4-1's means: drum prints shorter and wider
    assert s["length_mm"]["mean"] < 1.0 < s["width_mm"]["mean"]
    assert_allclose(s["length_mm"]["mean"], 0.92, atol=0.03)
    assert s["length_mm"]["min"] <= s["length_mm"]["mean"] <= s["length_mm"]["max"]
