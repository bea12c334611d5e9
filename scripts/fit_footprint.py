"""Global fit of the rounded footprint to the preserved prints, with leave-one-out.

Usage: ``python scripts/fit_footprint.py`` (about 2 minutes on one core). Prints the
model / measured ratios of every preserved print number for the plain patch (its
extent, Figure 5-15's ellipse, and the print ellipse of its outline) and for the
rounded footprint at the global fit, then the leave-one-out predictions. The output is
reproduced in ``docs/model.md`` ("Rounded footprint").
"""

from __future__ import annotations

import numpy as np

from contactpatch.study import footprint_fit as ff


def _plain_print(sh, conds) -> dict:
    """The plain outline measured like a print (print ellipse, area)."""
    saved = ff._plain
    ff._plain = lambda p: np.array([*ff.print_ellipse(p.outline), p.area])
    try:
        return ff.model_values(sh, conds, rounded=False)
    finally:
        ff._plain = saved


def main() -> None:
    """Fit, print the ratio table and the leave-one-out errors."""
    conds = ff.fit_conditions()
    every = [conds["maxxis_plate"], conds["maxxis_drum"], conds["big_apple"]]
    sh = ff.build_shapes(every + [c for pair in conds["pairs"] for c in pair])
    rounded = ff.model_values(sh, conds)
    plain = ff.model_values(sh, conds, rounded=False)
    plain_print = _plain_print(sh, conds)
    i, j, cost = ff.best_fit(rounded, list(ff.TARGETS))
    print(f"conditions for 4.1.10 / Table 4-1: {len(conds['pairs'])} (drum and plate each)")
    print(f"global fit: spread = {ff.SPREADS[i]:g} mm, threshold = {ff.THRESHOLDS[j]:g}")
    print(f"cost (sum of squared log ratios over {len(ff.TARGETS)} numbers) = {cost:.4f}\n")
    print(
        "| print number | measured | plain (Fig 5-15 ellipse) | plain (print ellipse) "
        "| rounded (print ellipse) |"
    )
    print("|---|---|---|---|---|")
    for n, (m, _) in ff.TARGETS.items():
        print(
            f"| {n} | {m:g} | {plain[n] / m:.3f} | {plain_print[n] / m:.3f} "
            f"| {rounded[n][i, j] / m:.3f} |"
        )
    for by in ("number", "group"):
        loo = ff.leave_one_out(rounded, by=by)
        print(f"\nleave-one-out by {by}:\n")
        print("| left out | refit spread [mm] | refit threshold | predicted / measured |")
        print("|---|---|---|---|")
        for r in loo:
            print(f"| {r['name']} | {r['spread_mm']:g} | {r['threshold']:g} | {r['ratio']:.3f} |")
        err = np.log([r["ratio"] for r in loo])
        print(f"\nRMS log error {np.sqrt(np.mean(err**2)):.3f}, max |log| {np.abs(err).max():.3f}")
    fit_err = np.log([rounded[n][i, j] / m for n, (m, _) in ff.TARGETS.items()])
    pl_err = np.log([plain_print[n] / m for n, (m, _) in ff.TARGETS.items()])
    print(
        f"\nin-sample RMS log error: rounded {np.sqrt(np.mean(fit_err**2)):.3f}, "
        f"plain (print ellipse) {np.sqrt(np.mean(pl_err**2)):.3f}"
    )


if __name__ == "__main__":
    main()
