#!/usr/bin/env python3
"""Independent test-sheet generator for the ``inkprint`` tool.

Every print is an analytic footprint in mm (tread elements clipped to a contact
outline, minus pores), kept as a dense shapely polygon.  The truth (length, width,
hull area, hull centroid) is computed from that polygon's convex hull only; the
image is rendered from the very same polygon by point-supersampling (S x S samples
per pixel, S*dpi >= 2000) with an exact even-odd scan-line rasteriser.  Degradations
(symmetric scanner blur, ink mottle, paper texture, noise, JPEG, illumination) do
not move the true edge.

Only numpy, opencv and shapely.  PDFs are written by a small
built-in writer (FlateDecode or DCTDecode page images).

    python gen.py OUT_DIR --files 120 --seed 1
"""

import argparse
import csv
import json
import math
import os
import struct
import zlib

import cv2
import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import LineString, MultiPolygon, Point, Polygon, box
from shapely.ops import nearest_points, unary_union

SHEETS = {"A4": (210.0, 297.0), "letter": (215.9, 279.4)}
CLASSES = [
    "slick",
    "treaded",
    "wide",
    "labels",
    "ruler",
    "chart",
    "lighting",
    "clipped",
    "dpi",
    "pdf",
    "tiny",
    "noise_page",
    "specks",
]
DPI_VARIANTS = ["untrusted+manifest", "untrusted", "nometa+manifest", "nometa"]

# ----------------------------------------------------------------------------
# geometry helpers (local print frame: u = rolling direction, v = across, mm)


def polys(g):
    if g is None or g.is_empty:
        return []
    if isinstance(g, Polygon):
        return [g]
    if isinstance(g, MultiPolygon):
        return list(g.geoms)
    out = []
    for h in getattr(g, "geoms", []):
        out += polys(h)
    return out


def ellipse(a, b, n=1440):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return Polygon(np.c_[a * np.cos(t), b * np.sin(t)])


def superellipse(a, b, e, n=2880):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    c, s = np.cos(t), np.sin(t)
    return Polygon(
        np.c_[a * np.sign(c) * np.abs(c) ** (2 / e), b * np.sign(s) * np.abs(s) ** (2 / e)]
    )


def rounded_rect(a, b, r):
    r = min(r, a * 0.99, b * 0.99)
    return box(-a + r, -b + r, a - r, b - r).buffer(r, quad_segs=64)


def lens(a, b, tip):
    R = (a * a + b * b) / (2 * b)
    c = R - b
    g = Point(0, -c).buffer(R, quad_segs=1024).intersection(Point(0, c).buffer(R, quad_segs=1024))
    return g.buffer(-tip, quad_segs=64).buffer(tip, quad_segs=64)


def egg(a, b, k, n=2880):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    s = np.cos(t)
    return Polygon(np.c_[a * s, b * np.sin(t) * (1 + k * s)])


def outline(rng, kind, L, W):
    a, b = L / 2, W / 2
    if kind == "ellipse":
        return ellipse(a, b)
    if kind == "superellipse":
        return superellipse(a, b, rng.uniform(2.3, 4.0))
    if kind == "rounded_rect":
        return rounded_rect(a, b, rng.uniform(0.35, 0.9) * b)
    if kind == "lens":
        return lens(a, b, rng.uniform(0.2, 0.6) * b)
    if kind == "egg":
        return egg(a, b, rng.uniform(0.08, 0.25) * rng.choice([-1, 1]))
    raise ValueError(kind)


def random_points_in(rng, region, n):
    if region.is_empty or n <= 0:
        return np.zeros((0, 2))
    x0, y0, x1, y1 = region.bounds
    pts = []
    got = 0
    for _ in range(50):
        m = max(4 * n, 64)
        c = np.c_[rng.uniform(x0, x1, m), rng.uniform(y0, y1, m)]
        c = c[shapely.contains_xy(region, c[:, 0], c[:, 1])]
        pts.append(c)
        got += len(c)
        if got >= n:
            break
    pts = np.concatenate(pts)[:n]
    return pts


def pores(rng, ink, density, rmin, rmax, blobs=0):
    """White unlinked dots (and a few larger uninked patches) strictly inside ink."""
    inner = ink.buffer(-(rmax + 0.35))
    holes = []
    if not inner.is_empty:
        n = rng.poisson(density * inner.area)
        for x, y in random_points_in(rng, inner, n):
            r = rng.uniform(rmin, rmax)
            e = rng.uniform(0.6, 1.0)
            h = affinity.rotate(
                affinity.scale(Point(0, 0).buffer(r, quad_segs=6), 1, e), rng.uniform(0, 180)
            )
            holes.append(affinity.translate(h, x, y))
    if blobs:
        inner2 = ink.buffer(-2.5)
        for x, y in random_points_in(rng, inner2, blobs):
            k = rng.integers(5, 9)
            ang = np.sort(rng.uniform(0, 2 * np.pi, k))
            rad = rng.uniform(0.4, 1.6, k)
            h = Polygon(np.c_[x + rad * np.cos(ang), y + rad * np.sin(ang)]).buffer(0.2)
            holes.append(h)
    if not holes:
        return ink
    return ink.difference(unary_union(holes))


def drop_small(g, frac, min_abs=0.0):
    """Drop pieces smaller than min_abs or than frac x the median piece."""
    ps = polys(g)
    if not ps:
        return g
    areas = np.array([p.area for p in ps])
    ref = np.median(areas)
    keep = [p for p, a in zip(ps, areas) if a >= max(frac * ref, min_abs)]
    return unary_union(keep)


def clip_elements(elements, O, frac, min_abs):
    """Clip each tread element to the outline; keep a piece only if it keeps at least
    frac of the element's own area (a block barely touching the paper is left out)."""
    keep = []
    for e in elements:
        for p in polys(e.intersection(O)):
            if p.area >= max(frac * e.area, min_abs):
                keep.append(p)
    return unary_union(keep)


def strip(u0, v0, ang, length, width):
    """Rectangle centred at (u0,v0), long side along angle ang (rad)."""
    d = np.array([math.cos(ang), math.sin(ang)]) * length / 2
    return LineString([(u0 - d[0], v0 - d[1]), (u0 + d[0], v0 + d[1])]).buffer(
        width / 2, cap_style="flat"
    )


def tread_file(rng, O):
    """Fine file tread: lattice of small white diamonds inside the outline."""
    pitch = rng.uniform(1.3, 2.6)
    size = rng.uniform(0.35, 0.55) * pitch
    ang = rng.uniform(-20, 20)
    a, b = O.bounds[2], O.bounds[3]
    inner = O.buffer(-0.8)
    holes = []
    d = Polygon([(size / 2, 0), (0, size / 3), (-size / 2, 0), (0, -size / 3)])
    n_u = int(2 * a / pitch) + 3
    n_v = int(2 * b / pitch) + 3
    ca, sa = math.cos(math.radians(ang)), math.sin(math.radians(ang))
    pts = []
    for i in range(-n_u, n_u + 1):
        for j in range(-n_v, n_v + 1):
            u = i * pitch + (j % 2) * pitch / 2
            v = j * pitch * 0.6
            pts.append((u * ca - v * sa, u * sa + v * ca))
    pts = np.array(pts)
    ok = shapely.contains_xy(inner.buffer(-size / 2), pts[:, 0], pts[:, 1])
    for x, y in pts[ok]:
        holes.append(affinity.translate(affinity.rotate(d, ang, origin=(0, 0)), x, y))
    return O.difference(unary_union(holes)) if holes else O


def tread_chevron(rng, O):
    bw = rng.uniform(2.0, 5.0)
    g = rng.uniform(1.0, 3.0)
    alpha = math.radians(rng.uniform(25, 60))  # from the v axis
    pitch = bw + g
    x0, y0, x1, y1 = O.bounds
    big = 2 * (x1 - x0 + y1 - y0)
    phase = rng.uniform(0, pitch)
    bars = []
    n = int(big / pitch) + 2
    ang = math.pi / 2 - alpha  # bar direction measured from u axis
    for k in range(-n, n + 1):
        u0 = k * pitch + phase
        bars.append(
            LineString([(u0, 0), (u0 + big * math.cos(ang), big * math.sin(ang))]).buffer(
                bw / 2, cap_style="flat"
            )
        )
    top = unary_union(bars).intersection(box(-big, 0, big, big))
    bot = affinity.scale(top, 1, -1, origin=(0, 0))
    t = unary_union([top, bot])
    if rng.random() < 0.5:
        t = t.union(box(-big, -rng.uniform(1, 3), big, rng.uniform(1, 3)))
    t = t.intersection(O)
    return drop_small(t, 0.0, 0.8)


def tread_knurl(rng, O):
    gw = rng.uniform(0.4, 1.0)
    pitch = rng.uniform(2.0, 4.0)
    beta = math.radians(rng.uniform(30, 60))
    x0, y0, x1, y1 = O.bounds
    big = 2 * (x1 - x0 + y1 - y0)
    grooves = []
    for sgn in (1, -1):
        ang = sgn * beta
        nrm = np.array([-math.sin(ang), math.cos(ang)])
        ph = rng.uniform(0, pitch)
        n = int(big / pitch) + 2
        for k in range(-n, n + 1):
            c = nrm * (k * pitch + ph)
            grooves.append(strip(c[0], c[1], ang, 2 * big, gw))
    t = O.difference(unary_union(grooves))
    return drop_small(t, 0.3, 0.5)


