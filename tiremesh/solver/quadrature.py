"""Clenshaw-Curtis quadrature between the exact patch ends (section 5.2)."""

from __future__ import annotations

import functools

import numpy as np


@functools.lru_cache(maxsize=32)
def clenshaw_curtis(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Clenshaw-Curtis nodes (ascending, endpoints included) and weights on [-1, 1].

    The patch width is analytic between its exact ends, so integrals over the patch
    (equations 5-25 and 5-26) converge spectrally with the number of nodes.

    Parameters
    ----------
    n : int
        Number of nodes, >= 3.

    Returns
    -------
    nodes, weights : (n,) float [-]
    """
    N = n - 1
    k = np.arange(n)
    nodes = -np.cos(np.pi * k / N)
    j = np.arange(1, N // 2 + 1)
    b = np.where(2 * j == N, 1.0, 2.0)
    c = np.where((k == 0) | (k == N), 1.0, 2.0)
    terms = (b / (4.0 * j * j - 1.0))[None, :] * np.cos(2.0 * np.pi * np.outer(k, j) / N)
    weights = c / N * (1.0 - terms.sum(axis=1))
    nodes.setflags(write=False)
    weights.setflags(write=False)
    return nodes, weights
