"""Batch analysis of many scans: a folder, a glob, or a manifest CSV.

* One row per print (an error row per failed file), every manifest column carried
  through; files are identified by the SHA-256 of their content.
* Parallel across local cores (processes) by default, or on a Dask cluster
  (``scheduler="tcp://host:8786"``, dask.distributed).
* Resumable: files whose content (SHA-256) already has rows in the output are
  skipped (a renamed copy reuses those rows); a file whose content changed is
  analysed again and its old rows dropped. A bad file becomes an error row; the
  batch goes on.
* Outputs (CSV, plus the same rows as JSON) are written atomically and checkpointed
  while the batch runs, so a killed batch leaves complete files and a re-run resumes.

Manifest: CSV with a ``file`` column (relative to the manifest's folder) and any
others; the recognised ones are ``print`` (0-based, top to bottom; absent = every
print of the file), ``pressure_bar``, ``load_N``, ``surface`` and ``dpi`` /
``mm_per_px`` (a per-file scale).
"""

from __future__ import annotations

import csv
import glob
import hashlib
import json
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

from contactpatch._util import number as _num

from .errors import InkPrintError, InvalidInput

SCAN_SUFFIXES = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".pdf", ".bmp"}
FIRST = ["file", "print", "status", "error", "sha256"]


@dataclass(frozen=True)
class Job:
    """One file to analyse and its manifest rows (by print index, or -1 for all)."""

    path: str
    meta: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Options:
    """Analysis options shared by every file of a batch."""

    dpi: float | None = None
    mm_per_px: float | None = None
    allow_pixels: bool = False
    method: str = "otsu"
    threshold: float | None = None
    sensitivity: bool = True
    overlay_dir: str | None = None


@dataclass(frozen=True)
class BatchResult:
    rows: list
    n_files: int
    n_skipped: int
    n_errors: int
    outputs: list


