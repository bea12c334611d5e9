"""Batch analysis of many scans: a folder, a glob, or a manifest CSV.

* One row per print (an error row per failed file or page), every manifest column
  carried through; every page of a PDF is its own sheet (``page`` column).
* Parallel across local cores (processes) by default, or on a Dask cluster
  (``scheduler="tcp://host:8786"``) through :func:`tiremesh.parallel.parallel_map`.
  The options travel with every task. Local worker processes watch the batch
  process and exit when it dies (no orphans after a ``kill -9``).
* Resume that is never stale: each row carries a ``run_key``, the SHA-256 of the
  file's content, of every option that changes a number (:class:`Options`, the
  :class:`~inkprint.AnalysisOptions` with them) and of the file's manifest rows. A
  re-run keeps a file's rows only when its key is unchanged; changed options, a new
  manifest row or a new content redo the file. An identical file under another name
  reuses the rows (once: no duplicate rows).
* One batch at a time per output: an exclusive lock (``<out>.lock``, released when
  the process ends, even killed); a second batch on it refuses with
  :class:`inkprint.OutputLocked`.
* Outputs are written atomically and checkpointed while the batch runs, in the
  format of the output's suffix: ``.csv`` (spreadsheet-safe, :mod:`inkprint.csvsafe`,
  with the same rows as a ``.json`` twin), ``.json`` or ``.parquet`` (typed columns,
  pyarrow); an unknown suffix is refused before any work. Resume reads the output
  back in its own format, so every format resumes.
* What is read: see :mod:`inkprint.jobs` (regular files only, links resolved once,
  manifest paths confined to the manifest's folder).
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib.util
import json
import math
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

from tiremesh.io import (
    TABLE_FORMATS,
    MissingDependency,
    cell_number,
    read_table,
    table_columns,
    write_table,
)
from tiremesh.parallel import (
    DEFAULT_SCHEDULER_TIMEOUT,
    check_scheduler,
    parallel_map,
    watch_parent,
)
from tiremesh.units import MPA_PER_BAR

from .errors import InkPrintError, InvalidInput, OutputLocked
from .jobs import SCAN_SUFFIXES, Job, collect_jobs, read_manifest
from .options import AnalysisOptions, resolve_threads

OUTPUT_FORMATS = TABLE_FORMATS
"""Suffixes of a batch table: .csv (with a .json twin), .json, .parquet."""
FIRST = ["file", "page", "print", "status", "flags", "error", "sha256"]
#: bump when the rows' meaning changes: older rows are then redone on resume
ROW_SCHEMA = 2
AXES = ("auto", "x", "y")


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
    trust_dpi : bool
        Accept 72 / 96 dpi metadata (camera and screen defaults, refused otherwise).
    paper : str, optional
        Paper of every sheet, photographed at a tilt: each page is rectified from its
        corners, its scale from the paper (:func:`inkprint.paper.rectify_page`; a
        manifest ``paper`` wins for its file).
    method : {'otsu', 'fixed', 'sauvola'}
        Threshold method.
    threshold : float, optional
        Grey level in (0, 1) for ``method='fixed'``.
    sensitivity : bool
        Compute the threshold sensitivity band.
    rolling_axis : {'auto', 'x', 'y'}
        Rolling direction on the sheet (a manifest ``rolling_axis`` wins for its file).
    pages : tuple of int, optional
        PDF pages to analyse (0-based); default all.
    overlay_dir : str, optional
        Write a QA overlay PNG per sheet to this folder.
    analysis : AnalysisOptions
        Judgement thresholds (a manifest ``group_mm`` wins for its file).
    threads : int, optional
        Threads measuring the prints of one sheet (:func:`inkprint.analyze_scan`):
        1 in a batch, which runs files in parallel; None: the cores (``inkprint
        analyze``).
    """

    dpi: float | None = None
    mm_per_px: float | None = None
    allow_pixels: bool = False
    trust_dpi: bool = False
    paper: str | None = None
    method: str = "otsu"
    threshold: float | None = None
    sensitivity: bool = True
    rolling_axis: str = "auto"
    pages: tuple | None = None
    overlay_dir: str | None = None
    analysis: AnalysisOptions = field(default_factory=AnalysisOptions)
    threads: int | None = 1

    def __post_init__(self) -> None:
        resolve_threads(self.threads)  # None stays None: the cores, resolved per sheet
        if self.rolling_axis not in AXES:
            raise InvalidInput("rolling_axis", self.rolling_axis, " | ".join(AXES))
        if self.paper is not None:  # (refused before any file is read)
            from .paper import paper_size

            paper_size(self.paper)
        if self.pages is not None:
            pages = tuple(int(p) for p in self.pages)
            if not pages or min(pages) < 0:
                raise InvalidInput("pages", self.pages, "0-based page numbers >= 0")
            object.__setattr__(self, "pages", pages)


