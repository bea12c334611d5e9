"""The failure classes of real scans as generated sheets with exact truth (issue 11).

Each class is a function ``(rng, dpi) -> Case`` building one file (one or more
sheets: a PDF holds several pages) with what the analysis must give:

``expect`` per print
    ``'measure'`` - the print is measurable: length, width and hull area must be
    right (within 1 %, 1 % and 2 %); ``'clipped'`` / ``'perspective'`` /
    ``'axis_misaligned'`` - the print cannot be measured from this file as the
    manifest asks and must be flagged so.
``error`` per file
    The error class the file must give instead of prints (``'NoInk'`` for a noise
    page, ``'ScaleMissing'`` for a 72-dpi file without a given scale).

Classes (:data:`CLASSES`): ``classic`` (Figure 3-2 sheets), ``mtb`` (wide-groove
knobs), ``car`` (ribs between wide grooves, often wider than long), ``wide``
(bicycle prints wider than long; the prints of these three are taped square to
the sheet, within 0.5 degrees, and the manifest gives the rolling axis), ``label`` (pen labels touching prints),
``ruler`` (a ruler line across a print), ``grid`` (gridlines across the sheet; on
half the sheets also printed millimetre lines too faint to threshold, the ink
stamped over them),
``light`` (gradient and shadow), ``shade`` (a shadow band as wide as a print, a
strong gradient and a vignette), ``photo`` (on a table, flat-on), ``tilted`` (not
flat-on), ``turned`` (a print turned 2-10 degrees on the sheet while the manifest
gives the sheet's axis: flagged ``axis_misaligned``), ``dpi72`` (72 dpi in the file, the true dpi in the manifest), ``pdf``
(several pages), ``clipped`` (a print off the edge), ``tiny`` (prints under 100
mm^2; on half the sheets one of them a lattice of separate diamonds), ``noise`` (a
page of noise or texture), ``tips`` (dark blocks at the tips and faint specks
touching the edge).

:func:`write_case` writes a case's file with its manifest and truth rows;
:func:`make_mixed_set` writes a fresh set of many sheets mixing every class.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .errors import InvalidInput
from .synth import (
    LETTER,
    PrintSpec,
    SheetSpec,
    drum_and_plate_sheet,
    render_sheet,
    save_scan,
)
from .synth_effects import Bed, Grid, Light, Line, Photo, Text, text_extent

MEASURE, CLIPPED, PERSPECTIVE = "measure", "clipped", "perspective"
MISALIGNED = "axis_misaligned"


@dataclass(frozen=True)
class Case:
    """One generated file of a failure class.

    Attributes
    ----------
    kind : str
        The class (a key of :data:`CLASSES`).
    sheets : tuple of SheetSpec
        One per page.
    suffix : str
        File format ('.png', '.jpg', '.tif' or '.pdf').
    file_dpi : float or None [dots per inch]
        Resolution written into the file (None: none); may differ from the truth.
    manifest : dict
        Manifest columns of the file (``dpi``, ``rolling_axis``, ...).
    expect : tuple of tuple of str
        Per page, per print (top to bottom): 'measure', 'clipped' or 'perspective'.
    error : str
        Error class expected instead of prints ('' when prints are expected).
    """

    kind: str
    sheets: tuple
    suffix: str = ".png"
    file_dpi: float | None = None
    manifest: dict = field(default_factory=dict)
    expect: tuple = ()
    error: str = ""


def _sheet(prints, dpi, rng, **kw) -> SheetSpec:
    return SheetSpec(
        tuple(prints),
        dpi=dpi,
        seed=int(rng.integers(1 << 30)),
        specks=int(rng.integers(10, 80)),
        **kw,
    )


def _axis(angle: float) -> str:
    """Manifest rolling axis of a print turned by ``angle`` degrees (near 0 or 90)."""
    return "x" if abs(math.cos(math.radians(angle))) > 0.7 else "y"


def _bicycle(rng, center, *, angle=None, tread=None, length=None, width=None, **kw) -> PrintSpec:
    tread = tread or str(rng.choice(["slick", "ribbed", "file", "knobby"]))
    return PrintSpec(
        float(length or rng.uniform(55, 110)),
        float(width or rng.uniform(8, 24)),
        center,
        float(rng.uniform(-30, 30) if angle is None else angle),
        tread,
        ink=float(rng.uniform(0.7, 0.92)),
        halo_spots=int(rng.integers(0, 8)),
        **kw,
    )


def _case_classic(rng, dpi: float) -> Case:
    """Figure 3-2 sheets: drum above plate, label, ruler, halo spots."""
    spec = drum_and_plate_sheet(
        tire_radius=float(rng.uniform(9, 24)),
        load=float(rng.uniform(250, 600)),
        pressure=float(rng.uniform(0.25, 0.75)),
        dpi=dpi,
        tread=str(rng.choice(["slick", "ribbed", "file", "knobby"])),
        seed=int(rng.integers(1 << 30)),
        label="T5 4BAR 400N",
        angle=float(rng.uniform(-40, 40)),
        halo_spots=int(rng.integers(0, 10)),
    )
    return Case("classic", (spec,), str(rng.choice([".png", ".jpg"])), dpi, {}, ((MEASURE,) * 2,))


def _case_mtb(rng, dpi: float) -> Case:
    """Wide-groove knobby prints (gaps as wide as the knobs): one or two."""
    n = int(rng.integers(1, 3))
    ys = (140.0,) if n == 1 else (205.0, 72.0)
    angle = float(rng.choice([0.0, 90.0]) + rng.uniform(-0.5, 0.5)) if n == 1 else 0.0
    prints = []
    for y in ys:
        b = float(rng.uniform(4, 7))
        w = float(rng.uniform(38, 60 if n == 2 else 75))
        prints.append(
            PrintSpec(
                float(rng.uniform(max(w, 60), 110 if angle < 45 else 100)),
                w,
                (108.0 + rng.uniform(-6, 6), y),
                angle,
                "mtb",
                ink=float(rng.uniform(0.7, 0.9)),
                block=b,
                gap=float(rng.uniform(0.8 * b, 1.5 * b)),
            )
        )
    manifest = {"rolling_axis": _axis(angle)}
    return Case("mtb", (_sheet(prints, dpi, rng),), ".png", dpi, manifest, ((MEASURE,) * n,))


def _case_car(rng, dpi: float) -> Case:
    """A car-like print: ribs between 8-14 mm grooves, often wider than long."""
    w = float(rng.uniform(130, 175))
    p = PrintSpec(
        float(rng.uniform(110, 165)),
        w,
        (108.0, 140.0),
        float(rng.uniform(-0.5, 0.5)),
        "car",
        ink=float(rng.uniform(0.7, 0.9)),
        exponent=4.0,
        block=float(rng.uniform(20, 32)),
        gap=float(rng.uniform(8, 14)),
    )
    manifest = {"rolling_axis": "x"}
    return Case("car", (_sheet([p], dpi, rng),), ".png", dpi, manifest, ((MEASURE,),))


def _case_wide(rng, dpi: float) -> Case:
    """Bicycle prints wider than long (wide tires at low pressure)."""
    angle = float(rng.choice([0.0, 90.0]) + rng.uniform(-0.5, 0.5))
    w = float(rng.uniform(45, 80))
    p = _bicycle(rng, (108.0, 140.0), angle=angle, length=w * rng.uniform(0.55, 0.85), width=w)
    manifest = {"rolling_axis": _axis(angle)}
    return Case("wide", (_sheet([p], dpi, rng),), ".png", dpi, manifest, ((MEASURE,),))


def _top_point(spec: PrintSpec) -> tuple[float, float]:
    """The highest point of a print's outline, sheet mm."""
    from .synth import _outline

    uv = _outline(spec)
    a = math.radians(spec.angle)
    x = spec.center[0] + uv[:, 0] * math.cos(a) - uv[:, 1] * math.sin(a)
    y = spec.center[1] + uv[:, 0] * math.sin(a) + uv[:, 1] * math.cos(a)
    k = int(np.argmax(y))
    return float(x[k]), float(y[k])


