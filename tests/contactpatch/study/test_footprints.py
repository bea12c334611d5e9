"""The report's plain-vs-rounded footprint comparison (issue 14): medians of the
print / model ratios per tire and surface, for each model footprint."""

import math

from numpy.testing import assert_allclose

from contactpatch.study.compare import pair_prints
from contactpatch.study.footprints import FOOTPRINTS, footprint_rows
from contactpatch.study.samples import synthetic_print_rows


def test_footprint_rows_are_medians_of_the_paired_ratios():
    paired = pair_prints(synthetic_print_rows(16, seed=2))
    rows = footprint_rows(paired)
    assert {r["footprint"] for r in rows} == {label for label, _ in FOOTPRINTS}
    every = [r for r in rows if r["tire"] == "all"]
    assert [r["n"] for r in every] == [len(paired)] * 3
    plain, _, rounded = every
    lengths = sorted(p["ratio_rounded_length"] for p in paired)
    assert_allclose(rounded["ratio_length"], (lengths[7] + lengths[8]) / 2, rtol=1e-12)
    # the rounded footprint is shorter than the pointed patch: print / model is larger
    assert rounded["ratio_length"] > plain["ratio_length"]
    assert all(math.isfinite(r["ratio_area"]) for r in rows)


def test_footprint_rows_skip_failed_model_rows():
    paired = pair_prints(synthetic_print_rows(4, seed=1))
    paired[0] = {**paired[0], "model_status": "error"}
    every = [r for r in footprint_rows(paired) if r["tire"] == "all"]
    assert every[0]["n"] == 3