@dataclass(frozen=True)
class BatchResult:
    """Outcome of :func:`run_batch`.

    Attributes
    ----------
    rows : list of dict
        Every row of the output (kept and new), sorted by file, page and print.
    n_files : int
        Files in this run.
    n_skipped : int
        Files not analysed again (their rows, with the same run key, were kept).
    n_errors : int
        Error rows of this run's files (the table may hold older rows of files not
        in this run).
    outputs : list of Path
        The CSV and its JSON twin.
    """

    rows: list
    n_files: int
    n_skipped: int
    n_errors: int
    outputs: list

    def __repr__(self) -> str:
        n_ok = sum(1 for r in self.rows if r.get("status") == "ok")
        return (
            f"BatchResult({self.n_files} files, {self.n_skipped} already done, {n_ok} prints ok, "
            f"{self.n_errors} errors -> {self.outputs[0] if self.outputs else '-'})"
        )

    def to_dataframe(self):
        """The rows as a pandas DataFrame (pandas is optional).

        Returns
        -------
        pandas.DataFrame
        """
        from .frames import dataframe

        return dataframe(self.rows)


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
    """SHA-256 of a regular file's content (devices and FIFOs refused, not read).

    Parameters
    ----------
    path : str or PathLike

    Returns
    -------
    str
        64 hex digits.

    Raises
    ------
    inkprint.ScanReadError
        Not a regular file, missing or unreadable.
    """
    from .read import read_file_bytes

    return hashlib.sha256(read_file_bytes(path)).hexdigest()


def run_key(digest: str, options: Options, job: Job) -> str:
    """The key a file's rows are kept under: content, options, manifest rows.

    Parameters
    ----------
    digest : str
        SHA-256 of the file's content.
    options : Options
    job : Job

    Returns
    -------
    str
        24 hex digits.
    """
    meta = {
        f"{p},{i}": {k: v for k, v in m.items() if k != "file"} for (p, i), m in job.meta.items()
    }
    blob = json.dumps(
        [ROW_SCHEMA, digest, dataclasses.asdict(options), meta], sort_keys=True, default=str
    )
    return hashlib.sha256(blob.encode()).hexdigest()[:24]


def _error_row(job: Job, exc, *, digest: str = "", key: str = "", page="") -> dict:
    text = exc if isinstance(exc, str) else f"{type(exc).__name__}: {exc}"
    return {
        **(job.file_meta() if page == "" else job.page_meta(int(page))),
        "file": job.display,
        "page": page,
        "print": "",
        "status": "error",
        "error": text,
        "sha256": digest,
        "run_key": key,
    }


def _file_options(job: Job, options: Options, page: int | None = None):
    """The scale, paper, rolling axis and analysis options of one file, or of one of
    its pages (batch settings, else the manifest's ``dpi`` / ``mm_per_px`` /
    ``paper``, ``rolling_axis``, ``group_mm``: of the page's own row where it has
    one)."""
    meta = job.file_meta() if page is None else job.page_meta(page)
    dpi, mmpp = options.dpi, options.mm_per_px
    paper = str(meta.get("paper") or "").strip() or options.paper
    if dpi is None and mmpp is None and not paper:
        dpi, mmpp = cell_number(meta.get("dpi")), cell_number(meta.get("mm_per_px"))
        if dpi is not None and mmpp is not None:
            raise InvalidInput("dpi/mm_per_px", (dpi, mmpp), "one of the two in the manifest")
    axis = str(meta.get("rolling_axis") or "").strip().lower() or None
    if axis is not None and axis not in AXES:
        raise InvalidInput("rolling_axis", axis, " | ".join(AXES) + " (manifest column)")
    analysis = options.analysis
    group = cell_number(meta.get("group_mm"))
    if group is not None:
        analysis = analysis.replace(group_mm=group)
    return dpi, mmpp, paper or None, axis, analysis


