"""Batch analysis of many scans: a folder, a glob, or a manifest CSV.

* One row per print (an error row per failed file), every manifest column carried
  through; files are identified by the SHA-256 of their content.
* Parallel across local cores (processes) by default, or on a Dask cluster
  (``scheduler="tcp://host:8786"``, dask.distributed), through
  :func:`tiremesh.parallel.parallel_map`. The options (judgement thresholds
  included) travel with every task, so workers use the caller's settings.
* Resumable: files whose content (SHA-256) already has rows in the output are
  skipped (a renamed copy reuses those rows); a file whose content changed is
  analysed again and its old rows dropped. A bad file becomes an error row; the
  batch goes on.
* Outputs (CSV, plus the same rows as JSON) are written atomically
  (:func:`tiremesh.io.write_table`) and checkpointed while the batch runs, so a
  killed batch leaves complete files and a re-run resumes.

Manifest: CSV with a ``file`` column (relative to the manifest's folder) and any
others; the recognised ones are ``print`` (0-based, top to bottom; absent = every
print of the file), ``pressure_bar``, ``load_N``, ``surface`` and ``dpi`` /
``mm_per_px`` (a per-file scale).
"""

from __future__ import annotations

import csv
import glob
import hashlib
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

from tiremesh.io import cell_number, read_table, table_columns, write_table
from tiremesh.parallel import parallel_map
from tiremesh.units import MPA_PER_BAR

from .errors import InkPrintError, InvalidInput
from .options import AnalysisOptions

SCAN_SUFFIXES = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".pdf", ".bmp"}
FIRST = ["file", "print", "status", "error", "sha256"]


@dataclass(frozen=True)
class Job:
    """One file to analyse.

    Attributes
    ----------
    path : str
        The scan file.
    meta : dict
        Its manifest rows by print index (-1: a row for every print).
    """

    path: str
    meta: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Options:
    """Options shared by every file of a batch (sent to every worker).

    Attributes
    ----------
    dpi : float, optional [dots per inch]
        Scale of every scan (overrides metadata and the manifest).
    mm_per_px : float, optional [mm / px]
        Scale of every scan; at most one of ``dpi`` and ``mm_per_px``.
    allow_pixels : bool
        Measure scans without a scale in pixels instead of an error row.
    method : {'otsu', 'fixed', 'sauvola'}
        Threshold method.
    threshold : float, optional
        Grey level in (0, 1) for ``method='fixed'``.
    sensitivity : bool
        Compute the threshold sensitivity band.
    overlay_dir : str, optional
        Write a QA overlay PNG per scan to this folder.
    analysis : AnalysisOptions
        Judgement thresholds.
    """

    dpi: float | None = None
    mm_per_px: float | None = None
    allow_pixels: bool = False
    method: str = "otsu"
    threshold: float | None = None
    sensitivity: bool = True
    overlay_dir: str | None = None
    analysis: AnalysisOptions = field(default_factory=AnalysisOptions)


@dataclass(frozen=True)
class BatchResult:
    """Outcome of :func:`run_batch`.

    Attributes
    ----------
    rows : list of dict
        Every row of the output (kept and new), sorted by file and print.
    n_files : int
        Files in this run.
    n_skipped : int
        Files not analysed again (their content already had rows).
    n_errors : int
        Error rows.
    outputs : list of Path
        The CSV and its JSON twin.
    """

    rows: list
    n_files: int
    n_skipped: int
    n_errors: int
    outputs: list


def _batch_options(options) -> Options:
    """Batch options from None, :class:`Options` or :class:`AnalysisOptions`."""
    if options is None:
        return Options()
    if isinstance(options, AnalysisOptions):
        return Options(analysis=options)
    if not isinstance(options, Options):
        raise InvalidInput(
            "options", type(options).__name__, "inkprint.batch.Options or inkprint.AnalysisOptions"
        )
    return options


def file_hash(path) -> str:
    """SHA-256 of a file's content.

    Parameters
    ----------
    path : str or PathLike

    Returns
    -------
    str
        64 hex digits.
    """
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def read_manifest(path) -> list[Job]:
    """Jobs from a manifest CSV (one row per print or per file).

    Parameters
    ----------
    path : str or PathLike
        CSV with a ``file`` column (relative to the manifest's folder).

    Returns
    -------
    list of Job
    """
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
    """Jobs from a folder, a glob pattern, a single file, and/or a manifest.

    Parameters
    ----------
    src : str or PathLike, optional
        Folder, glob pattern or scan file; with ``manifest``, only the files found
        here (matched by name) are analysed.
    manifest : str or PathLike, optional
        Manifest CSV (:func:`read_manifest`).

    Returns
    -------
    list of Job
    """
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


