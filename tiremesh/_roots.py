"""Vectorized, bracketed Newton iteration (one root per array element).

Used for every root of the model: side-bulge angles (section 5.1), patch ends
(section 5.2), the rim angle of equation 5-6 and the load search. Each element keeps a
bracket [lo, hi] with a sign change; a Newton step that leaves the bracket (or has
a zero / non-finite derivative) is replaced by bisection, so convergence is
guaranteed for continuous functions and quadratic near a simple root.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ._tol import tol
from .errors import NotConverged

FunAndDeriv = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


def newton_bracketed(
    fun: FunAndDeriv,
    x0: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    *,
    xtol: float,
    what: str,
    maxiter: int | None = None,
    sign_lo=None,
    ftol: float = 0.0,
) -> np.ndarray:
    """Solve ``fun(x)[0] == 0`` elementwise inside ``[lo, hi]``.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> (f, dfdx)``, vectorized, same shape as ``x``.
    x0, lo, hi : (...) float
        Start and bracket; ``f(lo)`` and ``f(hi)`` must differ in sign (not checked
        here: the callers build brackets from monotonicity arguments).
    xtol : float
        Absolute step tolerance.
    what : str
        Name used in the :class:`NotConverged` message.
    sign_lo : float or (...) float, optional
        Sign of ``f(lo)`` when the caller knows it (saves one evaluation).
    ftol : float
        Also stop once every ``|f| <= ftol`` (returns the current point).

    Returns
    -------
    x : (...) float
    """
    maxiter = tol.max_iter if maxiter is None else maxiter
    lo, hi = np.broadcast_arrays(np.asarray(lo, float), np.asarray(hi, float))
    lo, hi = lo.copy(), hi.copy()
    x = np.clip(np.broadcast_to(np.asarray(x0, float), lo.shape), lo, hi).copy()
    if sign_lo is None:
        sign_lo = np.sign(fun(lo)[0])
    for _ in range(maxiter):
        f, df = fun(x)
        if np.all(np.abs(f) <= ftol):
            return x
        same = np.sign(f) == sign_lo
        lo = np.where(same, x, lo)
        hi = np.where(same, hi, x)
        with np.errstate(divide="ignore", invalid="ignore"):
            x_new = x - f / df
        # closed bracket: a converged Newton point may sit exactly on lo or hi
        inside = np.isfinite(x_new) & (x_new >= lo) & (x_new <= hi)
        x_new = np.where(inside, x_new, 0.5 * (lo + hi))
        x_new = np.where(f == 0, x, x_new)
        step = np.abs(x_new - x)
        x = x_new
        if np.all((step <= xtol) | (hi - lo <= xtol)):
            return x
    raise NotConverged(
        what,
        {
            "iterations": maxiter,
            "worst_step": float(np.max(step)),
            "worst_bracket": float(np.max(hi - lo)),
            "x": x if x.size <= 8 else f"array of {x.size}",
        },
    )
