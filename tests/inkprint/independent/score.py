#!/usr/bin/env python3
"""Generate an independent set with gen.py, run `inkprint batch` on it and score it.

    python score.py --files 120 --seed 1            # set in /tmp/indep/1

Per truth print (matched to the nearest measured print of the same file/page by
centroid): pass (ok, |dL|<=1 %, |dW|<=1 %, |dA|<=2 %), flagged, out_of_bar (ok but
outside the bar: a silent wrong number), missing; per measured print without truth:
spurious (ok) or spurious_flagged.  Files that should fail: error_ok (right error
class), error_wrong (another class), error_absent (no error row came).
Clipped prints: pass = flagged 'clipped'; flagged without 'clipped' = flagged;
status ok = out_of_bar.  oob_alt: ok, outside the bar against the print's own rolling
axis but within it against the other reading (the sheet's x/y axis when the manifest
gives one and the print is turned by up to 0.5 deg; the hull's principal axis for auto).
"""

import argparse
import collections
import csv
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

BAR_L, BAR_W, BAR_A = 1.0, 1.0, 2.0


def fnum(x):
    try:
        v = float(x)
        return v if math.isfinite(v) else None
    except (TypeError, ValueError):
        return None


def pct(m, t):
    return 100.0 * (m - t) / t


def run_tool(d, workers):
    cmd = [
        "inkprint",
        "batch",
        d,
        "--manifest",
        os.path.join(d, "manifest.csv"),
        "-o",
        os.path.join(d, "results.csv"),
        "--workers",
        str(workers),
        "-q",
        "--no-resume",
    ]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode not in (0, 1):
        print("inkprint batch failed:", p.returncode, p.stderr[-3000:], file=sys.stderr)
        sys.exit(2)
    return p


def score(d):
    truth = list(csv.DictReader(open(os.path.join(d, "truth.csv"))))
    res = list(csv.DictReader(open(os.path.join(d, "results.csv"))))
    for r in res:  # the tool writes the path as given (absolute for an absolute folder)
        if os.path.isabs(r["file"]):
            r["file"] = os.path.relpath(r["file"], d)
    infos = {}
    for inf in json.load(open(os.path.join(d, "sheets.json"))):
        infos[(inf["file"], int(inf.get("page", 0)))] = inf
    byfp = collections.defaultdict(list)
    for r in res:
        pg = int(r["page"]) if r.get("page", "") not in ("", None) else 0
        byfp[(r["file"], pg)].append(r)
    byfile = collections.defaultdict(list)
    for r in res:
        byfile[r["file"]].append(r)
    tgroups = collections.defaultdict(list)
    for t in truth:
        tgroups[(t["file"], int(t["page"]))].append(t)

    outcomes = []  # dicts
    err_files_done = set()
    for (f, pg), ts in sorted(tgroups.items()):
        rows = byfp.get((f, pg), [])
        exp = ts[0]["expect"]
        if exp.startswith("error:"):
            if f in err_files_done:
                continue
            err_files_done.add(f)
            want = exp.split(":", 1)[1]
            errs = [r for r in byfile.get(f, []) if r["status"] == "error"]
            meas = [r for r in byfile.get(f, []) if r["status"] in ("ok", "flagged")]
            if errs and all(r["error"].startswith(want) for r in errs):
                oc = "error_ok"
            elif errs:
                oc = "error_wrong"
            else:
                oc = "error_absent"
            outcomes.append(
                {
                    "kind": ts[0]["kind"],
                    "file": f,
                    "page": pg,
                    "outcome": oc,
                    "expect": exp,
                    "got": "; ".join(r["error"][:140] for r in errs)
                    or f"{len(meas)} measured rows: "
                    + ", ".join(
                        f"{r['status']} L={fnum(r['length_mm']) or 0:.2f} W={fnum(r['width_mm']) or 0:.2f}"
                        for r in meas
                    ),
                }
            )
            continue
        meas = [
            r
            for r in rows
            if r["status"] in ("ok", "flagged") and fnum(r.get("centroid_x_mm")) is not None
        ]
        errs = [r for r in rows if r["status"] == "error"]
        pairs = []
        for i, t in enumerate(ts):
            tx, ty = float(t["centroid_x_mm"]), float(t["centroid_y_mm"])
            tol = 0.5 * max(float(t["length_mm"]), float(t["width_mm"])) + 10
            for j, r in enumerate(meas):
                dd = math.hypot(fnum(r["centroid_x_mm"]) - tx, fnum(r["centroid_y_mm"]) - ty)
                if dd <= tol:
                    pairs.append((dd, i, j))
        pairs.sort()
        ti, mj = {}, {}
        for dd, i, j in pairs:
            if i in ti or j in mj:
                continue
            ti[i], mj[j] = j, i
        for i, t in enumerate(ts):
            o = {"kind": t["kind"], "file": f, "page": pg, "expect": t["expect"], "truth": t}
            if i not in ti:
                o["outcome"] = "error_row" if errs else "missing"
                o["got"] = "; ".join(r["error"][:160] for r in errs)
                outcomes.append(o)
                continue
            r = meas[ti[i]]
            L, W, A = float(t["length_mm"]), float(t["width_mm"]), float(t["hull_area_mm2"])
            mL, mW, mA = fnum(r["length_mm"]), fnum(r["width_mm"]), fnum(r["hull_area_mm2"])
            dL, dW, dA = pct(mL, L), pct(mW, W), pct(mA, A)
            within = abs(dL) <= BAR_L and abs(dW) <= BAR_W and abs(dA) <= BAR_A
            flags = r.get("flags", "") or ""
            o.update(
                {
                    "status": r["status"],
                    "flags": flags,
                    "mL": mL,
                    "mW": mW,
                    "mA": mA,
                    "dL": dL,
                    "dW": dW,
                    "dA": dA,
                    "row": r,
                }
            )
            if fnum(t.get("length_alt_mm")) is not None:
                o["dL_alt"] = pct(mL, float(t["length_alt_mm"]))
                o["dW_alt"] = pct(mW, float(t["width_alt_mm"]))
            if t["expect"] == "clipped":
                if r["status"] == "flagged" and "clipped" in flags:
                    o["outcome"] = "pass"
                elif r["status"] == "flagged":
                    o["outcome"] = "flagged"
                else:
                    o["outcome"] = "out_of_bar"
            else:
                if r["status"] == "flagged":
                    o["outcome"] = "flagged"
                    o["within"] = within
                elif within:
                    o["outcome"] = "pass"
                elif (
                    "dL_alt" in o
                    and abs(o["dL_alt"]) <= BAR_L
                    and abs(o["dW_alt"]) <= BAR_W
                    and abs(dA) <= BAR_A
                ):
                    # right for the other reading of the axis (sheet axis / principal axis)
                    o["outcome"] = "oob_alt"
                else:
                    o["outcome"] = "out_of_bar"
            outcomes.append(o)
        for j, r in enumerate(meas):
            if j in mj:
                continue
            outcomes.append(
                {
                    "kind": ts[0]["kind"],
                    "file": f,
                    "page": pg,
                    "expect": "none",
                    "outcome": "spurious" if r["status"] == "ok" else "spurious_flagged",
                    "status": r["status"],
                    "flags": r.get("flags", ""),
                    "row": r,
                    "mL": fnum(r["length_mm"]),
                    "mW": fnum(r["width_mm"]),
                    "mA": fnum(r["hull_area_mm2"]),
                }
            )
    return outcomes, infos