def _touching_label(rng, spec: PrintSpec) -> Text:
    """A pen label whose letters touch the top of the print."""
    text = str(rng.choice(["T5 4BAR", "MAXXIS 6.9", "A3 400N", "PLATE 5"]))
    height = float(rng.uniform(3, 5))
    t = Text(text, (0.0, 0.0), height, float(rng.uniform(0.25, 0.4)), float(rng.uniform(0.7, 0.9)))
    w, _ = text_extent(t)
    x, y = _top_point(spec)
    return Text(text, (x - rng.uniform(0.2, 0.8) * w, y - 0.3), height, t.stroke, t.darkness)


def _case_label(rng, dpi: float) -> Case:
    """Pen labels touching a print, another one beside it."""
    p = _bicycle(rng, (108.0, 120.0), angle=float(rng.uniform(-10, 10)), tread="slick")
    marks = (
        _touching_label(rng, p),
        Text("TIRE 6", (20.0, 250.0), 4.0, 0.45, 0.85),
        Text("100PSI 304N", (120.0, 40.0), 3.5, 0.4, 0.8),
    )
    return Case("label", (_sheet([p], dpi, rng, marks=marks),), ".png", dpi, {}, ((MEASURE,),))


def _case_ruler(rng, dpi: float) -> Case:
    """A ruler line with ticks across a print."""
    p = _bicycle(rng, (108.0, 140.0))
    a = math.radians(rng.uniform(20, 160))
    cx, cy = p.center[0] + rng.uniform(-10, 10), p.center[1]
    d = np.array([math.cos(a), math.sin(a)]) * 90
    line = Line(
        (cx - d[0], cy - d[1]),
        (cx + d[0], cy + d[1]),
        float(rng.uniform(0.25, 0.5)),
        float(rng.uniform(0.7, 0.95)),
        ticks=float(rng.choice([5.0, 10.0])),
    )
    return Case("ruler", (_sheet([p], dpi, rng, marks=(line,)),), ".png", dpi, {}, ((MEASURE,),))


