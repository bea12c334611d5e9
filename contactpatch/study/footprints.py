"""Plain Rotta patch vs rounded print footprint, both against the prints.

The plain patch (chapter 5) has pointed ends; the rounded footprint
(:mod:`tiremesh.footprint`, beyond the dissertation: 7.3.1) smooths the membrane
pressure through tread, ink and paper and keeps where it reaches a fraction of the
inflation pressure. Per tire and surface this module gives the median print / model
ratio of length, width and hull area for the plain patch, its section 5.4 ellipse
(the dissertation's comparison, lengths and widths of ellipse fits on both sides)
and the rounded footprint, so the report shows which agrees with the prints.
"""

from __future__ import annotations

import math
import statistics

from tiremesh.io import cell_number

#: (label, print/model ratio columns of length, width, area) per model footprint
FOOTPRINTS = (
    ("plain patch", ("ratio_length", "ratio_width", "ratio_area")),
    ("plain, ellipse fits", ("ratio_ellipse_length", "ratio_ellipse_width", "ratio_ellipse_area")),
    ("rounded footprint", ("ratio_rounded_length", "ratio_rounded_width", "ratio_rounded_area")),
)


def _median(values) -> float:
    vals = [v for v in values if v is not None and math.isfinite(v)]
    return statistics.median(vals) if vals else math.nan


def footprint_rows(paired: list[dict]) -> list[dict]:
    """Median print / model ratios per tire and surface for each model footprint.

    Parameters
    ----------
    paired : list of dict
        Paired rows (:func:`contactpatch.study.compare.pair_prints`) with the ratio
        columns of :data:`contactpatch.study.compare.RATIOS`.

    Returns
    -------
    list of dict
        One row per (tire, surface, footprint) with ``n`` prints and
        ``ratio_length``, ``ratio_width``, ``ratio_area`` [-] (median print / model,
        1 = agreement), then one row per footprint over all prints (tire ``all``).
    """
    ok = [r for r in paired if r.get("model_status", "ok") == "ok"]
    groups: dict = {}
    for r in ok:
        groups.setdefault((str(r.get("tire", "")), str(r.get("surface", ""))), []).append(r)
    groups[("all", "")] = ok
    out = []
    for (tire, surface), rows in sorted(groups.items(), key=lambda kv: kv[0] == ("all", "")):
        for label, cols in FOOTPRINTS:
            med = [_median(cell_number(r.get(c)) for r in rows) for c in cols]
            out.append(
                {
                    "tire": tire,
                    "surface": surface,
                    "footprint": label,
                    "n": len(rows),
                    "ratio_length": med[0],
                    "ratio_width": med[1],
                    "ratio_area": med[2],
                }
            )
    return out


__all__ = ["FOOTPRINTS", "footprint_rows"]