def file_hash(path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def read_manifest(path) -> list[Job]:
    """Jobs from a manifest CSV (one row per print or per file)."""
    p = Path(path)
    if not p.is_file():
        raise InvalidInput("manifest", str(p), "an existing CSV file")
    with p.open(newline="", encoding="utf-8-sig") as fh:
        rows = list(csv.DictReader(fh))
    if not rows or "file" not in rows[0]:
        raise InvalidInput("manifest", str(p), "a CSV with a 'file' column")
    jobs: dict[str, dict] = {}
    for r in rows:
        f = r["file"]
        full = str((p.parent / f).resolve()) if not os.path.isabs(f) else f
        k = r.get("print", "")
        idx = int(k) if str(k).strip().lstrip("-").isdigit() else -1
        jobs.setdefault(full, {})[idx] = {**r, "file": f}
    return [Job(path, meta) for path, meta in jobs.items()]


def collect_jobs(src, manifest=None) -> list[Job]:
    """Jobs from a folder, a glob pattern, a single file, and/or a manifest."""
    if manifest is not None:
        jobs = read_manifest(manifest)
        if src is None:
            return jobs
        wanted = {Path(j.path).name: j for j in jobs}
        found = _paths(src)
        return [
            Job(str(p), wanted[Path(p).name].meta) if Path(p).name in wanted else Job(str(p))
            for p in found
        ]
    if src is None:
        raise InvalidInput("src", None, "a folder, a glob pattern, a scan file or --manifest")
    return [Job(str(p)) for p in _paths(src)]


def _paths(src) -> list[str]:
    s = str(src)
    p = Path(s)
    if p.is_dir():
        return sorted(
            str(q) for q in p.iterdir() if q.suffix.lower() in SCAN_SUFFIXES and q.is_file()
        )
    if p.is_file():
        return [s]
    hits = sorted(glob.glob(s, recursive=True))
    if not hits:
        raise InvalidInput("src", s, "an existing folder, file or glob pattern matching scans")
    return [h for h in hits if Path(h).is_file()]


def _display(job: Job) -> str:
    """The name a job's rows carry: the manifest's ``file`` entry, else the path."""
    return next((m.get("file", job.path) for m in job.meta.values()), job.path)


def _int(v) -> int:
    try:
        return int(v)
    except (TypeError, ValueError):
        return -1


def _row_meta(job: Job, index: int) -> dict:
    return dict(job.meta.get(index) or job.meta.get(-1) or {})


def process_file(job: Job, options: Options) -> list[dict]:
    """Analyse one file; never raises: failures become an error row."""
    from .analyze import analyze_scan
    from .read import read_scan

    base = {"file": _display(job)}
    try:
        digest = file_hash(job.path)
    except OSError as exc:
        return [
            {
                **_row_meta(job, -1),
                **base,
                "print": "",
                "status": "error",
                "sha256": "",
                "error": f"{type(exc).__name__}: {exc}",
            }
        ]
    try:
        meta0 = _row_meta(job, 0)
        dpi = options.dpi if options.dpi is not None else _num(meta0.get("dpi"))
        mmpp = options.mm_per_px if options.mm_per_px is not None else _num(meta0.get("mm_per_px"))
        if dpi is not None and mmpp is not None:
            dpi = None if options.dpi is None else dpi
            mmpp = None if dpi is not None else mmpp
        scan = read_scan(job.path, dpi=dpi, mm_per_px=mmpp, allow_pixels=options.allow_pixels)
        result = analyze_scan(
            scan,
            method=options.method,
            threshold=options.threshold,
            sensitivity=options.sensitivity,
        )
        rows = []
        for p in result.prints:
            meta = _row_meta(job, p.index)
            load = _num(meta.get("load_N"))
            p_bar = _num(meta.get("pressure_bar"))
            row = result.rows(load=load, pressure=None if p_bar is None else 0.1 * p_bar)[p.index]
            rows.append({**meta, **row, **base, "print": p.index, "sha256": digest})
        if options.overlay_dir:
            from .overlay import draw_overlay

            draw_overlay(
                scan, result, Path(options.overlay_dir) / (Path(job.path).stem + "_overlay.png")
            )
        return rows
    except (InkPrintError, ValueError, OSError, MemoryError) as exc:
        return [
            {
                **_row_meta(job, -1),
                **_row_meta(job, 0),
                **base,
                "print": "",
                "status": "error",
                "sha256": digest,
                "error": f"{type(exc).__name__}: {exc}",
            }
        ]


def _columns(rows: list[dict]) -> list[str]:
    cols = list(FIRST)
    for r in rows:
        for k in r:
            if k not in cols:
                cols.append(k)
    return cols


def _sort_key(r):
    return (str(r.get("file", "")), -1 if r.get("print", "") == "" else int(r["print"]))


def write_outputs(rows: list[dict], out) -> list[Path]:
    """Write ``out`` (CSV) and ``out`` with suffix .json, both atomically."""
    from contactpatch._io import atomic_path

    out = Path(out)
    rows = sorted(rows, key=_sort_key)
    cols = _columns(rows) if rows else list(FIRST)
    with atomic_path(out) as tmp, tmp.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=cols, extrasaction="ignore", lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    js = out.with_suffix(".json")
    with atomic_path(js) as tmp:
        tmp.write_text(json.dumps(rows, indent=1, default=_jsonable), encoding="utf-8")
    return [out, js]


def _jsonable(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return str(v)


def _read_existing(out) -> list[dict]:
    p = Path(out)
    if not p.is_file():
        return []
    with p.open(newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def run_batch(
    src=None,
    out="results.csv",
    *,
    manifest=None,
    options: Options | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    resume: bool = True,
    retry_errors: bool = False,
    progress: bool = True,
    checkpoint_seconds: float = 10.0,
) -> BatchResult:
    """Analyse every scan of ``src`` / ``manifest`` into the table ``out``.

    Parameters
    ----------
    src : folder, glob pattern or file, optional
    out : path of the CSV (a .json twin is written beside it)
    manifest : CSV, optional
    options : Options
    workers : int, optional
        Local worker processes (default: all cores; 1 = in this process).
    scheduler : str, optional
        Address of a dask.distributed scheduler; the work is sent there.
    resume : bool
        Keep the rows of ``out`` and skip their files (by content hash).
    retry_errors : bool
        With ``resume``, analyse again the files that failed before.
    """
    options = options or Options()
    jobs = collect_jobs(src, manifest)
    kept = _read_existing(out) if resume else []
    if retry_errors:
        kept = [r for r in kept if r.get("status") == "ok"]
    by_hash: dict[str, list[dict]] = {}
    for r in kept:
        if r.get("sha256"):
            by_hash.setdefault(r["sha256"], []).append(r)
    names = {_display(j) for j in jobs}
    rows = [r for r in kept if r.get("file") not in names]  # rows of files not in this run
    todo, skipped = [], 0
    for j in jobs:
        try:
            digest = file_hash(j.path) if by_hash else None
        except OSError:
            digest = None
        done = by_hash.get(digest) if digest else None
        if not done:
            todo.append(j)  # new, changed (its old rows are dropped) or unreadable
            continue
        skipped += 1
        same = [r for r in done if r.get("file") == _display(j)]
        if same:
            rows.extend(same)
        else:  # the same content under another name: reuse the rows
            rows.extend(
                {**r, **_row_meta(j, _int(r.get("print"))), "file": _display(j)} for r in done
            )
    if options.overlay_dir:
        Path(options.overlay_dir).mkdir(parents=True, exist_ok=True)
    last = time.monotonic()
    bar = _progress(len(todo), progress)
    for new in _execute(todo, options, workers, scheduler):
        rows.extend(new)
        bar.update(1)
        if time.monotonic() - last > checkpoint_seconds:
            write_outputs(rows, out)
            last = time.monotonic()
    bar.close()
    outputs = write_outputs(rows, out)
    n_err = sum(1 for r in rows if r.get("status") == "error")
    return BatchResult(
        rows=sorted(rows, key=_sort_key),
        n_files=len(jobs),
        n_skipped=skipped,
        n_errors=n_err,
        outputs=outputs,
    )


def _progress(total: int, enabled: bool):
    from tqdm import tqdm

    return tqdm(total=total, unit="scan", disable=not enabled or total == 0, dynamic_ncols=True)


def _execute(jobs: list[Job], options: Options, workers: int | None, scheduler: str | None):
    """Yield each file's rows as it completes."""
    if not jobs:
        return
    if scheduler:
        from dask.distributed import Client, as_completed

        with Client(scheduler, timeout="30s") as client:
            futures = client.map(process_file, jobs, options=options, pure=False)
            for fut in as_completed(futures):
                yield fut.result()
        return
    n = workers if workers is not None else (os.cpu_count() or 1)
    if n < 1:
        raise InvalidInput("workers", workers, ">= 1")
    if n == 1 or len(jobs) == 1:
        for j in jobs:
            yield process_file(j, options)
        return
    import multiprocessing as mp
    import warnings
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    ctx = mp.get_context("spawn" if os.name == "nt" else "forkserver")
    pending = dict(enumerate(jobs))
    try:
        with ProcessPoolExecutor(max_workers=min(n, len(jobs)), mp_context=ctx) as pool:
            futures = {pool.submit(process_file, j, options): i for i, j in pending.items()}
            for fut in as_completed(futures):
                rows = fut.result()
                del pending[futures[fut]]
                yield rows
    except BrokenProcessPool:
        # e.g. run from a notebook or stdin, whose __main__ worker processes cannot
        # import: finish in this process rather than lose the batch
        warnings.warn(
            "worker processes failed to start; analysing the rest in this process", stacklevel=2
        )
        for i in sorted(pending):
            yield process_file(pending[i], options)


__all__ = [
    "BatchResult",
    "Job",
    "Options",
    "collect_jobs",
    "process_file",
    "read_manifest",
    "run_batch",
]
