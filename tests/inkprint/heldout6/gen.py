#!/usr/bin/env python3
"""Held-out generator 6: scanned tire ink-print sheets with exact truth.

    python gen.py OUT_DIR --files 120 --seed N

Writes OUT_DIR/scan_XXX.{png,jpg,tif,pdf}, manifest.csv, truth.csv and sheets.json
for tests/inkprint/independent/score.py (`score(d)`).

Written from the user documentation and the scorer only (not from the tool).

Geometry: every print is a shapely (Multi)Polygon in millimetres, built in a local
frame (X = rolling direction, Y = across), turned and placed on the sheet.  Sheet
coordinates: x right, y up from the sheet's bottom-left corner (mm), as the
README's `inkprint.coords` states.  Truth is computed from that geometry only:
convex hull of all printed pieces; length/width = hull extents along/across the
print's own rolling direction; hull area; hull centroid.  Clipped prints: the
part on the sheet.  Rendering: exact area coverage (exact along x, 12 samples per
pixel along y), then symmetric blur, mottle, paper texture, noise, JPEG.
"""

import argparse
import csv
import json
import math
import os
import struct
import sys
import time
import zlib

import cv2
import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import LineString, MultiPolygon, Point, Polygon, box
from shapely.geometry.polygon import orient
from shapely.ops import unary_union

PAPERS = {"A4": (210.0, 297.0), "letter": (215.9, 279.4)}
# error class expected for a 72/96 dpi file without a manifest dpi (per the brief;
# docs/inkprint.md still names ScaleMissing for this case)
UNTRUSTED = "ScaleUntrusted"
KINDS = [
    "slick",
    "treaded",
    "car",
    "wide",
    "label",
    "ruler",
    "chart",
    "light",
    "tilt",
    "clipped",
    "tiny",
    "dust",
    "noise",
    "dpi_trap",
]
SUB = 12  # sub-rows per pixel in the coverage rasterizer
LUM = np.array([0.299, 0.587, 0.114])
TIRES = [
    "GP5000 28",
    "G-One 40-622",
    "Rocket Ron 2.25",
    "Nobby Nic",
    "Pro One 25",
    "Marathon 37-622",
    "205/55 R16",
    "EcoContact 195/65",
    "Minion DHF 2.5",
    "P Zero 225/45",
    "Hutchinson Fusion",
    "Vittoria Corsa",
    "Kenda K-rad",
    "Maxxis Ardent",
    "Michelin Power",
    "Rene Herse 38",
    "Gravelking SK",
]


# ----------------------------------------------------------------------------- geometry
def polys(g):
    if g is None or g.is_empty:
        return []
    if g.geom_type == "Polygon":
        return [g]
    out = []
    for s in getattr(g, "geoms", []):
        out += polys(s)
    return out


def clean(g, min_area, min_thick):
    """Drop pieces too small or too thin to print (they are then not on the sheet)."""
    keep = []
    for p in polys(g):
        if p.area < min_area:
            continue
        if p.buffer(-min_thick / 2, quad_segs=4).is_empty:
            continue
        keep.append(p)
    if not keep:
        return None
    return MultiPolygon(keep) if len(keep) > 1 else keep[0]


def outline(shape, L, W, rng):
    """Outline polygon, X along rolling (length L), Y across (width W)."""
    t = np.linspace(0, 2 * np.pi, 1440, endpoint=False)
    c, s = np.cos(t), np.sin(t)
    par = {}
    if shape == "ellipse":
        pts = np.c_[L / 2 * c, W / 2 * s]
    elif shape in ("superellipse", "rounded_rect"):
        n = rng.uniform(2.3, 4.0) if shape == "superellipse" else rng.uniform(4.0, 8.0)
        par["n"] = round(float(n), 3)
        pts = np.c_[
            L / 2 * np.sign(c) * np.abs(c) ** (2 / n), W / 2 * np.sign(s) * np.abs(s) ** (2 / n)
        ]
    elif shape == "lens":
        cc = L * L / (4 * W) - W / 4  # circles centred at (0, +-cc), radius R
        R = cc + W / 2
        lens = (
            Point(0, cc)
            .buffer(R, quad_segs=512)
            .intersection(Point(0, -cc).buffer(R, quad_segs=512))
        )
        rt = rng.uniform(0.08, 0.25) * W
        par["tip_round_mm"] = round(float(rt), 3)
        return lens.buffer(-rt, quad_segs=32).buffer(rt, quad_segs=32), par
    else:
        raise ValueError(shape)
    return Polygon(pts), par


def strips_x(ys, g, L):
    return [box(-L, y - g / 2, L, y + g / 2) for y in ys]


def bar(p0, p1, w):
    return LineString([p0, p1]).buffer(w / 2, cap_style="flat")


def tread_ribs(O, L, W, rng, small=False):
    n = int(rng.integers(1, 3)) if small else int(rng.integers(1, 5))
    g = rng.uniform(0.35, 0.8) if small else rng.uniform(0.8, 2.6)
    ys = ((np.arange(n) + 1) / (n + 1) - 0.5) * W + rng.uniform(-0.03, 0.03, n) * W
    return O.difference(unary_union(strips_x(ys, g, L))), {"grooves": n, "groove_mm": round(g, 3)}


def tread_herringbone(O, L, W, rng):
    c = rng.uniform(0.06, 0.25) * W
    g, p = rng.uniform(0.7, 1.8), rng.uniform(3.0, 7.0)
    beta = math.radians(rng.uniform(30, 60))
    cuts = []
    for sg in (1, -1):
        ph = rng.uniform(0, p)
        for xk in np.arange(-L / 2 - W - p + ph, L / 2 + W, p):
            u = np.array([math.cos(beta), sg * math.sin(beta)])
            p0 = np.array([xk, sg * c])
            cuts.append(bar(p0, p0 + u * (W / math.sin(beta)), g))
    return O.difference(unary_union(cuts)), {
        "band_mm": round(2 * c, 2),
        "groove_mm": round(g, 2),
        "pitch_mm": round(p, 2),
    }


def tread_chevron(O, L, W, rng):
    w, gap = rng.uniform(2.0, 4.5), rng.uniform(2.0, 5.0)
    p = w + gap
    a = math.radians(rng.uniform(30, 60))
    d = (W / 2 + 3) / math.tan(a)
    vs = [
        LineString([(xk - d, -(W / 2 + 3)), (xk, 0), (xk - d, W / 2 + 3)]).buffer(
            w / 2, cap_style="flat", join_style="mitre"
        )
        for xk in np.arange(-L / 2 - p, L / 2 + d + p, p)
    ]
    shape = unary_union(vs)
    rib = rng.random() < 0.4
    if rib:
        r = rng.uniform(1.0, 3.0)
        shape = shape.union(box(-L, -r, L, r))
    return O.intersection(shape), {
        "bar_mm": round(w, 2),
        "gap_mm": round(gap, 2),
        "centre_rib": rib,
    }


def tread_knobby(O, L, W, rng):
    kx, ky = rng.uniform(3.5, 7.5), rng.uniform(3.5, 7.5)
    gx, gy = rng.uniform(2.5, 6.0), rng.uniform(2.5, 5.5)
    px, py = kx + gx, ky + gy
    stagger = rng.random() < 0.7
    turn = rng.uniform(5, 15) if rng.random() < 0.3 else 0.0
    sh = rng.uniform(1.0, 1.4)
    ph = rng.uniform(0, px)
    knobs = []
    for i, x in enumerate(np.arange(-L / 2 - px + ph, L / 2 + px, px)):
        off = py / 2 if (stagger and i % 2) else 0.0
        for y in np.arange(-W / 2 - py, W / 2 + py, py) + off:
            yy = y
            a, b = kx, ky
            if abs(yy) > 0.55 * W / 2:
                b = ky * sh
            k = box(x - a / 2, yy - b / 2, x + a / 2, yy + b / 2)
            if turn:
                k = affinity.rotate(k, turn * np.sign(yy or 1), origin="centroid")
            knobs.append(k)
    return O.intersection(unary_union(knobs)), {
        "knob_mm": [round(kx, 2), round(ky, 2)],
        "gap_mm": [round(gx, 2), round(gy, 2)],
        "stagger": stagger,
        "knob_turn_deg": round(turn, 1),
    }


