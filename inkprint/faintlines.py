"""Faint page-axis lines across a print's edge: chart paper's gridlines, too light
to threshold as ink, darken the paper and the print's blurred edge where they cross
it. The print's edge, found at half contrast between the local paper and ink
(:func:`inkprint.analyze.edge_field`), bulges out by a pixel at each crossing, and
a line running along the print's widest side adds its width: tiny slick prints on
held-out chart-paper sheets measured 1.2 to 5.1 % too wide, with status ok.

The lines are taken out of the grey by dividing by their transmission (ink over a
printed line: the reflectances multiply). A row's transmission is read on the paper
either side of the print, in the margins of its box: the lighter side's median grey
(a label beside the print darkens one side only) against the rows near it. Only
lines letting through ``faint_line_least`` of the light or more are divided out:
darker gridlines threshold as ink and are taken out as gridlines
(:mod:`inkprint.gridlines`), and ink over them may hide rather than multiply. Only
page-axis lines: chart paper laid on a scanner is within a degree or two of the
page's axes.
"""

from __future__ import annotations

import numpy as np

__all__ = ["line_transmission", "without_faint_lines"]


def _row_medians(m: np.ndarray) -> np.ndarray:
    """``np.median(m, axis=1)`` of float grey levels (no NaN), to the last bit: the
    middle of each sorted row, or the mean of the middle two as numpy takes it
    (their sum in the array's dtype, halved). A sort of these short rows (a few
    dozen pixels) is twice as fast as numpy's median, whose selection is slow on
    rows of equal grey levels and on the strided rows of a margin's columns."""
    s = np.sort(m, axis=1)
    k = s.shape[1] // 2
    if s.shape[1] % 2:
        return s[:, k]
    return (s[:, k - 1] + s[:, k]) / s.dtype.type(2)


def _running_median(v: np.ndarray, half: int) -> np.ndarray:
    """Median of ``v`` over a window of ``2 half + 1`` (edge values repeated)."""
    from numpy.lib.stride_tricks import sliding_window_view

    return _row_medians(sliding_window_view(np.pad(v, half, mode="edge"), 2 * half + 1))


def line_transmission(before, after, *, line_px: int, darker: float, least: float) -> np.ndarray:
    """Each row's transmission of a line along it, read in the margins of paper
    either side of a print.

    A row's level is the lighter of its median grey in the two margins (a label
    beside the print darkens one side only; a gridline crosses both); its
    transmission, that level against the median level of the rows within
    ``3 line_px``. 1 where the row is not darker than those by more than
    ``darker``, or the transmission is below ``least`` (no faint line: ink, a
    ruler lying across).

    Parameters
    ----------
    before, after : (h, k) float [0-1]
        The grey of the margins, row by row (``k`` may be 0 for one of them: the
        print at the page's edge).
    line_px : int [px]
        The widest line.
    darker : float [grey]
        How much darker than the rows near it a row must be to hold a line.
    least : float
        The least transmission of a line divided out.

    Returns
    -------
    (h,) float in (0, 1]
    """
    sides = [_row_medians(m) for m in (before, after) if m.shape[1] >= line_px]
    if not sides or len(sides[0]) < 6 * line_px + 1:
        return np.ones(before.shape[0])
    level = np.maximum.reduce(sides)
    base = _running_median(level, 3 * line_px)
    t = np.minimum(level / np.maximum(base, 1e-6), 1.0)
    return np.where((base - level > darker) & (t >= least), t, 1.0)


def without_faint_lines(grey, inner: tuple, *, line_px: int, darker: float, least: float):
    """The grey of a print's box with faint row and column lines divided out
    (:func:`line_transmission`), read in the box's margins around ``inner``.

    Parameters
    ----------
    grey : (h, w) float32 [0-1]
        The print's box with a margin of paper around it.
    inner : (r0, r1, c0, c1) int [px]
        The print's own box within it.
    line_px, darker, least
        As for :func:`line_transmission`.

    Returns
    -------
    flat : (h, w) float32
        The grey without the lines (the same array when no line was found).
    on_line : (h, w) bool
        The pixels under a line found.
    """
    r0, r1, c0, c1 = inner
    kw = dict(line_px=line_px, darker=darker, least=least)
    tr = line_transmission(grey[:, :c0], grey[:, c1:], **kw)
    tc = line_transmission(grey[:r0].T, grey[r1:].T, **kw)
    on_line = (tr < 1.0)[:, None] | (tc < 1.0)[None, :]
    if not on_line.any():
        return grey, on_line
    return (grey / (tr[:, None] * tc[None, :])).astype(np.float32), on_line
