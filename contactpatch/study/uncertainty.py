"""Standard errors of the report's power-law exponents (Dressel 2013, 6.2.4).

:func:`contactpatch.study.trends.power_law_fit` gives the exponents of
``y ~ p^b F^c``; with a handful of points per group (4 in the bundled set: two
pressures x two loads) an exponent is only meaningful with its uncertainty. This
module refits the same points (same selection, same design) and adds the
ordinary least-squares standard errors, the residual degrees of freedom and the 95 %
interval half-widths (Student's t). With no residual degree of freedom the fit is
exact and no error can be estimated: the errors are NaN and ``dof`` is 0.
"""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np

from tiremesh.io import cell_number_or_nan as _f

from .trends import QUANTITIES, log_design, trend_table


def fit_with_errors(x_pressure, x_load, y) -> dict:
    """Exponents of ``y ~ p^b F^c`` with their standard errors.

    Parameters
    ----------
    x_pressure : (n,) float [bar]
    x_load : (n,) float [N]
    y : (n,) float
        Points with a value <= 0 or not finite in any of the three are left out
        (as :func:`~contactpatch.study.trends.power_law_fit` does).

    Returns
    -------
    dict
        ``b``, ``c``, ``b_se``, ``c_se``, ``b_ci95``, ``c_ci95`` (half-widths of the
        95 % intervals), ``n`` (points), ``dof`` (n minus fitted parameters); NaN
        where a variable does not vary, there are too few points, or ``dof`` is 0.
    """
    A, names, yy = log_design(x_pressure, x_load, y)
    nan = math.nan
    out = {"b": nan, "c": nan, "b_se": nan, "c_se": nan, "b_ci95": nan, "c_ci95": nan}
    out.update(n=int(yy.size), dof=0)
    if A.shape[1] == 1 or yy.size < A.shape[1]:
        return out
    coef, _, rank, _ = np.linalg.lstsq(A, yy, rcond=None)
    dof = int(yy.size - rank)
    out["dof"] = dof
    for name, value in zip(names, coef[1:], strict=True):
        out[name] = float(value)
    if dof <= 0 or rank < A.shape[1]:
        return out
    from scipy.special import stdtrit  # Student t quantile (scipy.stats is slow to import)

    resid = yy - A @ coef
    s2 = float(resid @ resid) / dof
    cov = s2 * np.linalg.inv(A.T @ A)
    t = float(stdtrit(dof, 0.975))
    for k, name in enumerate(names, start=1):
        se = math.sqrt(max(cov[k, k], 0.0))
        out[f"{name}_se"], out[f"{name}_ci95"] = se, t * se
    return out


def trend_table_with_errors(paired: list[dict], *, group_keys=("tire", "surface")) -> list[dict]:
    """:func:`~contactpatch.study.trends.trend_table` plus standard errors.

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints`.
    group_keys : tuple of str

    Returns
    -------
    list of dict
        The trend rows, each with ``print_dof`` and ``model_dof`` (residual degrees
        of freedom) and, for ``src`` in print, model and ``var`` in pressure, load,
        ``{src}_{var}_exp_se`` and ``{src}_{var}_exp_ci95``.
    """
    rows = trend_table(paired, group_keys=group_keys)
    groups = defaultdict(list)
    for r in paired:
        if r.get("status", "ok") == "ok" and r.get("model_status") == "ok":
            groups[tuple(str(r.get(k, "")) for k in group_keys)].append(r)
    out = []
    for row in rows:
        rs = groups[tuple(str(row[k]) for k in group_keys)]
        p = [_f(r.get("pressure_bar")) for r in rs]
        f = [_f(r.get("load_N")) for r in rs]
        extra = {}
        for src, key in zip(("print", "model"), QUANTITIES[row["quantity"]], strict=True):
            fit = fit_with_errors(p, f, [_f(r.get(key)) for r in rs])
            extra[f"{src}_dof"] = fit["dof"]
            for var, name in (("pressure", "b"), ("load", "c")):
                extra[f"{src}_{var}_exp_se"] = fit[f"{name}_se"]
                extra[f"{src}_{var}_exp_ci95"] = fit[f"{name}_ci95"]
        out.append({**row, **extra})
    return out


__all__ = ["fit_with_errors", "trend_table_with_errors"]
