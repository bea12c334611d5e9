"""Sheets of held-out generator 6 (tests/inkprint/heldout6, written from the user
docs and the scorer only) that a session's change measured right where it was
silently wrong, regenerated from their seed and index (the generator is
deterministic per sheet) and scored by the generator's own scorer
(tests/inkprint/independent/score.py): every print on the sheet is within the
issue's bar (1 % length and width, 2 % hull area) or flagged, none missing. A
session's cases:

* seed 4 sheet 109: a 0.08 mm^2 halo speck 0.5 mm off a tiny dot print's tip, kept
  as a cut dot, +4.9 % long (inkprint.sites, group._off_sites);
* seed 4 sheet 116: a tiny file print at 300 dpi whose outer row, cut to eight
  pieces, lost three as strokes: -4.1 % wide (group._dot_row with the pieces kept
  along the outline);
* seed 4 sheet 80: a tiny file print at 600 dpi, its cut wedges dropped as thin
  dots: -13.5 % wide (group._row_neighbours);
* seed 5 sheet 86: '51 kg' 3.8 mm off a car print's shoulder, 'k' set aside and
  '51', 'g' taken for the print's: +22 % wide (analyze._letters_pull, flagged now);
* seed 5 sheet 66 (a PDF, page 0): a tiny file print at 300 dpi whose outer row is
  six cut dots where it is widest, three a side: dropped as thin dots, -9.3 % wide
  (group._two_sided_row);
* seed 6 sheet 6: 'Maxxis Ardent 3.5bar', a bold label set against a slick print
  on chart paper, joined to it whole, no letter set aside: +101 % long
  (analyze._writing_pull, flagged now);
* seed 6 sheets 15, 75, 99 and 104: the next row of knobs or siped blocks beyond a
  print's tip, cut by the outline to slivers 2-7 px deep, set aside as letters,
  bold strokes or dust: -10.2, -10.3, -14.5 and -6.7 % long (inkprint.caps, every
  print on these sheets passes now);
* seed 6 sheets 60 and 117: a bold label ('GP5000 28', '90 psi') joined to a
  knobby and a siped print's side as their elements: +26 % and +54 % wide with
  status ok (inkprint.caps.off_lattice: flagged now);
* seed 2 sheet 3: a label's 'r' in such a row of caps above a knobby print, its
  foot on the knobs' edge: it is no cap (a letter's bends: inkprint.caps.CAP_SOLID;
  a first version took it, +1.0 % long, flagged);
* seed 7 sheet 38, seed 6 sheet 95: a tiny file and a tiny knurl print set aside as
  "a letter or a mark" (a print this small is solid), and seed 8 sheet 77, seed 3
  sheet 48: tiny prints set aside as fragments of a large print 12 mm off: missing
  with status ok (measured and flagged maybe_mark now);
* seed 9 sheet 93: a car print at 600 dpi whose three thin middle ribs were set
  aside as lines, its shoulders 41 mm apart kept as two prints: -80 % wide; seed 5
  sheet 49: a car print's 14.4 mm middle rib and 3.4 mm shoulders 12.4 mm apart,
  three prints not as long: -68 % wide, status ok (analyze._split_twins: flagged
  grouping_uncertain now);
* seed 7 sheet 2, seed 8 sheet 59, seed 3 sheet 40 (page 1): a bold label in a
  coloured pen ('run 19', '25 psi', '82 psi') joined to a car, knobby and rib
  print as its elements: +10 %, +21 % and +12 % with status ok (its letters paler
  than the print's ink: analyze._paler_at_edge, flagged mark_on_edge now);
* seed 2 sheet 61: a tiny file print at 150 dpi whose cut dots lie a pixel beyond
  its thin teeth, 6 px from its thick body: dropped, -16 % wide with status ok
  (group._body_gaps measures to the teeth now: within the bar);
* seed 7 sheet 10: a tiny file print at 300 dpi whose outline cut only its three
  middle teeth on one side to stubs: dropped as strokes' feet, -11 % wide with
  status ok (group._teeth takes a short side at a regular pitch now);
* seed 1 sheet 60, seed 7 sheets 47 and 60: labels written 1.9-5 mm off a print's
  tip, whose letters a first version of analyze._tip_pieces took for a tread
  block the outline cut (three good prints flagged): no such warning
  (analyze._alone; the sliver it flags: tests/inkprint/test_slivers.py).
"""

import csv
import json
import os

import pytest

import inkprint.cli
from tests.inkprint.heldout6 import gen
from tests.inkprint.independent.score import score


def _sheet(d: str, seed: int, index: int) -> list:
    """Write held-out 6 sheet ``index`` of ``seed`` to ``d`` with its truth, manifest
    and sheet notes, measure it with ``inkprint batch`` and score it: the
    outcomes (dicts with ``outcome``: pass, flagged, out_of_bar, missing, ...)."""
    truth, mani, infos = gen.make_file(d, index, seed, gen.KINDS[index % len(gen.KINDS)])
    for name, cols, rows in (
        ("truth.csv", gen.TRUTH_COLS, truth),
        ("manifest.csv", gen.MANI_COLS, mani),
    ):
        with open(os.path.join(d, name), "w", newline="") as fh:
            w = csv.DictWriter(fh, cols, extrasaction="ignore")
            w.writeheader()
            w.writerows(rows)
    with open(os.path.join(d, "sheets.json"), "w") as fh:
        json.dump(infos, fh, default=lambda o: o.item() if hasattr(o, "item") else str(o))
    out = os.path.join(d, "results.csv")
    manifest = os.path.join(d, "manifest.csv")
    code = inkprint.cli.main(["batch", d, "--manifest", manifest, "-o", out, "-q", "--no-resume"])
    assert code in (0, 1)
    return score(d)[0]