def tread_sipes(rng, O):
    x0, y0, x1, y1 = O.bounds
    W = y1 - y0
    sw = rng.uniform(0.3, 0.8)
    pitch = rng.uniform(3.0, 8.0)
    ang = math.radians(90 + rng.uniform(-30, 30))
    full = rng.random() < 0.3
    cuts = []
    k = 0
    u = x0 + rng.uniform(0, pitch)
    while u < x1:
        if full:
            cuts.append(strip(u, 0, ang, 3 * W, sw))
        else:
            f = rng.uniform(0.3, 0.8)
            side = 1 if k % 2 == 0 else -1
            va, vb = side * (W / 2 + 3), side * (W / 2 - f * W)
            vc = (va + vb) / 2
            cuts.append(
                strip(
                    u + vc * math.cos(ang) / math.sin(ang),
                    vc,
                    ang,
                    abs(va - vb) / abs(math.sin(ang)),
                    sw,
                )
            )
        u += pitch
        k += 1
    t = O.difference(unary_union(cuts))
    return drop_small(t, 0.0, 0.8)


def tread_knobby(rng, O):
    x0, y0, x1, y1 = O.bounds
    L, W = x1 - x0, y1 - y0
    bl = rng.uniform(3.0, 6.0)
    gap = rng.uniform(3.0, 8.0)
    lat_gap = rng.uniform(3.0, 8.0)
    cw = rng.uniform(4.0, 10.0)
    sw = rng.uniform(3.0, 7.0)
    P = bl + gap
    blocks = []
    u = x0 + rng.uniform(0, P)
    row = 0
    split = rng.random() < 0.4
    while u < x1 + P:
        if row % 2 == 0:
            if split:
                s = rng.uniform(1.0, 2.0)
                blocks.append(box(u - bl / 2, s / 2, u + bl / 2, cw / 2))
                blocks.append(box(u - bl / 2, -cw / 2, u + bl / 2, -s / 2))
            else:
                blocks.append(box(u - bl / 2, -cw / 2, u + bl / 2, cw / 2))
            off = cw / 2 + lat_gap + sw / 2 + rng.uniform(0, 2)
            for sg in (1, -1):
                blocks.append(box(u - bl / 2, sg * off - sw / 2, u + bl / 2, sg * off + sw / 2))
        else:
            m = lat_gap / 2 + sw / 2
            for sg in (1, -1):
                blocks.append(box(u - bl / 2, sg * m - sw / 2, u + bl / 2, sg * m + sw / 2))
            off2 = m + sw / 2 + lat_gap + sw / 2
            if off2 - sw / 2 < W / 2:
                for sg in (1, -1):
                    blocks.append(
                        box(u - bl / 2, sg * off2 - sw / 2, u + bl / 2, sg * off2 + sw / 2)
                    )
        u += P
        row += 1
    blocks = [bk.buffer(-0.4).buffer(0.4, quad_segs=8) for bk in blocks]
    skew = math.radians(rng.uniform(-8, 8))
    blocks = [affinity.skew(bk, xs=math.degrees(skew), origin=(0, 0)) for bk in blocks]
    return clip_elements(blocks, O, 0.35, 2.0)


def tread_car(rng, O):
    x0, y0, x1, y1 = O.bounds
    L, W = x1 - x0, y1 - y0
    ng = int(rng.integers(2, 5))
    gws = rng.uniform(4.0, 10.0, ng)
    # rib layout across v
    free = W - gws.sum()
    ribw = rng.dirichlet(np.full(ng + 1, 4.0)) * free
    edges = [y0]
    for i in range(ng):
        edges.append(edges[-1] + ribw[i])
        edges.append(edges[-1] + gws[i])
    edges.append(y1)
    ribs = []
    for i in range(ng + 1):
        va, vb = edges[2 * i], edges[2 * i + 1]
        rib = box(x0 - 5, va, x1 + 5, vb)
        shoulder = i in (0, ng)
        pitch = rng.uniform(6.0, 15.0)
        cut_w = rng.uniform(3.0, 6.0) if shoulder else rng.uniform(0.6, 2.5)
        ang = math.radians(90 + rng.uniform(-30, 30))
        partial = (not shoulder) and rng.random() < 0.5
        cuts = []
        u = x0 + rng.uniform(0, pitch)
        while u < x1 + pitch:
            if shoulder:
                # grooves from the outer edge inwards, 40-80 % of the rib
                f = rng.uniform(0.4, 0.8)
                vw = vb - va
                if i == 0:
                    vc, ln = va + f * vw / 2 - 5, f * vw + 10
                else:
                    vc, ln = vb - f * vw / 2 + 5, f * vw + 10
            elif partial:
                f = rng.uniform(0.4, 0.8)
                ln = f * (vb - va) + 2
                vc = va + ln / 2 - 2 if rng.random() < 0.5 else vb - ln / 2 + 2
            else:
                vc, ln = (va + vb) / 2, (vb - va) + 6
            cuts.append(
                strip(
                    u + (vc - (va + vb) / 2) / math.tan(ang),
                    vc,
                    ang,
                    ln / abs(math.sin(ang)),
                    cut_w,
                )
            )
            u += pitch
        ribs.append(rib.difference(unary_union(cuts)) if cuts else rib)
    t = unary_union(ribs).intersection(O)
    return drop_small(t, 0.0, 4.0)


TREADS = {
    "file": tread_file,
    "chevron": tread_chevron,
    "knurl": tread_knurl,
    "sipes": tread_sipes,
    "knobby": tread_knobby,
    "car": tread_car,
}


def make_print(rng, family, tire_seed=None, first=True):
    """Return dict with local ink geometry (u along rolling direction).

    Prints of one tire (same tire_seed) share outline law and tread parameters and
    differ in size (load); pores and ink are per print."""
    if tire_seed is None:
        tire_seed = int(rng.integers(2**31))
    trng = np.random.default_rng([tire_seed, 0])
    if family == "slick":
        L = trng.uniform(40, 130)
        W = trng.uniform(max(8, 0.15 * L), min(35, 0.6 * L))
        ol = str(trng.choice(["ellipse", "superellipse", "rounded_rect", "lens", "egg"]))
        tread = "file" if trng.random() < 0.4 else "slick"
    elif family == "tread":
        tread = str(
            trng.choice(
                ["chevron", "knurl", "sipes", "knobby", "car"], p=[0.22, 0.2, 0.22, 0.24, 0.12]
            )
        )
        if tread == "car":
            L = trng.uniform(90, 160)
            W = trng.uniform(110, 185)
            ol = str(trng.choice(["rounded_rect", "superellipse"]))
        elif tread == "knobby":
            L = trng.uniform(50, 120)
            W = trng.uniform(30, min(65, 0.9 * L))
            ol = str(trng.choice(["ellipse", "superellipse", "rounded_rect", "egg"]))
        else:
            L = trng.uniform(50, 130)
            W = trng.uniform(15, min(45, 0.7 * L))
            ol = str(trng.choice(["ellipse", "superellipse", "rounded_rect", "lens", "egg"]))
    elif family == "wide":
        tread = str(
            trng.choice(["slick", "knobby", "sipes", "file", "car"], p=[0.3, 0.25, 0.2, 0.1, 0.15])
        )
        if tread == "car":
            L = trng.uniform(80, 130)
            W = trng.uniform(max(1.1 * L, 110), 185)
            ol = str(trng.choice(["rounded_rect", "superellipse"]))
        else:
            L = trng.uniform(22 if tread != "knobby" else 35, 60)
            W = min(L * trng.uniform(1.08, 1.6), 75)
            ol = str(trng.choice(["ellipse", "superellipse", "rounded_rect", "egg"]))
    elif family == "tiny":
        A = trng.uniform(20, 100)
        asp = trng.uniform(2.0, 6.0)
        L = math.sqrt(4 * A * asp / math.pi)
        W = L / asp
        ol = str(trng.choice(["ellipse", "lens", "superellipse"]))
        tread = "slick"
    else:
        raise ValueError(family)
    if not first and family != "tiny":
        sL = rng.uniform(0.7, 1.0)
        sW = sL if family == "wide" else sL**0.3 * rng.uniform(0.97, 1.0)
        L, W = L * sL, W * sW
    O = outline(np.random.default_rng([tire_seed, 1]), ol, L, W)
    if tread == "slick":
        ink = O
    else:
        ink = TREADS[tread](np.random.default_rng([tire_seed, 2]), O)
        if tread != "file":
            # round every element's corners (opening, r = 0.4 mm): a sharp tip or a sliver
            # thinner than the scanner's blur has no well-defined half-level edge
            ink = unary_union(
                [
                    q
                    for p in polys(ink)
                    for q in polys(p.buffer(-0.4, quad_segs=16).buffer(0.4, quad_segs=16))
                    if q.area >= 0.8
                ]
            )
    if family == "tiny":
        ink = pores(rng, ink, rng.uniform(0, 0.3), 0.08, 0.2)
    elif tread in ("slick", "file"):
        ink = pores(
            rng,
            ink,
            rng.uniform(0.0, 0.4),
            0.1,
            rng.uniform(0.25, 0.5),
            blobs=int(rng.integers(0, 4)),
        )
    else:
        ink = pores(rng, ink, rng.uniform(0.0, 0.15), 0.1, 0.35)
    ink = shapely.make_valid(ink)
    ink = unary_union(polys(ink))
    return {
        "family": family,
        "outline": ol,
        "tread": tread,
        "ink": ink,
        "O": O,
        "tire_seed": tire_seed,
    }


