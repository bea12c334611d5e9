"""Public entry points of the solver: one load case (:func:`solve`) or many
(:func:`solve_many`), plus the load search on its own (:func:`find_sinkage`,
:func:`max_load`)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .. import validate as v
from .._tol import tol
from ..case import MAX_SECTIONS, CaseTable, LoadCase, slip_anchor
from ..errors import BulgeLimit, InvalidParameter, LoadTooHigh, NotConverged, TireModelError
from ..geometry import TireGeometry
from ..options import SolverOptions, using
from .arrays import (
    CaseArrays,
    case_arrays,
    group_by_surface,
    single_case_arrays,
    stack_surfaces,
)
from .evaluate import evaluate
from .kinematics import displacements, raise_case_errors
from .load import find_deflection, max_load_arrays
from .patch import ContactPatch, patch_from_arrays


def as_case(case, fields: dict) -> LoadCase:
    """A LoadCase from ``case`` (returned as is, with ``fields`` applied) or from a
    tire and keyword fields (the keyword convenience of every entry point).

    Parameters
    ----------
    case : LoadCase or TireGeometry
    fields : dict
        Load-case fields: applied with :meth:`LoadCase.replace` to a LoadCase, or
        the fields of a new case on a tire.

    Returns
    -------
    LoadCase

    Raises
    ------
    InvalidParameter
        ``case`` is neither a LoadCase nor a TireGeometry.
    """
    if isinstance(case, LoadCase):
        return case.replace(**fields) if fields else case
    if isinstance(case, TireGeometry):
        return LoadCase(case, **fields)
    raise InvalidParameter("case", case, "a LoadCase, or a TireGeometry with keyword fields")


def check_deflection(dw, cs: CaseArrays, name: str = "deflection"):
    """``dw`` as given if no case exceeds its largest deflection, else InvalidParameter.

    Only the upper bound (:meth:`CaseArrays.max_deflection`) is checked here;
    ``dw > 0`` is validated where a deflection is given (LoadCase, solve_many).

    Parameters
    ----------
    dw : (m, 1) float [mm]
        Wheel deflection.
    cs : CaseArrays
    name : str
        Parameter named in the error.

    Returns
    -------
    dw : (m, 1) float [mm]

    Raises
    ------
    InvalidParameter
        For the first case with ``dw > cs.max_deflection()``.
    """
    dmax = cs.max_deflection()
    if np.any(dw > dmax):
        i = int(np.argmax((dw > dmax).ravel()))
        raise InvalidParameter(
            name,
            float(dw.flat[i]),
            f"0 < {name} <= {float(dmax.flat[i]):.6g} mm",
            "a bead would reach the support surface or a bulge run out of carcass",
        )
    return dw


@dataclass(frozen=True)
class Solved:
    """Deflection-level solution of m cases on one surface (before the patch
    integrals at the requested section count).

    Attributes
    ----------
    cs : CaseArrays
        The cases, the slip anchor offset included in ``lateral``.
    dw : (m, 1) float [mm]
        Wheel deflection.
    ends : (rear, front) of (m, 1) float [rad], or None (not yet solved)
    track_offset : (m, 1) float [mm], or None
        Offset of a curved track (section 5.3.2), with ``ends``.
    slip_offset : (m, 1) float [mm]
        Lateral shift of the ``'leading'`` slip kinematics.
    """

    cs: CaseArrays
    dw: np.ndarray
    ends: tuple | None
    track_offset: np.ndarray | None
    slip_offset: np.ndarray

    def evaluate(self, n: int):
        """The patches with ``n`` sections (:func:`evaluate`).

        Parameters
        ----------
        n : int
            Sections (Clenshaw-Curtis nodes) between the exact patch ends, >= 3.

        Returns
        -------
        PatchArrays
            Per-section arrays (m, n), per-case results (m,).
        """
        return evaluate(self.cs, self.dw, n, ends=self.ends, offset=self.track_offset)


def check_room(cs: CaseArrays) -> None:
    """Raise :class:`BulgeLimit` if a case leaves no deflection room at all: its
    camber and lateral displacement already use up a side bulge's carcass.

    Parameters
    ----------
    cs : CaseArrays

    Returns
    -------
    None
    """
    dmax = cs.max_deflection()
    bad = ~(dmax > 0)
    if np.any(bad):
        i = int(np.argmax(bad.ravel()))
        name = "lateral" if cs.lateral[i, 0] else "camber"
        value = float((cs.lateral if name == "lateral" else cs.gamma)[i, 0])
        raise BulgeLimit(
            name,
            value,
            "a value that leaves a side bulge carcass to deflect with",
            {"case": i, "largest_deflection_mm": float(dmax[i, 0])},
        )


def _deflection(cs: CaseArrays, load, deflection, start=None):
    check_room(cs)
    if load is not None:
        return find_deflection(cs, load, start=start)
    return check_deflection(deflection, cs), None, None


def solve_arrays(cs: CaseArrays, *, load=None, deflection=None, anchor=None, start=None) -> Solved:
    """Wheel deflection, patch ends and slip anchor offset of m cases on one surface.

    Parameters
    ----------
    cs : CaseArrays
    load, deflection : (m, 1) float [N, mm]
        Exactly one given.
    anchor : (m, 1) float [mm], optional
        Where a slipping tread is undisplaced, as a distance ahead of the leading edge
        (:func:`tiremesh.case.slip_anchor`: 0 for ``'leading'``, the decay length for
        ``'relaxation'``, NaN for the appendix's ``'centre'`` turn). The lateral
        displacement is shifted by ``-(x_lead + anchor) tan(slip)`` (a fixed point,
        solved to ``tol.disk_offset_atol``). Default: 0 for every case.

    Returns
    -------
    Solved
    """
    ta = np.tan(cs.slip)
    ahead = np.zeros_like(cs.r0) if anchor is None else np.asarray(anchor, float)
    active = (ta != 0) & np.isfinite(ahead)
    ahead = np.where(active, ahead, 0.0)
    offset = np.zeros_like(cs.r0)
    cs_k = cs.with_lateral(cs.lateral)
    dw, ends, track = _deflection(cs_k, load, deflection, start)
    if not np.any(active):
        return Solved(cs_k, dw, ends, track, offset)
    if ends is None:
        ends, track = evaluate(cs_k, dw, 9).ends_and_offset()
    ends, prev = (ends[0].copy(), ends[1].copy()), None
    for _ in range(tol.max_iter):
        x_front = displacements(ends[1], dw, cs_k, 0.0).x
        g = offset + np.where(active, (x_front + ahead) * ta, 0.0)  # dh = lateral at the anchor
        todo = np.nonzero(np.abs(g[:, 0]) > tol.disk_offset_atol)[0]
        if todo.size == 0:
            return Solved(cs_k, dw, ends, track, offset)
        step = -g  # fixed-point step, then secant steps (the map is smooth and monotone)
        if prev is not None:
            with np.errstate(divide="ignore", invalid="ignore"):
                secant = -g * (offset - prev[0]) / (g - prev[1])
            step = np.where(np.isfinite(secant), secant, step)
        prev = (offset.copy(), g)
        offset[todo] += step[todo]
        cs_k = cs.with_lateral(cs.lateral + offset)
        # only the cases still moving are solved again: the others keep their solution
        _resolve(cs_k, todo, (load, deflection), (dw, ends, track))
    bad = np.nonzero(np.abs(g[:, 0]) > tol.disk_offset_atol)[0]
    raise_case_errors(
        {
            int(i): NotConverged(
                "leading-edge slip anchor", {"case": int(i), "offset_mm": float(offset[i, 0])}
            )
            for i in bad
        }
    )


def _resolve(cs_k: CaseArrays, todo, given, state) -> None:
    """Solve the cases ``todo`` of ``cs_k`` again, in place in ``state`` =
    ``(dw, (rear, front), track)``; their errors name the cases in ``cs_k``."""
    load, deflection = given
    dw, ends, track = state
    pick = lambda a: None if a is None else a[todo]
    sub = cs_k.take(todo)
    warm = (dw[todo], (ends[0][todo], ends[1][todo])) if load is not None else None
    try:
        dw_t, ends_t, track_t = _deflection(sub, pick(load), pick(deflection), warm)
    except TireModelError as exc:
        named = getattr(exc, "case_errors", None)
        if named:
            for err in named.values():
                if isinstance(getattr(err, "state", None), dict) and "case" in err.state:
                    err.state["case"] = int(todo[err.state["case"]])
            exc.case_errors = {int(todo[k]): e for k, e in named.items()}
            exc.partial = None  # the warm start of the subset does not fit the group
        raise
    if ends_t is None:
        ends_t, track_t = evaluate(sub, dw_t, 9).ends_and_offset()
    dw[todo], ends[0][todo], ends[1][todo] = dw_t, ends_t[0], ends_t[1]
    if track is not None and track_t is not None:
        track[todo] = track_t


def solve(
    case: LoadCase | TireGeometry, /, *, options: SolverOptions | None = None, **fields
) -> ContactPatch:
    """Solve the 3D Rotta model for one load case (sections 5.2, 5.3, 5.4 and 5.5).

    Parameters
    ----------
    case : LoadCase or TireGeometry
        The load case; or a tire, with the other :class:`LoadCase` fields as keywords
        (``pressure``, ``load`` or ``deflection``, ``camber``...).
    options : SolverOptions, optional
        Judgement thresholds (:class:`tiremesh.SolverOptions`); default: those of the
        enclosing call, or the defaults.
    **fields
        Load-case fields (applied with :meth:`LoadCase.replace` when ``case`` is a
        LoadCase).

    Returns
    -------
    ContactPatch

    Examples
    --------
    >>> import tiremesh as tm
    >>> patch = tm.solve(tm.get_tire(1), pressure=0.4, load=400.0)
    >>> round(patch.vertical_force, 6)
    400.0
    """
    case = as_case(case, fields)
    with using(options):
        cs = single_case_arrays(case)
        load = None if case.load is None else np.array([[case.load]])
        dw0 = None if case.deflection is None else np.array([[case.deflection]])
        anchor = np.array([[slip_anchor(case.slip_kinematics, case.relaxation)]])
        sv = solve_arrays(cs, load=load, deflection=dw0, anchor=anchor)
        out = sv.evaluate(case.n_sections)
    return patch_from_arrays(case, out, 0, float(sv.dw[0, 0]), float(sv.slip_offset[0, 0]))


def solve_patch(case: LoadCase | TireGeometry, deflection: float | None = None, /, **fields):
    """:func:`solve` at a given wheel ``deflection`` (keyword convenience).

    Parameters
    ----------
    case : LoadCase or TireGeometry
    deflection : float [mm], optional
        Replaces the case's load; None keeps the case's load or deflection.
    **fields
        Load-case fields, as for :func:`solve`.

    Returns
    -------
    ContactPatch
    """
    if deflection is not None:
        fields = {**fields, "deflection": deflection, "load": None}
    return solve(case, **fields)


def find_sinkage(
    case: LoadCase | TireGeometry,
    load: float | None = None,
    /,
    *,
    options: SolverOptions | None = None,
    **fields,
) -> float:
    """Wheel deflection [mm] at which the tire carries the case's load (Appendix C
    ``find_sinkage``).

    Parameters
    ----------
    case : LoadCase or TireGeometry
        With ``load`` given here or in the case.
    load : float [N], optional
    options : SolverOptions, optional
        Judgement thresholds (:class:`tiremesh.SolverOptions`); default: those of the
        enclosing call, or the defaults.
    **fields
        Load-case fields.

    Returns
    -------
    deflection : float [mm]

    Raises
    ------
    LoadTooHigh
        The load exceeds what the tire carries before a bead reaches the surface;
        ``.max_load`` holds that largest load [N].
    """
    if load is not None:
        fields = {**fields, "load": load, "deflection": None}
    case = as_case(case, fields)
    if case.load is None:
        raise InvalidParameter("load", None, "> 0 N (find_sinkage needs a load)")
    with using(options):
        sv = solve_arrays(
            single_case_arrays(case),
            load=np.array([[case.load]]),
            anchor=np.array([[slip_anchor(case.slip_kinematics, case.relaxation)]]),
        )
    return float(sv.dw[0, 0])


def max_load(
    case: LoadCase | TireGeometry, /, *, options: SolverOptions | None = None, **fields
) -> float:
    """Largest vertical load the model carries at this pressure: ``p A`` at
    :meth:`CaseArrays.max_deflection` (``options.rim_clearance`` times the deflection at
    which a bead reaches the surface or a side bulge runs out of carcass).

    Parameters
    ----------
    case : LoadCase or TireGeometry
        The case's own load or deflection is not used; a tire needs neither.
    options : SolverOptions, optional
        Judgement thresholds (:class:`tiremesh.SolverOptions`); default: those of the
        enclosing call, or the defaults.
    **fields
        Load-case fields (``pressure``, ``camber``...).

    Returns
    -------
    float [N]
    """
    if isinstance(case, TireGeometry) and "load" not in fields and "deflection" not in fields:
        fields = {**fields, "deflection": 1.0}
    case = as_case(case, fields)
    with using(options):
        fmax = max_load_arrays(single_case_arrays(case), tol.search_sections)[0]
    return float(fmax[0, 0])


RESULT_KEYS = (
    "deflection",
    "length",
    "width",
    "area",
    "vertical_force",
    "lateral_force",
    "net_force_orientation",
    "sinkage",
)


def _solve_group(table: CaseTable, n: int, start=None) -> dict[str, np.ndarray]:
    cs = case_arrays(table, stack_surfaces(table.surface))
    col = lambda a: a.reshape(-1, 1)
    by_load = not np.all(np.isnan(table.load))
    load = col(table.load) if by_load else None
    dw0 = None if by_load else v.positive("deflection", col(table.deflection), unit="mm")
    anchor = None if table.slip_anchor is None else col(table.slip_anchor)
    sv = solve_arrays(cs, load=load, deflection=dw0, anchor=anchor, start=start)
    cs, dw = sv.cs, sv.dw
    out = sv.evaluate(n)
    return {
        "deflection": dw[:, 0],
        "length": out.length,
        "width": out.width,
        "area": out.area,
        "vertical_force": out.vertical_force,
        "lateral_force": out.lateral_force,
        "net_force_orientation": np.arctan2(out.lateral_force, out.vertical_force),
        "sinkage": dw[:, 0] / cs.rim_height[:, 0],
    }


def _prescreen(table: CaseTable) -> dict[int, str]:
    """Flag, vectorized and before any search, the cases that cannot solve: no
    deflection room (camber or lateral displacement use up a bulge) and loads
    beyond what the tire carries. Returns ``{row: message}``."""
    cs = case_arrays(table, stack_surfaces(table.surface))
    flagged: dict[int, str] = {}
    for i in np.nonzero(~(cs.max_deflection()[:, 0] > 0))[0]:
        try:
            check_room(cs.take(np.array([i])))
        except BulgeLimit as exc:
            flagged[int(i)] = f"BulgeLimit: {exc}"
    rest = np.array([i for i in range(len(table)) if i not in flagged], int)
    if rest.size == 0 or np.all(np.isnan(table.load)):
        return flagged
    while True:  # cases that fail even at the largest deflection: left to the solve
        try:
            fmax, _ = max_load_arrays(cs.take(rest), tol.search_sections)
            break
        except TireModelError as exc:
            named = getattr(exc, "case_errors", None)
            if not named:
                return flagged
            rest = np.delete(rest, list(named))  # at least one case fewer each time
            if rest.size == 0:
                return flagged
    for j in np.nonzero(table.load[rest] > fmax[:, 0])[0]:
        i = int(rest[j])
        flagged[i] = f"LoadTooHigh: {LoadTooHigh('load', float(table.load[i]), float(fmax[j, 0]))}"
    return flagged


def _solve_isolating(table: CaseTable, n: int, out: dict, rows, errors: dict, start=None) -> None:
    """Solve ``table`` as one vectorized group. Cases the solver names as failed
    (``case_errors``) are recorded and the rest solved again; an error that names no
    case splits the group in halves until the failing case is alone. A case's result
    never depends on its companions, and the good cases stay vectorized."""
    try:
        got = _solve_group(table, n, start)
    except TireModelError as exc:
        named = getattr(exc, "case_errors", None) or {}
        if len(table) == 1:
            named = {0: exc}
        if named:
            for i, err in named.items():
                errors[int(rows[i])] = f"{type(err).__name__}: {err}"
            keep = np.setdiff1d(np.arange(len(table)), list(named))
            partial = getattr(exc, "partial", None)
            warm = (
                None
                if partial is None
                else (
                    partial[0][keep],
                    tuple(e[keep] for e in partial[1]),
                    *(p[keep] for p in partial[2:]),
                )
            )
            if keep.size:
                _solve_isolating(table.take(keep), n, out, rows[keep], errors, warm)
            return
        half = len(table) // 2
        for part in (np.arange(half), np.arange(half, len(table))):
            _solve_isolating(table.take(part), n, out, rows[part], errors)
        return
    for k in RESULT_KEYS:
        out[k][rows] = got[k]


def solve_many(
    cases: CaseTable | Sequence[LoadCase] | None = None,
    *,
    n_sections: int = 65,
    errors: str = "raise",
    chunk_size: int = 2048,
    options: SolverOptions | None = None,
    **columns,
) -> dict[str, np.ndarray]:
    """Solve many load cases at once, vectorized.

    Parameters
    ----------
    cases : CaseTable or sequence of LoadCase, optional
        The cases; or give ``columns`` instead, the keyword arguments of
        :meth:`CaseTable.from_columns` (``tire_radius``, ``rim_width``, ``pressure``,
        ``load`` or ``deflection``, ``camber``, ``slip``, ``lateral``,
        ``bead_seat_diameter``, ``surface``), broadcast together like numpy.
    n_sections : int
        Sections per patch (Clenshaw-Curtis), 9 .. 20001.
    errors : {'raise', 'flag'}
        ``'raise'``: the first case outside the model's domain raises its
        :class:`TireModelError`. ``'flag'``: such cases get NaN results, their
        message in ``error`` and ``ok = False``; the others are solved as if alone.
    chunk_size : int
        Cases solved together at most (bounds the memory: about 50 kB per case at
        65 sections).
    options : SolverOptions, optional
        Judgement thresholds (:class:`tiremesh.SolverOptions`); default: those of the
        enclosing call, or the defaults.
    **columns
        Columns of :meth:`CaseTable.from_columns` (when ``cases`` is None).

    Returns
    -------
    dict of (m,) arrays
        ``deflection [mm], length [mm], width [mm], area [mm^2], vertical_force [N],
        lateral_force [N], net_force_orientation [rad], sinkage [-]``; with
        ``errors='flag'`` also ``ok`` (bool) and ``error`` (str, empty when ok).
    """
    n = v.integer("n_sections", n_sections, 9, MAX_SECTIONS)
    chunk = v.integer("chunk_size", chunk_size, 1, 10**7)
    if errors not in ("raise", "flag"):
        raise InvalidParameter("errors", errors, "'raise' or 'flag'")
    if cases is None:
        table = CaseTable.from_columns(**columns)
    elif isinstance(cases, CaseTable):
        table = cases
    else:
        table = CaseTable.from_cases(list(cases))
    result = {k: np.full(len(table), np.nan) for k in RESULT_KEYS}
    messages: dict[int, str] = {}
    by_load = ~np.isnan(table.load)
    with using(options):
        for kind in (by_load, ~by_load):  # load cases and deflection cases apart
            sub_idx = np.nonzero(kind)[0]
            for rows in group_by_surface(table.take(sub_idx)):
                rows = sub_idx[rows]
                for start in range(0, rows.size, chunk):
                    _solve_chunk(table, rows[start : start + chunk], n, errors, result, messages)
    if errors == "flag":
        result["ok"] = np.ones(len(table), bool)
        result["error"] = np.full(len(table), "", dtype=object)
        for i, msg in messages.items():
            result["ok"][i], result["error"][i] = False, msg
    return result


def _solve_chunk(table, rows, n, errors, result, messages) -> None:
    sub = table.take(rows)
    if errors == "raise":
        got = _solve_group(sub, n)
        for k in RESULT_KEYS:
            result[k][rows] = got[k]
        return
    flagged = _prescreen(sub)
    messages.update({int(rows[i]): msg for i, msg in flagged.items()})
    keep = np.array([i for i in range(len(sub)) if i not in flagged], int)
    if keep.size:
        _solve_isolating(sub.take(keep), n, result, rows[keep], messages)