@pytest.mark.parametrize(
    ("seed", "index"),
    [
        (4, 109),
        (4, 116),
        (4, 80),
        (5, 86),
        (5, 66),
        (6, 6),
        (6, 60),
        (6, 117),
        (9, 93),
        (5, 49),
        (7, 2),
        (8, 59),
        (3, 40),
        (2, 61),
        (7, 10),
    ],
)
def test_heldout6_sheet_is_within_the_bar_or_flagged(tmp_path, seed, index):
    outcomes = [o for o in _sheet(str(tmp_path), seed, index) if o["expect"] == "measure"]
    assert outcomes
    wrong = [
        (o["file"], o["page"], o["outcome"], o.get("dL"), o.get("dW"), o.get("dA"))
        for o in outcomes
        if o["outcome"] not in ("pass", "flagged")
    ]
    assert not wrong


@pytest.mark.parametrize(("seed", "index"), [(6, 15), (6, 75), (6, 99), (6, 104), (2, 3)])
def test_heldout6_sheet_cut_caps_pass(tmp_path, seed, index):
    outcomes = [o for o in _sheet(str(tmp_path), seed, index) if o["expect"] == "measure"]
    assert outcomes
    assert all(o["outcome"] == "pass" for o in outcomes), [
        (o["page"], o["outcome"], o.get("dL"), o.get("dW"), o.get("dA")) for o in outcomes
    ]


@pytest.mark.parametrize(("seed", "index"), [(1, 60), (7, 47), (7, 60)])
def test_heldout6_sheet_label_off_a_tip_is_no_cut_block(tmp_path, seed, index):
    # labels written 1.9-5 mm off a print's tip: their letters near its axis are no
    # tread block the outline cut (analyze._tip_pieces with analyze._alone); a first
    # version flagged a good print on each of these sheets
    outcomes = [o for o in _sheet(str(tmp_path), seed, index) if o["expect"] == "measure"]
    assert outcomes
    with open(tmp_path / "results.csv", newline="") as fh:
        warnings = [r["warnings"] for r in csv.DictReader(fh)]
    assert warnings
    assert not any("set aside as a pen mark, tick or letter" in w for w in warnings)
    assert sum(o["outcome"] == "pass" for o in outcomes) >= 1


@pytest.mark.parametrize(("seed", "index"), [(7, 38), (6, 95), (8, 77), (3, 48)])
def test_heldout6_sheet_tiny_tread_print_set_aside_is_flagged(tmp_path, seed, index):
    # a tiny tread print (a file tread's 19.8 x 3.0 mm at 300 dpi; a knurl's 18.2 x
    # 6.1 mm at 240 dpi) inking 0.72-0.81 of its hull, set aside as "a letter or a
    # mark: a print this small or narrow is solid", or one 10.8 x 3.8 mm and 11.1 x
    # 4.6 mm set aside as a fragment of a large print 12 mm off, went missing with
    # status ok: it is measured and flagged maybe_mark
    # (inkprint.group.maybe_tiny_print)
    outcomes = [o for o in _sheet(str(tmp_path), seed, index) if o["expect"] == "measure"]
    assert outcomes
    assert all(o["outcome"] in ("pass", "flagged") for o in outcomes), [
        (o["page"], o["outcome"], o.get("dL"), o.get("dW")) for o in outcomes
    ]
    unsure = [o for o in outcomes if "maybe_mark" in (o.get("flags") or "")]
    assert len(unsure) == 1
    assert unsure[0]["truth"]["family"] == "tiny"
    assert float(unsure[0]["truth"]["length_mm"]) < 20.0
    # numbered after the sheet's other prints (a manifest's print numbers keep)
    with open(tmp_path / "results.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["status"] in ("ok", "flagged")]
    page = [r for r in rows if r["page"] == str(unsure[0]["page"])]
    last = max(page, key=lambda r: int(r["print"]))
    assert "maybe_mark" in last["flags"]
    assert sum("maybe_mark" in r["flags"] for r in page) == 1


def test_heldout6_sheet_group_set_aside_inside_a_print_stays_set_aside(tmp_path):
    # seed 1 sheet 108: a group the small-print rule set aside lies inside a tiny
    # lattice print's hull (the print's elements): no maybe_mark candidate, and it
    # stays among the marks (a first version dropped it from both)
    from inkprint import analyze_scan
    from inkprint.read import iter_scans

    truth, mani, _ = gen.make_file(str(tmp_path), 108, 1, gen.KINDS[108 % len(gen.KINDS)])
    name, dpi = mani[0]["file"], mani[0]["dpi"]
    (scan,) = iter_scans(tmp_path / name, dpi=float(dpi) if dpi else None)
    res = analyze_scan(scan, rolling_axis=mani[0]["rolling_axis"] or "auto", sensitivity=False)
    assert len(res.prints) == len(truth)
    assert not any("maybe_mark" in p.flags for p in res.prints)
    solid = [
        m for m in res.marks if m.kind == "writing" and "small or narrow is solid" in m.reason
    ]
    assert solid