def hull_extents(hull, ang_deg):
    """Extents of a polygon along and across a direction (deg)."""
    c = np.asarray(hull.exterior.coords)
    a = math.radians(ang_deg)
    u = c[:, 0] * math.cos(a) + c[:, 1] * math.sin(a)
    v = -c[:, 0] * math.sin(a) + c[:, 1] * math.cos(a)
    return u.max() - u.min(), v.max() - v.min()


def principal_angle(hull):
    """Principal axis (deg) of the hull polygon area (second moments)."""
    c = np.asarray(hull.exterior.coords)
    x, y = c[:, 0], c[:, 1]
    cr = x[:-1] * y[1:] - x[1:] * y[:-1]
    A = cr.sum() / 2
    cx = ((x[:-1] + x[1:]) * cr).sum() / (6 * A)
    cy = ((y[:-1] + y[1:]) * cr).sum() / (6 * A)
    x, y = x - cx, y - cy
    cr = x[:-1] * y[1:] - x[1:] * y[:-1]
    ixx = ((y[:-1] ** 2 + y[:-1] * y[1:] + y[1:] ** 2) * cr).sum() / 12
    iyy = ((x[:-1] ** 2 + x[:-1] * x[1:] + x[1:] ** 2) * cr).sum() / 12
    ixy = (
        (x[:-1] * y[1:] + 2 * x[:-1] * y[:-1] + 2 * x[1:] * y[1:] + x[1:] * y[:-1]) * cr
    ).sum() / 24
    # second moments about axes; long axis = direction of max spread (min inertia about it)
    sxx, syy, sxy = iyy, ixx, ixy  # spread along x, along y
    return 0.5 * math.degrees(math.atan2(2 * sxy, sxx - syy))


# ----------------------------------------------------------------------------
# page rendering


