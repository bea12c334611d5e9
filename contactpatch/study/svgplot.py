"""A small SVG plotter for the report's figures: scatter, lines, bars, log axes.

The report draws a handful of plain charts. Drawing them as SVG text directly (no
matplotlib) takes milliseconds instead of seconds, gives small files whose text is
text (searchable, selectable, in the page's font) and needs no import of a plotting
library. Every chart has fixed margins, axes from rounded limits, ticks at round
1-2-5 steps (or at the data's own values on a log axis with few of them) labelled
as plain numbers, and legends outside the plotting area.

Coordinates are pixels of the figure's ``viewBox``; the page scales the figure to
its box. Text is escaped: names are shown literally (``$`` included).
"""

from __future__ import annotations

import html
import math
import re
from dataclasses import dataclass, field

FONT = 'system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", Arial, sans-serif'
#: text width estimate per character, in font sizes
CHAR_WIDTH = 0.56
#: width of the legend column of the narrow (stacked) view [px]
NARROW_WIDTH = 360.0


def text_width(text: str, size: float) -> float:
    """Estimated width of ``text`` at font size ``size`` [px].

    Parameters
    ----------
    text : str
    size : float

    Returns
    -------
    float
    """
    return CHAR_WIDTH * size * len(text)


def _num(x: float) -> str:
    """A coordinate with 1 decimal, no '-0'."""
    s = f"{x:.1f}"
    return "0" if s in ("-0.0", "0.0") else s.removesuffix(".0")


def _esc(text) -> str:
    return html.escape(str(text), quote=True)


def tick_label(x: float) -> str:
    """A tick value as a plain number: ``0.5``, ``4``, ``1200``, ``6.9``.

    Parameters
    ----------
    x : float

    Returns
    -------
    str
    """
    s = f"{x:.6g}"
    if "e" in s:
        s = f"{x:.10f}".rstrip("0").rstrip(".")
    return "0" if float(s) == 0 else s


def linear_ticks(lo: float, hi: float, n: int = 5) -> list[float]:
    """Round ticks (1-2-5 steps) inside ``[lo, hi]``.

    Parameters
    ----------
    lo, hi : float
    n : int
        About this many intervals.

    Returns
    -------
    list of float
    """
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
        return [lo] if math.isfinite(lo) else []
    raw = (hi - lo) / n
    mag = 10.0 ** math.floor(math.log10(raw))
    step = next(k * mag for k in (1, 2, 5, 10) if k * mag >= raw * 0.999)
    k0, k1 = math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9)
    return [round(k * step, 12) + 0.0 for k in range(k0, k1 + 1)]


def nice_limits(lo: float, hi: float, *, zero: bool = False, pad: float = 0.06):
    """Axis limits: the data range padded, widened to round values.

    Parameters
    ----------
    lo, hi : float
        Data range.
    zero : bool
        Start at 0 (for sizes).
    pad : float
        Fraction of the range added on each side.

    Returns
    -------
    (float, float)
    """
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return 0.0, 1.0
    if hi - lo < 1e-12 * max(1.0, abs(hi)):
        lo, hi = lo - 0.5 * max(abs(lo), 1.0) * 0.1, hi + 0.5 * max(abs(hi), 1.0) * 0.1
    span = hi - lo
    lo, hi = (0.0 if zero else lo - pad * span), hi + pad * span
    t = linear_ticks(lo, hi)
    step = t[1] - t[0] if len(t) > 1 else span
    return (math.floor(lo / step + 1e-9) * step + 0.0, math.ceil(hi / step - 1e-9) * step + 0.0)


def log_ticks(lo: float, hi: float, values=()) -> list[float]:
    """Ticks of a log axis: the data's own values when there are 2 to 6, else
    round 1-2-5 numbers inside ``[lo, hi]``; never fewer than two.

    Parameters
    ----------
    lo, hi : float
        Axis limits (> 0).
    values : iterable of float
        The data's values on this axis.

    Returns
    -------
    list of float
    """
    v = sorted({round(x, 9) for x in values if math.isfinite(x) and x > 0 and lo <= x <= hi})
    if 2 <= len(v) <= 6:
        return v
    out = []
    for e in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1):
        out += [k * 10.0**e for k in (1, 2, 5) if lo <= k * 10.0**e <= hi]
    for n in (4, 6, 8):  # under a decade: linear steps, finer until three fit
        if len(out) >= 3:
            break
        out = [t for t in linear_ticks(lo, hi, n) if lo <= t <= hi]
    if len(out) < 2:  # a very short axis: its two ends, rounded inward
        out = sorted({float(f"{lo * 1.02:.3g}"), float(f"{hi / 1.02:.3g}"), *v})
    return out