COLS = [
    "pass",
    "flagged",
    "out_of_bar",
    "oob_alt",
    "missing",
    "error_row",
    "spurious",
    "spurious_flagged",
    "error_ok",
    "error_wrong",
    "error_absent",
]


def report(outcomes, infos, d):
    kinds = []
    for o in outcomes:
        if o["kind"] not in kinds:
            kinds.append(o["kind"])
    tab = {k: collections.Counter() for k in kinds}
    for o in outcomes:
        tab[o["kind"]][o["outcome"]] += 1
    hdr = f"{'class':<11}" + "".join(f"{c:>9}" if len(c) <= 9 else f"{c[:9]:>10}" for c in COLS)
    print(hdr)
    tot = collections.Counter()
    for k in kinds:
        print(
            f"{k:<11}"
            + "".join(f"{tab[k][c]:>9}" if len(c) <= 9 else f"{tab[k][c]:>10}" for c in COLS)
        )
        tot.update(tab[k])
    print(
        f"{'TOTAL':<11}"
        + "".join(f"{tot[c]:>9}" if len(c) <= 9 else f"{tot[c]:>10}" for c in COLS)
    )
    meas = [o for o in outcomes if o["expect"] == "measure"]
    npass = sum(o["outcome"] == "pass" for o in meas)
    print(
        f"\nmeasurable prints: {len(meas)}; pass {npass} ({100 * npass / max(len(meas), 1):.1f} %); "
        f"flagged {sum(o['outcome'] == 'flagged' for o in meas)} "
        f"(of which within the bar {sum(o['outcome'] == 'flagged' and o.get('within') for o in meas)}); "
        f"out_of_bar {sum(o['outcome'] == 'out_of_bar' for o in meas)}; "
        f"oob_alt (right only along the sheet/principal axis) {sum(o['outcome'] == 'oob_alt' for o in meas)}; "
        f"missing {sum(o['outcome'] in ('missing', 'error_row') for o in meas)}"
    )
    cl = [o for o in outcomes if o["expect"] == "clipped"]
    print(
        f"clipped prints: {len(cl)}; flagged clipped {sum(o['outcome'] == 'pass' for o in cl)}; "
        f"silent ok {sum(o['outcome'] == 'out_of_bar' for o in cl)}"
    )
    er = [o for o in outcomes if o["expect"].startswith("error:")]
    print(f"error files: {len(er)}; right error {sum(o['outcome'] == 'error_ok' for o in er)}")

    print("\n--- every non-pass ---")
    order = {
        "out_of_bar": 0,
        "oob_alt": 0.5,
        "spurious": 1,
        "missing": 2,
        "error_row": 3,
        "error_absent": 4,
        "error_wrong": 5,
        "flagged": 6,
        "spurious_flagged": 7,
    }
    for o in sorted(
        [o for o in outcomes if o["outcome"] not in ("pass", "error_ok")],
        key=lambda o: (order.get(o["outcome"], 9), o["kind"], o["file"]),
    ):
        path = os.path.join(d, o["file"])
        inf = infos.get((o["file"], o["page"]), {})
        meta = (
            f"dpi={inf.get('dpi')} fmt={inf.get('format', inf.get('pdf_enc'))} ch={inf.get('channels')} "
            f"axis={inf.get('rolling_axis')} blur={inf.get('blur_px')}"
        )
        line = f"[{o['outcome']}] {o['kind']} {path} p{o['page']} ({meta})"
        if "truth" in o:
            t = o["truth"]
            line += (
                f"\n    truth L={float(t['length_mm']):.2f} W={float(t['width_mm']):.2f} "
                f"A={float(t['hull_area_mm2']):.1f} at ({float(t['centroid_x_mm']):.1f},{float(t['centroid_y_mm']):.1f}) "
                f"{t['family']}/{t['outline']}/{t['tread']} ang={float(t['angle_deg']):.2f} expect={t['expect']} ink={t['ink_dark']}"
            )
            if t["notes"] not in ("{}", ""):
                line += f"\n    notes {t['notes']}"
        if o.get("mL") is not None:
            r = o["row"]
            line += (
                f"\n    got {o.get('status')} flags=[{o.get('flags')}] L={o['mL']:.2f} W={o['mW']:.2f} A={o['mA']:.1f} "
                f"at ({fnum(r['centroid_x_mm']):.1f},{fnum(r['centroid_y_mm']):.1f}) axis_src={r.get('axis_source')} "
                f"ang={r.get('angle_deg')} set_aside={r.get('set_aside')!r} warn={r.get('warnings')!r}"
            )
        if "dL" in o:
            line += f"\n    dL={o['dL']:+.2f}% dW={o['dW']:+.2f}% dA={o['dA']:+.2f}%"
            if "dL_alt" in o:
                line += f"  (vs {o['truth']['alt_kind']} extents: dL={o['dL_alt']:+.2f}% dW={o['dW_alt']:+.2f}%)"
            if "truth" in o:
                pmm = 25.4 / float(inf.get("dpi", 300))
                line += (
                    f"  [dL={o['mL'] - float(o['truth']['length_mm']):+.3f} mm, "
                    f"dW={o['mW'] - float(o['truth']['width_mm']):+.3f} mm; px={pmm:.4f} mm]"
                )
        if o.get("got"):
            line += f"\n    got: {o['got']}"
        print(line)
    # machine-readable
    with open(os.path.join(d, "score.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(
            [
                "kind",
                "file",
                "page",
                "expect",
                "outcome",
                "status",
                "flags",
                "truth_L",
                "truth_W",
                "truth_A",
                "L",
                "W",
                "A",
                "dL_pct",
                "dW_pct",
                "dA_pct",
                "dL_alt_pct",
                "dW_alt_pct",
            ]
        )
        for o in outcomes:
            t = o.get("truth", {})
            w.writerow(
                [
                    o["kind"],
                    o["file"],
                    o["page"],
                    o["expect"],
                    o["outcome"],
                    o.get("status", ""),
                    o.get("flags", ""),
                    t.get("length_mm", ""),
                    t.get("width_mm", ""),
                    t.get("hull_area_mm2", ""),
                    o.get("mL", ""),
                    o.get("mW", ""),
                    o.get("mA", ""),
                    *(
                        f"{o[k]:.3f}" if k in o else ""
                        for k in ("dL", "dW", "dA", "dL_alt", "dW_alt")
                    ),
                ]
            )
    return tot


def main():
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--files", type=int, default=120)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default=None, help="set folder (default /tmp/indep/<seed>)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--reuse", action="store_true", help="reuse an existing set and results.csv")
    a = ap.parse_args()
    d = a.out or f"/tmp/indep/{a.seed}"
    if not (a.reuse and os.path.exists(os.path.join(d, "results.csv"))):
        if not (a.reuse and os.path.exists(os.path.join(d, "truth.csv"))):
            import gen

            if os.path.isdir(d):
                for fn in os.listdir(d):
                    os.remove(os.path.join(d, fn))
            gen.make_set(d, a.files, a.seed)
        p = run_tool(d, a.workers)
        print(p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "", file=sys.stderr)
    outcomes, infos = score(d)
    print(f"set: {d}")
    report(outcomes, infos, d)


if __name__ == "__main__":
    main()