def _case_grid(rng, dpi: float) -> Case:
    """Chart-paper gridlines across the sheet and the prints."""
    prints = [_bicycle(rng, (108.0, 200.0), angle=0.0), _bicycle(rng, (108.0, 80.0), angle=0.0)]
    grid = Grid(
        float(rng.choice([5.0, 10.0])), float(rng.uniform(0.15, 0.3)), float(rng.uniform(0.5, 0.8))
    )
    # half the sheets: printed millimetre paper, its fine lines too light to
    # threshold, the ink stamped over them (faint lines, issue 11)
    fine = Grid(1.0, float(rng.uniform(0.08, 0.15)), float(rng.uniform(0.1, 0.3)), multiply=True)
    marks = (grid, fine) if rng.random() < 0.5 else (grid,)
    sheet = _sheet(prints, dpi, rng, marks=marks)
    return Case("grid", (sheet,), ".png", dpi, {}, ((MEASURE,) * 2,))


def _case_light(rng, dpi: float) -> Case:
    """A lighting gradient and a soft shadow over a print (a phone photo)."""
    prints = [_bicycle(rng, (108.0, 200.0)), _bicycle(rng, (108.0, 80.0))]
    x = float(rng.uniform(70, 140))
    light = Light(
        gradient=float(rng.uniform(0.2, 0.4)),
        direction=float(rng.uniform(0, 360)),
        shadow=((-10.0, -10.0), (x, -10.0), (x + rng.uniform(-40, 40), 300.0), (-10.0, 300.0)),
        shadow_depth=float(rng.uniform(0.25, 0.45)),
        softness=float(rng.uniform(6, 20)),
    )
    sheet = _sheet(prints, dpi, rng, light=light)
    return Case("light", (sheet,), ".jpg", dpi, {}, ((MEASURE,) * 2,))