class Page:
    def __init__(self, sheet, dpi, channels):
        Wn, Hn = SHEETS[sheet]
        self.sheet = sheet
        self.dpi = dpi
        self.p = 25.4 / dpi
        self.wpx = int(round(Wn / self.p))
        self.hpx = int(round(Hn / self.p))
        self.W = self.wpx * self.p
        self.H = self.hpx * self.p
        self.C = channels
        self.img = np.ones((self.hpx, self.wpx, channels), np.float32)
        self.S = int(math.ceil(2000 / dpi))

    def lum_absorb(self, rgb):
        rgb = np.asarray(rgb, np.float32)
        if self.C == 3:
            return rgb
        # grey: absorbance of luminance of the reflectance at full strength
        return np.array(
            [1 - (0.2126 * (1 - rgb[0]) + 0.7152 * (1 - rgb[1]) + 0.0722 * (1 - rgb[2]))],
            np.float32,
        )

    def block(self, bounds, pad=2):
        x0, y0, x1, y1 = bounds
        c0 = int(math.floor(x0 / self.p)) - pad
        c1 = int(math.ceil(x1 / self.p)) + pad
        r0 = int(math.floor((self.H - y1) / self.p)) - pad
        r1 = int(math.ceil((self.H - y0) / self.p)) + pad
        c0, r0 = max(c0, 0), max(r0, 0)
        c1, r1 = min(c1, self.wpx), min(r1, self.hpx)
        return r0, c0, max(r1 - r0, 0), max(c1 - c0, 0)

    def rasterize(self, geom, pad=2, S=None):
        """Exact point-supersampled coverage of a shapely (multi)polygon."""
        S = S or self.S
        r0, c0, h, w = self.block(geom.bounds, pad)
        out = np.zeros((h, w), np.float32)
        if h == 0 or w == 0:
            return out, r0, c0
        X0, Y0, X1, Y1 = [], [], [], []
        for pg in polys(geom):
            for ring in [pg.exterior] + list(pg.interiors):
                c = np.asarray(ring.coords)
                X = (c[:, 0] / self.p - c0) * S
                Y = ((self.H - c[:, 1]) / self.p - r0) * S
                X0.append(X[:-1])
                X1.append(X[1:])
                Y0.append(Y[:-1])
                Y1.append(Y[1:])
        x0 = np.concatenate(X0)
        x1 = np.concatenate(X1)
        y0 = np.concatenate(Y0)
        y1 = np.concatenate(Y1)
        nz = y0 != y1
        x0, x1, y0, y1 = x0[nz], x1[nz], y0[nz], y1[nz]
        hS, wS = h * S, w * S
        rs = np.clip(np.ceil(np.minimum(y0, y1) - 0.5), 0, hS).astype(np.int64)
        re = np.clip(np.ceil(np.maximum(y0, y1) - 0.5), 0, hS).astype(np.int64)
        cnt = re - rs
        m = cnt > 0
        x0, x1, y0, y1, rs, cnt = x0[m], x1[m], y0[m], y1[m], rs[m], cnt[m]
        if cnt.sum() == 0:
            return out, r0, c0
        e = np.repeat(np.arange(len(cnt)), cnt)
        offs = np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        rows = rs[e] + offs
        xc = x0[e] + (rows + 0.5 - y0[e]) * (x1[e] - x0[e]) / (y1[e] - y0[e])
        o = np.lexsort((xc, rows))
        rows, xc = rows[o], xc[o]
        ra = rows[0::2]
        assert len(rows) % 2 == 0 and np.array_equal(ra, rows[1::2]), "odd crossings"
        cs = np.clip(np.ceil(xc[0::2] - 0.5), 0, wS).astype(np.int64)
        ce = np.clip(np.ceil(xc[1::2] - 0.5), 0, wS).astype(np.int64)
        k = max(1, int(3e6 // (S * S * w + 1)))
        for fr in range(0, h, k):
            fe = min(h, fr + k)
            a, b = fr * S, fe * S
            i0, i1 = np.searchsorted(ra, a), np.searchsorted(ra, b)
            if i0 == i1:
                continue
            rr = ra[i0:i1] - a
            size = (b - a) * (wS + 1)
            d = np.bincount(rr * (wS + 1) + cs[i0:i1], minlength=size) - np.bincount(
                rr * (wS + 1) + ce[i0:i1], minlength=size
            )
            mm = np.cumsum(d.reshape(b - a, wS + 1), axis=1)[:, :wS].astype(np.float32)
            out[fr:fe] = mm.reshape(fe - fr, S, w, S).mean(axis=(1, 3))
        return out, r0, c0

    def apply(self, cov, r0, c0, absorb, dark):
        h, w = cov.shape
        if h == 0 or w == 0:
            return
        a = self.lum_absorb(absorb)
        t = (cov * dark)[..., None] * a[None, None, :]
        self.img[r0 : r0 + h, c0 : c0 + w, :] *= 1.0 - t

    def mm_to_canvas(self, pts, r0, c0, S):
        pts = np.asarray(pts, float)
        X = (pts[:, 0] / self.p - c0) * S - 0.5
        Y = ((self.H - pts[:, 1]) / self.p - r0) * S - 0.5
        return np.c_[X, Y]

    def coverage_to_mm_points(self, cov, r0, c0, thr=0.03):
        rr, cc = np.nonzero(cov > thr)
        return np.c_[(cc + c0 + 0.5) * self.p, self.H - (rr + r0 + 0.5) * self.p]


def smooth_field(rng, h, w, scale_px):
    gh = max(2, int(h / max(scale_px, 1)) + 3)
    gw = max(2, int(w / max(scale_px, 1)) + 3)
    g = rng.random((gh, gw)).astype(np.float32)
    f = cv2.resize(g, (max(w, 1), max(h, 1)), interpolation=cv2.INTER_CUBIC)
    f -= f.min()
    if f.max() > 0:
        f /= f.max()
    return f


# ----------------------------------------------------------------------------
# layers


def paper_layer(rng, page):
    base = rng.uniform(0.86, 0.97)
    tint = np.array([1.0, rng.uniform(0.98, 1.0), rng.uniform(0.94, 1.0)], np.float32)
    low = smooth_field(rng, page.hpx, page.wpx, 30 / page.p) - 0.5
    amp = rng.uniform(0.005, 0.02)
    grain = rng.normal(0, 1, (page.hpx, page.wpx)).astype(np.float32)
    grain = cv2.GaussianBlur(grain, (0, 0), max(0.6, 0.15 / page.p))
    grain *= rng.uniform(0.004, 0.015) / max(grain.std(), 1e-6)
    f = base * (1 + amp * low + grain)
    if page.C == 3:
        page.img *= f[..., None] * tint[None, None, :]
    else:
        page.img *= f[..., None]
    return {"paper": round(float(base), 3)}


def ink_layer(rng, page, geom, pr):
    cov, r0, c0 = page.rasterize(geom)
    h, w = cov.shape
    if h == 0 or w == 0:
        return
    dmin = rng.uniform(0.55, 0.8)
    dmax = rng.uniform(dmin + 0.05, 0.95)
    f = smooth_field(rng, h, w, rng.uniform(3, 20) / page.p)
    f2 = smooth_field(rng, h, w, rng.uniform(1, 4) / page.p)
    f = 0.75 * f + 0.25 * f2
    f = (f - f.min()) / max(f.max() - f.min(), 1e-6)
    dark = dmin + (dmax - dmin) * f
    if pr.get("edge_fade"):
        # lighter towards the contact edge (kept >= 0.55)
        dist = cv2.distanceTransform((cov > 0.5).astype(np.uint8), cv2.DIST_L2, 5) * page.p
        fade = 1 - pr["edge_fade"] * np.clip(1 - dist / 2.5, 0, 1)
        dark = np.maximum(dark * fade, 0.55)
    gr = rng.normal(0, rng.uniform(0.01, 0.03), (h, w)).astype(np.float32)
    gr = cv2.GaussianBlur(gr, (0, 0), 0.8)
    dark = np.clip(dark + gr, 0.5, 0.97)
    absorb = pr.get("ink_rgb", (1.0, 1.0, 1.0))
    page.apply(cov, r0, c0, absorb, dark)
    pr["ink_dark"] = [round(float(dmin), 3), round(float(dmax), 3)]


def grid_layer(rng, page):
    colors = {
        "blue": (0.5, 0.22, 0.04),
        "green": (0.42, 0.12, 0.38),
        "orange": (0.05, 0.32, 0.55),
        "grey": (0.3, 0.3, 0.3),
    }
    cname = str(rng.choice(list(colors)))
    col = np.array(colors[cname], np.float32)
    wmin, wmaj = rng.uniform(0.07, 0.15), rng.uniform(0.2, 0.4)
    dmin, dmaj = rng.uniform(0.3, 0.6), rng.uniform(0.6, 1.0)
    mid = rng.random() < 0.4
    wmid, dmid = rng.uniform(0.12, 0.25), rng.uniform(0.45, 0.8)
    ang = math.radians(rng.uniform(-0.3, 0.3))
    offx, offy = rng.uniform(0, 10), rng.uniform(0, 10)
    p = page.p
    a = page.lum_absorb(col)
    xs = (np.arange(page.wpx) + 0.5) * p

    def cov1d(d, wd):
        return np.clip(np.minimum(d + p / 2, wd / 2) - np.maximum(d - p / 2, -wd / 2), 0, None) / p

    def dist(t, pitch, off):
        return np.abs((t - off + pitch / 2) % pitch - pitch / 2)

    step = 512
    for r in range(0, page.hpx, step):
        re = min(page.hpx, r + step)
        ys = page.H - (np.arange(r, re) + 0.5) * p
        X, Y = np.meshgrid(xs, ys)
        xr = X * math.cos(ang) + Y * math.sin(ang)
        yr = -X * math.sin(ang) + Y * math.cos(ang)
        d = np.zeros_like(X, dtype=np.float32)
        for t, off in ((xr, offx), (yr, offy)):
            d = np.maximum(d, dmin * cov1d(dist(t, 1.0, off), wmin))
            if mid:
                d = np.maximum(d, dmid * cov1d(dist(t, 5.0, off), wmid))
            d = np.maximum(d, dmaj * cov1d(dist(t, 10.0, off), wmaj))
        page.img[r:re] *= 1 - d[..., None] * a[None, None, :]
    return {
        "grid": cname,
        "grid_w": [round(wmin, 3), round(wmaj, 3)],
        "grid_d": [round(dmin, 2), round(dmaj, 2)],
        "grid_ang_deg": round(math.degrees(ang), 3),
    }


def lighting_layer(rng, page, effects):
    ys, xs = np.mgrid[0 : page.hpx, 0 : page.wpx].astype(np.float32)
    X = (xs + 0.5) * page.p
    Y = page.H - (ys + 0.5) * page.p
    del xs, ys
    f = np.ones_like(X)
    info = {}
    if "gradient" in effects:
        th = rng.uniform(0, 2 * np.pi)
        t = X * math.cos(th) + Y * math.sin(th)
        t = (t - t.min()) / (t.max() - t.min())
        drop = rng.uniform(0.3, 0.5)
        f *= 1 - drop * t
        info["gradient_drop"] = round(float(drop), 3)
    if "shadow" in effects:
        th = rng.uniform(0, np.pi)
        d = X * math.cos(th) + Y * math.sin(th)
        c = rng.uniform(d.min() + 20, d.max() - 20)
        wdt = rng.uniform(10, 40)
        soft = rng.uniform(3, 15)
        depth = rng.uniform(0.2, 0.4)
        z = np.abs(d - c) - wdt / 2
        s = 1 / (1 + np.exp(np.clip(z / (soft / 4), -50, 50)))
        f *= 1 - depth * s
        info["shadow"] = [round(float(wdt), 1), round(float(soft), 1), round(float(depth), 2)]
    if "vignette" in effects:
        cx, cy = page.W / 2 + rng.uniform(-20, 20), page.H / 2 + rng.uniform(-20, 20)
        r2 = (X - cx) ** 2 + (Y - cy) ** 2
        v = rng.uniform(0.15, 0.35)
        f *= 1 - v * r2 / r2.max()
        info["vignette"] = round(float(v), 2)
    page.img *= f[..., None]
    return info


def dust_layer(rng, page, avoid, n):
    for _ in range(n):
        x, y = rng.uniform(3, page.W - 3), rng.uniform(3, page.H - 3)
        if avoid is not None and avoid.distance(Point(x, y)) < 6:
            continue
        r = rng.uniform(0.03, 0.1)
        g = Point(x, y).buffer(r, quad_segs=4)
        cov, r0, c0 = page.rasterize(g)
        page.apply(cov, r0, c0, (1, 1, 1), rng.uniform(0.3, 0.8))


# --- marks: text, arrows, scribbles, ruler -----------------------------------

FONTS = [
    cv2.FONT_HERSHEY_SIMPLEX,
    cv2.FONT_HERSHEY_PLAIN,
    cv2.FONT_HERSHEY_DUPLEX,
    cv2.FONT_HERSHEY_COMPLEX,
    cv2.FONT_HERSHEY_TRIPLEX,
    cv2.FONT_HERSHEY_COMPLEX_SMALL,
    cv2.FONT_HERSHEY_SCRIPT_SIMPLEX,
    cv2.FONT_HERSHEY_SCRIPT_COMPLEX,
]
PENS = {
    "black": (0.9, 0.9, 0.88),
    "blue": (0.75, 0.6, 0.15),
    "pencil": (0.55, 0.55, 0.55),
    "red": (0.15, 0.7, 0.65),
}


def label_text(rng):
    forms = [
        lambda: f"T{rng.integers(1, 20)} {rng.uniform(2, 8):.1f}bar {rng.integers(20, 90) * 10}N",
        lambda: f"T{rng.integers(1, 9)} {rng.integers(2, 7)}bar {rng.integers(2, 9) * 100}N",
        lambda: (
            f"{rng.choice(['GP5000', 'Pro One', 'Marathon', 'Rock Razor', 'Pirelli'])} {rng.integers(23, 60)}mm"
        ),
        lambda: f"#{rng.integers(1, 60)}",
        lambda: f"{rng.choice(['front', 'rear', 'left', 'right'])} {rng.uniform(1.5, 7):.1f} bar",
        lambda: f"{rng.integers(1, 29):02d}.{rng.integers(1, 13):02d}.{rng.integers(18, 25)}",
        lambda: f"p={rng.uniform(2, 8):.1f} F={rng.integers(20, 80) * 10}",
        lambda: f"run {rng.integers(1, 9)}",
        lambda: f"{rng.integers(200, 700)} N",
    ]
    return forms[int(rng.integers(len(forms)))]()


class Mark:
    """A drawn mark: coverage block + colour; and its ink points (mm) for gap checks."""

    def __init__(self, cov, r0, c0, rgb, dark, page, kind):
        self.cov, self.r0, self.c0, self.rgb, self.dark, self.kind = cov, r0, c0, rgb, dark, kind
        self.pts = page.coverage_to_mm_points(cov, r0, c0, 0.1)

    def gap_to(self, geom, page):
        if len(self.pts) == 0:
            return float("inf")
        mp = shapely.points(self.pts)
        d = shapely.distance(mp, geom)
        return float(d.min() - page.p / 2)

    def bounds(self):
        return shapely.MultiPoint(self.pts).bounds if len(self.pts) else None


def render_text(rng, page, text, height_mm, stroke_mm, angle_deg, font):
    S = 4
    scale_px = height_mm / page.p * S
    (tw, th), base = cv2.getTextSize(text, font, 1.0, 1)
    fs = scale_px / max(th, 1)
    thick = max(1, int(round(stroke_mm / page.p * S)))
    (tw, th), base = cv2.getTextSize(text, font, fs, thick)
    pad = thick + 4
    T = np.zeros((th + base + 2 * pad, tw + 2 * pad), np.uint8)
    cv2.putText(T, text, (pad, pad + th), font, fs, 255, thick, cv2.LINE_AA)
    # rotate (with a little shear for handwriting) about centre
    h, w = T.shape
    sh = rng.uniform(-0.2, 0.2)
    A = np.array([[1, sh, 0], [0, 1, 0]], np.float64)
    R = cv2.getRotationMatrix2D((w / 2, h / 2), angle_deg, 1.0)
    M = R @ np.vstack([A, [0, 0, 1]])
    corners = np.array([[0, 0, 1], [w, 0, 1], [0, h, 1], [w, h, 1]], float) @ M.T
    mn, mx = corners.min(0), corners.max(0)
    M[:, 2] -= mn
    out = cv2.warpAffine(
        T,
        M,
        (int(math.ceil(mx[0] - mn[0])), int(math.ceil(mx[1] - mn[1]))),
        flags=cv2.INTER_LINEAR,
    )
    return out, S  # canvas at S x page resolution


def place_canvas(page, canvas, S, centre_mm):
    """Place an S-times supersampled canvas centred at centre_mm, snapped to whole pixels."""
    h, w = canvas.shape
    # pad canvas to a multiple of S
    H2, W2 = int(math.ceil(h / S)) * S, int(math.ceil(w / S)) * S
    cc = np.zeros((H2, W2), np.uint8)
    cc[:h, :w] = canvas
    col = centre_mm[0] / page.p - W2 / S / 2
    row = (page.H - centre_mm[1]) / page.p - H2 / S / 2
    c0, r0 = int(round(col)), int(round(row))
    cov = cc.reshape(H2 // S, S, W2 // S, S).mean(axis=(1, 3)).astype(np.float32) / 255
    # crop to page
    rr0, cc0 = max(r0, 0), max(c0, 0)
    rr1, cc1 = min(r0 + H2 // S, page.hpx), min(c0 + W2 // S, page.wpx)
    if rr1 <= rr0 or cc1 <= cc0:
        return np.zeros((0, 0), np.float32), 0, 0
    return cov[rr0 - r0 : rr1 - r0, cc0 - c0 : cc1 - c0], rr0, cc0


def canvas_hull_rel(page, canvas, S):
    """Convex hull of canvas ink in mm, relative to the canvas centre (page frame, y up)."""
    ys, xs = np.nonzero(canvas > 25)
    if len(xs) == 0:
        return None
    h, w = canvas.shape
    pts = np.c_[(xs + 0.5 - w / 2) / S * page.p, -(ys + 0.5 - h / 2) / S * page.p]
    return shapely.MultiPoint(pts).convex_hull.buffer(page.p / 2)


def boundary_point_normal(rng, hull):
    ring = hull.exterior
    t = rng.uniform(0, ring.length)
    q = ring.interpolate(t)
    q2 = ring.interpolate((t + 0.5) % ring.length)
    q1 = ring.interpolate((t - 0.5) % ring.length)
    tx, ty = q2.x - q1.x, q2.y - q1.y
    n = np.array([ty, -tx]) / max(math.hypot(tx, ty), 1e-9)
    # outward?
    if hull.contains(Point(q.x + n[0] * 0.5, q.y + n[1] * 0.5)):
        n = -n
    return np.array([q.x, q.y]), n


def solve_offset(fn, target, lo=0.0, hi=300.0):
    """Find t with fn(t) == target for increasing fn (bisection)."""
    for _ in range(50):
        mid = (lo + hi) / 2
        if fn(mid) < target:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def make_text_mark(rng, page, target_ink, target_hull, gap, others, margin=3):
    """Text label at (approximately) `gap` mm from the target print (gap<=0: touching/overlapping)."""
    for _ in range(40):
        text = label_text(rng)
        font = int(rng.choice(FONTS)) | (cv2.FONT_ITALIC if rng.random() < 0.2 else 0)
        hmm = rng.uniform(2.5, 7.0)
        stroke = rng.uniform(0.25, 0.7)
        ang = rng.uniform(-12, 12) if rng.random() < 0.7 else rng.uniform(-90, 90)
        canvas, S = render_text(rng, page, text, hmm, stroke, ang, font)
        hrel = canvas_hull_rel(page, canvas, S)
        if hrel is None:
            continue
        q, n = boundary_point_normal(rng, target_hull)

        def dist_at(t):
            g = affinity.translate(hrel, q[0] + n[0] * t, q[1] + n[1] * t)
            if g.intersects(target_ink):
                return -(g.intersection(target_hull).area ** 0.5) * 0.01 - 1e-3 + 0  # overlapping
            return g.distance(target_ink)

        if gap > 0:
            t = solve_offset(dist_at, gap)
        else:
            t = solve_offset(
                lambda t: (
                    0.0
                    if affinity.translate(hrel, q[0] + n[0] * t, q[1] + n[1] * t).intersects(
                        target_ink
                    )
                    else 1.0
                ),
                0.5,
            )
            t -= -gap
        c = q + n * t
        cov, r0, c0 = place_canvas(page, canvas, S, c)
        if cov.size == 0:
            continue
        m = Mark(
            cov, r0, c0, PENS[str(rng.choice(list(PENS)))], rng.uniform(0.55, 0.9), page, "text"
        )
        bx = m.bounds()
        if (
            bx is None
            or bx[0] < margin
            or bx[1] < margin
            or bx[2] > page.W - margin
            or bx[3] > page.H - margin
        ):
            continue
        if any(m.gap_to(o, page) < 8 for o in others):
            continue
        m.info = {
            "mark": "text",
            "text": text,
            "h_mm": round(hmm, 2),
            "stroke_mm": round(stroke, 2),
            "gap_mm": round(m.gap_to(target_ink, page), 3),
        }
        return m
    return None


def bezier(p0, p1, p2, n=80):
    t = np.linspace(0, 1, n)[:, None]
    return (1 - t) ** 2 * p0 + 2 * (1 - t) * t * p1 + t**2 * p2


def make_stroke_mark(rng, page, target_ink, target_hull, gap, others, margin=3):
    """Arrow / scribble ending `gap` mm from the print (<=0: ending on its edge)."""
    for _ in range(60):
        q, n = boundary_point_normal(rng, target_hull)
        # nearest ink point near q
        qi = nearest_points(target_ink, Point(q))[0]
        q = np.array([qi.x, qi.y])
        E = q + n * gap
        D = rng.uniform(8, 30)
        rot = math.radians(rng.uniform(-45, 45))
        nd = np.array(
            [
                n[0] * math.cos(rot) - n[1] * math.sin(rot),
                n[0] * math.sin(rot) + n[1] * math.cos(rot),
            ]
        )
        S0 = E + nd * D
        perp = np.array([-nd[1], nd[0]])
        P1 = (E + S0) / 2 + perp * rng.uniform(-0.3, 0.3) * D
        kind = str(rng.choice(["arrow", "line", "scribble"]))
        pts = bezier(S0, P1, E)
        if kind == "scribble":
            # wavy squiggle along the curve
            tt = np.linspace(0, 1, len(pts))
            amp = rng.uniform(0.5, 2.0)
            fr = rng.uniform(2, 6)
            tang = np.gradient(pts, axis=0)
            tang /= np.linalg.norm(tang, axis=1, keepdims=True) + 1e-12
            nn = np.c_[-tang[:, 1], tang[:, 0]]
            pts = pts + nn * (amp * np.sin(2 * np.pi * fr * tt) * (1 - tt) ** 0.5)[:, None]
        lines = [pts]
        if kind == "arrow":
            tng = pts[-1] - pts[-4]
            tng /= np.linalg.norm(tng)
            hl = rng.uniform(1.5, 3.0)
            for s in (1, -1):
                a = math.radians(180 + s * rng.uniform(20, 35))
                d = np.array(
                    [
                        tng[0] * math.cos(a) - tng[1] * math.sin(a),
                        tng[0] * math.sin(a) + tng[1] * math.cos(a),
                    ]
                )
                lines.append(np.array([pts[-1], pts[-1] + d * hl]))
        stroke = rng.uniform(0.25, 0.8)
        allp = np.concatenate(lines)
        bx = (
            allp[:, 0].min() - 2,
            allp[:, 1].min() - 2,
            allp[:, 0].max() + 2,
            allp[:, 1].max() + 2,
        )
        if bx[0] < margin or bx[1] < margin or bx[2] > page.W - margin or bx[3] > page.H - margin:
            continue
        # the body of the stroke must stay off the print
        body = LineString(pts[: int(len(pts) * 0.85)])
        if body.distance(target_hull) < max(gap, 0) + 0.5:
            continue
        S = 4
        r0, c0, h, w = page.block(bx, 2)
        canvas = np.zeros((h * S, w * S), np.uint8)
        th = max(1, int(round(stroke / page.p * S)))
        for ln in lines:
            cp = page.mm_to_canvas(ln, r0, c0, S)
            cv2.polylines(
                canvas, [np.round(cp * 16).astype(np.int32)], False, 255, th, cv2.LINE_AA, shift=4
            )
        cov = canvas.reshape(h, S, w, S).mean(axis=(1, 3)).astype(np.float32) / 255
        m = Mark(
            cov, r0, c0, PENS[str(rng.choice(list(PENS)))], rng.uniform(0.55, 0.9), page, kind
        )
        if any(m.gap_to(o, page) < 8 for o in others):
            continue
        m.info = {
            "mark": kind,
            "stroke_mm": round(stroke, 2),
            "gap_mm": round(m.gap_to(target_ink, page), 3),
        }
        return m
    return None


def make_ruler(rng, page, target_ink, target_hull, axis_deg, mode, others):
    """Thin ruled line with ticks crossing or beside a print (shapely geometry, exact)."""
    lw = rng.uniform(0.2, 0.8)
    tw = lw * rng.uniform(0.6, 1.0)
    length = rng.uniform(100, 250)
    side = rng.choice([1, -1])
    pen = str(rng.choice(["pencil", "black", "blue"]))
    dark = rng.uniform(0.3, 0.6) if pen == "pencil" else rng.uniform(0.55, 0.85)
    numbers = rng.random() < 0.3

    def geom_at(P, phi):
        d = np.array([math.cos(phi), math.sin(phi)])
        nrm = np.array([-d[1], d[0]]) * side
        A, B = P - d * length / 2, P + d * length / 2
        parts = [LineString([A, B]).buffer(lw / 2, cap_style="flat")]
        k = 0
        off = rng_off
        t = 0.0
        while t <= length:
            tl = 3.0 if k % 10 == 0 else (1.8 if k % 5 == 0 else 1.0)
            c = A + d * (t + off)
            if t + off <= length:
                parts.append(
                    LineString([c, c + nrm * (tl + lw / 2)]).buffer(tw / 2, cap_style="flat")
                )
            t += 1.0
            k += 1
        return unary_union(parts)

    rng_off = rng.uniform(0, 1)
    cen = np.array(target_hull.centroid.coords[0])
    for _ in range(30):
        if mode == "cross":
            inner = target_hull.buffer(-3)
            if inner.is_empty:
                inner = target_hull
            P = random_points_in(rng, inner, 1)[0]
            phi = math.radians(axis_deg + rng.choice([0, 90, rng.uniform(0, 180)]))
            g = geom_at(P, phi)
            gap = -1.0
        else:
            gap = rng.uniform(0.5, 6.0)
            phi = math.radians(axis_deg + rng.choice([0, 90]) + rng.uniform(-5, 5))
            nrm = np.array([-math.sin(phi), math.cos(phi)]) * rng.choice([1, -1])
            t = solve_offset(
                lambda t: (
                    geom_at(cen + nrm * t, phi).distance(target_ink)
                    if not geom_at(cen + nrm * t, phi).intersects(target_hull)
                    else -1.0
                ),
                gap,
                0,
                200,
            )
            P = cen + nrm * t
            g = geom_at(P, phi)
            gap = g.distance(target_ink)
        g = g.intersection(box(0, 0, page.W, page.H))
        if any(g.distance(o) < 6 for o in others):
            continue
        cov, r0, c0 = page.rasterize(g, S=max(2, page.S // 2))
        m = Mark(cov, r0, c0, PENS[pen], dark, page, "ruler")
        m.info = {
            "mark": "ruler",
            "mode": mode,
            "line_mm": round(lw, 2),
            "pen": pen,
            "gap_mm": round(float(gap), 3),
            "angle_rel_deg": round((math.degrees(phi) - axis_deg) % 180, 1),
        }
        m.extra = []
        if numbers:
            d = np.array([math.cos(phi), math.sin(phi)])
            nrm = np.array([-d[1], d[0]]) * side
            A = P - d * length / 2
            for k in range(0, int(length / 10) + 1):
                c = A + d * (rng_off + 10 * k) + nrm * 5.5
                if target_hull.distance(Point(c)) < 4 or any(
                    o.distance(Point(c)) < 8 for o in others
                ):
                    continue
                if not (5 < c[0] < page.W - 5 and 5 < c[1] < page.H - 5):
                    continue
                cv_, S = render_text(
                    rng, page, str(k), 2.2, 0.25, math.degrees(phi), cv2.FONT_HERSHEY_SIMPLEX
                )
                cov2, rr, cc = place_canvas(page, cv_, S, c)
                if cov2.size:
                    m.extra.append((cov2, rr, cc))
        return m
    return None


def specks_and_halo(rng, page, ink, hull, pr):
    info = {}
    nd = int(rng.integers(3, 16))
    dots = []
    gaps = []
    for _ in range(nd):
        r = rng.uniform(0.1, 0.3)
        g = rng.uniform(0.2, 2.5)
        q, n = boundary_point_normal(rng, hull)
        c = q + n * (g + r)
        dot = Point(c).buffer(r, quad_segs=8)
        gg = dot.distance(ink)
        dots.append(dot)
        gaps.append(gg)
        cov, r0, c0 = page.rasterize(dot)
        page.apply(cov, r0, c0, pr.get("ink_rgb", (1, 1, 1)), rng.uniform(0.12, 0.45))
    info["dots"] = nd
    info["dot_gap_min_mm"] = round(float(min(gaps)), 3)
    if rng.random() < 0.75:
        g = rng.uniform(0.2, 1.0)
        w = rng.uniform(0.3, 1.5)
        ring = hull.buffer(g + w, quad_segs=32).difference(hull.buffer(g, quad_segs=32))
        cov, r0, c0 = page.rasterize(ring)
        h, wd = cov.shape
        f = smooth_field(rng, h, wd, rng.uniform(3, 12) / page.p)
        f = np.clip((f - rng.uniform(0.1, 0.5)) * 3, 0, 1)
        page.apply(cov, r0, c0, pr.get("ink_rgb", (1, 1, 1)), rng.uniform(0.06, 0.22) * f)
        info["halo"] = [round(g, 2), round(w, 2)]
    return info


# ----------------------------------------------------------------------------
# encoding


def png_bytes(img, dpi):
    ok, buf = cv2.imencode(".png", img)
    b = bytes(buf)
    if dpi is None:
        return b
    ppm = int(round(dpi / 0.0254))
    data = struct.pack(">IIB", ppm, ppm, 1)
    chunk = (
        struct.pack(">I", 9)
        + b"pHYs"
        + data
        + struct.pack(">I", zlib.crc32(b"pHYs" + data) & 0xFFFFFFFF)
    )
    return b[:33] + chunk + b[33:]


def jpeg_bytes(img, dpi, q):
    ok, buf = cv2.imencode(".jpg", img, [cv2.IMWRITE_JPEG_QUALITY, int(q)])
    b = bytearray(bytes(buf))
    assert b[2:4] == b"\xff\xe0" and b[6:11] == b"JFIF\x00", "no JFIF header"
    if dpi is None:
        b[13] = 0
        b[14:18] = struct.pack(">HH", 1, 1)
    else:
        b[13] = 1
        b[14:18] = struct.pack(">HH", int(dpi), int(dpi))
    return bytes(b)


def tiff_write(path, img, dpi):
    params = []
    if dpi is not None:
        params = [
            cv2.IMWRITE_TIFF_RESUNIT,
            2,
            cv2.IMWRITE_TIFF_XDPI,
            int(dpi),
            cv2.IMWRITE_TIFF_YDPI,
            int(dpi),
        ]
    params += [cv2.IMWRITE_TIFF_COMPRESSION, 5 if img.dtype == np.uint8 else 1]
    ok = cv2.imwrite(path, img, params)
    assert ok


def write_pdf(path, pages):
    """pages: list of (img uint8 grey HxW or RGB HxWx3, dpi, 'flate'|'dct', quality)."""
    objs = {}
    n_pages = len(pages)
    kids = []
    nxt = 3
    for img, dpi, enc, q in pages:
        pid, cid, iid = nxt, nxt + 1, nxt + 2
        nxt += 3
        kids.append(pid)
        h, w = img.shape[:2]
        wpt, hpt = w * 72.0 / dpi, h * 72.0 / dpi
        grey = img.ndim == 2
        if enc == "dct":
            ok, buf = cv2.imencode(
                ".jpg", img if grey else img[..., ::-1], [cv2.IMWRITE_JPEG_QUALITY, int(q)]
            )
            data, filt = bytes(buf), "/DCTDecode"
        else:
            data, filt = zlib.compress(np.ascontiguousarray(img).tobytes(), 6), "/FlateDecode"
        cs = "/DeviceGray" if grey else "/DeviceRGB"
        objs[iid] = (
            (
                f"<< /Type /XObject /Subtype /Image /Width {w} /Height {h} /ColorSpace {cs} "
                f"/BitsPerComponent 8 /Filter {filt} /Length {len(data)} >>"
            ).encode(),
            data,
        )
        content = f"q {wpt:.4f} 0 0 {hpt:.4f} 0 0 cm /Im0 Do Q".encode()
        objs[cid] = f"<< /Length {len(content)} >>".encode(), content
        objs[pid] = (
            (
                f"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {wpt:.4f} {hpt:.4f}] "
                f"/Resources << /XObject << /Im0 {iid} 0 R >> >> /Contents {cid} 0 R >>"
            ).encode(),
            None,
        )
    objs[1] = b"<< /Type /Catalog /Pages 2 0 R >>", None
    objs[2] = (
        (
            f"<< /Type /Pages /Kids [{' '.join(f'{k} 0 R' for k in kids)}] /Count {n_pages} >>"
        ).encode(),
        None,
    )
    out = bytearray(b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n")
    offs = {}
    for i in sorted(objs):
        offs[i] = len(out)
        d, stream = objs[i]
        out += f"{i} 0 obj\n".encode() + d
        if stream is not None:
            out += b"\nstream\n" + stream + b"\nendstream"
        out += b"\nendobj\n"
    xref = len(out)
    nobj = max(objs) + 1
    out += f"xref\n0 {nobj}\n0000000000 65535 f \n".encode()
    for i in range(1, nobj):
        out += f"{offs[i]:010d} 00000 n \n".encode()
    out += f"trailer\n<< /Size {nobj} /Root 1 0 R >>\nstartxref\n{xref}\n%%EOF\n".encode()
    with open(path, "wb") as fh:
        fh.write(out)


def finish(rng, page):
    """Scanner blur + noise; return float image (H,W,C) in [0,1]."""
    sig = rng.uniform(0.35, 0.9)
    img = page.img
    for c in range(page.C):
        img[..., c] = cv2.GaussianBlur(img[..., c], (0, 0), sig)
    ns = rng.uniform(0.004, 0.02)
    img += rng.normal(0, ns, img.shape).astype(np.float32)
    np.clip(img, 0, 1, out=img)
    return {"blur_px": round(float(sig), 3), "noise": round(float(ns), 4)}


def to_uint(img, bits):
    if bits == 16:
        a = np.round(img * 65535).astype(np.uint16)
    else:
        a = np.round(img * 255).astype(np.uint8)
    if a.shape[2] == 1:
        return a[..., 0]
    return a[..., ::-1].copy()  # RGB -> BGR for cv2


# ----------------------------------------------------------------------------
# sheet composition


def rotate_to_page(g, ang_deg, cx, cy):
    return affinity.translate(affinity.rotate(g, ang_deg, origin=(0, 0)), cx, cy)


def choose_angle(rng, axis):
    tilt = rng.uniform(-0.5, 0.5)
    if axis == "x":
        return float(rng.choice([0.0, 180.0]) + tilt)
    if axis == "y":
        return float(rng.choice([90.0, 270.0]) + tilt)
    return float(rng.uniform(0, 360))


def place(rng, page, ink_local, ang, placed, clearance, margin=6.0, clip_side=None):
    hull_rot = affinity.rotate(ink_local.convex_hull, ang, origin=(0, 0))
    x0, y0, x1, y1 = hull_rot.bounds
    for _ in range(400):
        if clip_side is None:
            lo_x, hi_x = margin - x0, page.W - margin - x1
            lo_y, hi_y = margin - y0, page.H - margin - y1
            if hi_x < lo_x or hi_y < lo_y:
                return None
            cx, cy = rng.uniform(lo_x, hi_x), rng.uniform(lo_y, hi_y)
        else:
            side, over = clip_side  # over: mm beyond the page edge
            cx, cy = (
                rng.uniform(margin - x0, page.W - margin - x1),
                rng.uniform(margin - y0, page.H - margin - y1),
            )
            if side == "left":
                cx = -x0 - over
            elif side == "right":
                cx = page.W - x1 + over
            elif side == "bottom":
                cy = -y0 - over
            else:
                cy = page.H - y1 + over
        h = affinity.translate(hull_rot, cx, cy)
        if all(h.distance(o) > clearance for o in placed):
            return cx, cy
    return None


def family_for(rng, cls):
    if cls == "slick":
        return "slick"
    if cls == "treaded":
        return "tread"
    if cls == "wide":
        return "wide"
    if cls == "tiny":
        return "tiny"
    return "slick" if rng.random() < 0.6 else "tread"


def build_sheet(rng, cls, sub=None, single=False, sheet=None, dpi=None, channels=None):
    """Render one sheet.  Returns (page, prints, info)."""
    sheet = sheet or str(rng.choice(list(SHEETS)))
    if dpi is None:
        dpi = int(rng.choice([150, 200, 240, 300, 400, 600], p=[0.2, 0.2, 0.1, 0.25, 0.15, 0.1]))
    if channels is None:
        channels = 3 if (rng.random() < 0.4 and dpi <= 400) else 1
    page = Page(sheet, dpi, channels)
    info = {"sheet": sheet, "dpi": dpi, "channels": channels, "class": cls}
    info.update(paper_layer(rng, page))
    if cls == "chart":
        info.update(grid_layer(rng, page))
    prints = []
    if cls == "noise_page":
        if rng.random() < 0.5:
            info.update(lighting_layer(rng, page, ["gradient"]))
        dust_layer(rng, page, None, int(rng.integers(0, 12)))
        # faint large stains
        for _ in range(int(rng.integers(0, 3))):
            c = (rng.uniform(20, page.W - 20), rng.uniform(20, page.H - 20))
            g = Point(c).buffer(rng.uniform(5, 25))
            cov, r0, c0 = page.rasterize(g, S=2)
            h, w = cov.shape
            cov = cv2.GaussianBlur(cov, (0, 0), 4 / page.p)
            page.apply(cov, r0, c0, (0.6, 0.7, 0.9), rng.uniform(0.02, 0.06))
        info.update(finish(rng, page))
        info["rolling_axis"] = "auto"
        return page, prints, info

    n = 1 if single else int(rng.integers(1, 4))
    same_tire = rng.random() < 0.7 and cls != "tiny"
    specs = []
    for k in range(n):
        if k == 0 or not same_tire:
            fam = family_for(rng, cls)
            seed_k = int(rng.integers(2**31))
            s0 = make_print(rng, fam, seed_k, True)
        else:
            s0 = make_print(rng, fam, seed_k, False)
        if s0["tread"] == "car" and (k > 0 or n > 1):
            if k == 0:
                specs.append(s0)
                break
            continue
        specs.append(s0)
    info["same_tire"] = bool(same_tire)
    if any(s["tread"] not in ("slick", "file") for s in specs) or cls in ("treaded", "wide"):
        axis = str(rng.choice(["x", "y"]))
    elif cls == "slick" or rng.random() < 0.7:
        axis = "auto"
    else:
        axis = str(rng.choice(["x", "y"]))
    info["rolling_axis"] = axis
    # big prints first
    specs.sort(key=lambda s: -s["ink"].convex_hull.area)
    clearance = 40.0 if cls in ("labels", "ruler") else 25.0
    placed = []
    inkrgb = (1.0, 1.0, 1.0) if rng.random() < 0.8 else (0.95, 0.9, 0.72)
    for i, s in enumerate(specs):
        ang = choose_angle(rng, axis)
        clip_side = None
        if cls == "clipped" and i == 0:
            hl = affinity.rotate(s["ink"].convex_hull, ang, origin=(0, 0))
            side = str(rng.choice(["left", "right", "bottom", "top"]))
            ext = (
                (hl.bounds[2] - hl.bounds[0])
                if side in ("left", "right")
                else (hl.bounds[3] - hl.bounds[1])
            )
            over = rng.uniform(0.0, 1.0) if rng.random() < 0.3 else rng.uniform(0.02, 0.3) * ext
            clip_side = (side, float(over))
        pos = place(rng, page, s["ink"], ang, placed, clearance, clip_side=clip_side)
        if pos is None:
            continue
        cx, cy = pos
        ink = rotate_to_page(s["ink"], ang, cx, cy)
        hull = ink.convex_hull
        placed.append(hull)
        hl_local = s["ink"].convex_hull
        L, W = hull_extents(hl_local, 0.0)
        pr = {
            "ink_page": ink,
            "hull_page": hull,
            "angle_deg": ang,
            "ink_rgb": inkrgb,
            "family": s["family"],
            "outline": s["outline"],
            "tread": s["tread"],
            "length_mm": L,
            "width_mm": W,
            "hull_area_mm2": hl_local.area,
            "centroid_x_mm": hull.centroid.x,
            "centroid_y_mm": hull.centroid.y,
            "expect": "measure",
            "notes": {},
        }
        if clip_side is not None:
            vis = ink.intersection(box(0, 0, page.W, page.H))
            pr["expect"] = "clipped"
            pr["notes"]["clip"] = [clip_side[0], round(clip_side[1], 2)]
            if not vis.is_empty:
                vh = vis.convex_hull
                pr["centroid_x_mm"], pr["centroid_y_mm"] = vh.centroid.x, vh.centroid.y
                pr["notes"]["visible_area_mm2"] = round(vh.area, 2)
        # alternatives for judging axis ambiguity
        if axis in ("x", "y"):
            la, wa = hull_extents(hull, 0.0 if axis == "x" else 90.0)
            pr["alt"] = ("sheet_axis", la, wa)
        else:
            pa = principal_angle(hull)
            la, wa = hull_extents(hull, pa)
            if wa > la:
                la, wa = wa, la
            pr["alt"] = ("principal", la, wa)
        if s["tread"] in ("slick", "file") and rng.random() < 0.5:
            pr["edge_fade"] = rng.uniform(0.1, 0.35)
        prints.append(pr)
        if cls == "tiny":
            pass
    for pr in prints:
        ink_layer(rng, page, pr["ink_page"], pr)

    all_hulls = [p["hull_page"] for p in prints]
    marks = []
    if cls == "labels":
        for i, pr in enumerate(prints):
            others = [h for j, h in enumerate(all_hulls) if j != i]
            for _ in range(int(rng.integers(1, 4))):
                touch = rng.random() < 0.35
                gap = rng.uniform(-0.6, 0.0) if touch else rng.uniform(1.0, 10.0)
                if rng.random() < 0.5:
                    m = make_text_mark(rng, page, pr["ink_page"], pr["hull_page"], gap, others)
                else:
                    m = make_stroke_mark(rng, page, pr["ink_page"], pr["hull_page"], gap, others)
                if m is not None:
                    marks.append(m)
                    pr["notes"].setdefault("marks", []).append(m.info)
    if cls == "ruler":
        for i, pr in enumerate(prints):
            if i > 0 and rng.random() < 0.5:
                continue
            others = [h for j, h in enumerate(all_hulls) if j != i]
            mode = "cross" if rng.random() < 0.5 else "beside"
            axis_deg = pr["angle_deg"]
            m = make_ruler(rng, page, pr["ink_page"], pr["hull_page"], axis_deg, mode, others)
            if m is not None:
                marks.append(m)
                pr["notes"].setdefault("marks", []).append(m.info)
    if cls == "specks":
        for pr in prints:
            pr["notes"].update(specks_and_halo(rng, page, pr["ink_page"], pr["hull_page"], pr))
    for m in marks:
        page.apply(m.cov, m.r0, m.c0, m.rgb, m.dark)
        for cov2, rr, cc in getattr(m, "extra", []):
            page.apply(cov2, rr, cc, m.rgb, m.dark)
    dust_layer(rng, page, unary_union(all_hulls) if all_hulls else None, int(rng.integers(0, 8)))
    if cls == "lighting":
        effs = [e for e in ["gradient", "shadow", "vignette"] if rng.random() < 0.5] or [
            str(rng.choice(["gradient", "shadow", "vignette"]))
        ]
        info.update(lighting_layer(rng, page, effs))
        info["lighting"] = effs
    info.update(finish(rng, page))
    return page, prints, info


def truth_rows(fname, page_no, cls, prints, expect_override=None):
    rows = []
    for k, pr in enumerate(prints):
        exp = expect_override or pr["expect"]
        alt = pr.get("alt", ("", float("nan"), float("nan")))
        rows.append(
            {
                "file": fname,
                "page": page_no,
                "print": k,
                "kind": cls,
                "expect": exp,
                "length_mm": f"{pr['length_mm']:.4f}",
                "width_mm": f"{pr['width_mm']:.4f}",
                "hull_area_mm2": f"{pr['hull_area_mm2']:.3f}",
                "centroid_x_mm": f"{pr['centroid_x_mm']:.3f}",
                "centroid_y_mm": f"{pr['centroid_y_mm']:.3f}",
                "family": pr["family"],
                "outline": pr["outline"],
                "tread": pr["tread"],
                "angle_deg": f"{pr['angle_deg']:.3f}",
                "alt_kind": alt[0],
                "length_alt_mm": f"{alt[1]:.4f}",
                "width_alt_mm": f"{alt[2]:.4f}",
                "ink_dark": json.dumps(pr.get("ink_dark")),
                "notes": json.dumps(pr["notes"]),
            }
        )
    return rows


def manifest_row(fname, dpi, axis, rng):
    return {
        "file": fname,
        "page": "",
        "tire": str(
            rng.choice(
                [
                    "GP5000 28-622",
                    "Pro One 25-622",
                    "Marathon 40-622",
                    "Rock Razor 57-584",
                    "car 205/55R16",
                ]
            )
        ),
        "pressure_bar": f"{rng.uniform(2, 8):.1f}",
        "load_N": f"{rng.integers(20, 90) * 10}",
        "surface": "paper",
        "dpi": "" if dpi is None else str(dpi),
        "rolling_axis": axis,
    }


def save_image(rng, path_noext, page, img, dpi_meta):
    fmt = str(rng.choice(["png", "jpg", "tif"], p=[0.45, 0.25, 0.3]))
    q = None
    bits = 16 if (fmt == "tif" and rng.random() < 0.3) else 8
    arr = to_uint(img, bits)
    if fmt == "png":
        path = path_noext + ".png"
        with open(path, "wb") as fh:
            fh.write(png_bytes(arr, dpi_meta))
    elif fmt == "jpg":
        q = int(rng.integers(70, 96))
        path = path_noext + ".jpg"
        with open(path, "wb") as fh:
            fh.write(jpeg_bytes(arr, dpi_meta, q))
    else:
        path = path_noext + ".tif"
        tiff_write(path, arr, dpi_meta)
    return path, {"format": fmt, "bits": bits, "jpeg_q": q, "dpi_meta": dpi_meta}


def make_set(out_dir, n_files, seed):
    os.makedirs(out_dir, exist_ok=True)
    master = np.random.default_rng(seed)
    order = []
    while len(order) < n_files:
        order += list(master.permutation(CLASSES))
    order = order[:n_files]
    truth, manifest, infos = [], [], []
    dpi_k = 0
    for i, cls in enumerate(order):
        rng = np.random.default_rng([seed, i])
        stem = f"s{seed}_{i:03d}_{cls}"
        if cls == "pdf":
            npg = int(rng.integers(2, 5))
            dpi = int(rng.choice([150, 200, 300, 400]))
            sheet = str(rng.choice(list(SHEETS)))
            ch = 3 if rng.random() < 0.3 else 1
            enc = "dct" if rng.random() < 0.5 else "flate"
            q = int(rng.integers(75, 96))
            pages = []
            axes = set()
            for pg in range(npg):
                page, prints, info = build_sheet(
                    rng, "pdf", single=True, sheet=sheet, dpi=dpi, channels=ch
                )
                axes.add(info["rolling_axis"])
                arr = np.round(page.img * 255).astype(np.uint8)
                arr = arr[..., 0] if ch == 1 else arr
                pages.append((arr, dpi, enc, q))
                truth += truth_rows(stem + ".pdf", pg, cls, prints)
                info.update({"file": stem + ".pdf", "page": pg, "pdf_enc": enc})
                infos.append(info)
                del page
            write_pdf(os.path.join(out_dir, stem + ".pdf"), pages)
            give_dpi = rng.random() < 0.5
            if len(axes) == 1:
                manifest.append(
                    manifest_row(stem + ".pdf", dpi if give_dpi else None, axes.pop(), rng)
                )
            else:
                for pg, inf in enumerate(infos[-npg:]):
                    mr = manifest_row(
                        stem + ".pdf", dpi if give_dpi else None, inf["rolling_axis"], rng
                    )
                    mr["page"] = str(pg)
                    manifest.append(mr)
            continue
        sub = None
        if cls == "dpi":
            sub = DPI_VARIANTS[dpi_k % len(DPI_VARIANTS)]
            dpi_k += 1
        page, prints, info = build_sheet(rng, cls, sub=sub)
        dpi = page.dpi
        meta, man_dpi, override = dpi, None, None
        if cls == "dpi":
            info["dpi_variant"] = sub
            if sub.startswith("untrusted"):
                meta = int(rng.choice([72, 96]))
            else:
                meta = None
            if sub.endswith("+manifest"):
                man_dpi = dpi
            else:
                override = "error:ScaleUntrusted" if sub == "untrusted" else "error:ScaleMissing"
        img = page.img
        path, finfo = save_image(rng, os.path.join(out_dir, stem), page, img, meta)
        fname = os.path.basename(path)
        info.update(finfo)
        info["file"] = fname
        infos.append(info)
        if cls == "noise_page":
            truth.append(
                {
                    "file": fname,
                    "page": 0,
                    "print": "",
                    "kind": cls,
                    "expect": "error:NoInk",
                    "length_mm": "",
                    "width_mm": "",
                    "hull_area_mm2": "",
                    "centroid_x_mm": "",
                    "centroid_y_mm": "",
                    "family": "",
                    "outline": "",
                    "tread": "",
                    "angle_deg": "",
                    "alt_kind": "",
                    "length_alt_mm": "",
                    "width_alt_mm": "",
                    "ink_dark": "",
                    "notes": "{}",
                }
            )
        else:
            truth += truth_rows(fname, 0, cls, prints, override)
        manifest.append(manifest_row(fname, man_dpi, info["rolling_axis"], rng))
        del page, img
    mpath = os.path.join(out_dir, "manifest.csv")
    tpath = os.path.join(out_dir, "truth.csv")
    with open(mpath, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(manifest[0]))
        w.writeheader()
        w.writerows(manifest)
    with open(tpath, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(truth[0]))
        w.writeheader()
        w.writerows(truth)
    with open(os.path.join(out_dir, "sheets.json"), "w") as fh:
        json.dump(infos, fh, indent=1, default=str)
    return mpath, tpath


def main():
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("out_dir")
    ap.add_argument("--files", type=int, default=120)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    m, t = make_set(a.out_dir, a.files, a.seed)
    print(m)
    print(t)


if __name__ == "__main__":
    main()
