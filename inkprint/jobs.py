"""What a batch reads: files from a folder, a glob or a manifest, each resolved once.

* Every path is resolved once (symlinks followed to the real file): two names of one
  file are analysed once (a recursive glob through a ``self -> .`` link finds the
  same scan many times); a symlink loop or a dangling link becomes an error row.
* Anything that is not a folder is listed (with a scan suffix): a device or a FIFO
  becomes an error row when it is read (:func:`inkprint.read.read_file_bytes`),
  never a hang.
* Manifest paths are relative to the manifest's folder and must stay inside it
  (after resolving links): ``../../etc/passwd`` or an absolute path elsewhere is an
  error row unless ``allow_outside`` (``--allow-outside``); nothing outside is read.

Manifest: CSV with a ``file`` column and any others, one row per print or per file;
recognised: ``page`` and ``print`` (0-based; absent = every page / print),
``pressure_bar``, ``load_N``, ``surface``, ``dpi`` / ``mm_per_px`` (the file's
scale), ``paper`` (a photo's paper: rectified from the page's corners, the scale
from the paper), ``rolling_axis`` (x | y | auto), ``group_mm`` (footprint grouping
distance).
"""

from __future__ import annotations

import glob
import os
from dataclasses import dataclass, field
from pathlib import Path

from .errors import InvalidInput

SCAN_SUFFIXES = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".pdf", ".bmp"}


@dataclass(frozen=True)
class Job:
    """One file to analyse.

    Attributes
    ----------
    path : str
        The file (resolved: no symlink left), or the path as found when it cannot be
        resolved.
    meta : dict
        Its manifest rows by ``(page, print)`` (-1: every page / print).
    name : str
        The name its rows carry (the manifest's ``file`` entry, else the path as
        found).
    error : str
        Why the file is not read ('' when it is): a dangling link, a loop, a path
        outside the manifest's folder.
    """

    path: str
    meta: dict = field(default_factory=dict)
    name: str = ""
    error: str = ""

    @property
    def display(self) -> str:
        """The name the job's rows carry."""
        return self.name or self.path

    def meta_for(self, page: int, index: int) -> dict:
        """Manifest columns of one print (most specific row first), or {}.

        Parameters
        ----------
        page, index : int
            0-based page and print.

        Returns
        -------
        dict
        """
        for key in ((page, index), (-1, index), (page, -1), (-1, -1)):
            if key in self.meta:
                return dict(self.meta[key])
        return {}

    def file_meta(self) -> dict:
        """Manifest columns that hold for the whole file (the first row's).

        Returns
        -------
        dict
        """
        for key in sorted(self.meta):
            return dict(self.meta[key])
        return {}

    def page_meta(self, page: int) -> dict:
        """Manifest columns that hold for one page: its first row (lowest print),
        else the first row for every page, else :meth:`file_meta`.

        Parameters
        ----------
        page : int
            0-based.

        Returns
        -------
        dict
        """
        for want in (page, -1):
            for key in sorted(k for k in self.meta if k[0] == want):
                return dict(self.meta[key])
        return self.file_meta()

    @property
    def pages_named(self) -> list[int]:
        """The pages the manifest has rows for (0-based, ascending; [] when its
        rows hold for every page)."""
        return sorted({k[0] for k in self.meta if k[0] >= 0})


def resolve_once(path) -> tuple[str, str]:
    """The real path of a file (symlinks followed), or why it cannot be had.

    Parameters
    ----------
    path : str or PathLike

    Returns
    -------
    real : str
        The resolved path ('' when it cannot be resolved).
    error : str
        '' or the reason (a symlink loop, a dangling link, no such file).
    """
    p = Path(path)
    try:
        return str(p.resolve(strict=True)), ""
    except RuntimeError:
        return "", f"{p}: symlink loop"
    except FileNotFoundError:
        why = "dangling symlink" if p.is_symlink() else "no such file"
        return "", f"{p}: {why}"
    except OSError as exc:
        if getattr(exc, "errno", None) == 40:  # ELOOP
            return "", f"{p}: symlink loop"
        return "", f"{p}: cannot resolve ({exc.strerror or exc})"


def _cell_index(v) -> int:
    s = str(v if v is not None else "").strip()
    return int(s) if s.lstrip("-").isdigit() else -1