def _band(rng, through, width: float, angle: float | None = None) -> tuple:
    """A shadow band ``width`` mm wide crossing the whole sheet, its middle line
    passing through ``through`` (x, y) [mm] at ``angle`` [deg] from +x (default
    random)."""
    a = math.radians(float(rng.uniform(0, 180)) if angle is None else angle)
    ux, uy = math.cos(a), math.sin(a)  # along the band
    nx, ny = -uy, ux
    x, y = through
    far, half = 600.0, width / 2
    return tuple(
        (x + s * far * ux + t * half * nx, y + s * far * uy + t * half * ny)
        for s, t in ((-1, -1), (1, -1), (1, 1), (-1, 1))
    )


def _case_shade(rng, dpi: float) -> Case:
    """A phone's light as the independent set draws it: a shadow band 10-40 mm wide
    with 3-15 mm soft edges, 20-40 % darker, across the sheet over or beside a print;
    a 30-50 % gradient; a 15-35 % vignette. The band is as wide as a print: no
    closing of the paper's brightness tells them apart by size."""
    prints = [_bicycle(rng, (108.0, 200.0)), _bicycle(rng, (108.0, 80.0))]
    on = prints[int(rng.integers(2))].center
    off = rng.uniform(-25, 25, size=2)
    light = Light(
        gradient=float(rng.uniform(0.3, 0.5)),
        direction=float(rng.uniform(0, 360)),
        shadow=_band(rng, (on[0] + off[0], on[1] + off[1]), float(rng.uniform(10, 40))),
        shadow_depth=float(rng.uniform(0.2, 0.4)),
        softness=float(rng.uniform(3, 15)),
        vignette=float(rng.uniform(0.15, 0.35)),
    )
    sheet = _sheet(prints, dpi, rng, light=light)
    return Case("shade", (sheet,), ".jpg", dpi, {}, ((MEASURE,) * 2,))


def _case_photo(rng, dpi: float) -> Case:
    """The sheet on a table, photographed flat-on (the scale given in the manifest)."""
    prints = [_bicycle(rng, (108.0, 190.0)), _bicycle(rng, (108.0, 90.0))]
    sheet = _sheet(prints, dpi, rng, photo=Photo(border=float(rng.uniform(10, 30))))
    manifest = {"dpi": dpi}
    return Case("photo", (sheet,), ".jpg", 72.0, manifest, ((MEASURE,) * 2,))


def _case_tilted(rng, dpi: float) -> Case:
    """The sheet photographed at an angle: no single scale, must be flagged."""
    prints = [_bicycle(rng, (108.0, 190.0)), _bicycle(rng, (108.0, 90.0))]
    photo = Photo(border=float(rng.uniform(15, 30)), tilt=float(rng.uniform(8, 20)))
    manifest = {"dpi": dpi}
    sheet = _sheet(prints, dpi, rng, photo=photo)
    return Case("tilted", (sheet,), ".jpg", 72.0, manifest, ((PERSPECTIVE,) * 2,))


def _case_turned(rng, dpi: float) -> Case:
    """Prints taped askew while the manifest gives the sheet's x axis: one 2-9
    degrees (a sheet taped or scanned crooked: measured along its own axis, within
    ``axis_misaligned_deg``; a solid tread: a knob pattern is snapped within 1
    degree only), one 20-40 degrees (along x it reads up to +60 % wide:
    it must be flagged ``axis_misaligned``)."""
    sign = rng.choice([-1, 1], size=2)
    prints = [
        _bicycle(
            rng,
            (108.0, 190.0),
            angle=float(sign[0] * rng.uniform(2, 9)),
            tread=str(rng.choice(["slick", "ribbed", "file"])),
        ),
        _bicycle(rng, (108.0, 90.0), angle=float(sign[1] * rng.uniform(20, 40))),
    ]
    manifest = {"rolling_axis": "x"}
    expect = ((MEASURE, MISALIGNED),)
    return Case("turned", (_sheet(prints, dpi, rng),), ".png", dpi, manifest, expect)


