"""Issue 11: marks touching a print's outline that widened it silently (seeds of the
mixed sets): a one-pixel dust speck at the widest point, a label's stroke off a
slick print's tip.

``make_case(kind, seed=S * 100_003 + k)`` is file ``k`` of seed ``S`` of
``python -m inkprint.accuracy``.
"""

import numpy as np
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.analyze import edge_field
from inkprint.group import thin_protrusions
from inkprint.synth import render_sheet
from inkprint.synth_cases import make_case
from tests.inkprint.test_classes import assert_passes, outcomes


def mixed_file(seed: int, k: int) -> int:
    return seed * 100_003 + k


def test_analyze_scan_dust_pip_at_the_widest_point():
    # 4244/0082 page 0: a one-pixel speck (grey 71) on the print's top row at its
    # widest point, paper (~230) on both sides of it: width +1.15 %
    case = make_case("pdf", seed=mixed_file(4244, 82))
    img, truths = render_sheet(case.sheets[0])
    res = ip.analyze_scan(ip.Scan(img, 25.4 / case.sheets[0].dpi, "given"), sensitivity=False)
    m, t = res.prints[0].metrics, truths[0]
    assert_allclose(
        [m.length / t.length, m.width / t.width, m.hull_area / t.hull_area], 1.0, atol=0.005
    )


def test_edge_field_dust_pip_reads_as_paper_an_edge_run_as_ink():
    grey = np.full((20, 40), 0.95, np.float32)
    grey[10:, :] = 0.05  # ink below row 10
    grey[9, 20] = 0.3  # a dust speck on the edge
    grey[9, 5:8] = 0.3  # a short run of the edge itself (three pixels)
    mask = grey < 0.5
    f = edge_field(grey, mask, mm_per_px=0.1)
    assert f[9, 20] > 0  # paper: the outline stays on the edge
    assert (f[9, 5:8] < 0).all()  # the run keeps its ink
    loose = ip.AnalysisOptions(edge_pip_jump=1.0)
    assert edge_field(grey, mask, mm_per_px=0.1, options=loose)[9, 20] < 0


def test_thin_protrusions_label_stroke_off_a_slick_print_tip(tmp_path):
    # 4246/0060: a label's letter (A) beside a slick print's tip, off its ends along
    # its major axis, was kept as a tip block's sliver: hull area +2.5 %
    results, _ = outcomes(tmp_path, "label", mixed_file(4246, 60), dpi=None)
    assert_passes(results)
    (r,) = results
    assert_allclose([r["err_width"], r["err_hull_area"]], 0.0, atol=0.015)


def test_thin_protrusions_keeps_tip_pieces_of_a_block_pattern_only():
    m = np.zeros((60, 200), bool)
    m[20:40, 20:180] = True  # one-piece print
    m[28:31, 182:186] = True  # a thin piece off its right end
    assert not thin_protrusions(m, width_px=6.0)[28:31, 182:186].any()
    blocks = m.copy()
    blocks[20:40, 95:105] = False  # two blocks: a tread pattern
    assert thin_protrusions(blocks, width_px=6.0)[28:31, 182:186].all()
    one = ip.AnalysisOptions(tip_block_strokes=20.0)  # no piece is a block
    assert not thin_protrusions(blocks, width_px=6.0, options=one)[28:31, 182:186].any()
