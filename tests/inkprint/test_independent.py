"""The analysis on sheets of a second generator, written without reading the tool.

``tests/inkprint/independent`` (``gen.py``: one sheet per class: slick, treaded -
chevron, knurl, sipes, knobby, car -, wide, labels, ruler, chart paper, lighting,
clipped, untrusted or missing dpi, multi-page PDF, tiny, noise page, specks; exact
truth from the drawn geometry; ``score.py``: the outcomes) was written from the
issue's list of failure classes by someone who had not read ``inkprint``: a check
on inputs the tool was not shaped around (issue 11). Its bar is the issue's: every
print within 1 % length, 1 % width and 2 % hull area or flagged, every file that
cannot be measured an error row, nothing silently wrong. Run a whole set with
``python tests/inkprint/independent/score.py --files 120 --seed N``.
"""

import csv
import json
import os
from collections import Counter

import numpy as np
import pytest

from inkprint.batch import Options, run_batch

from .independent import gen, score

#: outcomes that are silent wrong numbers (a print measured out of the bar with
#: status ok, one not found, one that is not a print, an error that did not come)
SILENT = {"out_of_bar", "oob_alt", "missing", "spurious", "error_absent"}


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory):
    d = tmp_path_factory.mktemp("independent")
    gen.make_set(str(d), len(gen.CLASSES), 2027)  # one sheet of each class
    return _batch_outcomes(d, workers=2)


def _batch_outcomes(d, *, workers: int) -> list:
    """``run_batch`` over the set in ``d`` (its manifest; no threshold band), scored:
    its outcomes (:func:`score.score`)."""
    run_batch(
        None,
        d / "results.csv",
        manifest=d / "manifest.csv",
        options=Options(sensitivity=False),
        workers=workers,
        progress=False,
        resume=False,
    )
    return score.score(str(d))[0]


def test_independent_sheets_have_no_silent_wrong_number(outcomes):
    silent = [
        (o["file"], o["page"], o["outcome"], o.get("dL"), o.get("dW"), o.get("dA"))
        for o in outcomes
        if o["outcome"] in SILENT
    ]
    assert not silent, silent


def test_independent_sheets_every_class_is_measured(outcomes):
    kinds = Counter(o["kind"] for o in outcomes)
    assert set(kinds) == set(gen.CLASSES)
    measurable = [o for o in outcomes if o.get("expect") == "measure"]
    passed = [o for o in measurable if o["outcome"] == "pass"]
    assert len(passed) >= 0.9 * len(measurable), Counter(o["outcome"] for o in measurable)


def _sheet_of_set(d, seed: int, index: int) -> list:
    """Sheet ``index`` of the independent set ``seed`` (as ``gen.make_set`` makes
    it; not a PDF, not a dpi sheet), batched into ``d``: its outcomes."""
    master = np.random.default_rng(seed)
    order = []
    while len(order) <= index:
        order += list(master.permutation(gen.CLASSES))
    cls = order[index]
    assert cls not in ("pdf", "dpi"), cls
    rng = np.random.default_rng([seed, index])
    page, prints, info = gen.build_sheet(rng, cls)
    stem = os.path.join(d, f"s{seed}_{index:03d}_{cls}")
    path, _ = gen.save_image(rng, stem, page, page.img, page.dpi)
    fname = os.path.basename(path)
    rows = {
        "manifest.csv": [gen.manifest_row(fname, None, info["rolling_axis"], rng)],
        "truth.csv": gen.truth_rows(fname, 0, cls, prints),
    }
    info.update({"file": fname, "page": 0})
    with open(os.path.join(d, "sheets.json"), "w") as fh:
        json.dump([info], fh, default=str)
    for name, table in rows.items():
        with open(os.path.join(d, name), "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(table[0]))
            w.writeheader()
            w.writerows(table)
    return _batch_outcomes(d, workers=1)


def test_independent_sheet_bold_label_below_a_tip_is_no_part_of_the_print(tmp_path):
    # set 1 sheet 30: a marker's 'T6 2.4bar 360N' (6.1 mm, 14 letters) touching a
    # slick print's tip; 12 of the print's 14 elements were letters, so its
    # "typical element" was a letter and every letter a copy of it: the label
    # joined the print, width +226 %, status ok
    out = _sheet_of_set(tmp_path, 1, 30)
    assert len(out) == 3
    assert not [o for o in out if o["outcome"] in SILENT], out
    (first,) = [o for o in out if abs(float(o["truth"]["length_mm"]) - 65.89) < 0.01]
    # the label is no part of it (its width within the bar); its tip, where a letter
    # touches, is flagged (with OpenCV 5.0's glyphs the length reads -1.5 %)
    assert first["outcome"] in ("pass", "flagged") and abs(first["dW"]) <= 1.0, first


def test_independent_sheet_label_beside_a_chevron_print_is_set_aside_whole(tmp_path):
    # set 2 sheet 45: 'Pirelli 33mm' 3 mm off a chevron print. With the typical
    # elements taken from the print's own (not the letters), 'l' and 'i' stayed cut
    # copies of a chevron's arm, the print's, and flagged it; chained to the other
    # letters they are set aside with them (LABEL_LETTERS)
    out = _sheet_of_set(tmp_path, 2, 45)
    assert [o["outcome"] for o in out] == ["pass"], out