def _case_dpi72(rng, dpi: float) -> Case:
    """A file carrying the 72 dpi default; the true resolution is in the manifest."""
    case = _case_classic(rng, dpi)
    return Case("dpi72", case.sheets, ".png", 72.0, {"dpi": dpi}, case.expect)


def _case_dpi72_bare(rng, dpi: float) -> Case:
    """A file carrying the 72 dpi default and nothing else: a clear error."""
    case = _case_classic(rng, dpi)
    return Case("dpi72_bare", case.sheets, ".png", 72.0, {}, (), "ScaleUntrusted")


def _case_pdf(rng, dpi: float) -> Case:
    """A multi-page PDF: each page its own sheet."""
    pages = tuple(_case_classic(rng, dpi).sheets[0] for _ in range(int(rng.integers(2, 4))))
    return Case("pdf", pages, ".pdf", dpi, {}, ((MEASURE,) * 2,) * len(pages))


def _case_clipped(rng, dpi: float) -> Case:
    """A print running off the sheet's edge (flagged) beside a whole one."""
    whole = _bicycle(rng, (108.0, 80.0), angle=0.0)
    cut = _bicycle(rng, (0.0, 200.0), angle=0.0)
    side = rng.integers(0, 3)  # left, right, top edge
    if side == 0:
        cut = _moved(cut, (rng.uniform(-0.3, 0.3) * cut.length, 200.0))
    elif side == 1:
        cut = _moved(cut, (LETTER[0] + rng.uniform(-0.3, 0.3) * cut.length, 200.0))
    else:
        cut = _moved(cut, (108.0, LETTER[1] + rng.uniform(-0.3, 0.3) * cut.width))
    return Case(
        "clipped", (_sheet([whole, cut], dpi, rng),), ".png", dpi, {}, ((CLIPPED, MEASURE),)
    )


def _moved(p: PrintSpec, center) -> PrintSpec:
    import dataclasses

    return dataclasses.replace(p, center=(float(center[0]), float(center[1])))


def _tiny_lattice(rng, center) -> PrintSpec:
    """A tiny print of separate diamonds (knurl, 0.9-1.2 mm, no body), 10-16 x
    3-4 mm, turned at random (:mod:`inkprint.lattice`)."""
    block = float(rng.uniform(0.9, 1.2))
    return PrintSpec(
        float(rng.uniform(10, 16)),
        float(rng.uniform(3, 4)),
        center,
        float(rng.uniform(0, 180)),
        "knurl",
        block=block,
        gap=0.5 * block,
    )


def _case_tiny(rng, dpi: float) -> Case:
    """Prints under 100 mm^2 of ink (a small wheel at high pressure), 600 dpi."""
    dpi = max(dpi, 600.0)
    prints = [
        _bicycle(
            rng, (50.0, 65.0), tread="slick", length=rng.uniform(9, 16), width=rng.uniform(4, 7)
        ),
        _bicycle(
            rng, (50.0, 25.0), tread="slick", length=rng.uniform(9, 16), width=rng.uniform(4, 7)
        ),
    ]
    if rng.random() < 0.5:  # a track tire's file tread: separate diamonds, no body
        prints[1] = _tiny_lattice(rng, (50.0, 25.0))
    sheet = SheetSpec(
        tuple(prints), dpi=dpi, size=(100.0, 90.0), seed=int(rng.integers(1 << 30)), specks=30
    )
    return Case("tiny", (sheet,), ".png", dpi, {}, ((MEASURE,) * 2,))