@dataclass
class Panel:
    """One plotting area: a box [px] and its data limits.

    Attributes
    ----------
    x, y, w, h : float [px]
        The plotting area in the figure (y down).
    xlim, ylim : (float, float)
    xlog, ylog : bool
    items : list of str
        SVG elements drawn in this panel (clipped to it).
    pad_left : float [px]
        Room its tick and axis labels take to its left (set by :meth:`Plot.axes`).
    """

    x: float
    y: float
    w: float
    h: float
    xlim: tuple = (0.0, 1.0)
    ylim: tuple = (0.0, 1.0)
    xlog: bool = False
    ylog: bool = False
    items: list = field(default_factory=list)
    pad_left: float = 82.0

    def sx(self, v: float) -> float:
        """Data x -> pixel x.

        Parameters
        ----------
        v : float
            In data units (> 0 on a log axis).

        Returns
        -------
        float [px]
        """
        a, b = self.xlim
        if self.xlog:
            v, a, b = math.log(v), math.log(a), math.log(b)
        return self.x + (v - a) / (b - a) * self.w

    def sy(self, v: float) -> float:
        """Data y -> pixel y (down).

        Parameters
        ----------
        v : float
            In data units (> 0 on a log axis).

        Returns
        -------
        float [px]
        """
        a, b = self.ylim
        if self.ylog:
            v, a, b = math.log(v), math.log(a), math.log(b)
        return self.y + self.h - (v - a) / (b - a) * self.h

    def _ok(self, x, y) -> bool:
        good = math.isfinite(x) and math.isfinite(y)
        return good and (not self.xlog or x > 0) and (not self.ylog or y > 0)

    def scatter(self, xs, ys, *, colour: str, marker: str = "o", filled=True, size=4.5, alpha=1.0):
        """Markers at the points (non-finite points are left out), in one group.

        Parameters
        ----------
        xs, ys : sequence of float
            Data coordinates, equal lengths.
        colour : str
        marker : {'o', 's', 'D', '^', 'v'}
        filled : bool
            Filled, or white with a coloured edge.
        size : float [px]
            Half-width of a marker.
        alpha : float
            Opacity in [0, 1].

        Returns
        -------
        None
        """
        shapes = [
            _shape(self.sx(x), self.sy(y), marker, size)
            for x, y in zip(xs, ys, strict=True)
            if self._ok(x, y)
        ]
        if shapes:
            self.items.append(f"<g {_style(colour, filled, alpha)}>{''.join(shapes)}</g>")

    def line(self, xs, ys, *, colour: str, dashed: bool = False, width: float = 1.6):
        """A polyline through the points (non-finite points are left out).

        Parameters
        ----------
        xs, ys : sequence of float
            Data coordinates, equal lengths.
        colour : str
        dashed : bool
        width : float [px]
            Stroke width.

        Returns
        -------
        None
        """
        pts = [
            f"{_num(self.sx(x))},{_num(self.sy(y))}"
            for x, y in zip(xs, ys, strict=True)
            if self._ok(x, y)
        ]
        if len(pts) > 1:
            dash = ' stroke-dasharray="5 3"' if dashed else ""
            self.items.append(
                f'<polyline points="{" ".join(pts)}" fill="none" stroke="{colour}" '
                f'stroke-width="{width}"{dash}/>'
            )

    def rule(self, value: float, *, axis: str = "y", colour="#555", dashed=True, width=1.0):
        """A horizontal (``axis='y'``) or vertical line across the panel at ``value``.

        Parameters
        ----------
        value : float
            Data coordinate (> 0 on a log axis).
        axis : {'y', 'x'}
            ``'y'``: a horizontal line at y = value; ``'x'``: a vertical one.
        colour : str
        dashed : bool
        width : float [px]

        Returns
        -------
        None
        """
        dash = ' stroke-dasharray="2 3"' if dashed else ""
        if axis == "y":
            y = _num(self.sy(value))
            d = f"M{_num(self.x)},{y}H{_num(self.x + self.w)}"
        else:
            x = _num(self.sx(value))
            d = f"M{x},{_num(self.y)}V{_num(self.y + self.h)}"
        self.items.append(f'<path d="{d}" stroke="{colour}" stroke-width="{width}"{dash}/>')

    def segment(self, x0, y0, x1, y1, *, colour="#000", width=1.6):
        """A line segment in data coordinates.

        Parameters
        ----------
        x0, y0, x1, y1 : float
            End points (data units).
        colour : str
        width : float [px]

        Returns
        -------
        None
        """
        self.items.append(
            f'<path d="M{_num(self.sx(x0))},{_num(self.sy(y0))}L{_num(self.sx(x1))},'
            f'{_num(self.sy(y1))}" stroke="{colour}" stroke-width="{width}"/>'
        )

    def bar(self, x: float, width: float, height: float, *, fill: str, stroke="#222", hatch=False):
        """A bar from 0 (or the lower limit) to ``height`` centred at ``x``.

        Parameters
        ----------
        x : float
            Centre (data units).
        width : float
            Bar width (data units).
        height : float
            Top of the bar (data units).
        fill : str
        stroke : str
        hatch : bool
            Fill with the figure's hatch pattern instead of ``fill``.

        Returns
        -------
        None
        """
        base = max(self.ylim[0], 0.0)
        x0, x1 = self.sx(x - width / 2), self.sx(x + width / 2)
        y0, y1 = self.sy(height), self.sy(base)
        fill_attr = "url(#hatch)" if hatch else fill
        self.items.append(
            f'<rect x="{_num(x0)}" y="{_num(min(y0, y1))}" width="{_num(x1 - x0)}" '
            f'height="{_num(abs(y1 - y0))}" fill="{fill_attr}" stroke="{stroke}" stroke-width="0.8"/>'
        )

    def text(self, x: float, y: float, s: str, *, size=11, anchor="middle", dy=0.0, colour="#222"):
        """Text at a data point, shifted ``dy`` px.

        Parameters
        ----------
        x, y : float
            Data coordinates.
        s : str
            Shown literally (escaped).
        size : float [px]
        anchor : {'start', 'middle', 'end'}
        dy : float [px]
            Downward shift.
        colour : str

        Returns
        -------
        None
        """
        self.items.append(
            f'<text x="{_num(self.sx(x))}" y="{_num(self.sy(y) + dy)}" font-size="{size}" '
            f'text-anchor="{anchor}" fill="{colour}">{_esc(s)}</text>'
        )