def _load_case(meta: dict) -> tuple:
    """Load [N] and pressure [N/mm^2] of a manifest row (None when absent)."""
    load = cell_number(meta.get("load_N"))
    p_bar = cell_number(meta.get("pressure_bar"))
    if load is not None and load <= 0:
        raise InvalidInput("load_N", meta.get("load_N"), "> 0 N (manifest column)")
    if p_bar is not None and p_bar <= 0:
        raise InvalidInput("pressure_bar", meta.get("pressure_bar"), "> 0 bar (manifest column)")
    return load, None if p_bar is None else p_bar * MPA_PER_BAR


def _sheet_rows(job: Job, result, digest: str, key: str, overlay: str) -> list[dict]:
    """One row per print of one sheet: manifest columns, then the measurements."""
    rows = []
    for p in result.prints:
        meta = job.meta_for(result.page, p.index)
        load, pressure = _load_case(meta)
        row = result.row(p.index, load=load, pressure=pressure)
        rows.append(
            {
                **meta,
                **row,
                "file": job.display,
                "sha256": digest,
                "run_key": key,
                "overlay": overlay,
            }
        )
    return rows


def overlay_name(job: Job, page: int) -> str:
    """QA overlay file name, unique per file and page: the stem, the suffix, a hash
    of the real path and the page (two ``a.jpg`` in different folders, or ``a.jpg``
    and ``a.png``, never overwrite each other).

    Parameters
    ----------
    job : Job
    page : int

    Returns
    -------
    str
    """
    p = Path(job.path)
    tag = hashlib.sha256(os.path.normcase(job.path).encode()).hexdigest()[:8]
    return f"{p.stem}_{p.suffix.lstrip('.').lower()}_{tag}_p{page}_overlay.png"


def _page_plans(job: Job, data: bytes, options: Options) -> list[tuple]:
    """``(pages, file options)`` to read the file with: one plan for the whole file,
    or, when the manifest has rows for single pages whose scale, rolling axis or
    grouping differ, one per set of pages that share them (a PDF's pages of several
    tires, some wider than long: each page's own ``rolling_axis``; the first row's
    was used for every page, length and width swapped silently)."""
    named = job.pages_named
    whole = _file_options(job, options)
    if not named:
        return [(options.pages, whole)]
    from .read import page_count

    pages = range(page_count(job.path, data=data)) if options.pages is None else options.pages
    plans: dict = {}
    for k in pages:
        plans.setdefault(_file_options(job, options, int(k)), []).append(int(k))
    if len(plans) == 1:
        return [(options.pages, next(iter(plans)))]
    return [(ks, opts) for opts, ks in sorted(plans.items(), key=lambda kv: kv[1][0])]


def _analyze_job(job: Job, data: bytes, digest: str, key: str, options: Options) -> list[dict]:
    rows = []
    for pages, file_opts in _page_plans(job, data, options):
        rows += _analyze_pages(job, data, digest, key, options, pages, file_opts)
    return sorted(rows, key=lambda r: -1 if r.get("page") in ("", None) else int(r["page"]))


def _analyze_pages(
    job: Job, data: bytes, digest: str, key: str, options: Options, pages, file_opts
):
    """The rows of some pages of a file (``pages`` None: all), read and analysed with
    ``file_opts`` (:func:`_file_options`)."""
    from .errors import NoInk
    from .read import iter_scans

    dpi, mmpp, paper, axis, analysis = file_opts
    axis_source = "manifest" if axis else ("auto" if options.rolling_axis == "auto" else "given")
    axis = axis or options.rolling_axis
    scans = iter_scans(
        job.path,
        dpi=dpi,
        mm_per_px=mmpp,
        allow_pixels=options.allow_pixels,
        trust_dpi=options.trust_dpi,
        pages=pages,
        options=analysis,
        data=data,
        paper=paper,
    )
    rows = []
    for scan in scans:
        # imported once the first page is decoded: ``inkprint analyze`` imports the
        # analysis in a thread meanwhile (cli._warm_imports)
        from .analyze import analyze_scan

        try:
            result = analyze_scan(
                scan,
                method=options.method,
                threshold=options.threshold,
                sensitivity=options.sensitivity,
                rolling_axis=axis,
                options=analysis,
                threads=options.threads,
            )
        except NoInk as exc:  # one page without a print: the other pages go on
            rows.append(_error_row(job, exc, digest=digest, key=key, page=scan.page))
            continue
        result = dataclasses.replace(result, path=job.display, axis_source=axis_source)
        overlay = ""
        if options.overlay_dir:
            from .overlay import draw_overlay

            overlay = str(Path(options.overlay_dir) / overlay_name(job, scan.page))
            draw_overlay(scan, result, overlay)
        rows.extend(_sheet_rows(job, result, digest, key, overlay))
    return rows


