"""Load cases as broadcast arrays for the vectorized solver.

A :class:`CaseArrays` holds ``m`` load cases on one support surface, each parameter
of shape (m, 1) so that per-section arrays (m, n) broadcast against it. Cases on
different surfaces are solved in separate groups (:func:`group_by_surface`), so one
case's surface never changes how its batch companions are solved.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..case import CaseTable, LoadCase
from ..geometry import arc_length, rim_angle
from ..options import active
from ..section import bead_positions
from ..surface import Surface


@dataclass(frozen=True)
class CaseArrays:
    """Parameters of m load cases on one surface, each of shape (m, 1).

    Attributes
    ----------
    r0, w : (m, 1) float [mm]
        Tire radius and rim width.
    R : (m, 1) float [mm]
        Axle height of the unloaded wheel, ``D_bead / 2 + h`` (``h`` of equation 5-3).
    gamma, slip : (m, 1) float [rad]
    lateral : (m, 1) float [mm]
    pressure : (m, 1) float [N/mm^2]
    surface : Surface
    appendix_forces : (m, 1) bool, optional
        Cases whose lateral force uses Appendix C's length element
        (``force_convention='appendix'``).
    """

    r0: np.ndarray
    w: np.ndarray
    R: np.ndarray
    gamma: np.ndarray
    slip: np.ndarray
    lateral: np.ndarray
    pressure: np.ndarray
    surface: Surface
    appendix_forces: np.ndarray | None = None

    @property
    def m(self) -> int:
        """Number of cases."""
        return self.r0.shape[0]

    @property
    def rim_height(self) -> np.ndarray:
        """Rim height ``r0 + sqrt(r0^2 - w^2 / 4)`` (m, 1) [mm], equation 5-3."""
        return self.r0 + np.sqrt(self.r0**2 - 0.25 * self.w**2)

    def with_lateral(self, lateral) -> CaseArrays:
        """The same cases with another lateral displacement (m, 1) [mm].

        Parameters
        ----------
        lateral : (m, 1) float [mm]

        Returns
        -------
        CaseArrays
        """
        return dataclasses.replace(self, lateral=lateral)

    def take(self, index) -> CaseArrays:
        """The cases ``index`` (int array) as new arrays.

        Parameters
        ----------
        index : (k,) int

        Returns
        -------
        CaseArrays
            ``k`` cases, parameters (k, 1).
        """
        pick = lambda a: a[index]
        return CaseArrays(
            *(
                pick(getattr(self, f))
                for f in ("r0", "w", "R", "gamma", "slip", "lateral", "pressure")
            ),
            take_surface(self.surface, index),
            None if self.appendix_forces is None else self.appendix_forces[index],
        )

    def max_deflection(self) -> np.ndarray:
        """Largest wheel deflection (m, 1) [mm] before a bead reaches the ground or a
        bulge runs out of carcass at the central section, times the active
        :attr:`SolverOptions.rim_clearance <tiremesh.SolverOptions>`.

        Returns
        -------
        (m, 1) float [mm]
        """
        cg, sg = np.cos(self.gamma), np.sin(self.gamma)
        xb1, zb1, xb2, zb2 = bead_positions(self.r0, self.w, self.gamma)
        limit = (np.minimum(zb1, zb2) + self.r0) / cg
        half_s0 = 0.5 * arc_length(self.r0, rim_angle(self.w, self.r0))
        delta = self.r0 * self.gamma
        c1_room = half_s0 + delta + xb1 - self.lateral  # c1 > 0 -> dv tan g < c1_room
        c2_room = half_s0 - delta - xb2 + self.lateral  # c2 > 0 -> dv tan g > -c2_room
        with np.errstate(all="ignore"):
            lim1 = np.where(sg > 0, c1_room / sg, np.inf)
            lim2 = np.where(sg < 0, -c2_room / sg, np.inf)
        return active().rim_clearance * np.minimum(limit, np.minimum(lim1, lim2))


def case_arrays(table: CaseTable, surface: Surface) -> CaseArrays:
    """Solver arrays of all rows of ``table``.

    Parameters
    ----------
    table : CaseTable
        m load cases (columns (m,)), all on ``surface``.
    surface : Surface

    Returns
    -------
    CaseArrays
        Each parameter (m, 1); ``R = D_bead / 2 + h`` [mm] with ``h`` of equation 5-3.
    """
    r0, w = table.tire_radius, table.rim_width
    R = 0.5 * table.bead_seat_diameter + r0 + np.sqrt(r0**2 - 0.25 * w**2)
    col = lambda a: np.asarray(a, float).reshape(-1, 1)
    return CaseArrays(
        col(r0),
        col(w),
        col(R),
        col(table.camber),
        col(table.slip),
        col(table.lateral),
        col(table.pressure),
        surface,
        np.array([c == "appendix" for c in table.force_convention], bool).reshape(-1, 1)
        if table.force_convention
        else None,
    )


def single_case_arrays(case: LoadCase) -> CaseArrays:
    """Solver arrays of one load case.

    Parameters
    ----------
    case : LoadCase

    Returns
    -------
    CaseArrays
        Each parameter (1, 1).
    """
    return case_arrays(CaseTable.from_cases([case]), case.surface)


def group_by_surface(table: CaseTable) -> list[np.ndarray]:
    """Row indices of ``table`` in groups that one vectorized solve can take:
    cases on surfaces of one class that stacks (:meth:`SurfaceBase.stack`), else on
    equal surfaces; in first-seen order.

    Parameters
    ----------
    table : CaseTable

    Returns
    -------
    list of (k,) int
        One array of row indices per group.
    """
    groups: dict = {}
    for i, s in enumerate(table.surface):
        key = type(s) if getattr(type(s), "stack_fields", ()) else s
        groups.setdefault(key, []).append(i)
    return [np.asarray(idx) for idx in groups.values()]


def take_surface(surface: Surface, index) -> Surface:
    """The cases ``index`` of a stacked surface (fields (m, 1) arrays); a plain
    surface is shared by all cases and returned as is.

    Parameters
    ----------
    surface : Surface
    index : (k,) int

    Returns
    -------
    Surface
    """
    fields = getattr(type(surface), "stack_fields", ())
    if not fields or np.ndim(getattr(surface, fields[0])) == 0:
        return surface
    out = object.__new__(type(surface))
    for f in fields:
        object.__setattr__(out, f, getattr(surface, f)[index])
    return out


def stack_surfaces(surfaces) -> Surface:
    """One surface for a group from :func:`group_by_surface` (see
    :meth:`SurfaceBase.stack`).

    Parameters
    ----------
    surfaces : sequence of Surface
        One per case.

    Returns
    -------
    Surface
    """
    first = surfaces[0]
    stack = getattr(type(first), "stack", None)
    stacked = stack(list(surfaces)) if stack is not None else None
    if stacked is None:
        if any(s != first for s in surfaces):
            raise ValueError("surfaces of one group must stack or be equal")
        return first
    return stacked