def tread_siped(O, L, W, rng):
    bx, by = rng.uniform(5, 10), rng.uniform(5, 10)
    gx, gy = rng.uniform(2.0, 3.5), rng.uniform(2.0, 3.5)
    sw, ns = rng.uniform(0.4, 0.8), int(rng.integers(1, 4))
    closed = rng.random() < 0.5
    px, py = bx + gx, by + gy
    blocks = []
    ph = rng.uniform(0, px)
    for i, x in enumerate(np.arange(-L / 2 - px + ph, L / 2 + px, px)):
        off = py / 2 if i % 2 else 0.0
        for j, y in enumerate(np.arange(-W / 2 - py, W / 2 + py, py) + off):
            b = box(x - bx / 2, y - by / 2, x + bx / 2, y + by / 2)
            cuts = []
            for m in range(ns):
                xs = x - bx / 2 + bx * (m + 1) / (ns + 1)
                if closed:
                    y0, y1 = y - 0.3 * by, y + 0.3 * by
                elif j % 2:
                    y0, y1 = y - by, y + 0.25 * by
                else:
                    y0, y1 = y - 0.25 * by, y + by
                cuts.append(box(xs - sw / 2, y0, xs + sw / 2, y1))
            blocks.append(b.difference(unary_union(cuts)))
    return O.intersection(unary_union(blocks)), {
        "block_mm": [round(bx, 2), round(by, 2)],
        "sipe_mm": round(sw, 2),
        "sipes": ns,
        "closed": closed,
    }


def diamond_cells(bounds, p, g, theta):
    """Rhombic cells between two families of grooves (width g, spacing p) at +-theta."""
    n1 = np.array([-math.sin(theta), math.cos(theta)])
    n2 = np.array([math.sin(theta), math.cos(theta)])
    M = np.array([n1, n2])
    Mi = np.linalg.inv(M)
    x0, y0, x1, y1 = bounds
    corners = np.array([[x0, y0], [x0, y1], [x1, y0], [x1, y1]])
    k1 = corners @ n1 / p
    k2 = corners @ n2 / p
    ks = np.arange(math.floor(k1.min()) - 1, math.ceil(k1.max()) + 1)
    ms = np.arange(math.floor(k2.min()) - 1, math.ceil(k2.max()) + 1)
    K, Mm = np.meshgrid(ks, ms, indexing="ij")
    K, Mm = K.ravel(), Mm.ravel()
    lo1, hi1 = K * p + g / 2, (K + 1) * p - g / 2
    lo2, hi2 = Mm * p + g / 2, (Mm + 1) * p - g / 2
    quad = np.stack([np.c_[lo1, lo2], np.c_[hi1, lo2], np.c_[hi1, hi2], np.c_[lo1, hi2]], axis=1)
    pts = quad @ Mi.T
    return shapely.polygons(pts)


def tread_file(O, L, W, rng, full=False, small=False):
    g = rng.uniform(0.2, 0.35) if small else rng.uniform(0.3, 0.6)
    p = rng.uniform(0.8, 1.5) if small else rng.uniform(1.3, 2.5)
    th = math.radians(rng.uniform(25, 60))
    cells = diamond_cells(O.buffer(p).bounds, p, g, th)
    par = {
        "groove_mm": round(g, 3),
        "pitch_mm": round(p, 3),
        "angle_deg": round(math.degrees(th), 1),
    }
    if full:
        return O.intersection(MultiPolygon(list(cells))), par
    c = rng.uniform(0.15, 0.35) * W
    par["slick_centre_mm"] = round(2 * c, 2)
    sh = box(-L, -W, L, -c).union(box(-L, c, L, W))
    cells = shapely.intersection(cells, sh)
    cells = [q for q in cells if not q.is_empty]
    return unary_union(
        [O.intersection(box(-L, -c, L, c))] + list(shapely.intersection(cells, O))
    ), par


def tread_dots(O, L, W, rng, small=False):
    r = rng.uniform(0.35, 0.6) if small else rng.uniform(0.6, 1.5)
    gap = rng.uniform(0.35, 0.7) if small else rng.uniform(0.8, 2.0)
    s = 2 * r + gap
    x0, y0, x1, y1 = O.bounds
    pts = []
    for j, y in enumerate(np.arange(y0 - s, y1 + s, s * math.sqrt(3) / 2)):
        for x in np.arange(x0 - s, x1 + s, s) + (s / 2 if j % 2 else 0):
            pts.append((x, y))
    discs = shapely.buffer(shapely.points(np.array(pts)), r, quad_segs=8)
    return O.intersection(MultiPolygon(list(discs))), {
        "dot_mm": round(2 * r, 2),
        "gap_mm": round(gap, 2),
    }


def tread_pores(O, L, W, rng):
    r, s = rng.uniform(0.3, 0.7), rng.uniform(2.5, 4.0)
    x0, y0, x1, y1 = O.bounds
    pts = [
        (x, y)
        for j, y in enumerate(np.arange(y0, y1, s * 0.87))
        for x in np.arange(x0, x1, s) + (s / 2 if j % 2 else 0)
    ]
    holes = shapely.buffer(shapely.points(np.array(pts)), r, quad_segs=8)
    return O.difference(MultiPolygon(list(holes))), {
        "pore_mm": round(2 * r, 2),
        "pitch_mm": round(s, 2),
    }


def tread_car(O, L, W, rng):
    n = int(rng.integers(2, 5))
    g = rng.uniform(6.0, 13.0)
    span = rng.uniform(0.45, 0.62) * W / 2
    ys = np.linspace(-span, span, n)
    cuts = strips_x(ys, g, L)
    ysh = span + g / 2 + rng.uniform(0, 6)
    lw, lp = rng.uniform(3.0, 6.0), rng.uniform(18.0, 30.0)
    slant = math.radians(rng.uniform(-15, 15))
    for sg in (1, -1):
        ph = rng.uniform(0, lp)
        for xk in np.arange(-L / 2 - lp + ph, L / 2 + lp, lp):
            p0 = (xk, sg * (ysh - 1))
            p1 = (xk + math.tan(slant) * W / 2, sg * (W / 2 + 6))
            cuts.append(bar(p0, p1, lw))
    sipes = rng.random() < 0.6
    if sipes:
        sw, sp = rng.uniform(0.6, 1.0), rng.uniform(8.0, 15.0)
        for a, b in zip(ys[:-1], ys[1:]):
            for xk in np.arange(-L / 2, L / 2, sp):
                cuts.append(
                    bar((xk, a + g / 2 - 0.5), (xk + 2.0, a + g / 2 + 0.6 * (b - a - g)), sw)
                )
    return O.difference(unary_union(cuts)), {
        "grooves": n,
        "groove_mm": round(g, 2),
        "lateral_mm": round(lw, 2),
        "lateral_pitch_mm": round(lp, 1),
        "sipes": sipes,
    }


TREADS = {
    "slick": lambda O, L, W, rng, small=False: (O, {}),
    "ribs": tread_ribs,
    "herringbone": lambda O, L, W, rng, small=False: tread_herringbone(O, L, W, rng),
    "chevron": lambda O, L, W, rng, small=False: tread_chevron(O, L, W, rng),
    "knobby": lambda O, L, W, rng, small=False: tread_knobby(O, L, W, rng),
    "siped": lambda O, L, W, rng, small=False: tread_siped(O, L, W, rng),
    "file": lambda O, L, W, rng, small=False: tread_file(O, L, W, rng, False, small),
    "knurl": lambda O, L, W, rng, small=False: tread_file(O, L, W, rng, True, small),
    "dots": tread_dots,
    "pores": lambda O, L, W, rng, small=False: tread_pores(O, L, W, rng),
    "car": lambda O, L, W, rng, small=False: tread_car(O, L, W, rng),
}


def pick(rng, items, w=None):
    w = np.asarray(w if w is not None else [1] * len(items), float)
    return items[int(rng.choice(len(items), p=w / w.sum()))]