def _case_noise(rng, dpi: float) -> Case:
    """A page of noise or texture: no print, a clear reason."""
    kind = str(rng.choice(["noise", "texture"]))
    sheet = SheetSpec((), dpi=min(dpi, 200.0), seed=int(rng.integers(1 << 30)), texture=kind)
    return Case("noise", (sheet,), ".png", min(dpi, 200.0), {}, (), "NoInk")


def _case_scanner(rng, dpi: float) -> Case:
    """A page shifted and skewed (up to 1.5 degrees) on the scanner's glass: the
    dark bed shows along one or two sides as straight wedges (1-8 mm at one end,
    ending before the other corner where the skew takes the page's edge off the
    image), often through two or three punch holes; the prints keep clear of it."""
    n = int(rng.integers(1, 3))
    ys = (190.0, 90.0)[:n] if n == 2 else (140.0,)
    prints = [_bicycle(rng, (float(rng.uniform(95, 120)), y), angle=None) for y in ys]
    sides = [str(rng.choice(["top", "bottom"])), str(rng.choice(["left", "right"]))]
    sides = sides[: int(rng.integers(1, 3))] if rng.random() < 0.7 else sides[1:]
    # the page turned by ``skew`` (clockwise on the image): every edge by as much
    t = math.tan(math.radians(rng.uniform(-1.5, 1.5)))
    w, h = LETTER
    grow = {"top": w * t, "right": h * t, "bottom": -w * t, "left": -h * t}
    starts = {s: float(rng.uniform(1, 8)) + max(-grow[s], 0.0) * rng.random() for s in sides}
    strips = tuple((s, starts[s], starts[s] + grow[s]) for s in sides)
    bed = Bed(strips, holes=int(rng.choice([0, 2, 3])), level=float(rng.uniform(0.15, 0.4)))
    sheet = _sheet(prints, dpi, rng, bed=bed)
    return Case("scanner", (sheet,), ".png", dpi, {}, ((MEASURE,) * n,))


def _case_tips(rng, dpi: float) -> Case:
    """Knobby prints whose tip blocks are small but dark (load-bearing), and faint
    specks touching the edge (not)."""
    prints = [
        _bicycle(rng, (108.0, 200.0), tread="knobby", angle=0.0, halo_touching=6),
        _bicycle(rng, (108.0, 80.0), tread="slick", angle=0.0, halo_touching=6),
    ]
    return Case("tips", (_sheet(prints, dpi, rng),), ".png", dpi, {}, ((MEASURE,) * 2,))


CLASSES = {
    "classic": _case_classic,
    "mtb": _case_mtb,
    "car": _case_car,
    "wide": _case_wide,
    "label": _case_label,
    "ruler": _case_ruler,
    "grid": _case_grid,
    "light": _case_light,
    "photo": _case_photo,
    "tilted": _case_tilted,
    "turned": _case_turned,
    "dpi72": _case_dpi72,
    "dpi72_bare": _case_dpi72_bare,
    "pdf": _case_pdf,
    "clipped": _case_clipped,
    "tiny": _case_tiny,
    "noise": _case_noise,
    "tips": _case_tips,
    "shade": _case_shade,
    "scanner": _case_scanner,
}
#: each class's place in the random seed of its cases: the classes' sorted order
#: when there were 18, later classes after them (a new class leaves the old ones'
#: cases, and the tests' seeds that name them, as they were)
_SEED_ORDER = (*sorted(k for k in CLASSES if k not in ("shade", "scanner")), "shade", "scanner")