def read_manifest(path, *, allow_outside: bool = False) -> list[Job]:
    """Jobs from a manifest CSV (one row per print, per page or per file).

    Parameters
    ----------
    path : str or PathLike
        CSV with a ``file`` column (relative to the manifest's folder).
    allow_outside : bool
        Read files outside the manifest's folder (else they are error rows).

    Returns
    -------
    list of Job

    Raises
    ------
    InvalidInput
        No such manifest, or no ``file`` column.
    """
    from .csvsafe import read_csv

    p = Path(path)
    if not p.is_file():
        raise InvalidInput("manifest", str(p), "an existing CSV file")
    rows = read_csv(p)
    if not rows or "file" not in rows[0]:
        raise InvalidInput("manifest", str(p), "a CSV with a 'file' column and rows")
    root = p.parent.resolve()
    jobs: dict[str, Job] = {}
    for r in rows:
        f = str(r.get("file") or "").strip()
        if not f:
            continue
        key = (_cell_index(r.get("page")), _cell_index(r.get("print")))
        if f not in jobs:
            jobs[f] = _manifest_job(root, f, allow_outside)
        jobs[f].meta[key] = {**r, "file": f}
    return list(jobs.values())


def _manifest_job(root: Path, f: str, allow_outside: bool) -> Job:
    real, err = resolve_once(root / f)
    if err:
        return Job(str(root / f), {}, f, err)
    if not allow_outside and not Path(real).is_relative_to(root):
        return Job(
            str(root / f),
            {},
            f,
            f"{f}: outside the manifest's folder {root}; not read (pass --allow-outside "
            f"to read files elsewhere)",
        )
    return Job(real, {}, f)


def _listed(src) -> list[str]:
    """Paths named by a folder (its entries with a scan suffix, links included), a
    glob pattern, or one path."""
    s = str(src)
    p = Path(s)
    if p.is_dir():
        try:
            entries = list(p.iterdir())
        except OSError as exc:
            raise InvalidInput("src", s, f"a readable folder ({exc.strerror or exc})") from exc
        return sorted(
            str(q)
            for q in entries
            if q.suffix.lower() in SCAN_SUFFIXES and (q.is_symlink() or not q.is_dir())
        )
    if p.exists() or p.is_symlink():
        return [s]
    hits = sorted(glob.glob(s, recursive=True))
    if not hits:
        raise InvalidInput("src", s, "an existing folder, file or glob pattern matching scans")
    return [h for h in hits if Path(h).is_symlink() or not Path(h).is_dir()]


def collect_jobs(src, manifest=None, *, allow_outside: bool = False) -> list[Job]:
    """Jobs from a folder, a glob pattern, a single file, and/or a manifest.

    Parameters
    ----------
    src : str or PathLike, optional
        Folder, glob pattern or scan file; with ``manifest``, only the files found
        here (matched by name) are analysed, with their manifest rows.
    manifest : str or PathLike, optional
        Manifest CSV (:func:`read_manifest`).
    allow_outside : bool
        Read manifest files outside the manifest's folder.

    Returns
    -------
    list of Job
        One per real file (duplicates through links dropped), plus error jobs.
    """
    if manifest is not None:
        jobs = read_manifest(manifest, allow_outside=allow_outside)
        if src is None:
            return jobs  # every manifest entry is the user's own row
        wanted = {Path(j.display).name: j for j in jobs}
        out = []
        for p in _listed(src):
            real, err = resolve_once(p)
            meta = wanted[Path(p).name].meta if Path(p).name in wanted else {}
            out.append(Job(real or p, meta, p, err))
        return _unique(out)
    if src is None:
        raise InvalidInput("src", None, "a folder, a glob pattern, a scan file or --manifest")
    out = []
    for p in _listed(src):
        real, err = resolve_once(p)
        out.append(Job(real or p, {}, p, err))
    return _unique(out)


def _unique(jobs: list[Job]) -> list[Job]:
    """One job per real file, under its shortest name; one error job per broken link
    (a loop or a dangling link reached through several folder links counts once).

    A recursive glob through a ``self -> .`` link finds ``a.jpg``, ``self/a.jpg``,
    ``self/self/a.jpg``...; the row carries the name with the fewest folders (then
    the file's own name over a link's, then the shortest, then the first in order):
    ``a.jpg``, whatever the order the names were found in.
    """
    best: dict[str, Job] = {}
    for j in jobs:
        if j.error:
            p = Path(j.display)
            key = os.path.join(os.path.realpath(p.parent), p.name)
        else:
            key = j.path
        key = os.path.normcase(key)
        if key not in best or _name_rank(j) < _name_rank(best[key]):
            best[key] = j
    return list(best.values())  # in the order each file was first found


def _name_rank(j: Job) -> tuple:
    """Sort key of a job's names: fewer folders, its own name, shorter, first."""
    shown = Path(j.display)
    return (len(shown.parts), shown.name != Path(j.path).name, len(j.display))


__all__ = ["SCAN_SUFFIXES", "Job", "collect_jobs", "read_manifest", "resolve_once"]