def marker_svg(x, y, marker: str, *, colour: str, filled: bool, size: float, alpha=1.0) -> str:
    """One marker: ``o`` circle, ``s`` square, ``D`` diamond, ``^`` / ``v`` triangle.

    Parameters
    ----------
    x, y : float [px]
    marker : str
    colour : str
    filled : bool
    size : float [px]
        Half-width.
    alpha : float

    Returns
    -------
    str
    """
    shape = _shape(x, y, marker, size)
    return shape.replace("/>", f" {_style(colour, filled, alpha)}/>")


def _style(colour: str, filled: bool, alpha: float) -> str:
    style = f'fill="{colour if filled else "#fff"}" stroke="{colour}" stroke-width="1.4"'
    if alpha < 1:
        style += f' fill-opacity="{alpha:.2f}" stroke-opacity="{alpha:.2f}"'
    return style


def _shape(x: float, y: float, marker: str, r: float) -> str:
    """A marker's geometry without its style (an element ending in '/>')."""
    if marker == "s":
        r *= 0.88
        return f'<rect x="{_num(x - r)}" y="{_num(y - r)}" width="{_num(2 * r)}" height="{_num(2 * r)}"/>'
    if marker in ("D", "^", "v"):
        if marker == "D":
            pts = [(x, y - 1.25 * r), (x + r, y), (x, y + 1.25 * r), (x - r, y)]
        else:
            k = 1 if marker == "^" else -1  # apex up or down
            pts = [
                (x, y - k * 1.2 * r),
                (x + 1.1 * r, y + k * 0.8 * r),
                (x - 1.1 * r, y + k * 0.8 * r),
            ]
        return '<polygon points="' + " ".join(f"{_num(a)},{_num(b)}" for a, b in pts) + '"/>'
    return f'<circle cx="{_num(x)}" cy="{_num(y)}" r="{_num(r)}"/>'


