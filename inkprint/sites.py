"""The sites of a fine tread's lattice: where its elements lie, and whether a speck
does.

A fine tread (knurl, file, dots) prints its elements on a two-dimensional lattice:
every element's centre is ``origin + i * a + j * b`` for whole ``i, j``. The outline
cuts the elements at its edge to crescents and wedges, each lying on its element's
site; a halo speck or a dust speck beside the print lies anywhere. The section
7.1.1 rule keeps a speck within the tread's reach (its pattern gap) as a cut
element: a speck off a tiny print's tip, half a gap out, read the print 4.9 % and
8.7 % long with status ok (held-out 6 seed 4 sheet 109, seed 2 sheet 65). A speck
off every site is no element.

Pure numpy over (x, y) points in pixels; :func:`inkprint.group._spots` uses it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import InvalidInput, check_points

__all__ = ["Lattice", "fit_lattice", "nearest_site", "site_distance"]

#: fewest whole elements to fit a lattice from
LATTICE_LEAST = 6
#: neighbours: centres within this many times the median nearest-neighbour distance
NEIGHBOUR_REACH = 1.35
#: a direction of the lattice: neighbour vectors within this angle [degrees] of it
DIRECTION_DEG = 8.0
#: ... the second direction at least this angle [degrees] off the first
APART_DEG = 25.0
#: ... each direction seen this many times or more
DIRECTION_LEAST = 3
#: the fit holds when the centres' median distance from their sites is at most this
#: share of the lattice's step
FIT_SHARE = 0.12


@dataclass(frozen=True)
class Lattice:
    """A two-dimensional lattice of sites ``origin + i * basis[0] + j * basis[1]``.

    Attributes
    ----------
    origin : (2,) float [px]
    basis : (2, 2) float [px]
        Its two steps, one a row.
    step : float [px]
        The median distance between neighbouring centres.
    misfit : float [px]
        The centres' median distance from their sites.
    """

    origin: np.ndarray
    basis: np.ndarray
    step: float
    misfit: float


def _direction(v: np.ndarray, skip_deg: np.ndarray | None = None) -> np.ndarray | None:
    """The best supported direction of vectors ``v`` ((m, 2), signs folded so the
    angle lies in [0, 180) degrees): the mean of the vectors within
    :data:`DIRECTION_DEG` of the one with most such neighbours, or None with fewer
    than :data:`DIRECTION_LEAST`. ``skip_deg``: angles at most :data:`APART_DEG`
    from it are not candidates."""
    ang = np.degrees(np.arctan2(v[:, 1], v[:, 0])) % 180.0
    diff = np.abs(ang[:, None] - ang[None, :])
    diff = np.minimum(diff, 180.0 - diff)  # (directions, not vectors)
    support = (diff <= DIRECTION_DEG).sum(axis=1)
    if skip_deg is not None:
        off = np.abs(ang - skip_deg)
        support[np.minimum(off, 180.0 - off) <= APART_DEG] = 0
    best = int(np.argmax(support))
    if support[best] < DIRECTION_LEAST:
        return None
    near = diff[best] <= DIRECTION_DEG
    w = v[near]
    w = np.where((w @ v[best] < 0)[:, None], -w, w)  # (one sense)
    return w.mean(axis=0)


def fit_lattice(centres: np.ndarray, *, reach: float = NEIGHBOUR_REACH) -> Lattice | None:
    """Fit a lattice to the centres of whole tread elements.

    Parameters
    ----------
    centres : (k, 2) float [px]
        (x, y) of the elements (a few strays, a slick centre's, are outvoted).
    reach : float [-]
        Neighbours are centres within this many times the median nearest-neighbour
        distance, in (1, 2) (a lattice's second step can be this much longer than
        its first; twice the first would mix its multiples in).

    Returns
    -------
    Lattice or None
        None with fewer than :data:`LATTICE_LEAST` centres, without two directions
        of neighbours, or when the centres miss their sites by more than
        :data:`FIT_SHARE` of the step (a row, not a lattice; a field of all sizes).

    Raises
    ------
    InvalidInput
        ``centres`` not (k, 2) finite numbers.
    """
    c = check_points("centres", centres, "(x, y) pixels")
    if not 1.0 < reach < 2.0:
        raise InvalidInput("reach", reach, "1 < reach < 2 [-]")
    if len(c) < LATTICE_LEAST:
        return None
    d = c[None, :, :] - c[:, None, :]  # d[i, j] = c[j] - c[i]
    dist = np.hypot(d[..., 0], d[..., 1])
    np.fill_diagonal(dist, np.inf)
    step = float(np.median(dist.min(axis=1)))
    if not step > 0:
        return None
    i, j = np.nonzero(np.triu(dist <= reach * step, 1))  # (each pair once)
    v = d[i, j]
    if len(v) < 2 * DIRECTION_LEAST:
        return None
    a = _direction(v)
    if a is None:
        return None
    b = _direction(v, skip_deg=np.degrees(np.arctan2(a[1], a[0])) % 180.0)
    if b is None:
        return None
    basis = np.array([a, b])
    if abs(np.linalg.det(basis)) < 1e-6 * step * step:
        return None
    inv = np.linalg.inv(basis)
    k = np.round((c - c[0]) @ inv)
    origin = np.median(c - k @ basis, axis=0)
    off = c - origin - np.round((c - origin) @ inv) @ basis
    misfit = float(np.median(np.hypot(off[:, 0], off[:, 1])))
    if misfit > FIT_SHARE * step:
        return None
    return Lattice(origin, basis, step, misfit)


def nearest_site(lattice: Lattice, points: np.ndarray) -> np.ndarray:
    """The nearest site of ``lattice`` to each point (x, y).

    Parameters
    ----------
    lattice : Lattice
    points : (m, 2) float [px]

    Returns
    -------
    (m, 2) float [px]

    Raises
    ------
    InvalidInput
        ``points`` not (m, 2) finite numbers.
    """
    p = check_points("points", points, "(x, y) pixels") - lattice.origin
    base = np.floor(p @ np.linalg.inv(lattice.basis))
    # the cell's corners and their neighbours (a skewed basis's nearest site may lie
    # outside the cell holding the point)
    steps = np.stack(np.meshgrid([-1.0, 0.0, 1.0, 2.0], [-1.0, 0.0, 1.0, 2.0]), -1).reshape(-1, 2)
    sites = (base[:, None, :] + steps[None]) @ lattice.basis  # (m, 16, 2)
    off = p[:, None, :] - sites
    best = np.hypot(off[..., 0], off[..., 1]).argmin(axis=1)
    return sites[np.arange(len(p)), best] + lattice.origin


def site_distance(lattice: Lattice, points: np.ndarray) -> np.ndarray:
    """Distance [px] of each point (x, y) from its nearest site of ``lattice``.

    Parameters
    ----------
    lattice : Lattice
    points : (m, 2) float [px]

    Returns
    -------
    (m,) float [px]

    Raises
    ------
    InvalidInput
        ``points`` not (m, 2) finite numbers.
    """
    p = check_points("points", points, "(x, y) pixels")
    return np.hypot(*(p - nearest_site(lattice, p)).T)