def make_print(rng, family, mmpp, tread=None):
    """A print in its local frame: dict with geom (X = rolling direction)."""
    if family == "road":
        L = rng.uniform(40, 130)
        W = min(rng.uniform(12, 45), L / 1.6)
        shape = pick(rng, ["lens", "ellipse", "superellipse"])
        tread = tread or pick(
            rng,
            ["slick", "ribs", "herringbone", "file", "knurl", "dots", "pores"],
            [3, 2, 1.5, 1.5, 1, 1, 1],
        )
    elif family == "mtb":
        L = rng.uniform(50, 110)
        W = min(rng.uniform(35, 70), L / 1.25)
        shape = pick(rng, ["ellipse", "superellipse"])
        tread = tread or pick(
            rng, ["knobby", "chevron", "siped", "herringbone", "dots"], [4, 2, 2, 1, 1]
        )
    elif family == "car":
        L = rng.uniform(100, 160)
        W = rng.uniform(95, 185)
        shape = "rounded_rect"
        tread = "car"
    elif family == "wide":
        L = rng.uniform(40, 95)
        W = min(L * rng.uniform(1.1, 1.6), 150)
        shape = pick(rng, ["ellipse", "superellipse", "rounded_rect"])
        tread = tread or pick(rng, ["slick", "knobby", "siped", "ribs", "car"], [2, 2, 1, 1, 1])
    elif family == "tiny":
        L = rng.uniform(10, 25)
        W = min(rng.uniform(3, 8), L / 2.0)
        shape = pick(rng, ["lens", "ellipse", "superellipse"])
        tread = tread or pick(rng, ["slick", "ribs", "knurl", "file", "dots"], [4, 2, 1.5, 1.5, 1])
    else:
        raise ValueError(family)
    O, opar = outline(shape, L, W, rng)
    small = family == "tiny"
    g, tpar = TREADS[tread](O, L, W, rng, small=small)
    g = clean(
        g, max(0.15 if small else 0.3, 6 * mmpp * mmpp), max(0.15 if small else 0.25, 1.5 * mmpp)
    )
    if g is None or g.convex_hull.area < 0.5 * O.area:
        tread, tpar, g = "slick", {"fallback": True}, O
    return {
        "family": family,
        "outline": shape,
        "tread": tread,
        "L_nom": L,
        "W_nom": W,
        "local": g,
        "params": {**opar, **tpar},
    }


# ----------------------------------------------------------------------------- truth
def hull_pts(h):
    return np.asarray(h.exterior.coords)[:-1]


def extents(pts, ang_deg):
    a = math.radians(ang_deg)
    u = np.array([math.cos(a), math.sin(a)])
    v = np.array([-math.sin(a), math.cos(a)])
    return float(np.ptp(pts @ u)), float(np.ptp(pts @ v))