@dataclass(frozen=True)
class LegendItem:
    """A legend entry: a marker and/or a line sample, and its label.

    Attributes
    ----------
    label : str
    colour : str
    marker : str or None
        ``o``, ``s``, ``D``, ``^`` or None (no marker).
    filled : bool
    line : bool
        Draw a line sample.
    dashed : bool
    """

    label: str
    colour: str = "#333"
    marker: str | None = "o"
    filled: bool = True
    line: bool = False
    dashed: bool = False


class Plot:
    """A figure: panels, axes, legends and free text, written as one SVG.

    Parameters
    ----------
    width, height : float [px]
        The figure's ``viewBox``.
    """

    def __init__(self, width: float, height: float) -> None:
        self.width, self.height = width, height
        self.panels: list[Panel] = []
        self.items: list[str] = []
        self.legend_items: list[LegendItem] = []  # every entry, for the narrow layout

    def panel(self, x, y, w, h, *, xlim, ylim, xlog=False, ylog=False) -> Panel:
        """Add a plotting area with its data limits.

        Parameters
        ----------
        x, y, w, h : float [px]
            The area in the figure (y down).
        xlim, ylim : (float, float)
            Data limits (positive on a log axis).
        xlog, ylog : bool
            Logarithmic axes.

        Returns
        -------
        Panel
        """
        p = Panel(x, y, w, h, tuple(xlim), tuple(ylim), xlog, ylog)
        self.panels.append(p)
        return p

    def axes(
        self,
        p: Panel,
        *,
        xlabel="",
        ylabel="",
        xticks=None,
        yticks=None,
        ycats=None,
        xgrid=True,
        ygrid=True,
        ylabels=True,
    ):
        """Frame, grid, ticks and labels of a panel.

        Parameters
        ----------
        p : Panel
        xlabel, ylabel : str
            Axis labels (empty: none).
        xticks, yticks : sequence of float, optional
            Tick values (default: round ones, :func:`linear_ticks` / :func:`log_ticks`).
        ycats : sequence of str, optional
            Category names at y = 0, 1, ... instead of numbers.
        xgrid, ygrid : bool
            Grid lines at the ticks.
        ylabels : bool
            Label the y ticks.

        Returns
        -------
        None
        """
        xt = xticks if xticks is not None else self._auto(p.xlim, p.xlog)
        if ycats is not None:
            yt = list(range(len(ycats)))
        else:
            yt = yticks if yticks is not None else self._auto(p.ylim, p.ylog)
        out = []
        for v in xt:
            x = _num(p.sx(v))
            if xgrid:
                out.append(f'<path d="M{x},{_num(p.y)}V{_num(p.y + p.h)}" class="grid"/>')
            out.append(f'<path d="M{x},{_num(p.y + p.h)}v5" class="tick"/>')
            out.append(
                f'<text x="{x}" y="{_num(p.y + p.h + 18)}" text-anchor="middle">{tick_label(v)}</text>'
            )
        for k, v in enumerate(yt):
            y = _num(p.sy(v))
            if ygrid and ycats is None:
                out.append(f'<path d="M{_num(p.x)},{y}H{_num(p.x + p.w)}" class="grid"/>')
            out.append(f'<path d="M{_num(p.x)},{y}h-5" class="tick"/>')
            if ylabels:
                label = ycats[k] if ycats is not None else tick_label(v)
                out.append(
                    f'<text x="{_num(p.x - 8)}" y="{y}" dy="0.35em" text-anchor="end">{_esc(label)}</text>'
                )
        out.append(
            f'<path d="M{_num(p.x)},{_num(p.y)}V{_num(p.y + p.h)}H{_num(p.x + p.w)}" class="frame"/>'
        )
        if xlabel:
            out.append(
                f'<text x="{_num(p.x + p.w / 2)}" y="{_num(p.y + p.h + 38)}" text-anchor="middle" class="label">{_esc(xlabel)}</text>'
            )
        if ylabel:
            cx, cy = p.x - (self._ylabel_offset(yt, ycats)), p.y + p.h / 2
            out.append(
                f'<text transform="translate({_num(cx)},{_num(cy)}) rotate(-90)" text-anchor="middle" class="label">{_esc(ylabel)}</text>'
            )
        labels = [str(c) for c in ycats] if ycats is not None else [tick_label(v) for v in yt]
        ticks_w = max([0.0, *(text_width(t, 12) for t in labels)]) if ylabels else 0.0
        p.pad_left = (self._ylabel_offset(yt, ycats) + 14) if ylabel else ticks_w + 16
        self.items.extend(out)

    @staticmethod
    def _auto(lim, log):
        return log_ticks(*lim) if log else linear_ticks(*lim)

    @staticmethod
    def _ylabel_offset(yt, ycats) -> float:
        labels = ycats if ycats is not None else [tick_label(v) for v in yt]
        return 20 + max([text_width(str(t), 12) for t in labels] + [10])

    def legend(self, items, x: float, y: float, *, width: float, size: float = 12) -> float:
        """Legend entries laid out in rows from (x, y), wrapping within ``width``.

        Parameters
        ----------
        items : sequence of LegendItem
        x, y : float [px]
            Top left corner.
        width : float [px]
            Width available; an entry that does not fit starts a new row.
        size : float [px]
            Font size.

        Returns
        -------
        float [px]
            The height used.
        """
        self.legend_items += [it for it in items if it not in self.legend_items]
        return self._legend_rows(items, x, y, width=width, size=size)

    def _legend_rows(self, items, x, y, *, width, size=12.0) -> float:
        cx, cy, row_h = x, y, size * 1.6
        for it in items:
            w = 34 + text_width(it.label, size)
            if cx > x and cx + w > x + width:
                cx, cy = x, cy + row_h
            mid = cy + row_h / 2
            if it.line:
                dash = ' stroke-dasharray="5 3"' if it.dashed else ""
                self.items.append(
                    f'<path d="M{_num(cx)},{_num(mid)}h24" stroke="{it.colour}" stroke-width="1.6"{dash}/>'
                )
            if it.marker:
                self.items.append(
                    marker_svg(
                        cx + 12, mid, it.marker, colour=it.colour, filled=it.filled, size=4.5
                    )
                )
            self.items.append(
                f'<text x="{_num(cx + 30)}" y="{_num(mid)}" dy="0.35em">{_esc(it.label)}</text>'
            )
            cx += w + 14
        return cy + row_h - y

    def text(self, x, y, s, *, anchor="start", cls="", size=None):
        """Free text at (x, y).

        Parameters
        ----------
        x, y : float [px]
        s : str
            Shown literally (escaped).
        anchor : {'start', 'middle', 'end'}
        cls : str
            CSS class (``title``, ``label``).
        size : float [px], optional

        Returns
        -------
        None
        """
        c = f' class="{cls}"' if cls else ""
        fs = f' font-size="{size}"' if size else ""
        self.items.append(
            f'<text x="{_num(x)}" y="{_num(y)}" text-anchor="{anchor}"{c}{fs}>{_esc(s)}</text>'
        )

    def _crop(self, p: Panel) -> tuple[float, float, float, float]:
        """A panel's box with room for its ticks, labels and title, stopping short
        of the neighbours' (panels sharing an axis sit close together)."""
        row = [q for q in self.panels if q is not p and _overlap(p.y, p.h, q.y, q.h)]
        col = [q for q in self.panels if q is not p and _overlap(p.x, p.w, q.x, q.w)]
        x0 = max([p.x - p.pad_left, 0.0, *(q.x + q.w + 18 for q in row if q.x + q.w <= p.x)])
        x1 = min(
            [p.x + p.w + 18, self.width, *(q.x - q.pad_left for q in row if q.x >= p.x + p.w)]
        )
        y0 = max([p.y - 46, 0.0, *(q.y + q.h + 44 for q in col if q.y + q.h <= p.y)])
        y1 = min([p.y + p.h + 48, self.height, *(q.y - 12 for q in col if q.y >= p.y + p.h)])
        return x0, y0, max(x1, p.x + p.w + 4), max(y1, p.y + p.h + 24)

    def _narrow_layout(self) -> tuple[str, str]:
        """The crops of the narrow (stacked) view and its legend.

        Each panel with its tick labels, axis labels and title is one crop; every
        legend entry of the figure is laid out again, one column of
        :data:`NARROW_WIDTH` px, below the figure's ``viewBox`` (so the wide view
        does not show it), and is the last crop.
        """
        crops = []
        for p in self.panels:
            x0, y0, x1, y1 = self._crop(p)
            crops.append((x0, y0, x1 - x0, y1 - y0))
        narrow = ""
        if self.legend_items:
            kept, self.items = self.items, []
            y0 = self.height + 20
            h = self._legend_rows(self.legend_items, 8, y0, width=NARROW_WIDTH - 16)
            narrow, self.items = "".join(self.items), kept
            crops.append((0.0, y0 - 6, NARROW_WIDTH, h + 12))
        return ";".join(" ".join(_num(v) for v in c) for c in crops), narrow

    def svg(self, name: str, title: str = "") -> str:
        """The figure as an SVG document.

        Parameters
        ----------
        name : str
            Prefix of the SVG's ids (unique on a page).
        title : str
            ``<title>`` (accessible name).

        Returns
        -------
        str
        """
        defs = [
            f'<clipPath id="{name}-c{k}"><rect x="{_num(p.x)}" y="{_num(p.y)}" '
            f'width="{_num(p.w)}" height="{_num(p.h)}"/></clipPath>'
            for k, p in enumerate(self.panels)
        ]
        defs.append(
            f'<pattern id="{name}-hatch" width="6" height="6" patternUnits="userSpaceOnUse" '
            'patternTransform="rotate(45)"><rect width="6" height="6" fill="#ddd"/>'
            '<path d="M0,0V6" stroke="#777" stroke-width="1.5"/></pattern>'
        )
        crops, narrow = self._narrow_layout()
        body = [
            f'<g clip-path="url(#{name}-c{k})">'
            + "".join(p.items).replace("url(#hatch)", f"url(#{name}-hatch)")
            + "</g>"
            for k, p in enumerate(self.panels)
        ]
        style = (
            "<style>text{fill:#222;font-size:12px}.label{font-size:13px}"
            ".grid{stroke:#e3e3e3;stroke-width:1}.tick,.frame{stroke:#444;stroke-width:1;fill:none}"
            ".title{font-size:13px;font-weight:600}</style>"
        )
        return (
            '<?xml version="1.0" encoding="utf-8"?>\n'
            f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {_num(self.width)} {_num(self.height)}" '
            f'width="{_num(self.width)}" height="{_num(self.height)}" font-family=\'{FONT}\' '
            f'data-crops="{crops}">'
            + (f"<title>{_esc(title)}</title>" if title else "")
            + style
            + f"<defs>{''.join(defs)}</defs>"
            + f'<g id="{name}-all">'
            + f'<rect width="{_num(self.width)}" height="{_num(self.height)}" fill="#fff"/>'
            + "".join(self.items)
            + "".join(body)
            + narrow
            + "</g></svg>\n"
        )


