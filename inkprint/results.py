"""Results of a sheet's analysis: prints, what was set aside, flags; rows and reprs.

Flags say when a number must not be trusted. A print is ``status = 'flagged'`` when
it cannot be measured from this file (:data:`UNMEASURABLE`: ``clipped`` - it runs
off the image or the photographed page; ``perspective`` - the page was not
photographed flat-on; ``mark_on_edge`` - a mark set aside, a line along the edge or
a label's strokes, lay on the outline; ``faint_edge`` - a tread-sized blob at the
edge, inked lighter than ``edge_spot_faintness`` of the print, was left out as not
load-bearing (section 7.1.1) and would change the size by more than
``edge_uncertainty``; ``light_uncertain`` - the light changes around the print (a
shadow's edge crossing it) by more than its ink lies below the threshold, so the
paper's brightness filled in under it may move its outline; ``axis_misaligned`` - the
print is turned more than a degree against the rolling axis given, so its length and
width along that axis are too large: use ``auto`` or square the print;
``axis_ambiguous`` - measured along its principal axis (``auto``), the print's
bounding rectangle lies turned from it by more than a degree and its length or width
differ between the two (a knob pattern's moments tilt): give ``--rolling-axis``;
``grouping_uncertain`` - parts lying side by side (a car print's ribs, or two
prints?) were joined or kept apart by a gap near the footprint rule's limit:
``--group-mm`` decides; ``coarse_elements`` - a tiny print made of separate tread
elements (a lattice of diamonds, :mod:`inkprint.lattice`) too few pixels wide at
this resolution: its outline is its elements' corners, which the half-contrast edge
cuts short by about half a pixel across, more than 1 % of its width); ``coarse`` -
a print under 25 px across (a tiny print at 150 dpi): its edges are good to about a
quarter pixel between them, more than 1 % of its width; ``scale_mismatch`` - a
ruler on the sheet reads its ticks' pitch more than 2 % off every ruler's (1 mm,
1/16 or 1/10 inch): the file's dpi (or the one given) is wrong, and so is every
length (:mod:`inkprint.ruler`); ``maybe_mark`` - a small group the tiny-print rule
set aside as a letter (a print this small is solid) that looks like a tiny tread
print (:func:`inkprint.group.maybe_tiny_print`). A flagged print's
measurements are still in the row, for inspection, but :mod:`contactpatch`'s
pairing skips it. Advisory flags keep ``status = 'ok'``:
``uneven_light`` (flattened before thresholding), ``axis_uncertain`` (``auto``
rolling axis on a print nearly as wide as long: give ``--rolling-axis``).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from .coords import mm_per_px_to_dpi, px_to_mm

BAND_KEYS = ("length", "width", "hull_area", "area", "ellipse_length", "ellipse_width")
UNMEASURABLE = (
    "clipped",
    "perspective",
    "mark_on_edge",
    "axis_misaligned",
    "axis_ambiguous",
    "faint_edge",
    "light_uncertain",
    "grouping_uncertain",
    "coarse_elements",
    "coarse",
    "scale_mismatch",
    "maybe_mark",
)


@dataclass(frozen=True, repr=False)
class PrintResult:
    """One print on a sheet.

    Attributes
    ----------
    index : int
        0-based, top to bottom (prints flagged ``maybe_mark`` after the others).
    metrics : contactpatch.PatchMetrics
        Load-bearing ink (edge spots removed) [mm, or px without a scale]; length
        along the rolling direction, width across it.
    metrics_all : contactpatch.PatchMetrics
        All ink of the print.
    n_blobs : int
        8-connected ink blobs of the print.
    n_edge_spots : int
        Blobs that touched the paper without bearing load (section 7.1.1).
    edge_spot_area : float [mm^2]
        Ink area of the edge spots.
    hull_px : (k, 2) float [px]
        Load-bearing hull, continuous (row, col) pixel coordinates (for overlays).
    band : dict
        ``{key: (low, high)}`` for each of ``BAND_KEYS`` over the thresholds
        x (1 -+ ``AnalysisOptions.sensitivity``).
    bbox : (row0, col0, row1, col1) int [px]
        The print's box on the sheet.
    flags : tuple of str
        ``clipped``, ``axis_uncertain``, ... (see the module's notes).
    warnings : tuple of str
        What each flag means for this print, in words.
    unit : str
        Length unit of the metrics: 'mm', or 'px' when the sheet has no scale
        (shown in the repr).
    caps : tuple of (row0, col0, row1, col1) int [px]
        Boxes of the cut caps of its next row of elements joined to it
        (:func:`inkprint.caps.cut_caps`): the marks they were set aside as go.
    """

    index: int
    metrics: object
    metrics_all: object
    n_blobs: int
    n_edge_spots: int
    edge_spot_area: float
    hull_px: np.ndarray = field(repr=False)
    band: dict = field(repr=False)
    bbox: tuple[int, int, int, int] = (0, 0, 0, 0)
    flags: tuple = ()
    warnings: tuple = ()
    unit: str = "mm"
    caps: tuple = field(default=(), repr=False)

    @property
    def status(self) -> str:
        """'flagged' when a flag makes the print unmeasurable, else 'ok'."""
        return "flagged" if any(f in UNMEASURABLE for f in self.flags) else "ok"

    def __repr__(self) -> str:
        m, u = self.metrics, self.unit
        flags = f", flags={','.join(self.flags)}" if self.flags else ""
        return (
            f"PrintResult(#{self.index}: length {m.length:.2f} {u}, width {m.width:.2f} {u}, "
            f"hull area {m.hull_area:.1f} {u}2, net/gross {m.solidity:.2f}{flags})"
        )

    def _repr_html_(self) -> str:
        m, u = self.metrics, self.unit
        cells = [
            ("print", f"#{self.index}"),
            ("status", self.status),
            (f"length [{u}]", f"{m.length:.2f}"),
            (f"width [{u}]", f"{m.width:.2f}"),
            (f"hull area [{u}2]", f"{m.hull_area:.1f}"),
            (f"net area [{u}2]", f"{m.area:.1f}"),
            ("net / gross", f"{m.solidity:.3f}"),
            ("edge spots", str(self.n_edge_spots)),
            ("flags", ", ".join(self.flags) or "-"),
        ]
        return _html_table("PrintResult", cells)


def _html_table(title: str, cells) -> str:
    import html  # notebooks only: html.entities is a large table

    rows = "".join(
        f"<tr><th style='text-align:left'>{html.escape(k)}</th><td>{html.escape(v)}</td></tr>"
        for k, v in cells
    )
    return f"<table><caption>{html.escape(title)}</caption>{rows}</table>"


def marks_summary(marks) -> str:
    """'2 line, 3 text, 40 dust' (kinds by count), or ''.

    Parameters
    ----------
    marks : sequence of inkprint.marks.Mark

    Returns
    -------
    str
    """
    return ", ".join(f"{n} {k}" for k, n in Counter(m.kind for m in marks).most_common())


@dataclass(frozen=True, repr=False)
class SheetResult:
    """All prints of one scanned sheet (one page of a file).

    Attributes
    ----------
    path : str
        The scan's file ('' for a scan made in memory).
    page : int
        Page of a PDF (0-based).
    mm_per_px : float [mm / px]
    scale_source : str
        'given', 'metadata', 'pdf', 'paper' (a photo rectified onto its paper) or
        'pixels'.
    unit : str
        'mm', or 'px' without a scale.
    method : str
        Threshold method ('otsu', 'fixed' or 'sauvola').
    threshold : float [grey level]
    shape : (rows, cols) int [px]
    prints : list of PrintResult
        Top to bottom.
    marks : list of inkprint.marks.Mark
        Ink set aside: lines, gridlines, text, dust, noise (kind, box, reason).
    rolling_axis : str
        'auto', 'x' or 'y' (the sheet's x: across the image, left to right).
    axis_source : str
        'auto' (each print's principal axis), 'given' or 'manifest'.
    flags : tuple of str
        Sheet flags, also on every print (``perspective``, ``uneven_light``).
    warnings : tuple of str
        Sheet warnings in words.
    light_range : (low, high) float
        The paper's brightness, darkest over brightest (1 = even).
    n_pages : int
        Pages of the file.
    scales : tuple of inkprint.ruler.RulerScale
        Rulers' scales found among the marks (:func:`inkprint.ruler.find_scales`).
    """

    path: str
    page: int
    mm_per_px: float
    scale_source: str
    unit: str
    method: str
    threshold: float
    shape: tuple[int, int]
    prints: list
    marks: list = field(default_factory=list)
    rolling_axis: str = "auto"
    axis_source: str = "auto"
    flags: tuple = ()
    warnings: tuple = ()
    light_range: tuple = (1.0, 1.0)
    n_pages: int = 1
    scales: tuple = field(default=(), repr=False)

    @property
    def rejected(self) -> list[str]:
        """Why each mark set aside is not a print (one string per mark)."""
        return [f"{m.kind}: {m.reason}" if m.reason else m.kind for m in self.marks]

    def __repr__(self) -> str:
        name = self.path.rsplit("/", 1)[-1] if self.path else "in memory"
        page = f" page {self.page}" if self.n_pages > 1 else ""
        aside = marks_summary(self.marks)
        flags = f", flags={','.join(self.flags)}" if self.flags else ""
        return (
            f"SheetResult({name}{page}: {len(self.prints)} print(s), "
            f"{mm_per_px_to_dpi(self.mm_per_px):.0f} dpi ({self.scale_source}), "
            f"axis {self.rolling_axis} ({self.axis_source})"
            f"{', set aside ' + aside if aside else ''}{flags})"
        )

    def print_flags(self, index: int) -> tuple:
        """The flags of print ``index`` with the sheet's (``perspective``,
        ``scale_mismatch``, ``uneven_light``: on every print of the sheet), first the
        sheet's.

        Parameters
        ----------
        index : int
            0-based, top to bottom.

        Returns
        -------
        tuple of str
        """
        return tuple(dict.fromkeys((*self.flags, *self.prints[index].flags)))

    def print_status(self, index: int) -> str:
        """'flagged' when print ``index`` or its sheet has a flag of
        :data:`UNMEASURABLE`, else 'ok' (:meth:`print_flags`).

        Parameters
        ----------
        index : int
            0-based, top to bottom.

        Returns
        -------
        str
        """
        return "flagged" if any(f in UNMEASURABLE for f in self.print_flags(index)) else "ok"

    def _repr_html_(self) -> str:
        import html

        head = html.escape(repr(self))
        u = self.unit
        cols = ["print", "status", f"length [{u}]", f"width [{u}]", f"hull area [{u}2]", "flags"]
        body = "".join(
            "<tr>"
            + "".join(
                f"<td>{html.escape(v)}</td>"
                for v in (
                    str(p.index),
                    self.print_status(i),
                    f"{p.metrics.length:.2f}",
                    f"{p.metrics.width:.2f}",
                    f"{p.metrics.hull_area:.1f}",
                    ", ".join(self.print_flags(i)) or "-",
                )
            )
            + "</tr>"
            for i, p in enumerate(self.prints)
        )
        th = "".join(f"<th>{html.escape(c)}</th>" for c in cols)
        return f"<div><p>{head}</p><table><tr>{th}</tr>{body}</table></div>"

    def to_dataframe(self, **kw):
        """The rows (:meth:`rows`) as a pandas DataFrame (pandas is optional).

        Parameters
        ----------
        **kw
            ``load`` and ``pressure`` as for :meth:`rows`.

        Returns
        -------
        pandas.DataFrame
        """
        from .frames import dataframe

        return dataframe(self.rows(**kw))

    def rows(self, *, load: float | None = None, pressure: float | None = None) -> list[dict]:
        """One table row per print.

        Parameters
        ----------
        load : float, optional [N]
        pressure : float, optional [N/mm^2]
            With ``load``, add the load / area comparison of section 4.1.1.

        Returns
        -------
        list of dict
            Keys carry their unit (``length_mm``, ``hull_area_mm2``, ...).
        """
        return [self.row(p.index, load=load, pressure=pressure) for p in self.prints]

    def row(self, index: int, *, load: float | None = None, pressure: float | None = None) -> dict:
        """The table row of print ``index`` (see :meth:`rows`).

        Parameters
        ----------
        index : int
            0-based, top to bottom.
        load : float, optional [N]
        pressure : float, optional [N/mm^2]

        Returns
        -------
        dict
        """
        p = self.prints[index]
        u = self.unit
        flags = self.print_flags(index)
        row = {
            "file": self.path,
            "page": self.page,
            "print": p.index,
            "n_prints": len(self.prints),
            "status": self.print_status(index),
            "flags": ";".join(flags),
            "warnings": "; ".join(dict.fromkeys((*self.warnings, *p.warnings))),
            "error": "",
            "mm_per_px": self.mm_per_px,
            "dpi": mm_per_px_to_dpi(self.mm_per_px),
            "scale_source": self.scale_source,
            "rolling_axis": self.rolling_axis,
            "axis_source": self.axis_source,
            "threshold_method": self.method,
            "threshold": self.threshold,
            "light_min": self.light_range[0],
            "n_set_aside": len(self.marks),
            "set_aside": marks_summary(self.marks),
        }
        row.update(p.metrics.as_row(unit=u))
        a = p.metrics_all
        row.update(
            {
                f"all_ink_area_{u}2": a.area,
                f"all_ink_hull_area_{u}2": a.hull_area,
                f"all_ink_length_{u}": a.length,
                f"all_ink_width_{u}": a.width,
                "n_blobs": p.n_blobs,
                "n_edge_spots": p.n_edge_spots,
                f"edge_spot_area_{u}2": p.edge_spot_area,
            }
        )
        for key, (lo, hi) in p.band.items():
            unit = f"_{u}2" if "area" in key else f"_{u}"
            row[f"{key}{unit}_lo"], row[f"{key}{unit}_hi"] = lo, hi
        row.update(contact_pressure(p.metrics, load, pressure))
        row["hull_wkt"] = self._hull_wkt(p)
        return row

    def _hull_wkt(self, p: PrintResult) -> str:
        x, y = px_to_mm(
            p.hull_px[:, 0], p.hull_px[:, 1], n_rows=self.shape[0], mm_per_px=self.mm_per_px
        )
        ring = [*zip(x, y, strict=True), (x[0], y[0])]
        return "POLYGON ((" + ", ".join(f"{a:.4f} {b:.4f}" for a, b in ring) + "))"


def contact_pressure(metrics, load: float | None, pressure: float | None) -> dict:
    """Load / area and its percentage of the inflation pressure (section 4.1.1).

    Parameters
    ----------
    metrics : contactpatch.PatchMetrics
        Uses ``hull_area`` (gross) and ``area`` (net) [mm^2].
    load : float or None [N]
    pressure : float or None [N/mm^2]
        Inflation pressure.

    Returns
    -------
    dict
        ``load_per_hull_area_N_mm2``, ``load_per_net_area_N_mm2`` [N/mm^2] and their
        ``_pct`` of ``pressure`` [%]; NaN where not given.
    """
    nan = float("nan")
    if load is None or not np.isfinite(load):
        return {
            "load_per_hull_area_N_mm2": nan,
            "load_per_hull_area_pct": nan,
            "load_per_net_area_N_mm2": nan,
            "load_per_net_area_pct": nan,
        }
    gross, net = load / metrics.hull_area, load / metrics.area
    pct = (lambda q: 100.0 * q / pressure) if pressure else (lambda q: nan)
    return {
        "load_per_hull_area_N_mm2": gross,
        "load_per_hull_area_pct": pct(gross),
        "load_per_net_area_N_mm2": net,
        "load_per_net_area_pct": pct(net),
    }


__all__ = [
    "BAND_KEYS",
    "UNMEASURABLE",
    "PrintResult",
    "SheetResult",
    "contact_pressure",
    "marks_summary",
]
