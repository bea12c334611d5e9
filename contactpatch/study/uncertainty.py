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

#: Student t 97.5 % quantiles for 1..30 degrees of freedom, exactly
#: ``scipy.special.stdtrit(dof, 0.975)`` (importing scipy.special takes ~1 s of the
#: report; more degrees of freedom ask scipy)
T975 = (
    12.706204736174694,
    4.302652729749462,
    3.1824463052837078,
    2.7764451051977934,
    2.5705818356363146,
    2.4469118511449786,
    2.364624251592784,
    2.306004135204166,
    2.262157162798205,
    2.228138851986274,
    2.200985160091639,
    2.1788128296672284,
    2.1603686564627913,
    2.144786687917804,
    2.131449545559776,
    2.1199052992212546,
    2.1098155778333156,
    2.1009220402410382,
    2.0930240544083087,
    2.085963447265864,
    2.0796138447276795,
    2.0738730679040254,
    2.0686576104190486,
    2.0638985616280245,
    2.0595385527532972,
    2.0555294386428735,
    2.0518305164802846,
    2.0484071417952454,
    2.045229642132703,
    2.0422724563012378,
)


def t975(dof: int) -> float:
    """The Student t distribution's 97.5 % quantile (95 % two-sided interval).

    Parameters
    ----------
    dof : int
        Degrees of freedom, >= 1.

    Returns
    -------
    float
    """
    if 1 <= dof <= len(T975):
        return T975[dof - 1]
    from scipy.special import stdtrit

    return float(stdtrit(dof, 0.975))


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
    resid = yy - A @ coef
    s2 = float(resid @ resid) / dof
    cov = s2 * np.linalg.inv(A.T @ A)
    t = t975(dof)
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


__all__ = ["T975", "fit_with_errors", "t975", "trend_table_with_errors"]