def _overlap(a: float, la: float, b: float, lb: float) -> bool:
    """Whether the intervals [a, a + la] and [b, b + lb] overlap."""
    return a < b + lb and b < a + la


def stack_html(svg: str) -> str:
    """The narrow view of a figure: each panel, then the legend, as a small SVG of
    its own that shows a crop of the figure (``<use>`` of its group, no copy).

    A page shows it instead of the wide figure on small screens (the figure stays in
    the page, so the crops can refer to it).

    Parameters
    ----------
    svg : str
        A figure of :meth:`Plot.svg` (inlined in the same page).

    Returns
    -------
    str
        ``<div class="stack">`` with one ``<svg>`` per crop; empty when the figure
        has fewer than two crops (a single panel scales well enough).
    """
    crops = re.search(r'data-crops="([^"]*)"', svg)
    group = re.search(r'<g id="([^"]+)-all">', svg)
    boxes = [c for c in (crops.group(1).split(";") if crops else []) if c]
    if group is None or len(boxes) < 2:
        return ""
    ref = _esc(group.group(1) + "-all")
    parts = [
        f"<svg viewBox=\"{_esc(b)}\" font-family='{FONT}' "
        f'style="aspect-ratio:{float(b.split()[2]):.1f}/{float(b.split()[3]):.1f}">'
        f'<use href="#{ref}"/></svg>'
        for b in boxes
    ]
    return f'<div class="stack" aria-hidden="true">{"".join(parts)}</div>'


__all__ = [
    "NARROW_WIDTH",
    "LegendItem",
    "Panel",
    "Plot",
    "linear_ticks",
    "log_ticks",
    "marker_svg",
    "nice_limits",
    "stack_html",
    "text_width",
    "tick_label",
]
