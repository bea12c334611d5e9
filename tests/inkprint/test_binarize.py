"""inkprint.binarize: the sparse-ink fallback on a photographed sheet (issue 11)."""

import numpy as np
import pytest

import inkprint as ip


def _photo(fill_share=0.4):
    """A page (grey 0.8, grain 0.01) whose left ``fill_share`` of the image is the
    white fill put off a photographed sheet, with a 3 x 12 mm print (grey 0.2) at
    0.1 mm per px: about 0.1 % of the image."""
    rng = np.random.default_rng(4)
    grey = (0.8 + rng.normal(0.0, 0.01, (800, 1000))).astype(np.float32)
    sheet = np.ones(grey.shape, bool)
    sheet[:, : int(fill_share * grey.shape[1])] = False
    grey[~sheet] = 1.0
    grey[400:430, 600:720] = 0.2
    return grey, sheet


def test_binarize_tiny_print_on_a_photographed_sheet_reads_the_paper_alone():
    # held-out 11 sheets 8 and 116, 12 sheets 72 and 100: the fill spread the
    # histogram's interquartile range from paper to white, the grain looked 6x as
    # wide, and the print gave "nothing darker than the paper"
    grey, sheet = _photo()
    with pytest.raises(ip.NoInk, match="darker than the paper"):
        ip.binarize(grey, mm_per_px=0.1)
    b = ip.binarize(grey, mm_per_px=0.1, sheet=sheet)
    assert b.mask[400:430, 600:720].all()
    assert np.count_nonzero(b.mask) == 30 * 120
    assert 0.2 < b.threshold < 0.8


def test_binarize_sheet_of_another_shape_is_refused():
    grey, sheet = _photo()
    with pytest.raises(ip.InvalidInput, match="sheet"):
        ip.binarize(grey, mm_per_px=0.1, sheet=sheet[:, :-1])
