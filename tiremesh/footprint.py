"""The footprint an ink print shows: the Rotta patch with rounded ends (beyond the
dissertation, section 7.3.1; derivation in ``docs/model.md``, "Rounded footprint").

The Rotta membrane presses the ground with exactly the inflation pressure ``p`` inside
its pointed patch and with 0 outside (sections 5.5, 6.1.1: vertical force = ``p`` x
area). Between the carcass and the paper lie the tread (thickness ``t``, Figure 2-3),
the ink film and the paper: an elastic layer that spreads the load over a length of
the order of its thickness. The pressure the paper feels is modelled as the membrane
pressure smoothed by a 2D Gaussian of standard deviation ``spread``::

    q(x, y) = p * (1_patch * G_spread)(x, y)

and the print shows where ``q >= threshold * p``. The smoothing conserves the load
(the integral of ``q`` is ``p`` x patch area = Fz), keeps every level set convex where
the patch is convex (Prekopa-Leindler: the convolution of two log-concave functions
is log-concave), leaves straight edges in place at ``threshold = 0.5`` and cuts back
the pointed tips, narrower than about ``spread``, into round ends.

Computation (vectorized): the patch is cut into columns of width ``resolution`` along
``x``; in each column the ``y`` integral of the Gaussian over the patch's intervals is
exact (normal CDFs at the crossings of the outline), and the ``x`` integral is a
discrete Gaussian filter along the columns. The ``threshold`` level line is traced
with sub-cell linear interpolation (contourpy).

Units: mm; ``threshold`` and ``q / p`` are dimensionless.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .errors import InvalidParameter, TireModelError

FOOTPRINT_KINDS = ("rotta", "rounded")
#: global defaults, fitted once over all tires to the preserved prints
#: (``scripts/fit_footprint.py``, ``docs/model.md``)
DEFAULT_SPREAD_MM = 2.25
DEFAULT_THRESHOLD = 0.45
#: largest spread accepted [mm] (a tread/paper layer, not a tire size)
MAX_SPREAD_MM = 50.0
#: grid spacing bounds [mm] for the default resolution ``spread / 4``
MIN_RESOLUTION, MAX_RESOLUTION = 0.01, 0.5
#: Gaussian tails kept on each side [standard deviations]
TRUNCATE = 6.0


class FootprintVanished(TireModelError):
    """No part of the smoothed pressure reaches the threshold (patch narrower than
    the spread everywhere): the rounded footprint is empty."""


@dataclass(frozen=True)
class Footprint:
    """Which footprint a load case reports: the plain Rotta patch or the print.

    Attributes
    ----------
    kind : {'rotta', 'rounded'}
        ``'rotta'`` (default): the exact pointed patch of chapter 5. ``'rounded'``:
        the level set ``q >= threshold * p`` of the smoothed pressure.
    spread_mm : float [mm]
        Standard deviation of the Gaussian that spreads the membrane pressure
        through tread, ink and paper; in (0, 50].
    threshold : float [-]
        Fraction of the inflation pressure above which ink transfers; in (0, 1).
    """

    kind: str = "rotta"
    spread_mm: float = DEFAULT_SPREAD_MM
    threshold: float = DEFAULT_THRESHOLD

    def __post_init__(self) -> None:
        if self.kind not in FOOTPRINT_KINDS:
            raise InvalidParameter("footprint.kind", self.kind, "'rotta' or 'rounded'")
        s = float(self.spread_mm)
        if not (math.isfinite(s) and 0 < s <= MAX_SPREAD_MM):
            raise InvalidParameter("footprint.spread_mm", self.spread_mm, "0 < spread <= 50 mm")
        t = float(self.threshold)
        if not (math.isfinite(t) and 0 < t < 1):
            raise InvalidParameter("footprint.threshold", self.threshold, "0 < threshold < 1")
        object.__setattr__(self, "spread_mm", s)
        object.__setattr__(self, "threshold", t)

    @property
    def spec(self) -> str:
        """``'rotta'`` or ``'rounded:SPREAD_MM:THRESHOLD'`` (parsed by :func:`parse_footprint`)."""
        if self.kind == "rotta":
            return "rotta"
        return f"rounded:{self.spread_mm:g}:{self.threshold:g}"


def parse_footprint(value) -> Footprint:
    """A :class:`Footprint` from itself, ``None`` or a spec string.

    Parameters
    ----------
    value : Footprint, None or str
        ``'rotta'``, ``'rounded'`` (default parameters) or
        ``'rounded:SPREAD_MM[:THRESHOLD]'``.

    Returns
    -------
    Footprint
    """
    if value is None:
        return Footprint()
    if isinstance(value, Footprint):
        return value
    if not isinstance(value, str):
        raise InvalidParameter("footprint", value, "a Footprint or 'rotta' / 'rounded[:S[:T]]'")
    kind, *nums = value.strip().lower().split(":")
    if kind not in FOOTPRINT_KINDS or len(nums) > 2 or (kind == "rotta" and nums):
        raise InvalidParameter("footprint", value, "'rotta' or 'rounded[:SPREAD_MM[:THRESHOLD]]'")
    try:
        vals = [float(n) for n in nums]
    except ValueError:
        raise InvalidParameter("footprint", value, "numbers after 'rounded:'") from None
    names = ("spread_mm", "threshold")
    return Footprint(kind, **dict(zip(names, vals, strict=False)))


@dataclass(frozen=True)
class FootprintShape:
    """An outline with its extents, as the ink print would show it.

    Attributes
    ----------
    outline : (k, 2) float [mm]
        Closed counter-clockwise polygon in ground ``(x, y)`` (first point repeated).
    length, width, area : float [mm, mm, mm^2]
        Extent along ``x``, extent along ``y``, enclosed area.
    footprint : Footprint
        The model that made it.
    """

    outline: np.ndarray = field(repr=False)
    length: float
    width: float
    area: float
    footprint: Footprint = field(default_factory=Footprint)

    def mean_pressure(self, load: float) -> float:
        """Load over footprint area [N/mm^2] (Figure 4-3's load / print area).

        Parameters
        ----------
        load : float [N]

        Returns
        -------
        float [N/mm^2]
        """
        return float(load) / self.area


def _crossings(outline: np.ndarray, xc: np.ndarray) -> np.ndarray:
    """``y`` of the outline's crossings of the vertical lines ``x = xc``, sorted per
    line (NaN-padded; an even count per line, even-odd rule).

    Parameters
    ----------
    outline : (k, 2) float [mm]
        Closed polygon.
    xc : (m,) float [mm]
        Column centres.

    Returns
    -------
    (m, c) float [mm]
    """
    a, b = outline[:-1], outline[1:]
    x0, y0, x1, y1 = a[:, 0], a[:, 1], b[:, 0], b[:, 1]
    lo, hi = np.minimum(x0, x1), np.maximum(x0, x1)
    X = xc[:, None]
    hit = (X >= lo) & (X < hi)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (X - x0) / (x1 - x0)
        y = np.where(hit, y0 + t * (y1 - y0), np.nan)
    y = np.sort(y, axis=1)
    c = int(np.max(np.sum(hit, axis=1), initial=0))
    c += c % 2
    return y[:, : max(c, 2)]


def smoothed_pressure(outline, *, spread: float, resolution: float):
    """The membrane pressure smoothed by a Gaussian, as a fraction of ``p``.

    Parameters
    ----------
    outline : (k, 2) float [mm]
        Closed patch polygon in ground ``(x, y)``.
    spread : float [mm]
        Standard deviation of the Gaussian.
    resolution : float [mm]
        Grid spacing in ``x`` and ``y``.

    Returns
    -------
    xs : (m,) float [mm]
    ys : (r,) float [mm]
    q : (m, r) float [-]
        ``q / p`` at the grid nodes (its integral times ``p`` is the load).
    """
    from scipy.ndimage import gaussian_filter1d
    from scipy.special import ndtr

    pts = np.asarray(outline, float)
    if not np.array_equal(pts[0], pts[-1]):
        pts = np.vstack([pts, pts[:1]])
    pad = TRUNCATE * spread + 2 * resolution
    (xmin, ymin), (xmax, ymax) = pts.min(axis=0) - pad, pts.max(axis=0) + pad
    xs = np.arange(xmin, xmax + resolution, resolution)
    ys = np.arange(ymin, ymax + resolution, resolution)
    # exact y integral per column of width h, the column averaged over 4 sub-lines
    sub = (np.arange(4) + 0.5) / 4 - 0.5
    cross = _crossings(pts, (xs[:, None] + sub * resolution).ravel())
    sign = np.where(np.arange(cross.shape[1]) % 2, 1.0, -1.0)
    cdf = ndtr((cross[:, :, None] - ys[None, None, :]) / spread)
    col = np.nansum(sign[None, :, None] * cdf, axis=1)
    col = col.reshape(len(xs), len(sub), len(ys)).mean(axis=1)
    q = gaussian_filter1d(col, spread / resolution, axis=0, mode="constant", truncate=TRUNCATE)
    return xs, ys, q


def level_outline(xs, ys, q, level: float) -> np.ndarray:
    """The largest closed ``q = level`` line (sub-cell linear interpolation).

    Parameters
    ----------
    xs : (m,) float [mm]
    ys : (r,) float [mm]
    q : (m, r) float [-]
        Smoothed pressure over ``p`` (:func:`smoothed_pressure`).
    level : float [-]
        Threshold.

    Returns
    -------
    (k, 2) float [mm]
        Closed counter-clockwise ring; raises :class:`FootprintVanished` if none.
    """
    import contourpy

    gen = contourpy.contour_generator(ys, xs, q, line_type="Separate")
    lines = [ln for ln in gen.lines(level) if len(ln) >= 4]
    if not lines:
        raise FootprintVanished(
            f"the smoothed pressure stays below threshold {level:g} p everywhere "
            f"(max {q.max():.3g} p): the patch is narrower than the spread"
        )
    rings = [ln[:, ::-1] for ln in lines]
    areas = [_signed_area(r) for r in rings]
    i = int(np.argmax(np.abs(areas)))
    ring = rings[i] if areas[i] > 0 else rings[i][::-1]
    if not np.array_equal(ring[0], ring[-1]):
        ring = np.vstack([ring, ring[:1]])
    return ring


def _signed_area(ring: np.ndarray) -> float:
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def default_resolution(spread: float) -> float:
    """Grid spacing for a spread: ``spread / 4`` within [0.01, 0.5] mm.

    Parameters
    ----------
    spread : float [mm]

    Returns
    -------
    float [mm]
    """
    return float(np.clip(spread / 4.0, MIN_RESOLUTION, MAX_RESOLUTION))


def rounded_footprint(outline, footprint: Footprint, *, resolution: float | None = None):
    """The print of a patch: the ``threshold`` level set of the smoothed pressure.

    Parameters
    ----------
    outline : (k, 2) float [mm]
        Closed patch polygon in ground ``(x, y)`` (``ContactPatch.outline``).
    footprint : Footprint
        Spread [mm] and threshold [-] (its ``kind`` is not read).
    resolution : float [mm], optional
        Grid spacing; default :func:`default_resolution`.

    Returns
    -------
    FootprintShape
        Raises :class:`FootprintVanished` when nothing reaches the threshold.
    """
    h = default_resolution(footprint.spread_mm) if resolution is None else float(resolution)
    if not (math.isfinite(h) and 0 < h <= MAX_RESOLUTION * 4):
        raise InvalidParameter("resolution", resolution, "0 < resolution <= 2 mm")
    xs, ys, q = smoothed_pressure(outline, spread=footprint.spread_mm, resolution=h)
    ring = level_outline(xs, ys, q, footprint.threshold)
    return shape_of(ring, footprint)


def shape_of(ring, footprint: Footprint | None = None) -> FootprintShape:
    """Extents and area of a closed outline.

    Parameters
    ----------
    ring : (k, 2) float [mm]
        Closed polygon.
    footprint : Footprint, optional
        Recorded in the result (default: the plain patch).

    Returns
    -------
    FootprintShape
    """
    ring = np.asarray(ring, float)
    ext = ring.max(axis=0) - ring.min(axis=0)
    return FootprintShape(
        outline=ring,
        length=float(ext[0]),
        width=float(ext[1]),
        area=abs(_signed_area(ring)),
        footprint=footprint or Footprint(),
    )


def footprint_of(patch) -> FootprintShape:
    """The footprint a solved patch's load case asks for.

    Parameters
    ----------
    patch : tiremesh.ContactPatch

    Returns
    -------
    FootprintShape
        For ``'rotta'`` exactly the patch's own ``outline``, ``length``, ``width``
        and ``area``; for ``'rounded'`` :func:`rounded_footprint` of its outline.
    """
    fp = patch.case.footprint
    if fp.kind == "rotta":
        return FootprintShape(patch.outline, patch.length, patch.width, patch.area, fp)
    return rounded_footprint(patch.outline, fp)
