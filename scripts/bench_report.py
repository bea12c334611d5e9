"""Benchmark: the README main job, end to end and per stage (issue 5).

Stages: batch analysis of the bundled scans (2 workers), model pairing (one solve
per load case), trends + tables + figures, renders; then the whole job through the
``inkprint batch ... --report`` command as a user runs it.

Run: python scripts/bench_report.py
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from contactpatch import build_report, pair_prints  # noqa: E402
from contactpatch.study.report import render_tires  # noqa: E402
from inkprint.batch import Options, run_batch  # noqa: E402

ASSETS = ROOT / "assets" / "prints"


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "report"
        t0 = time.perf_counter()
        res = run_batch(
            ASSETS,
            out / "prints.csv",
            manifest=ASSETS / "manifest.csv",
            options=Options(),
            workers=2,
            progress=False,
        )
        t1 = time.perf_counter()
        paired = pair_prints(res.rows)
        t2 = time.perf_counter()
        build_report(res.rows, out, renders=False)
        t3 = time.perf_counter()
        render_tires(paired, out / "figures")
        t4 = time.perf_counter()
        print(f"{len({r['file'] for r in res.rows})} scans, {len(res.rows)} prints")
        print(f"  batch analysis (2 workers)           : {t1 - t0:6.2f} s")
        print(
            f"  model pairing ({len({(r['tire'], r['pressure_bar'], r['load_N'], r['surface']) for r in res.rows})} load cases)         : {t2 - t1:6.2f} s"
        )
        print(
            f"  trends, tables, figures, HTML        : {t3 - t2:6.2f} s (includes a second pairing)"
        )
        print(f"  renders (2 views x 3 tires)          : {t4 - t3:6.2f} s")
        shutil.rmtree(out)
        t5 = time.perf_counter()
        subprocess.run(
            [
                sys.executable,
                "-m",
                "inkprint.cli",
                "batch",
                str(ASSETS),
                "--manifest",
                str(ASSETS / "manifest.csv"),
                "-o",
                str(out / "prints.csv"),
                "--report",
                str(out),
                "--quiet",
            ],
            check=True,
            capture_output=True,
        )
        t6 = time.perf_counter()
        print(f"README main job end to end (command)   : {t6 - t5:6.2f} s  (target < 180 s)")


if __name__ == "__main__":
    main()