def principal_angle(h):
    """Major principal axis (deg) of the convex hull polygon's area moments."""
    p = hull_pts(orient(h, 1.0))
    p = p - p.mean(axis=0)
    x, y = p[:, 0], p[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cr = x * yn - xn * y
    A = cr.sum() / 2
    cx = ((x + xn) * cr).sum() / (6 * A)
    cy = ((y + yn) * cr).sum() / (6 * A)
    Ixx = ((y * y + y * yn + yn * yn) * cr).sum() / 12 - A * cy * cy  # int y^2
    Iyy = ((x * x + x * xn + xn * xn) * cr).sum() / 12 - A * cx * cx  # int x^2
    Ixy = ((x * yn + 2 * x * y + 2 * xn * yn + xn * y) * cr).sum() / 24 - A * cx * cy
    return math.degrees(0.5 * math.atan2(2 * Ixy, Iyy - Ixx))


def truth_of(geom, theta, axis):
    h = geom.convex_hull
    pts = hull_pts(h)
    L, W = extents(pts, theta)
    if axis in ("x", "y"):
        La, Wa = extents(pts, 0.0 if axis == "x" else 90.0)
        alt = "sheet_axis"
    else:
        pa = principal_angle(h)
        La, Wa = extents(pts, pa)
        if La < Wa:
            La, Wa = Wa, La
        alt = "principal_axis"
    c = h.centroid
    return {
        "length_mm": L,
        "width_mm": W,
        "hull_area_mm2": h.area,
        "centroid_x_mm": c.x,
        "centroid_y_mm": c.y,
        "alt_kind": alt,
        "length_alt_mm": La,
        "width_alt_mm": Wa,
    }


# ----------------------------------------------------------------------------- rasterizer
def rings_of(geom):
    out = []
    for p in polys(geom):
        p = orient(p, 1.0)
        out.append(np.asarray(p.exterior.coords))
        out += [np.asarray(r.coords) for r in p.interiors]
    return out


def coverage(rings, x0, y0, w, h, S=SUB):
    """Area coverage of oriented rings (pixel coords col,row) on the window
    [x0, x0+w) x [y0, y0+h): exact along x, S sample rows per pixel along y."""
    if not rings or w <= 0 or h <= 0:
        return np.zeros((max(h, 0), max(w, 0)), np.float32)
    E = np.vstack([np.hstack([r[:-1], r[1:]]) for r in rings]).astype(np.float64)
    xa, ya, xb, yb = E[:, 0] - x0, E[:, 1] - y0, E[:, 2] - x0, E[:, 3] - y0
    m = ya != yb
    xa, ya, xb, yb = xa[m], ya[m], xb[m], yb[m]
    sg = np.where(yb > ya, 1.0, -1.0)
    j0 = np.clip(np.ceil(np.minimum(ya, yb) * S - 0.5), 0, h * S).astype(np.int64)
    j1 = np.clip(np.ceil(np.maximum(ya, yb) * S - 0.5), 0, h * S).astype(np.int64)
    cnt = j1 - j0
    W2 = w + 1
    D = np.zeros(h * W2)
    P = np.zeros(h * w)
    csum = np.cumsum(cnt)
    CH = 3_000_000
    start = 0
    while start < len(cnt):
        base = csum[start - 1] if start else 0
        end = max(int(np.searchsorted(csum, base + CH, side="right")), start + 1)
        c = cnt[start:end]
        tot = int(c.sum())
        if tot:
            idx = np.repeat(np.arange(start, end), c)
            offs = np.repeat(np.cumsum(c) - c, c)
            j = j0[idx] + (np.arange(tot) - offs)
            yc = (j + 0.5) / S
            x = xa[idx] + (yc - ya[idx]) * (xb[idx] - xa[idx]) / (yb[idx] - ya[idx])
            wt = sg[idx] / S
            r = j // S
            k = np.floor(x).astype(np.int64)
            D += np.bincount(r * W2 + np.clip(k + 1, 0, w), weights=wt, minlength=h * W2)
            ib = (k >= 0) & (k < w)
            P += np.bincount(r[ib] * w + k[ib], weights=(wt * (k + 1 - x))[ib], minlength=h * w)
        start = end
    cov = np.cumsum(D.reshape(h, W2), axis=1)[:, :w] + P.reshape(h, w)
    return np.clip(np.abs(cov), 0, 1).astype(np.float32)


class Canvas:
    """Reflectance image (float32, 1 or 3 channels) of a sheet; geometry in sheet mm."""

    def __init__(self, wpx, hpx, mmpp, ch, paper_rgb):
        self.w, self.h, self.mmpp, self.ch = wpx, hpx, mmpp, ch
        self.Hmm = hpx * mmpp
        col = np.asarray(paper_rgb, np.float32)
        if ch == 1:
            col = np.array([float(LUM @ col)], np.float32)
        self.img = np.empty((hpx, wpx, ch), np.float32)
        self.img[:] = col

    def absorb(self, rgb):
        a = np.asarray(rgb, np.float32)
        return np.array([float(LUM @ a)], np.float32) if self.ch == 1 else a

    def to_px(self, pts):
        pts = np.asarray(pts, float)
        return np.c_[pts[:, 0] / self.mmpp, (self.Hmm - pts[:, 1]) / self.mmpp]

    def window(self, geom, pad=2):
        x0, y0, x1, y1 = geom.bounds
        c0 = max(int(math.floor(x0 / self.mmpp)) - pad, 0)
        c1 = min(int(math.ceil(x1 / self.mmpp)) + pad, self.w)
        r0 = max(int(math.floor((self.Hmm - y1) / self.mmpp)) - pad, 0)
        r1 = min(int(math.ceil((self.Hmm - y0) / self.mmpp)) + pad, self.h)
        return c0, r0, c1, r1

    def stamp(self, geom, absorb_rgb, mottle=None, rng=None):
        """Multiply the sheet by (1 - coverage * absorption [* mottle])."""
        if geom is None or geom.is_empty:
            return
        c0, r0, c1, r1 = self.window(geom)
        if c1 <= c0 or r1 <= r0:
            return
        cov = coverage([self.to_px(r) for r in rings_of(geom)], c0, r0, c1 - c0, r1 - r0)
        if mottle:
            cov *= mottle_field(rng, r1 - r0, c1 - c0, self.mmpp, *mottle)
        self.mul(cov, c0, r0, absorb_rgb)

    def mul(self, cov, c0, r0, absorb_rgb):
        a = self.absorb(absorb_rgb)
        h, w = cov.shape
        reg = self.img[r0 : r0 + h, c0 : c0 + w]
        reg *= 1.0 - cov[:, :, None] * a[None, None, :]


def smooth_noise(rng, h, w, cell_px, lo=0.0, hi=1.0):
    gh, gw = max(int(h / cell_px) + 2, 2), max(int(w / cell_px) + 2, 2)
    g = rng.uniform(lo, hi, (gh, gw)).astype(np.float32)
    return cv2.resize(g, (w, h), interpolation=cv2.INTER_CUBIC)


def mottle_field(rng, h, w, mmpp, amp, cell_mm):
    f = smooth_noise(rng, h, w, max(cell_mm / mmpp, 2.0))
    return (1.0 - amp * np.clip(f, 0, 1)).astype(np.float32)


# ----------------------------------------------------------------------------- text
FONTS = [
    cv2.FONT_HERSHEY_SIMPLEX,
    cv2.FONT_HERSHEY_PLAIN,
    cv2.FONT_HERSHEY_DUPLEX,
    cv2.FONT_HERSHEY_COMPLEX,
    cv2.FONT_HERSHEY_TRIPLEX,
    cv2.FONT_HERSHEY_SCRIPT_SIMPLEX,
    cv2.FONT_HERSHEY_SCRIPT_COMPLEX,
]


def text_size_mm(text, font, h_mm, stroke_mm):
    """Box (w, h) in mm of text whose cap height is h_mm."""
    (tw, th), base = cv2.getTextSize(text, font, 1.0, 1)
    s = h_mm / th
    return tw * s + stroke_mm, (th + base) * s + stroke_mm


def draw_text(cv, text, font, h_mm, stroke_mm, centre, angle_deg, absorb_rgb):
    """Render text (cap height h_mm, stroke width stroke_mm) centred at centre (mm),
    turned angle_deg counter-clockwise, multiplied onto the sheet."""
    R = 2.0 / cv.mmpp  # canvas px per mm (2x the sheet)
    (tw1, th1), _ = cv2.getTextSize(text, font, 1.0, 1)
    thick = max(1, int(round(stroke_mm * R)))
    scale = h_mm * R / th1
    (tw, th), base = cv2.getTextSize(text, font, scale, thick)
    pad = thick + 4
    cw, chh = tw + 2 * pad, th + base + 2 * pad
    can = np.zeros((chh, cw), np.uint8)
    cv2.putText(can, text, (pad, pad + th), font, scale, 255, thick, cv2.LINE_AA)
    can = cv2.resize(can, (max(cw // 2, 1), max(chh // 2, 1)), interpolation=cv2.INTER_AREA)
    ch2, cw2 = can.shape
    a = math.radians(angle_deg)
    # canvas px (u, v) -> local mm (u*mmpp - cw2*mmpp/2, -(v*mmpp - ch2*mmpp/2)) -> turn -> centre
    # -> sheet px (x/mmpp, (Hmm - y)/mmpp)
    ca, sa = math.cos(a), math.sin(a)
    cx_px, cy_px = centre[0] / cv.mmpp, (cv.Hmm - centre[1]) / cv.mmpp
    # in pixel units with y down: rotation by -a
    M = np.array([[ca, sa, 0.0], [-sa, ca, 0.0]])
    M[:, 2] = np.array([cx_px, cy_px]) - M[:, :2] @ np.array([cw2 / 2, ch2 / 2])
    half = 0.5 * math.hypot(cw2, ch2) + 2
    c0, c1 = max(int(cx_px - half), 0), min(int(cx_px + half) + 1, cv.w)
    r0, r1 = max(int(cy_px - half), 0), min(int(cy_px + half) + 1, cv.h)
    if c1 <= c0 or r1 <= r0:
        return
    M[:, 2] -= [c0, r0]
    cov = cv2.warpAffine(
        can.astype(np.float32) / 255.0, M, (c1 - c0, r1 - r0), flags=cv2.INTER_LINEAR
    )
    cv.mul(cov, c0, r0, absorb_rgb)


def text_box(centre, w, h, angle):
    return affinity.rotate(
        box(centre[0] - w / 2, centre[1] - h / 2, centre[0] + w / 2, centre[1] + h / 2),
        angle,
        origin=tuple(centre),
    )


# ----------------------------------------------------------------------------- marks
PENS = {
    "black": (0.85, 0.85, 0.82),
    "blue": (0.78, 0.62, 0.12),
    "red": (0.12, 0.72, 0.66),
    "green": (0.62, 0.25, 0.62),
    "pencil": (0.42, 0.42, 0.40),
}


def label_text(rng):
    t = rng.integers(0, 8)
    p = rng.uniform(1.2, 7.5)
    if t == 0:
        return f"p={p:.1f} bar"
    if t == 1:
        return f"F={int(rng.integers(200, 1200))}N"
    if t == 2:
        return f"{int(rng.integers(20, 110))} psi"
    if t == 3:
        return pick(rng, TIRES)
    if t == 4:
        return f"{pick(rng, TIRES)} {p:.1f}bar"
    if t == 5:
        return f"{int(rng.integers(25, 95))} kg"
    if t == 6:
        return f"run {int(rng.integers(1, 40))}"
    return f"{p:.1f} bar {int(rng.integers(200, 900))} N"


def place_beside(rng, target, w, h, angle, gap, obstacles, sheet, tries=80):
    """Centre of a w x h box turned `angle` beside `target` at distance `gap`
    (negative: overlapping its edge by -gap), clear of obstacles. None if none fits."""
    c = target.centroid
    inner = sheet.buffer(-3.0)
    for _ in range(tries):
        phi = rng.uniform(0, 2 * math.pi)
        d = np.array([math.cos(phi), math.sin(phi)])
        lo, hi = 0.0, 400.0
        for _ in range(30):
            mid = (lo + hi) / 2
            b = text_box((c.x + d[0] * mid, c.y + d[1] * mid), w, h, angle)
            ok = b.distance(target) >= gap if gap > 0 else not b.intersects(target)
            if ok:
                hi = mid
            else:
                lo = mid
        t = hi + (gap if gap < 0 else 0.0)
        cen = (c.x + d[0] * t, c.y + d[1] * t)
        b = text_box(cen, w, h, angle)
        if not inner.contains(b):
            continue
        if any(b.distance(o) < dmin for o, dmin in obstacles):
            continue
        return cen, b
    return None


def ruler_parts(length, width, rng):
    """Ruler in its own frame (x along, y across from the tick edge): geometry lists."""
    tw = rng.uniform(0.12, 0.22)
    x0 = rng.uniform(2, 8)
    ticks = []
    nums = []
    for k in range(int((length - 2 * x0) // 1) + 1):
        x = x0 + k
        tl = 5.0 if k % 10 == 0 else (3.5 if k % 5 == 0 else 2.0)
        ticks.append(box(x - tw / 2, 0.4, x + tw / 2, 0.4 + tl))
        if k % 10 == 0:
            nums.append((str(k // 10), x))
    edge = rng.uniform(0.15, 0.3)
    edges = [box(0, 0, length, edge), box(0, width - edge, length, width)]
    return MultiPolygon(ticks), unary_union(edges), box(0, 0, length, width), nums, tw


def line_cov_1d(n, mmpp, pitch, width, offset):
    e = np.arange(n + 1) * mmpp - offset + width / 2
    q = np.floor(e / pitch)
    F = q * width + np.minimum(e - q * pitch, width)
    return ((F[1:] - F[:-1]) / mmpp).astype(np.float32)


# ----------------------------------------------------------------------------- page
def choose_axis(rng, prints, allow_auto=True):
    need = any(p["family"] in ("car", "wide") or p["L_nom"] / p["W_nom"] < 1.4 for p in prints)
    if allow_auto and not need and rng.random() < 0.35:
        return "auto"
    return "x" if rng.random() < 0.5 else "y"


def families_for(kind, rng):
    mix = ["road", "road", "road", "mtb", "mtb", "tiny", "wide"]
    if kind == "slick":
        return [("road", "slick") for _ in range(int(rng.integers(1, 4)))]
    if kind == "treaded":
        out = []
        for _ in range(int(rng.integers(1, 4))):
            if rng.random() < 0.45:
                out.append(
                    ("road", pick(rng, ["ribs", "herringbone", "file", "knurl", "dots", "pores"]))
                )
            else:
                out.append(("mtb", None))
        return out
    if kind == "car":
        return [("car", None)]
    if kind == "wide":
        return [("wide", None) for _ in range(int(rng.integers(1, 3)))]
    if kind == "tiny":
        f = [("tiny", None) for _ in range(int(rng.integers(1, 4)))]
        if rng.random() < 0.3:
            f.append(("road", None))
        return f
    if kind == "noise":
        return []
    if kind == "tilt":
        mix = ["road", "road", "mtb", "mtb", "wide"]
    out = [(pick(rng, mix), None) for _ in range(int(rng.integers(1, 4)))]
    if kind == "chart" and rng.random() < 0.15:
        out = [("car", None)]
    return out


def make_page(rng, kind, dpi, ch, photo=None):
    """Render one page. Returns (img float32 HxWxC reflectance, truth rows, info)."""
    paper = pick(rng, ["A4", "letter"])
    pw, ph = PAPERS[paper]
    fams = families_for(kind, rng)
    land = rng.random() < 0.2 and not any(f == "car" for f, _ in fams)
    if land:
        pw, ph = ph, pw
    wpx, hpx = int(round(pw / 25.4 * dpi)), int(round(ph / 25.4 * dpi))
    mmpp = 25.4 / dpi
    Wmm, Hmm = wpx * mmpp, hpx * mmpp
    sheet = box(0, 0, Wmm, Hmm)
    prints = [make_print(rng, f, mmpp, t) for f, t in fams]
    prints.sort(key=lambda p: -p["L_nom"] * p["W_nom"])
    axis = choose_axis(rng, prints) if prints else "auto"
    marks = []
    # ---- place prints
    margin = 16.0 if kind == "tilt" else 8.0
    placed = []
    clip_idx = 0 if kind == "clipped" else -1
    if kind == "clipped" and prints and rng.random() < 0.5:
        clip_idx = int(rng.integers(0, len(prints)))
    for i, p in enumerate(prints):
        if axis == "auto":
            theta = rng.uniform(0, 180)
        else:
            d = rng.uniform(-0.5, 0.5) if rng.random() < 0.8 else 0.0
            theta = (0.0 if axis == "x" else 90.0) + d
        g = affinity.rotate(p["local"], theta, origin=(0, 0), use_radians=False)
        x0, y0, x1, y1 = g.bounds
        clr = 15.0 if p["family"] == "tiny" else 25.0
        ok = False
        for _ in range(300):
            if i == clip_idx:
                side = int(rng.integers(0, 4))
                f = rng.uniform(0.12, 0.45)
                ext = (x1 - x0) if side < 2 else (y1 - y0)
                cx = rng.uniform(margin - x0, Wmm - margin - x1)
                cy = rng.uniform(margin - y0, Hmm - margin - y1)
                if side == 0:
                    cx = -x0 - f * ext
                elif side == 1:
                    cx = Wmm - x1 + f * ext
                elif side == 2:
                    cy = -y0 - f * ext
                else:
                    cy = Hmm - y1 + f * ext
            else:
                lo_x, hi_x = margin - x0, Wmm - margin - x1
                lo_y, hi_y = margin - y0, Hmm - margin - y1
                if hi_x < lo_x or hi_y < lo_y:
                    break
                cx, cy = rng.uniform(lo_x, hi_x), rng.uniform(lo_y, hi_y)
            gg = affinity.translate(g, cx, cy)
            hh = gg.convex_hull
            if all(hh.distance(q["hull_full"]) >= max(clr, q["clr"]) for q in placed):
                ok = True
                break
        if not ok:
            continue
        q = dict(p, theta=theta, geom_full=gg, hull_full=hh, clr=clr, clipped=(i == clip_idx))
        if q["clipped"]:
            vis = clean(gg.intersection(sheet), max(0.3, 6 * mmpp * mmpp), max(0.25, 1.5 * mmpp))
            if vis is None or vis.convex_hull.area < 0.3 * hh.area:
                continue
            q["geom"] = vis
            q["full_length_mm"] = extents(hull_pts(hh), theta)[0]
        else:
            q["geom"] = gg
        placed.append(q)
    prints = placed
    pu = unary_union([p["geom"] for p in prints]) if prints else None

    # ---- colours and paper
    paper_rgb = np.array([rng.uniform(0.90, 0.97)] * 3) * np.array(
        [1.0, rng.uniform(0.985, 1.0), rng.uniform(0.95, 1.0)]
    )
    cv = Canvas(wpx, hpx, mmpp, ch, paper_rgb)
    tex = smooth_noise(rng, hpx, wpx, max(0.6 / mmpp, 2), -1, 1)
    cv.img *= (1.0 + rng.uniform(0.004, 0.015) * tex)[:, :, None]
    del tex

    # ---- chart paper (printed under everything)
    if kind == "chart" or (kind in ("label", "tiny", "dust") and rng.random() < 0.15):
        col = pick(
            rng,
            [
                (0.45, 0.08, 0.35),
                (0.35, 0.12, 0.02),
                (0.05, 0.35, 0.45),
                (0.05, 0.25, 0.30),
                (0.3, 0.3, 0.3),
            ],
        )
        col = np.array(col)
        grids = pick(rng, [("1+5",), ("1",), ("5",)], [3, 1, 1])[0]
        ox, oy = rng.uniform(0, 5), rng.uniform(0, 5)
        gi = {"type": "grid", "grids": grids}
        layers = []
        if "1" in grids:
            a1, w1 = rng.uniform(0.15, 0.55), rng.uniform(0.08, 0.18)
            layers.append((1.0, w1, a1))
            gi["minor"] = {"width_mm": round(w1, 3), "dark": round(a1, 3)}
        if "5" in grids:
            a5, w5 = rng.uniform(0.3, 0.8), rng.uniform(0.15, 0.3)
            layers.append((5.0, w5, a5))
            gi["major"] = {"width_mm": round(w5, 3), "dark": round(a5, 3)}
        for pitch, wd, a in layers:
            cx_ = line_cov_1d(wpx, mmpp, pitch, wd, ox)
            cy_ = line_cov_1d(hpx, mmpp, pitch, wd, oy)
            cov = 1.0 - (1.0 - cx_[None, :]) * (1.0 - cy_[:, None])
            cv.mul(cov, 0, 0, col * a)
            del cov
        gi["colour_absorb"] = [round(float(v), 3) for v in col]
        marks.append(gi)

    # ---- prints
    for p in prints:
        d = rng.uniform(0.55, 0.93)
        tint = pick(rng, [(1.0, 1.0, 1.0), (0.97, 0.97, 1.0), (1.0, 0.97, 0.9), (0.93, 0.96, 1.0)])
        p["ink_dark"] = d
        amp = rng.uniform(0.0, 0.15)
        cv.stamp(p["geom"], np.array(tint) * d, mottle=(amp, rng.uniform(0.5, 2.5)), rng=rng)
        p["marks"] = []

    # ---- halo specks around prints
    if prints and (kind == "dust" or rng.random() < 0.2):
        for p in prints:
            hh = p["geom"].convex_hull
            n = int(rng.integers(5, 40))
            c = np.array(hh.centroid.coords[0])
            cnt = 0
            for _ in range(n):
                b = hh.exterior.interpolate(rng.uniform(0, 1), normalized=True)
                v = np.array(b.coords[0]) - c
                v /= np.linalg.norm(v) + 1e-9
                r = rng.uniform(0.05, 0.18)
                q = np.array(b.coords[0]) + v * rng.uniform(0.7, 3.0)
                s = Point(*q).buffer(r, quad_segs=4)
                if s.distance(pu) < 0.5 or not sheet.buffer(-1).contains(s):
                    continue
                cv.stamp(s, np.ones(3) * p["ink_dark"] * rng.uniform(0.6, 1.0))
                cnt += 1
            p["marks"].append({"type": "halo_specks", "n": cnt, "min_gap_mm": 0.5})

    # ---- labels
    obstacles = [(p["geom"], 6.0) for p in prints]
    extra = []
    if prints:
        for pi, p in enumerate(prints):
            nl = int(rng.integers(1, 3)) if kind == "label" else int(rng.random() < 0.3)
            for _ in range(nl):
                text = label_text(rng)
                font = pick(rng, FONTS) | (cv2.FONT_ITALIC if rng.random() < 0.15 else 0)
                marker = rng.random() < 0.3
                hmm_ = rng.uniform(3.0, 8.0) if p["family"] != "tiny" else rng.uniform(2.5, 5.0)
                stroke = rng.uniform(1.0, 1.8) if marker else rng.uniform(0.25, 0.6)
                ang = rng.uniform(-8, 8) if rng.random() < 0.7 else rng.uniform(-35, 35)
                touch = kind == "label" and rng.random() < 0.3
                gap = rng.uniform(-1.0, 0.2) if touch else rng.uniform(1.5, 8.0)
                w, h = text_size_mm(text, font, hmm_, stroke)
                obs = [(o, dm) for o, dm in obstacles if o is not p["geom"]] + extra
                got = place_beside(rng, p["geom"], w, h, ang, gap, obs, sheet)
                if got is None:
                    continue
                cen, bx = got
                pen = pick(rng, list(PENS))
                dark = rng.uniform(0.6, 1.0)
                draw_text(cv, text, font, hmm_, stroke, cen, ang, np.array(PENS[pen]) * dark)
                extra.append((bx, 2.0))
                p["marks"].append(
                    {
                        "type": "label",
                        "text": text,
                        "pen": pen,
                        "marker": bool(marker),
                        "h_mm": round(hmm_, 2),
                        "stroke_mm": round(stroke, 2),
                        "angle_deg": round(ang, 1),
                        "box_gap_mm": round(gap, 2),
                        "touch": bool(touch),
                        "box_dist_mm": round(bx.distance(p["geom"]), 2),
                    }
                )

    # ---- rulers
    if prints and (kind == "ruler" or rng.random() < 0.08):
        for _ in range(int(rng.integers(1, 3)) if kind == "ruler" else 1):
            p = prints[int(rng.integers(0, len(prints)))]
            length, width = rng.uniform(150, 320), rng.uniform(25, 36)
            ticks, edges, body, nums, tw = ruler_parts(length, width, rng)
            hh = p["geom"].convex_hull
            c = hh.centroid
            mode = pick(rng, ["crossing", "along"])
            if mode == "crossing":
                ang = p["theta"] + 90 + rng.uniform(-15, 15)
                offs = rng.uniform(-0.3, 0.3) * width
                shift = 0.0
            else:
                ang = p["theta"] + rng.uniform(-3, 3)
                Lp, Wp = extents(hull_pts(hh), p["theta"])
                offs = None
                shift = Wp / 2 + rng.uniform(2, 10)
            # ruler frame: tick edge y=0; centre the ruler's length on the print
            a = math.radians(ang)
            u = np.array([math.cos(a), math.sin(a)])
            n = np.array([-math.sin(a), math.cos(a)])
            t0 = rng.uniform(0.3, 0.7) * length
            if mode == "crossing":
                origin = np.array([c.x, c.y]) - u * t0 - n * (width / 2 + offs)
            else:
                sgn = 1 if rng.random() < 0.5 else -1
                origin = (
                    np.array([c.x, c.y]) - u * t0 + n * sgn * shift - (n * width if sgn < 0 else 0)
                )

            def tf(g):
                g = affinity.rotate(g, ang, origin=(0, 0))
                return affinity.translate(g, origin[0], origin[1])

            cv.stamp(tf(body).intersection(sheet), np.ones(3) * rng.uniform(0.02, 0.06))
            cv.stamp(tf(edges).intersection(sheet), np.ones(3) * rng.uniform(0.15, 0.35))
            tk = rng.uniform(0.7, 0.92)
            cv.stamp(tf(ticks).intersection(sheet), np.ones(3) * tk)
            nh = rng.uniform(2.2, 3.2)
            for s_, x in nums:
                q = origin + u * x + n * (0.4 + 5.0 + 0.8 + nh / 2)
                if 2 < q[0] < Wmm - 2 and 2 < q[1] < Hmm - 2:
                    draw_text(cv, s_, cv2.FONT_HERSHEY_SIMPLEX, nh, 0.25, q, ang, np.ones(3) * tk)
            d_ = tf(body).distance(p["geom"])
            p["marks"].append(
                {
                    "type": "ruler",
                    "mode": mode,
                    "angle_deg": round(ang, 1),
                    "width_mm": round(width, 1),
                    "dist_mm": round(d_, 2),
                }
            )

    # ---- dust and fibres (kept 1 mm clear of prints)
    nd = int(rng.integers(150, 700)) if kind in ("dust", "noise") else int(rng.integers(0, 80))
    pts = np.c_[rng.uniform(1, Wmm - 1, nd), rng.uniform(1, Hmm - 1, nd)]
    rads = np.clip(rng.lognormal(math.log(0.07), 0.5, nd), 0.02, 0.25)
    if pu is not None and nd:
        keep = ~shapely.dwithin(pu, shapely.points(pts), rads + 1.0)
        pts, rads = pts[keep], rads[keep]
    for q, r in zip(pts, rads):
        cv.stamp(Point(*q).buffer(r, quad_segs=3), np.ones(3) * rng.uniform(0.25, 0.85))
    nf = int(rng.integers(0, 6)) if kind in ("dust", "noise") else int(rng.integers(0, 2))
    nfib = 0
    for _ in range(nf):
        q = np.array([rng.uniform(5, Wmm - 5), rng.uniform(5, Hmm - 5)])
        steps = np.cumsum(rng.normal(0, 0.5, (8, 2)) + rng.normal(0, 0.6, 2), axis=0)
        f = LineString(q + steps).buffer(rng.uniform(0.03, 0.06))
        if pu is not None and f.distance(pu) < 1.5:
            continue
        cv.stamp(f, np.ones(3) * rng.uniform(0.15, 0.35))
        nfib += 1
    marks.append({"type": "dust", "specks": int(len(pts)), "fibres": nfib})

    info = {"paper": paper, "landscape": bool(land), "rolling_axis": axis, "sheet_mm": [Wmm, Hmm]}
    img = cv.img
    # ---- photo: light, perspective
    if photo:
        img, pinfo = photograph(rng, img, mmpp, photo)
        info.update(pinfo)
        marks.append({"type": "photo", **pinfo})
    blur = rng.uniform(0.35, 1.0) if not photo else rng.uniform(0.6, 1.3)
    cv2.GaussianBlur(img, (0, 0), blur, dst=img)
    info["blur_px"] = round(blur, 3)

    rows = []
    for p in prints:
        t = truth_of(p["geom"], p["theta"], axis)
        ang = p["theta"] if axis == "auto" else p["theta"] - (0.0 if axis == "x" else 90.0)
        notes = {
            "marks": p["marks"] + [m for m in marks if m["type"] in ("grid", "photo")],
            "params": p["params"],
            "L_nom": round(p["L_nom"], 2),
            "W_nom": round(p["W_nom"], 2),
            "pieces": len(polys(p["geom"])),
            "net_area_mm2": round(p["geom"].area, 2),
        }
        if p["clipped"]:
            notes["full_length_mm"] = round(p["full_length_mm"], 2)
            notes["full_hull_area_mm2"] = round(p["hull_full"].area, 2)
        rows.append(
            {
                "kind": kind,
                "expect": "clipped" if p["clipped"] else "measure",
                **t,
                "family": p["family"],
                "outline": p["outline"],
                "tread": p["tread"],
                "angle_deg": ang,
                "ink_dark": p["ink_dark"],
                "notes": notes,
            }
        )
    rows.sort(key=lambda r: -r["centroid_y_mm"])
    for i, r in enumerate(rows):
        r["print"] = i
    info["marks"] = marks
    return img, rows, info


def photograph(rng, img, mmpp, mode):
    """Uneven light (gradient, vignette, shadow) and perspective ('slight' or 'tilt')."""
    h, w = img.shape[:2]
    sh = (max(h // 8, 2), max(w // 8, 2))
    yy, xx = np.mgrid[0 : sh[0], 0 : sh[1]].astype(np.float32)
    yy /= sh[0]
    xx /= sh[1]
    a = rng.uniform(0, 2 * np.pi)
    gs = rng.uniform(0.1, 0.3)
    F = 1.0 - gs * (0.5 + 0.5 * (np.cos(a) * (xx - 0.5) + np.sin(a) * (yy - 0.5)) * 1.4)
    vg = rng.uniform(0.05, 0.2)
    F *= 1.0 - vg * ((xx - 0.5) ** 2 + (yy - 0.5) ** 2) / 0.5
    info = {"gradient": round(gs, 3), "vignette": round(vg, 3)}
    if rng.random() < 0.6:
        # a soft shadow (hand/phone) from one side
        b = rng.uniform(0.15, 0.45)
        s = rng.uniform(0.12, 0.3)
        soft = rng.uniform(0.02, 0.08)
        side = int(rng.integers(0, 4))
        coord = [xx, 1 - xx, yy, 1 - yy][side] + 0.15 * np.sin(
            6 * [yy, yy, xx, xx][side] + rng.uniform(0, 6)
        )
        F *= 1.0 - s * (1.0 / (1.0 + np.exp((coord - b) / soft)))
        info["shadow"] = {"side": side, "depth": round(s, 3)}
    F = cv2.resize(F.astype(np.float32), (w, h), interpolation=cv2.INTER_CUBIC)
    img *= F[:, :, None]
    src = np.float32([[0, 0], [w, 0], [w, h], [0, h]])
    if mode == "tilt":
        k = rng.uniform(0.04, 0.10)
        m = rng.uniform(0.03, 0.05)
        dst = np.float32(
            [
                [w * (m + k / 2), h * m],
                [w * (1 - m - k / 2), h * m],
                [w * (1 - m), h * (1 - m)],
                [w * m, h * (1 - m)],
            ]
        )
        if rng.random() < 0.5:  # keystone at the bottom instead
            dst = np.float32(
                [
                    [w * m, h * m],
                    [w * (1 - m), h * m],
                    [w * (1 - m - k / 2), h * (1 - m)],
                    [w * (m + k / 2), h * (1 - m)],
                ]
            )
        table = rng.uniform(0.12, 0.4)
        Hm = cv2.getPerspectiveTransform(src, dst)
        img = cv2.warpPerspective(
            img,
            Hm,
            (w, h),
            flags=cv2.INTER_LINEAR,
            borderMode=cv2.BORDER_CONSTANT,
            borderValue=(table, table * 0.95, table * 0.85, 0),
        )
        info.update(
            {
                "perspective": "tilt",
                "keystone": round(k, 4),
                "page_margin": round(m, 4),
                "expect_flag": "perspective",
                "page_offset_mm": [round(w * m * mmpp, 1), round(h * m * mmpp, 1)],
            }
        )
    else:
        dmax = rng.uniform(0.2, 0.6) / mmpp  # corner shifts in px (< ~0.3 deg of corner angle)
        dst = (src + rng.uniform(-dmax, dmax, (4, 2))).astype(np.float32)
        Hm = cv2.getPerspectiveTransform(src, dst)
        img = cv2.warpPerspective(
            img, Hm, (w, h), flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE
        )
        info.update({"perspective": "slight", "corner_shift_mm": round(dmax * mmpp, 3)})
    if img.ndim == 2:
        img = img[:, :, None]
    return img, info


# ----------------------------------------------------------------------------- encoders
def quantize(img, bits, rng, noise):
    img = img + rng.standard_normal(img.shape[:2] + (1,), dtype=np.float32) * np.float32(noise)
    top = 255 if bits == 8 else 65535
    q = np.clip(img * top + 0.5, 0, top).astype(np.uint8 if bits == 8 else np.uint16)
    if q.shape[2] == 1:
        return q[:, :, 0]
    return q


def bgr(q):
    return q[:, :, ::-1].copy() if q.ndim == 3 else q


def png_bytes(q, dpi):
    ok, buf = cv2.imencode(".png", bgr(q), [cv2.IMWRITE_PNG_COMPRESSION, 1])
    b = buf.tobytes()
    if dpi:
        ppm = int(round(dpi / 0.0254))
        data = b"pHYs" + struct.pack(">IIB", ppm, ppm, 1)
        chunk = struct.pack(">I", 9) + data + struct.pack(">I", zlib.crc32(data) & 0xFFFFFFFF)
        b = b[:33] + chunk + b[33:]
    return b


def jpeg_bytes(q, dpi, quality):
    ok, buf = cv2.imencode(".jpg", bgr(q), [cv2.IMWRITE_JPEG_QUALITY, int(quality)])
    b = bytearray(buf.tobytes())
    assert b[6:11] == b"JFIF\x00"
    if dpi:
        b[13] = 1
        b[14:18] = struct.pack(">HH", int(dpi), int(dpi))
    else:
        b[13] = 0
        b[14:18] = struct.pack(">HH", 1, 1)
    return bytes(b)


def write_tiff(path, q, dpi):
    prm = [cv2.IMWRITE_TIFF_COMPRESSION, cv2.IMWRITE_TIFF_COMPRESSION_LZW]
    if dpi:
        prm += [
            cv2.IMWRITE_TIFF_RESUNIT,
            2,
            cv2.IMWRITE_TIFF_XDPI,
            int(dpi),
            cv2.IMWRITE_TIFF_YDPI,
            int(dpi),
        ]
    assert cv2.imwrite(path, bgr(q), prm)


def write_pdf(path, pages):
    """Minimal PDF: one full-page image per page. pages: dicts q (uint8), enc, w_pt, h_pt, quality."""
    objs = [None, None]  # 1 catalog, 2 pages
    kids = []
    for pg in pages:
        q = pg["q"]
        grey = q.ndim == 2
        hh, ww = q.shape[:2]
        if pg["enc"] == "dct":
            ok, buf = cv2.imencode(".jpg", bgr(q), [cv2.IMWRITE_JPEG_QUALITY, int(pg["quality"])])
            data, filt = buf.tobytes(), "/DCTDecode"
        else:
            data, filt = zlib.compress(np.ascontiguousarray(q).tobytes(), 6), "/FlateDecode"
        cs = "/DeviceGray" if grey else "/DeviceRGB"
        img = (
            (
                f"<< /Type /XObject /Subtype /Image /Width {ww} /Height {hh} /ColorSpace {cs} "
                f"/BitsPerComponent 8 /Filter {filt} /Length {len(data)} >>\nstream\n"
            ).encode()
            + data
            + b"\nendstream"
        )
        objs.append(img)
        im_no = len(objs)
        content = f"q {pg['w_pt']:.4f} 0 0 {pg['h_pt']:.4f} 0 0 cm /Im0 Do Q".encode()
        objs.append(f"<< /Length {len(content)} >>\nstream\n".encode() + content + b"\nendstream")
        c_no = len(objs)
        objs.append(
            f"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {pg['w_pt']:.4f} {pg['h_pt']:.4f}] "
            f"/Resources << /XObject << /Im0 {im_no} 0 R >> >> /Contents {c_no} 0 R >>".encode()
        )
        kids.append(len(objs))
    objs[0] = b"<< /Type /Catalog /Pages 2 0 R >>"
    objs[1] = (
        f"<< /Type /Pages /Kids [{' '.join(f'{k} 0 R' for k in kids)}] /Count {len(kids)} >>"
    ).encode()
    out = bytearray(b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n")
    offs = []
    for i, o in enumerate(objs, 1):
        offs.append(len(out))
        out += f"{i} 0 obj\n".encode() + o + b"\nendobj\n"
    xref = len(out)
    out += f"xref\n0 {len(objs) + 1}\n0000000000 65535 f \n".encode()
    for o in offs:
        out += f"{o:010d} 00000 n \n".encode()
    out += f"trailer\n<< /Size {len(objs) + 1} /Root 1 0 R >>\nstartxref\n{xref}\n%%EOF\n".encode()
    with open(path, "wb") as fh:
        fh.write(out)


# ----------------------------------------------------------------------------- set
DPIS = [150, 200, 240, 300, 360, 400, 600]
DPI_W = [14, 20, 10, 30, 8, 13, 5]
IMG_FORMATS = ["png8", "png16", "jpeg", "tiff8", "tiff16"]


def make_file(d, i, seed, kind):
    rng = np.random.default_rng([seed, i])
    photo = {"light": "slight", "tilt": "tilt"}.get(kind)
    pdf = kind not in ("dpi_trap", "tilt") and rng.random() < 0.16
    dpi = int(pick(rng, DPIS, DPI_W))
    if pdf or photo:
        dpi = min(dpi, 400)
    ch = 1 if dpi >= 600 else (3 if rng.random() < 0.45 else 1)
    if photo:
        ch = 3 if rng.random() < 0.8 else 1
    base = f"scan_{i:03d}"
    truth, mani, infos = [], [], []
    blank = {k: "" for k in TRUTH_COLS[5:-1]}  # (the measured columns)
    if pdf:
        fn = base + ".pdf"
        enc = "dct" if rng.random() < 0.45 else "flate"
        npg = int(rng.integers(2, 5))
        pages = []
        for pg in range(npg):
            k = (
                kind
                if pg == 0
                else pick(
                    rng,
                    [x for x in KINDS if x not in ("dpi_trap", "tilt", "noise")] + ["noise"],
                    None,
                )
            )
            pdpi = dpi if pg == 0 else int(pick(rng, DPIS[:6], DPI_W[:6]))
            img, rows, info = make_page(
                rng, k, pdpi, ch, photo if pg == 0 else ({"light": "slight"}.get(k))
            )
            noise = rng.uniform(0.003, 0.01)
            q = quantize(img, 8, rng, noise)
            del img
            hpx, wpx = q.shape[:2]
            pages.append(
                {
                    "q": q,
                    "enc": enc,
                    "w_pt": wpx * 72.0 / pdpi,
                    "h_pt": hpx * 72.0 / pdpi,
                    "quality": int(rng.integers(80, 96)),
                }
            )
            exp_err = None if rows else "error:NoInk"
            add_rows(truth, fn, pg, k, rows, exp_err, blank)
            mani.append(
                {
                    "file": fn,
                    "page": pg,
                    "dpi": "",
                    "rolling_axis": info["rolling_axis"],
                    "tire": pick(rng, TIRES),
                }
            )
            infos.append(
                {
                    "file": fn,
                    "page": pg,
                    "kind": k,
                    "dpi": pdpi,
                    "format": "pdf",
                    "pdf_enc": enc,
                    "channels": ch,
                    "bits": 8,
                    "noise": round(noise, 4),
                    **info,
                    "page_pt": [round(wpx * 72.0 / pdpi, 4), round(hpx * 72.0 / pdpi, 4)],
                }
            )
        write_pdf(os.path.join(d, fn), pages)
        return truth, mani, infos
    fmt = pick(rng, IMG_FORMATS, [4, 1.2, 3, 1.5, 1.2])
    if photo:
        fmt = pick(rng, ["jpeg", "png8"], [4, 1])
    if dpi >= 600 and fmt.endswith("16"):
        fmt = fmt[:-2] + "8"
    bits = 16 if fmt.endswith("16") else 8
    img, rows, info = make_page(rng, kind, dpi, ch, photo)
    noise = rng.uniform(0.002, 0.008) if not photo else rng.uniform(0.006, 0.015)
    q = quantize(img, bits, rng, noise)
    del img
    meta_dpi, man_dpi, exp_err = dpi, "", None
    if kind == "dpi_trap":
        meta_dpi = pick(rng, [72, 96, None], [1, 1, 1])
        if rng.random() < 0.4:
            man_dpi = dpi
        elif meta_dpi is None:
            exp_err = "error:ScaleMissing"
        else:
            exp_err = f"error:{UNTRUSTED}"
    elif rng.random() < 0.15:
        man_dpi = dpi
    if not rows:
        exp_err = "error:NoInk" if exp_err is None else exp_err
    ext = {"png8": "png", "png16": "png", "jpeg": "jpg", "tiff8": "tif", "tiff16": "tif"}[fmt]
    fn = f"{base}.{ext}"
    path = os.path.join(d, fn)
    quality = None
    if ext == "png":
        with open(path, "wb") as fh:
            fh.write(png_bytes(q, meta_dpi))
    elif ext == "jpg":
        quality = int(rng.integers(78, 96))
        with open(path, "wb") as fh:
            fh.write(jpeg_bytes(q, meta_dpi, quality))
    else:
        write_tiff(path, q, meta_dpi)
    add_rows(truth, fn, 0, kind, rows, exp_err, blank)
    mani.append(
        {
            "file": fn,
            "page": "",
            "dpi": man_dpi,
            "rolling_axis": info["rolling_axis"],
            "tire": pick(rng, TIRES),
        }
    )
    infos.append(
        {
            "file": fn,
            "page": 0,
            "kind": kind,
            "dpi": dpi,
            "format": fmt,
            "channels": ch,
            "bits": bits,
            "meta_dpi": meta_dpi,
            "manifest_dpi": man_dpi,
            "jpeg_quality": quality,
            "noise": round(noise, 4),
            **info,
        }
    )
    return truth, mani, infos


def add_rows(truth, fn, page, kind, rows, exp_err, blank):
    if exp_err:
        notes = {
            "prints": [
                {
                    k: (round(v, 3) if isinstance(v, float) else v)
                    for k, v in r.items()
                    if k
                    in (
                        "length_mm",
                        "width_mm",
                        "hull_area_mm2",
                        "centroid_x_mm",
                        "centroid_y_mm",
                        "family",
                        "tread",
                    )
                }
                for r in rows
            ]
        }
        truth.append(
            {
                "file": fn,
                "page": page,
                "print": "",
                "kind": kind,
                "expect": exp_err,
                **blank,
                "notes": json.dumps(notes),
            }
        )
        return
    for r in rows:
        row = {"file": fn, "page": page}
        for k, v in r.items():
            row[k] = f"{v:.4f}" if isinstance(v, float) else v
        row["notes"] = json.dumps(r["notes"], default=float)
        truth.append(row)


TRUTH_COLS = [
    "file",
    "page",
    "print",
    "kind",
    "expect",
    "length_mm",
    "width_mm",
    "hull_area_mm2",
    "centroid_x_mm",
    "centroid_y_mm",
    "family",
    "outline",
    "tread",
    "angle_deg",
    "alt_kind",
    "length_alt_mm",
    "width_alt_mm",
    "ink_dark",
    "notes",
]
MANI_COLS = ["file", "page", "dpi", "rolling_axis", "tire"]


def make_set(d, n, seed, verbose=True):
    os.makedirs(d, exist_ok=True)
    truth, mani, infos = [], [], []
    t0 = time.time()
    for i in range(n):
        kind = KINDS[i % len(KINDS)]
        t, m, inf = make_file(d, i, seed, kind)
        truth += t
        mani += m
        infos += inf
        if verbose:
            print(f"[{i + 1}/{n}] {m[0]['file']} {kind} {time.time() - t0:.1f}s", file=sys.stderr)
    with open(os.path.join(d, "truth.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, TRUTH_COLS, extrasaction="ignore")
        w.writeheader()
        w.writerows(truth)
    with open(os.path.join(d, "manifest.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, MANI_COLS)
        w.writeheader()
        w.writerows(mani)
    with open(os.path.join(d, "sheets.json"), "w") as fh:
        json.dump(
            infos, fh, indent=1, default=lambda o: o.item() if hasattr(o, "item") else str(o)
        )
    return truth


def main():
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("out")
    ap.add_argument("--files", type=int, default=120)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("-q", "--quiet", action="store_true")
    a = ap.parse_args()
    t0 = time.time()
    make_set(a.out, a.files, a.seed, verbose=not a.quiet)
    print(f"{a.files} files in {a.out} ({time.time() - t0:.1f} s)", file=sys.stderr)


if __name__ == "__main__":
    main()