def _error_row(job: Job, exc: BaseException, *, digest: str, meta: dict) -> dict:
    return {
        **meta,
        "file": _display(job),
        "print": "",
        "status": "error",
        "sha256": digest,
        "error": f"{type(exc).__name__}: {exc}",
    }


@dataclass(frozen=True)
class ScanScale:
    """The scale a file is read with (at most one is set; neither: the metadata).

    Attributes
    ----------
    dpi : float or None [dots per inch]
    mm_per_px : float or None [mm / px]
    """

    dpi: float | None
    mm_per_px: float | None


def scan_scale(job: Job, options: Options) -> ScanScale:
    """The batch's scale if given, else the manifest's ``dpi`` / ``mm_per_px``.

    Parameters
    ----------
    job : Job
    options : Options

    Returns
    -------
    ScanScale
    """
    meta0 = _row_meta(job, 0)
    dpi = options.dpi if options.dpi is not None else cell_number(meta0.get("dpi"))
    mmpp = (
        options.mm_per_px if options.mm_per_px is not None else cell_number(meta0.get("mm_per_px"))
    )
    if dpi is not None and mmpp is not None:  # the batch's setting wins over the manifest's
        dpi = None if options.dpi is None else dpi
        mmpp = None if dpi is not None else mmpp
    return ScanScale(dpi, mmpp)


def _print_rows(job: Job, result, digest: str) -> list[dict]:
    """One row per print: manifest columns, then the measurements."""
    rows = []
    for p in result.prints:
        meta = _row_meta(job, p.index)
        load = cell_number(meta.get("load_N"))
        p_bar = cell_number(meta.get("pressure_bar"))
        pressure = None if p_bar is None else p_bar * MPA_PER_BAR
        row = result.row(p.index, load=load, pressure=pressure)
        rows.append({**meta, **row, "file": _display(job), "print": p.index, "sha256": digest})
    return rows


def _analyze_job(job: Job, digest: str, options: Options) -> list[dict]:
    from .analyze import analyze_scan
    from .read import read_scan

    scale = scan_scale(job, options)
    scan = read_scan(
        job.path,
        dpi=scale.dpi,
        mm_per_px=scale.mm_per_px,
        allow_pixels=options.allow_pixels,
        options=options.analysis,
    )
    result = analyze_scan(
        scan,
        method=options.method,
        threshold=options.threshold,
        sensitivity=options.sensitivity,
        options=options.analysis,
    )
    rows = _print_rows(job, result, digest)
    if options.overlay_dir:
        from .overlay import draw_overlay

        name = Path(job.path).stem + "_overlay.png"
        draw_overlay(scan, result, Path(options.overlay_dir) / name)
    return rows


def process_file(job: Job, *, options: Options | AnalysisOptions | None = None) -> list[dict]:
    """Analyse one file; never raises: failures become an error row.

    Parameters
    ----------
    job : Job
    options : Options or AnalysisOptions, optional
        Batch options (an :class:`AnalysisOptions` alone: the other batch options
        at their defaults).

    Returns
    -------
    list of dict
        One row per print, or one error row (``status`` 'error', ``error`` the
        exception's type and message).
    """
    opts = _batch_options(options)
    try:
        digest = file_hash(job.path)
    except OSError as exc:
        return [_error_row(job, exc, digest="", meta=_row_meta(job, -1))]
    try:
        return _analyze_job(job, digest, opts)
    except (InkPrintError, ValueError, OSError, MemoryError) as exc:
        meta = {**_row_meta(job, -1), **_row_meta(job, 0)}
        return [_error_row(job, exc, digest=digest, meta=meta)]


def _sort_key(r):
    return (str(r.get("file", "")), -1 if r.get("print", "") == "" else int(r["print"]))


def _check_out(out) -> Path:
    out = Path(out)
    if out.suffix.lower() != ".csv":
        raise InvalidInput("out", str(out), "a .csv path (a .json twin is written beside it)")
    return out


def write_outputs(rows: list[dict], out) -> list[Path]:
    """Write the rows to ``out`` (CSV) and ``out`` with suffix .json, both atomically.

    Parameters
    ----------
    rows : list of dict
    out : str or PathLike
        A .csv path.

    Returns
    -------
    list of Path
        The CSV and the JSON.
    """
    out = _check_out(out)
    rows = sorted(rows, key=_sort_key)
    cols = table_columns(rows, first=FIRST)
    return [
        write_table(rows, out, columns=cols),
        write_table(rows, out.with_suffix(".json"), columns=cols),
    ]


