"""Benchmark: the README main job, today's (a baseline commit) and the new one side by
side in one run, stage by stage; and the report at 24, 200 and 1,000 prints (issues 5,
13).

* The baseline is extracted with ``git archive BASE | tar -x`` into a temporary folder
  (the repository is only read). Its own ``scripts/bench_report.py`` prints its stage
  times; its ``inkprint batch ... --report`` is today's main job.
* The new stages are timed in a fresh interpreter, as a user runs them.
* The main jobs run alternately ``--runs`` times; the best and median of each and
  their ratio are printed. The new job is the README command; if the working tree's
  ``inkprint`` command does not start, the same two calls (``run_batch``, then
  ``build_report``) through the Python API.
* The new report's validation section is cached between reports (``$ROTTA_CACHE_DIR``):
  the first new run computes it (printed as "validation cold"), the others read it.
* Scale: the report of synthetic paired rows (4 tires, ellipse hulls, no scans) for
  200 and 1,000 prints, and of the bundled 24, with renders, without validation:
  time and size of ``index.html``.

Run: python scripts/bench_report.py [--base 622b585] [--runs 3] [--no-scale]
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ASSETS = ROOT / "assets" / "prints"
README_JOB = ["batch", "assets/prints", "--manifest", "assets/prints/manifest.csv"]

NEW_STAGES = textwrap.dedent(
    """
    import sys, time
    from pathlib import Path

    def main():
        t0 = time.perf_counter()
        from inkprint.batch import Options, run_batch
        from contactpatch.study import report as R
        from contactpatch.study.pages import html_page, markdown_page
        from contactpatch.study.worker import Job
        out = Path(sys.argv[1])
        lap = [time.perf_counter()]
        def say(name):
            now = time.perf_counter()
            print(f"  {name:38s}: {now - lap[0]:6.2f} s")
            lap[0] = now
        say("imports")
        try:
            rows = run_batch("assets/prints", out / "prints.csv",
                             manifest="assets/prints/manifest.csv", options=Options(), workers=2,
                             progress=False).rows
            say("batch analysis (2 workers)")
        except Exception as exc:  # the working tree's inkprint is being edited
            import csv
            print(f"  batch analysis failed in the working tree ({type(exc).__name__}: {exc});")
            print("  the report stages below use today's batch table")
            with open(sys.argv[2], newline="", encoding="utf-8") as fh:
                rows = list(csv.DictReader(fh))
            lap[0] = time.perf_counter()
        start = time.perf_counter()
        from tiremesh.render import render_many
        cases = R.representative_cases(rows)
        job = Job(render_many, R.render_items(cases, out / "figures"), size=R.RENDER_SIZE)
        tables = R.compute_tables(rows)
        say("pairing, trends, errors, rim (tables)")
        colours = R.tire_colours(r["tire"] for r in tables.paired if r.get("model_status") == "ok")
        R.write_tables(out, tables, R.report_config(rows, tables))
        figs = R.draw_figures(tables, out / "figures", colours)
        say(f"figures ({4 + len(colours)}, SVG, drawn once)")
        sheets = R.collect_sheets(tables.paired)
        say(f"scans: QA overlays ({len(sheets)} sheets)")
        viewer = R.viewer_cases(cases)
        say("3D view meshes")
        paths = job.result()
        renders = [R.Render(p, p.read_bytes(), R.render_caption(c, cases), R.RENDER_SIZE)
                   for p, c in zip(paths, cases)]
        say(f"renders ({len(renders)} x 1200x900, worker process: wait)")
        figs = R.ReportFigures(figs.key, figs.ratios, figs.load, figs.drum, figs.tire_trends, renders)
        content = R.ReportContent(
            config=R.report_config(rows, tables), tables=tables, figures=figs, colours=colours,
            sheets=sheets, viewer=viewer, validation=None, facts=R.key_facts(tables, colours),
            expand_prints=True, outline_scale=R.outline_scale(tables.paired))
        (out / "index.html").write_text(html_page(content))
        (out / "report.md").write_text(markdown_page(content))
        say("pages")
        print(f"  {'report (renders in parallel)':38s}: {time.perf_counter() - start:6.2f} s")
        print(f"  {'total':38s}: {time.perf_counter() - t0:6.2f} s")

    if __name__ == "__main__":
        main()
    """
)

REPORT_ONLY = textwrap.dedent(
    """
    import sys, time
    from pathlib import Path

    def main():
        try:
            from contactpatch import build_report
        except ImportError:  # the baseline's place
            from contactpatch.report import build_report
        import csv
        with open(sys.argv[1], newline="", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))  # text cells: both reports accept them
        kw = {} if len(sys.argv) < 4 else {"validation": sys.argv[3] == "validation"}
        t = time.perf_counter()
        build_report(rows, Path(sys.argv[2]), **kw)
        print(f"{time.perf_counter() - t:.3f}")

    if __name__ == "__main__":
        main()
    """
)

API_JOB = textwrap.dedent(
    """
    import sys
    from pathlib import Path

    def main():
        from inkprint.batch import Options, run_batch
        from contactpatch import build_report
        out = Path(sys.argv[1])
        res = run_batch("assets/prints", out / "prints.csv", manifest="assets/prints/manifest.csv",
                        options=Options(), progress=False)
        build_report(res.rows, out, source=str(res.outputs[0]),
                     validation="--no-validation" not in sys.argv)

    if __name__ == "__main__":
        main()
    """
)


def extract(base: str, dest: Path) -> Path:
    """The baseline commit's tree in ``dest`` (``git archive``: the repository is only
    read)."""
    dest.mkdir(parents=True, exist_ok=True)
    archive = subprocess.run(
        ["git", "-C", str(ROOT), "archive", base], check=True, capture_output=True
    ).stdout
    subprocess.run(["tar", "-x", "-C", str(dest)], input=archive, check=True)
    return dest


def run(cmd, cwd: Path, env=None) -> tuple[float, subprocess.CompletedProcess]:
    """Wall time of a command (seconds) and its result."""
    t = time.perf_counter()
    proc = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=env)
    return time.perf_counter() - t, proc


def new_job_command(tmp: Path) -> list[str]:
    """The README command if the working tree's CLI starts, else the same calls."""
    probe = subprocess.run(
        [sys.executable, "-m", "inkprint.cli", "batch", "--help"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    if probe.returncode == 0:
        return [sys.executable, "-m", "inkprint.cli", *README_JOB]
    print("  (the working tree's `inkprint` command does not start; the new job runs the")
    print("   same calls through the API: run_batch, then build_report)")
    script = tmp / "api_job.py"
    script.write_text(API_JOB)
    return [sys.executable, str(script)]


def _best_median(label: str, ts: list[float]) -> None:
    print(
        f"  {label}: best {min(ts):6.2f} s, median {statistics.median(ts):6.2f} s"
        f"  ({', '.join(f'{t:.2f}' for t in ts)})"
    )


class JobFailed(RuntimeError):
    """A main job did not finish (the working tree is being edited)."""


def _new_job(tmp: Path, env: dict):
    """A function running the new main job into ``tmp/new{k}``: its time and page."""
    new_cmd = new_job_command(tmp)
    cli = "inkprint.cli" in new_cmd
    api = tmp / "api_job.py"
    api.write_text(API_JOB)

    def new(k, *, validation=True):
        out = tmp / f"new{k}"
        api_cmd = [sys.executable, str(api), str(out)]
        if not validation:
            cmd = [*api_cmd, "--no-validation"]
        elif cli:
            cmd = [*new_cmd, "-o", str(out / "prints.csv"), "--report", str(out), "--quiet"]
        else:
            cmd = api_cmd
        dt, proc = run(cmd, ROOT, env)
        if proc.returncode != 0 and cmd is not api_cmd:
            # the working tree's command broke under us (others edit it): the same calls
            print(f"  (inkprint command failed: {proc.stderr.strip()[-160:]}; API job instead)")
            dt, proc = run(api_cmd, ROOT, env)
        if proc.returncode != 0:
            raise JobFailed(proc.stderr.strip()[-300:])
        return dt, out / "index.html"

    return new


def main_jobs(old: Path, tmp: Path, runs: int) -> None:
    """Today's and the new main job, alternately; then both reports alone on today's
    batch table (which needs only today's job to run)."""
    env = dict(os.environ, ROTTA_CACHE_DIR=str(tmp / "cache"))
    new = _new_job(tmp, env)
    times = {"today": [], "new": [], "new, no validation": []}
    size, failed = 0, None
    try:
        cold, _ = new("cold")
        print(f"  new main job, validation cold (first report)   : {cold:6.2f} s")
    except JobFailed as exc:
        failed = exc
    for k in range(runs):
        out = tmp / f"old{k}"
        cmd = [sys.executable, "-m", "inkprint.cli", *README_JOB, "-o", str(out / "prints.csv")]
        dt, proc = run([*cmd, "--report", str(out), "--quiet"], old)
        assert proc.returncode == 0, proc.stderr[-2000:]
        times["today"].append(dt)
        if failed is None:
            dt, index = new(k)
            times["new"].append(dt)
            size = index.stat().st_size
            times["new, no validation"].append(new(f"nv{k}", validation=False)[0])
    if failed is not None:
        print(f"  the new main job does not run in the working tree now: {failed}")
    for name, ts in times.items():
        if ts:
            _best_median(f"{name + ' main job':28s}", ts)
    for name in ("new", "new, no validation"):
        if times[name]:
            ratio = min(times["today"]) / min(times[name])
            med = statistics.median(times["today"]) / statistics.median(times[name])
            print(f"  speed-up, {name}: {ratio:.1f}x (best), {med:.1f}x (median)")
    if size:
        print(f"  new index.html {size / 1e6:.2f} MB")
    report_alone(old, tmp, runs, env)


def report_alone(old: Path, tmp: Path, runs: int, env: dict) -> None:
    """The report step alone (build_report on the batch's table), alternately."""
    script = tmp / "report_only.py"
    script.write_text(REPORT_ONLY)
    table = tmp / "old0" / "prints.csv"  # one input for both: today's batch table
    cases = {
        "today's report": (old, table, []),
        "new report, validation cached": (ROOT, table, ["validation"]),
        "new report, no validation": (ROOT, table, ["none"]),
    }
    times = {name: [] for name in cases}
    for k in range(runs):
        for name, (cwd, table, extra) in cases.items():
            out = tmp / f"alone{k}-{len(times[name])}-{cwd.name}-{extra}"
            tree_env = dict(env, PYTHONPATH=str(cwd))  # this tree's packages first
            _, proc = run(
                [sys.executable, str(script), str(table), str(out), *extra], cwd, tree_env
            )
            assert proc.returncode == 0, proc.stderr[-2000:]
            times[name].append(float(proc.stdout.split()[-1]))
    print("report step alone (build_report on today's batch table, time inside the call):")
    for name, ts in times.items():
        _best_median(f"{name:30s}", ts)
    base = statistics.median(times["today's report"])
    for name in list(cases)[1:]:
        print(f"  speed-up, {name}: {base / statistics.median(times[name]):.1f}x (median)")


def synthetic(n: int, seed: int = 0) -> list[dict]:
    """``n`` print rows like a batch's on 4 tires (hull: an ellipse), no scans."""
    from contactpatch.study.samples import synthetic_print_rows

    return synthetic_print_rows(n, seed=seed)


def scale(tmp: Path) -> None:
    """The report of 24 (bundled), 200 and 1,000 prints: time and size."""
    sys.path.insert(0, str(ROOT))
    from contactpatch import build_report
    from tiremesh.io import read_table

    bundled = read_table(tmp / "old0" / "prints.csv")  # today's batch of the 24 prints
    for n, rows in ((24, bundled), (200, synthetic(200)), (1000, synthetic(1000))):
        out = tmp / f"scale{n}"
        t = time.perf_counter()
        index = build_report(rows, out, validation=False, scan_dirs=[ASSETS])
        dt = time.perf_counter() - t
        mb = index.stat().st_size / 1e6
        print(f"  {n:5d} prints: {dt:6.2f} s, index.html {mb:5.2f} MB")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base", default="622b585", help="baseline commit (today's code)")
    ap.add_argument("--runs", type=int, default=3, help="main-job runs of each")
    ap.add_argument("--no-scale", action="store_true", help="skip the 200 / 1,000 print reports")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench-report-") as d:
        tmp = Path(d)
        old = extract(a.base, tmp / "base")
        print(f"today ({a.base}), stage by stage (its scripts/bench_report.py):")
        _, proc = run([sys.executable, "scripts/bench_report.py"], old)
        print(textwrap.indent(proc.stdout.strip() or proc.stderr[-1500:], "  "))
        print(f"README main job, today and new, alternately ({a.runs} runs each):")
        main_jobs(old, tmp, a.runs)
        print("new, stage by stage:")
        (tmp / "stages.py").write_text(NEW_STAGES)
        table = str(tmp / "old0" / "prints.csv")
        _, proc = run([sys.executable, str(tmp / "stages.py"), str(tmp / "stages"), table], ROOT)
        print(proc.stdout.rstrip() or proc.stderr[-1500:])
        if not a.no_scale:
            print("report at scale (renders on, validation off):")
            scale(tmp)
        shutil.rmtree(tmp / "base", ignore_errors=True)


if __name__ == "__main__":
    main()