def process_file(
    job: Job, *, options: Options | AnalysisOptions | None = None, watch: int | None = None
) -> list[dict]:
    """Analyse one file (every page); never raises: failures become error rows.

    Parameters
    ----------
    job : Job
    options : Options or AnalysisOptions, optional
        Batch options (an :class:`AnalysisOptions` alone: the other batch options
        at their defaults).
    watch : int, optional
        Process id of the batch: a worker process exits when it dies.

    Returns
    -------
    list of dict
        One row per print, and an error row per file or page that failed
        (``status`` 'error', ``error`` the exception's type and message).
    """
    from .read import read_file_bytes

    if watch is not None:
        from .allocator import keep_freed_memory

        watch_parent(watch, exit_code=3)  # a killed batch leaves no worker blocked
        keep_freed_memory()  # a local worker process: reuse freed image buffers
    opts = _batch_options(options)
    if job.error:
        return [_error_row(job, job.error)]
    try:
        data = read_file_bytes(job.path)
    except InkPrintError as exc:
        return [_error_row(job, exc)]
    digest = hashlib.sha256(data).hexdigest()
    key = run_key(digest, opts, job)
    try:
        return _analyze_job(job, data, digest, key, opts)
    except (InkPrintError, ValueError, OSError, MemoryError) as exc:
        return [_error_row(job, exc, digest=digest, key=key)]
    except Exception as exc:  # a bug: this file's row says so, the batch goes on
        why = (
            f"internal error ({type(exc).__name__}: {exc}): a bug, please report it with the file"
        )
        return [_error_row(job, why, digest=digest, key=key)]


def _sort_key(r):
    def num(v):
        return -1 if v in ("", None) else int(float(v))

    return (str(r.get("file", "")), num(r.get("page")), num(r.get("print")))


def _check_out(out) -> Path:
    """``out`` as a Path, its format known and writable (pyarrow for Parquet)."""
    out = Path(out)
    suffix = out.suffix.lower()
    if suffix not in OUTPUT_FORMATS:
        raise InvalidInput(
            "out", str(out), "a .csv (with a .json twin), .json or .parquet path (pyarrow)"
        )
    if suffix == ".parquet" and importlib.util.find_spec("pyarrow") is None:
        raise MissingDependency("pyarrow", f"writing {out} (Parquet)", "parquet")
    return out


def write_outputs(rows: list[dict], out) -> list[Path]:
    """Write the rows to ``out`` in the format of its suffix, atomically.

    Parameters
    ----------
    rows : list of dict
    out : str or PathLike
        ``.csv`` (spreadsheet-safe, :mod:`inkprint.csvsafe`; a ``.json`` twin is
        written beside it), ``.json`` or ``.parquet`` (typed columns, needs pyarrow).

    Returns
    -------
    list of Path
        The table first (then the CSV's JSON twin).
    """
    from .csvsafe import write_csv

    out = _check_out(out)
    rows = sorted(rows, key=_sort_key)
    cols = table_columns(rows, first=FIRST)
    if out.suffix.lower() != ".csv":
        return [write_table(rows, out, columns=cols)]
    # the twin first: once the table a re-run resumes from exists, so does the twin
    # (a batch killed between the two left the CSV without its JSON)
    twin = write_table(rows, out.with_suffix(".json"), columns=cols)
    return [write_csv(rows, out, columns=cols, lineterminator="\n"), twin]


@dataclass(frozen=True)
class ResumePlan:
    """What a batch re-run keeps and what it analyses.

    Attributes
    ----------
    rows : list of dict
        Rows kept from the previous output (files done before with the same run
        key, files not in this run).
    todo : list of Job
        Files to analyse: new, changed (content, options or manifest rows), failed
        (with ``retry_errors``) or unreadable.
    n_skipped : int
        Files whose rows were kept.
    """

    rows: list[dict]
    todo: list[Job]
    n_skipped: int


def _previous(out, resume: bool, retry_errors: bool) -> list[dict]:
    from .csvsafe import read_csv

    if not (resume and Path(out).is_file()):
        return []
    # resume reads the output back in its own format (CSV cells unescaped)
    kept = read_csv(out) if Path(out).suffix.lower() == ".csv" else read_table(out)
    return [r for r in kept if r.get("status") != "error"] if retry_errors else kept


