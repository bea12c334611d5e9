"""Accuracy of the print analysis on a fresh generated set mixing every failure class.

``python -m inkprint.accuracy --files 120 --seed 7`` writes a new set of sheets with
:func:`inkprint.synth_cases.make_mixed_set` (exact truth), runs ``inkprint batch``
on it with its manifest (``dpi``, ``rolling_axis`` per file, as a user would write
it), and compares every print with its truth. The bar (issue 11): at least 95 % of
the measurable prints within 1 % in length, 1 % in width and 2 % in hull area, and
no silent wrong number: a print that cannot be measured (clipped, photographed at
an angle) must be flagged, a file that cannot be read must give an error row.

Outcomes per expected print: ``pass`` (measured, unflagged, within the bar),
``out_of_bar`` (measured, unflagged, outside: a silent wrong number), ``flagged``
(an unmeasurable print, flagged as expected), ``missed_flag`` (an unmeasurable print
reported as ok: silent), ``overflagged`` (a measurable print flagged: lost, not
silent), ``missing`` (no print found where one is; loud when the file has an error
row); per file: ``error_ok`` (the expected error), ``spurious`` (a print that is not
one, unflagged).
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from collections import Counter, defaultdict
from pathlib import Path

from tiremesh.io import cell_number

TOLERANCE = {"length_mm": 0.01, "width_mm": 0.01, "hull_area_mm2": 0.02}


def _errors(measured: dict, truth: dict) -> dict:
    return {
        k: (cell_number(measured.get(k)) or math.nan) / float(truth[k]) - 1.0 for k in TOLERANCE
    }


def _within(err: dict) -> bool:
    return all(abs(err[k]) <= tol for k, tol in TOLERANCE.items())


def _match(truths: list[dict], measured: list[dict]) -> list[tuple]:
    """Pairs (truth, measured or None) by nearest centroid, each used once."""
    pairs, free = [], list(measured)
    for t in sorted(truths, key=lambda t: -float(t["hull_area_mm2"])):
        tx, ty = float(t["centroid_x_mm"]), float(t["centroid_y_mm"])
        reach = 0.35 * max(float(t["length_mm"]), float(t["width_mm"]))
        best, dist = None, reach
        for m in free:
            d = math.hypot(
                (cell_number(m.get("centroid_x_mm")) or 1e9) - tx,
                (cell_number(m.get("centroid_y_mm")) or 1e9) - ty,
            )
            if d <= dist:
                best, dist = m, d
        if best is not None:
            free.remove(best)
        pairs.append((t, best))
    return pairs + [(None, m) for m in free]


def _outcome(t: dict | None, m: dict | None) -> tuple[str, dict]:
    if t is None:
        return ("flagged_spurious" if m.get("status") == "flagged" else "spurious"), {}
    if m is None:
        return "missing", {}
    flagged = m.get("status") == "flagged"
    if t["expect"] != "measure":
        return ("flagged" if flagged else "missed_flag"), {}
    err = _errors(m, t)
    if flagged:
        return "overflagged", err
    return ("pass" if _within(err) else "out_of_bar"), err


def compare(rows: list[dict], truth: list[dict]) -> list[dict]:
    """Every expected print (and every file's expected error) with its outcome.

    Parameters
    ----------
    rows : list of dict
        An ``inkprint batch`` table (file, page, status, flags, length_mm, ...).
    truth : list of dict
        :func:`inkprint.synth_cases.make_mixed_set`'s ``truth.csv``.

    Returns
    -------
    list of dict
        ``file``, ``kind``, ``page``, ``outcome``, the relative errors
        ``err_length``, ``err_width``, ``err_hull_area`` and the measured ``flags``.
    """
    by_file = defaultdict(list)
    for r in rows:
        by_file[str(r.get("file", "")).rsplit("/", 1)[-1]].append(r)
    out = []
    for fname, ts in _group(truth).items():
        got = by_file.get(fname, [])
        errs = [r for r in got if r.get("status") == "error"]
        expect_error = [t for t in ts if t.get("error")]
        if expect_error:
            want = expect_error[0]["error"]
            ok = bool(errs) and any(str(r.get("error", "")).startswith(want) for r in errs)
            out.append(_row(fname, expect_error[0], "", "error_ok" if ok else "error_missed", {}))
            continue
        for page in sorted({str(t["page"]) for t in ts}):
            tp = [t for t in ts if str(t["page"]) == page]
            mp = [r for r in got if str(r.get("page", "0")) == page and r.get("status") != "error"]
            for t, m in _match(tp, mp):
                outcome, err = _outcome(t, m)
                if outcome == "missing" and errs:
                    outcome = "missing_error"
                out.append(_row(fname, t or tp[0], page, outcome, err, m))
    return out


def _group(truth: list[dict]) -> dict:
    g = defaultdict(list)
    for t in truth:
        g[t["file"]].append(t)
    return g


def _row(fname, t, page, outcome, err, m=None) -> dict:
    return {
        "file": fname,
        "kind": t.get("kind", ""),
        "page": page,
        "expect": t.get("expect") or t.get("error", ""),
        "outcome": outcome,
        "err_length": err.get("length_mm", math.nan),
        "err_width": err.get("width_mm", math.nan),
        "err_hull_area": err.get("hull_area_mm2", math.nan),
        "flags": (m or {}).get("flags", ""),
        "error": (m or {}).get("error", ""),
    }


SILENT = ("out_of_bar", "missed_flag", "spurious", "error_missed", "missing")


def summary(results: list[dict]) -> str:
    """A text report: pass rate, silent failures, per-class outcomes.

    Parameters
    ----------
    results : list of dict
        From :func:`compare`.

    Returns
    -------
    str
    """
    measurable = [r for r in results if r["expect"] == "measure"]
    passed = sum(r["outcome"] == "pass" for r in measurable)
    silent = [r for r in results if r["outcome"] in SILENT]
    lines = [
        f"measurable prints: {len(measurable)}, within 1 % length, 1 % width, 2 % hull "
        f"area: {passed} ({100 * passed / max(len(measurable), 1):.1f} %)",
        f"silent wrong outcomes (unflagged out of bar, missed flags or errors, spurious, "
        f"missing): {len(silent)}",
        "",
        f"{'class':<11} {'n':>4}  outcomes",
    ]
    for kind in sorted({r["kind"] for r in results}):
        rs = [r for r in results if r["kind"] == kind]
        c = Counter(r["outcome"] for r in rs)
        lines.append(
            f"{kind:<11} {len(rs):>4}  " + ", ".join(f"{k} {v}" for k, v in c.most_common())
        )
    bad = [r for r in results if r["outcome"] not in ("pass", "flagged", "error_ok")]
    if bad:
        lines += ["", "not passing:"]
        for r in bad:
            lines.append(
                f"  {r['file']} p{r['page']} {r['outcome']}: dL {100 * r['err_length']:+.2f} %, "
                f"dW {100 * r['err_width']:+.2f} %, dA {100 * r['err_hull_area']:+.2f} % "
                f"{r['flags']} {r['error'][:80]}"
            )
    return "\n".join(lines)


def run(
    out_dir, *, n_files: int, seed: int, workers: int | None = None, dpi: float | None = None
) -> list[dict]:
    """Generate a mixed set in ``out_dir``, analyse it with its manifest, compare.

    Parameters
    ----------
    out_dir : str or PathLike
    n_files : int
    seed : int
    workers : int, optional
        Batch worker processes.
    dpi : float, optional [dots per inch]
        One resolution for every sheet (see :func:`make_mixed_set`).

    Returns
    -------
    list of dict
        :func:`compare`'s outcomes.
    """
    from .batch import Options, run_batch
    from .csvsafe import read_csv
    from .synth_cases import make_mixed_set

    manifest, truth = make_mixed_set(out_dir, n_files=n_files, seed=seed, dpi=dpi)
    res = run_batch(
        None,
        Path(out_dir) / "results.csv",
        manifest=manifest,
        options=Options(sensitivity=False),
        workers=workers,
        progress=False,
        resume=False,
    )
    return compare(res.rows, read_csv(truth))


def main(argv=None) -> int:
    """Command line: generate, analyse, compare, print the report.

    Parameters
    ----------
    argv : sequence of str, optional

    Returns
    -------
    int
        0 when the bar is met and nothing is silently wrong, else 1.
    """
    p = argparse.ArgumentParser(
        prog="python -m inkprint.accuracy", description=__doc__.split("\n")[0]
    )
    p.add_argument("--files", type=int, default=120, help="files to generate (>= 100 sheets)")
    p.add_argument("--seed", type=int, default=int(time.time()) % 100_000)
    p.add_argument("--workers", type=int)
    p.add_argument(
        "--keep", metavar="DIR", help="write the set here (default: a temporary folder)"
    )
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    if a.keep:
        results = run(a.keep, n_files=a.files, seed=a.seed, workers=a.workers)
    else:
        with tempfile.TemporaryDirectory() as tmp:
            results = run(tmp, n_files=a.files, seed=a.seed, workers=a.workers)
    print(f"seed {a.seed}, {a.files} files, {time.perf_counter() - t0:.0f} s")
    print(summary(results))
    measurable = [r for r in results if r["expect"] == "measure"]
    rate = sum(r["outcome"] == "pass" for r in measurable) / max(len(measurable), 1)
    return 0 if rate >= 0.95 and not any(r["outcome"] in SILENT for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