def make_case(kind: str, *, seed: int = 0, dpi: float | None = None) -> Case:
    """One file of a failure class.

    Parameters
    ----------
    kind : str
        A key of :data:`CLASSES`.
    seed : int
        Random seed of the layout (same seed, same case).
    dpi : float, optional [dots per inch]
        Default: drawn from 150, 200, 300 and 400.

    Returns
    -------
    Case
    """
    if kind not in CLASSES:
        raise InvalidInput("kind", kind, " | ".join(CLASSES))
    rng = np.random.default_rng([seed, _SEED_ORDER.index(kind)])
    d = float(dpi if dpi is not None else rng.choice([150.0, 200.0, 300.0, 400.0]))
    return CLASSES[kind](rng, d)


def write_case(case: Case, out_dir, name: str) -> tuple[Path, list[dict], list[dict]]:
    """Render and write a case's file; its manifest rows and truth rows.

    Parameters
    ----------
    case : Case
    out_dir : str or PathLike
    name : str
        File name without the suffix.

    Returns
    -------
    path : Path
    manifest : list of dict
        One row for the file (``file`` and the case's columns).
    truth : list of dict
        One row per expected print (``page``, ``print``, ``expect``, ``length_mm``,
        ``width_mm``, ``hull_area_mm2``, ``net_area_mm2``, ``centroid_x_mm``,
        ``centroid_y_mm``), or one row with the expected ``error``.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    fname = name + case.suffix
    images, truth = [], []
    for page, (spec, expect) in enumerate(
        zip(case.sheets, case.expect or (None,) * len(case.sheets), strict=True)
    ):
        img, truths = render_sheet(spec)
        images.append(img)
        if expect is None:  # the file must give an error, not prints
            continue
        for i, (t, e) in enumerate(zip(truths, expect, strict=True)):
            c = t.ink.convex_hull.centroid
            truth.append(
                {
                    "file": fname,
                    "kind": case.kind,
                    "page": page,
                    "print": i,
                    "expect": e,
                    "error": "",
                    "length_mm": t.length,
                    "width_mm": t.width,
                    "hull_area_mm2": t.hull_area,
                    "net_area_mm2": t.net_area,
                    "centroid_x_mm": c.x,
                    "centroid_y_mm": c.y,
                    "dpi": spec.dpi,
                }
            )
    if case.error:
        truth.append(
            {"file": fname, "kind": case.kind, "page": "", "print": "", "error": case.error}
        )
    path = save_scan(
        images if case.suffix == ".pdf" else images[0], out / fname, dpi=case.file_dpi
    )
    return path, [{"file": fname, "kind": case.kind, **case.manifest}], truth


def make_mixed_set(
    out_dir, *, n_files: int = 120, seed: int = 2024, dpi: float | None = None
) -> tuple[Path, Path]:
    """Write a fresh set mixing every failure class, with manifest and truth.

    Classes are taken in turn (every class ``n_files / len(CLASSES)`` times or
    more), each with fresh random parameters.

    Parameters
    ----------
    out_dir : str or PathLike
    n_files : int
        Files to write (a PDF holds 2-3 sheets).
    seed : int
    dpi : float, optional [dots per inch]
        One resolution for every sheet (a quick set); default drawn per file.

    Returns
    -------
    manifest, truth : Path
        ``manifest.csv`` (file, kind, dpi, rolling_axis) and ``truth.csv``.
    """
    from .csvsafe import write_csv

    if n_files < 1:
        raise InvalidInput("n_files", n_files, ">= 1")
    kinds = sorted(CLASSES)
    manifest, truth = [], []
    for k in range(n_files):
        kind = kinds[k % len(kinds)]
        case = make_case(kind, seed=seed * 100_003 + k, dpi=dpi)
        _, m, t = write_case(case, out_dir, f"{k:04d}_{kind}")
        manifest.extend(m)
        truth.extend(t)
    out = Path(out_dir)
    return write_csv(manifest, out / "manifest.csv"), write_csv(truth, out / "truth.csv")


__all__ = [
    "CLASSES",
    "CLIPPED",
    "MEASURE",
    "MISALIGNED",
    "PERSPECTIVE",
    "Case",
    "make_case",
    "make_mixed_set",
    "write_case",
]