def plan_resume(
    jobs: list[Job],
    out,
    *,
    options: Options | None = None,
    resume: bool = True,
    retry_errors: bool = False,
) -> ResumePlan:
    """Match the jobs with the rows already in ``out`` by run key (:func:`run_key`).

    Parameters
    ----------
    jobs : list of Job
    out : str or PathLike
        The batch's CSV (may not exist yet).
    options : Options, optional
        This run's options (part of the key).
    resume : bool
        Keep the rows of ``out`` (else start afresh).
    retry_errors : bool
        Drop the error rows, so the files that failed are analysed again.

    Returns
    -------
    ResumePlan
    """
    opts = _batch_options(options)
    kept = _previous(out, resume, retry_errors)
    by_key: dict[str, dict[str, list]] = {}
    for r in kept:
        if r.get("run_key"):
            by_key.setdefault(r["run_key"], {}).setdefault(r.get("file", ""), []).append(r)
    names = {j.display for j in jobs}
    rows = [r for r in kept if r.get("file") not in names]  # files not in this run
    todo, skipped = [], 0
    for j in jobs:
        done = _done_rows(j, by_key, opts) if by_key and not j.error else None
        if done is None:
            todo.append(j)
            continue
        skipped += 1
        rows.extend(done)
    return ResumePlan(rows, todo, skipped)


def _done_rows(job: Job, by_key: dict, opts: Options) -> list[dict] | None:
    """The kept rows of a job under this run's key (its own, or an identical
    file's, renamed), or None."""
    try:
        key = run_key(file_hash(job.path), opts, job)
    except InkPrintError:
        return None
    files = by_key.get(key)
    if not files:
        return None
    if job.display in files:
        return files[job.display]
    source = files[sorted(files)[0]]  # an identical file under another name: once
    return [
        {**r, **job.meta_for(_int(r.get("page")), _int(r.get("print"))), "file": job.display}
        for r in source
    ]


def _int(v) -> int:
    try:
        return int(float(v))
    except (TypeError, ValueError):
        return -1


class _Lock:
    """An exclusive lock on ``<out>.lock`` for the life of a batch (the OS releases
    it when the process ends, however it ends)."""

    def __init__(self, out: Path) -> None:
        self.path = out.with_name(out.name + ".lock")
        self.fh = None

    def __enter__(self):
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.fh = open(self.path, "a+b")
        try:
            _lock_file(self.fh)
        except OSError as exc:
            self.fh.close()
            raise OutputLocked(
                f"{self.path.with_suffix('')}: another inkprint batch is writing this output "
                f"(lock {self.path} is held); wait for it to finish or choose another -o"
            ) from exc
        return self

    def __exit__(self, *exc) -> None:
        _unlock_file(self.fh)
        self.fh.close()


def _lock_file(fh) -> None:
    if os.name == "nt":  # pragma: no cover - Windows
        import msvcrt

        msvcrt.locking(fh.fileno(), msvcrt.LK_NBLCK, 1)
    else:
        import fcntl

        fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)


def _unlock_file(fh) -> None:
    if os.name == "nt":  # pragma: no cover - Windows
        import msvcrt

        msvcrt.locking(fh.fileno(), msvcrt.LK_UNLCK, 1)
    else:
        import fcntl

        fcntl.flock(fh.fileno(), fcntl.LOCK_UN)


def _progress(total: int, enabled: bool):
    from tqdm import tqdm

    return tqdm(total=total, unit="scan", disable=not enabled or total == 0, dynamic_ncols=True)


def _analyze_jobs(
    plan: ResumePlan,
    out,
    *,
    options: Options,
    workers,
    scheduler,
    scheduler_timeout,
    progress,
    checkpoint_seconds,
) -> list[dict]:
    """The plan's rows plus those of its jobs, checkpointing ``out`` as they come."""
    rows = list(plan.rows)
    last = time.monotonic()
    bar = _progress(len(plan.todo), progress)
    kwargs = {"options": options}
    if scheduler is None:
        kwargs["watch"] = os.getpid()  # local workers exit when this process dies
    try:
        for _, new in parallel_map(
            process_file,
            plan.todo,
            workers=workers,
            scheduler=scheduler,
            scheduler_timeout=scheduler_timeout,
            kwargs=kwargs,
        ):
            rows.extend(new)
            bar.update(1)
            if time.monotonic() - last > checkpoint_seconds:
                write_outputs(rows, out)
                last = time.monotonic()
    finally:
        bar.close()
    return rows