@dataclass(frozen=True)
class ResumePlan:
    """What a batch re-run keeps and what it analyses.

    Attributes
    ----------
    rows : list of dict
        Rows kept from the previous output (files done before, files not in this run).
    todo : list of Job
        Files to analyse: new, changed, failed (with ``retry_errors``) or unreadable.
    n_skipped : int
        Files whose content already had rows.
    """

    rows: list[dict]
    todo: list[Job]
    n_skipped: int


def _reused_rows(job: Job, done: list[dict]) -> list[dict]:
    """Rows of ``job``'s content from the previous output, under ``job``'s name."""
    same = [r for r in done if r.get("file") == _display(job)]
    if same:
        return same
    # the same content under another name: reuse the rows
    return [{**r, **_row_meta(job, _int(r.get("print"))), "file": _display(job)} for r in done]


def plan_resume(
    jobs: list[Job], out, *, resume: bool = True, retry_errors: bool = False
) -> ResumePlan:
    """Match the jobs with the rows already in ``out`` (by content hash).

    Parameters
    ----------
    jobs : list of Job
    out : str or PathLike
        The batch's CSV (may not exist yet).
    resume : bool
        Keep the rows of ``out`` (else start afresh).
    retry_errors : bool
        Drop the error rows, so the files that failed are analysed again.

    Returns
    -------
    ResumePlan
    """
    kept = read_table(out) if resume and Path(out).is_file() else []
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
        rows.extend(_reused_rows(j, done))
    return ResumePlan(rows, todo, skipped)


def _progress(total: int, enabled: bool):
    from tqdm import tqdm

    return tqdm(total=total, unit="scan", disable=not enabled or total == 0, dynamic_ncols=True)


def _analyze_jobs(
    plan: ResumePlan, out, *, options: Options, workers, scheduler, progress, checkpoint_seconds
) -> list[dict]:
    """The plan's rows plus those of its jobs, checkpointing ``out`` as they come."""
    rows = list(plan.rows)
    last = time.monotonic()
    bar = _progress(len(plan.todo), progress)
    try:
        results = parallel_map(
            process_file,
            plan.todo,
            workers=workers,
            scheduler=scheduler,
            kwargs={"options": options},
        )
        for _, new in results:
            rows.extend(new)
            bar.update(1)
            if time.monotonic() - last > checkpoint_seconds:
                write_outputs(rows, out)
                last = time.monotonic()
    finally:
        bar.close()
    return rows


def run_batch(
    src=None,
    out="results.csv",
    *,
    manifest=None,
    options: Options | AnalysisOptions | None = None,
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
    src : str or PathLike, optional
        Folder, glob pattern or scan file.
    out : str or PathLike
        Path of the CSV (a .json twin is written beside it).
    manifest : str or PathLike, optional
        Manifest CSV (see the module's documentation).
    options : Options or AnalysisOptions, optional
        Batch options; an :class:`AnalysisOptions` alone sets the judgement
        thresholds with the other batch options at their defaults. They reach every
        worker process or Dask worker.
    workers : int, optional
        Local worker processes (default: all cores; 1 = in this process).
    scheduler : str, optional
        Address of a dask.distributed scheduler; the work is sent there.
    resume : bool
        Keep the rows of ``out`` and skip their files (by content hash).
    retry_errors : bool
        With ``resume``, analyse again the files that failed before.
    progress : bool
        Show a progress bar.
    checkpoint_seconds : float [s]
        Rewrite the outputs at most this often while the batch runs.

    Returns
    -------
    BatchResult
    """
    opts = _batch_options(options)
    _check_out(out)
    if workers is not None and workers < 1:
        raise InvalidInput("workers", workers, ">= 1")
    jobs = collect_jobs(src, manifest)
    plan = plan_resume(jobs, out, resume=resume, retry_errors=retry_errors)
    if opts.overlay_dir:
        Path(opts.overlay_dir).mkdir(parents=True, exist_ok=True)
    rows = _analyze_jobs(
        plan,
        out,
        options=opts,
        workers=workers,
        scheduler=scheduler,
        progress=progress,
        checkpoint_seconds=checkpoint_seconds,
    )
    outputs = write_outputs(rows, out)
    return BatchResult(
        rows=sorted(rows, key=_sort_key),
        n_files=len(jobs),
        n_skipped=plan.n_skipped,
        n_errors=sum(1 for r in rows if r.get("status") == "error"),
        outputs=outputs,
    )


__all__ = [
    "BatchResult",
    "Job",
    "Options",
    "ResumePlan",
    "ScanScale",
    "collect_jobs",
    "file_hash",
    "plan_resume",
    "process_file",
    "read_manifest",
    "run_batch",
    "scan_scale",
    "write_outputs",
]