def idle_cores() -> int:
    """Cores not busy with other work: the CPU count less the 1-minute load average,
    at least 1 (then the batch runs in this process).

    On a machine whose cores other programs already keep busy, more worker processes
    only add their start-up (a fresh interpreter importing OpenCV, scikit-image and
    shapely, ~1 s each) and contend for the same cores; on an idle machine every
    core works.

    Returns
    -------
    int
    """
    cores = os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):  # pragma: no cover - no load average (Windows)
        return cores
    return max(1, min(cores, math.floor(cores - load + 0.5)))  # a core half idle counts


def run_batch(
    src=None,
    out="results.csv",
    *,
    manifest=None,
    options: Options | AnalysisOptions | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    scheduler_timeout: float = DEFAULT_SCHEDULER_TIMEOUT,
    resume: bool = True,
    retry_errors: bool = False,
    progress: bool = True,
    checkpoint_seconds: float = 10.0,
    allow_outside: bool = False,
) -> BatchResult:
    """Analyse every scan of ``src`` / ``manifest`` into the table ``out``.

    Parameters
    ----------
    src : str or PathLike, optional
        Folder, glob pattern or scan file.
    out : str or PathLike
        The table, its format by suffix: ``.csv`` (a ``.json`` twin is written
        beside it), ``.json`` or ``.parquet`` (needs pyarrow). Resume reads it back
        in the same format.
    manifest : str or PathLike, optional
        Manifest CSV (see :mod:`inkprint.jobs`).
    options : Options or AnalysisOptions, optional
        Batch options; they reach every worker process or Dask worker.
    workers : int, optional
        Local worker processes (default: the idle cores, :func:`idle_cores`; 1 = in
        this process).
    scheduler : str, optional
        Address of a dask.distributed scheduler; the work is sent there.
    scheduler_timeout : float [s]
        How long to wait for the scheduler to accept and answer; it is checked
        before any work (:func:`tiremesh.parallel.check_scheduler`).
    resume : bool
        Keep the rows of ``out`` whose run key still holds (see the module's notes).
    retry_errors : bool
        With ``resume``, analyse again the files that failed before.
    progress : bool
        Show a progress bar.
    checkpoint_seconds : float [s]
        Rewrite the outputs at most this often while the batch runs.
    allow_outside : bool
        Read manifest files outside the manifest's folder.

    Returns
    -------
    BatchResult

    Raises
    ------
    OutputLocked
        Another batch is writing ``out``.
    InvalidInput
        Bad options, ``out`` not a .csv, .json or .parquet path, no such source or
        manifest (all checked before any work).
    tiremesh.io.MissingDependency
        A ``.parquet`` output without pyarrow installed.
    OSError
        An output cannot be written (the message names the path).
    tiremesh.parallel.SchedulerError
        The scheduler cannot be reached within ``scheduler_timeout`` or is not a Dask
        scheduler (the message names the address).
    """
    opts = _batch_options(options)
    out = _check_out(out)
    if workers is not None and workers < 1:
        raise InvalidInput("workers", workers, ">= 1")
    if workers is None and not scheduler:
        workers = idle_cores()
    if isinstance(scheduler, str) and scheduler.strip():
        check_scheduler(scheduler, timeout=scheduler_timeout)  # before any work
    jobs = collect_jobs(src, manifest, allow_outside=allow_outside)
    with _Lock(out):
        plan = plan_resume(jobs, out, options=opts, resume=resume, retry_errors=retry_errors)
        if opts.overlay_dir:
            Path(opts.overlay_dir).mkdir(parents=True, exist_ok=True)
        rows = _analyze_jobs(
            plan,
            out,
            options=opts,
            workers=workers,
            scheduler=scheduler,
            scheduler_timeout=scheduler_timeout,
            progress=progress,
            checkpoint_seconds=checkpoint_seconds,
        )
        outputs = write_outputs(rows, out)
    names = {j.display for j in jobs}
    return BatchResult(
        rows=sorted(rows, key=_sort_key),
        n_files=len(jobs),
        n_skipped=plan.n_skipped,
        n_errors=sum(1 for r in rows if r.get("status") == "error" and r.get("file") in names),
        outputs=outputs,
    )


__all__ = [
    "FIRST",
    "OUTPUT_FORMATS",
    "SCAN_SUFFIXES",
    "BatchResult",
    "Job",
    "Options",
    "ResumePlan",
    "collect_jobs",
    "file_hash",
    "idle_cores",
    "overlay_name",
    "plan_resume",
    "process_file",
    "read_manifest",
    "run_batch",
    "run_key",
    "write_outputs",
]
