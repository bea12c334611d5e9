"""The solved contact patch of one load case (sections 5.2, 5.3, 5.4 and 5.5)."""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass, field

import numpy as np

from ..case import LoadCase
from ..section import SectionSolution
from ..units import MPA_PER_BAR
from .arrays import CaseArrays, single_case_arrays
from .evaluate import PatchArrays
from .kinematics import section_to_ground, sections_at


@dataclass(frozen=True)
class ContactPatch:
    """Solved Rotta tire: per-section arrays, patch outline, forces.

    Units: mm, N, N/mm^2, rad. Ground frame: ``x`` forward, ``y`` toward section
    side 2 (the side the wheel top leans to for positive camber), ``z`` up.

    Attributes
    ----------
    case : LoadCase
        The load case solved (``tire``, ``pressure``, ``camber``, ``slip``,
        ``lateral``, ``surface`` are shortcuts to its fields).
    deflection : float [mm]
        Wheel displacement in its own plane (``delta_w``), given or found.
    slip_offset : float [mm]
        Lateral shift that puts the slip kinematics' anchor in place
        (``-x_lead tan(slip)`` for ``'leading'``, 0 for ``'centre'``).
    phi : (n,) float [rad]
        Section angles from bottom dead centre (Clenshaw-Curtis nodes between the
        exact patch ends).
    x : (n,) float [mm]
        Forward position of each section (``(R - dv) sin phi``).
    sections : SectionSolution
        Section geometry, arrays of shape (n,).
    outline : (2n + 1, 2) float [mm]
        Closed counter-clockwise patch polygon in ground ``(x, y)`` (first point
        repeated at the end).
    centerline : (n, 2) float [mm]
        Where each section's first-touching carcass point lies (Figure 5-8).
    length, width, area : float [mm, mm, mm^2]
        Extent along x, extent along y, and the ground area (equation 5-26).
    vertical_force, lateral_force : float [N]
        ``p * area`` (equation 5-26) and ``integral p (r1 - r2) dx`` (equation 5-25).
    disk_offset : float [mm]
        Track offset of section 5.3.2 (0 on a straight track).
    flatness : float [mm]
        Largest height of a patch edge above/below the central contact line
        (Figure 5-9: the 3D Rotta patch of a cambered tire is not exactly flat).
    surface_z : float [mm]
        Height of the support surface below the axle.
    phi_ends : (float, float) [rad]
        Rear and front patch-end angles.
    x_weights : (n,) float [mm]
        Quadrature weights along the patch: ``integral f dx = sum(x_weights * f)``.
    """

    case: LoadCase = field(repr=False)
    deflection: float
    slip_offset: float
    phi: np.ndarray = field(repr=False)
    x: np.ndarray = field(repr=False)
    sections: SectionSolution = field(repr=False)
    outline: np.ndarray = field(repr=False)
    centerline: np.ndarray = field(repr=False)
    length: float
    width: float
    area: float
    vertical_force: float
    lateral_force: float
    disk_offset: float
    flatness: float
    surface_z: float = 0.0
    phi_ends: tuple[float, float] = (0.0, 0.0)
    x_weights: np.ndarray = field(default=None, repr=False)

    tire = property(lambda self: self.case.tire, doc="Shortcut to ``case.tire``.")
    pressure = property(lambda self: self.case.pressure, doc="Shortcut to ``case.pressure``.")
    camber = property(lambda self: self.case.camber, doc="Shortcut to ``case.camber``.")
    slip = property(lambda self: self.case.slip, doc="Shortcut to ``case.slip``.")
    lateral = property(lambda self: self.case.lateral, doc="Shortcut to ``case.lateral``.")
    surface = property(lambda self: self.case.surface, doc="Shortcut to ``case.surface``.")

    @functools.cached_property
    def footprint(self):
        """The footprint the case asks for (:func:`tiremesh.footprint.footprint_of`):
        the patch itself for ``'rotta'``, the rounded print for ``'rounded'``."""
        from ..footprint import footprint_of

        return footprint_of(self)

    @property
    def net_force_orientation(self) -> float:
        """Angle of the ground reaction from the vertical, ``atan2(Fy, Fz)`` [rad]."""
        return float(np.arctan2(self.lateral_force, self.vertical_force))

    @property
    def sinkage(self) -> float:
        """Wheel deflection over rim height [-] (section 6.1.2 reports it in %)."""
        return self.deflection / self.tire.rim_height

    @property
    def lateral_force_density(self) -> np.ndarray:
        """dS/dx per section [N/mm], equation 5-25."""
        return self.sections.lateral_force_density(self.pressure)

    @property
    def vertical_force_density(self) -> np.ndarray:
        """dN/dx per section [N/mm], equation 5-26."""
        return self.sections.vertical_force_density(self.pressure)

    def arrays(self) -> CaseArrays:
        """This case as (1, 1) solver arrays (slip anchor included in ``lateral``).

        Returns
        -------
        CaseArrays
            One case, one surface; ``lateral`` [mm] includes ``slip_offset``.
        """
        cs = single_case_arrays(self.case)
        return cs.with_lateral(cs.lateral + self.slip_offset)

    def sections_at(self, phi) -> tuple[SectionSolution, np.ndarray]:
        """Rotta sections of this load case at any angles ``phi`` (n,) [rad], inside or
        beyond the patch (beyond it the edges cross: negative width).

        Parameters
        ----------
        phi : (n,) float [rad]
            Section angles from bottom dead centre (a scalar is one section).

        Returns
        -------
        sections : SectionSolution, arrays (n,)
        x : (n,) float [mm]
            Forward position ``(R - dv) sin phi``.
        """
        phi = np.atleast_1d(np.asarray(phi, float))[None, :]
        dw = np.array([[self.deflection]])
        sol, d = sections_at(phi, dw, self.arrays(), self.disk_offset, True)
        return _row(sol, 0, phi.shape), d.x[0]

    def to_ground(self, xs, zs, phi):
        """Section-frame points -> ground frame (z = 0 on the surface under the central
        section), see :func:`section_to_ground`.

        Parameters
        ----------
        xs, zs : (...) float [mm]
            Points in the section frame of :mod:`tiremesh.section`.
        phi : (...) float [rad]
            Section angle of each point.

        Returns
        -------
        x, y, z : (...) float [mm]
            Forward, lateral (toward side 2), up.
        """
        return section_to_ground(
            xs,
            zs,
            phi,
            tire_radius=self.tire.tire_radius,
            wheel_radius=self.tire.wheel_radius,
            camber=self.camber,
            ground_z=self.surface_z,
        )

    def __repr__(self) -> str:
        c = self.case
        return (
            f"ContactPatch({c.tire.name or 'tire'}, {c.pressure / MPA_PER_BAR:.4g} bar, "
            f"{self.vertical_force:.4g} N, {c.surface.spec}: length {self.length:.2f} mm, "
            f"width {self.width:.2f} mm, area {self.area:.1f} mm^2, "
            f"lateral force {self.lateral_force:.4g} N)"
        )

    def _repr_html_(self) -> str:
        """A summary table for notebooks."""
        return summary_html("ContactPatch", self.summary())

    def section_table(self) -> dict[str, np.ndarray]:
        """Per-section arrays with unit-carrying names (for tables and DataFrames).

        Returns
        -------
        dict of (n,) float arrays
            ``phi_rad, x_mm, edge1_mm, edge2_mm, width_mm, radius1_mm, radius2_mm,
            dv_mm, dh_mm, dS_N_per_mm, dN_N_per_mm, weight_mm``.
        """
        sec, n = self.sections, len(self.phi)
        cols = {
            "phi_rad": self.phi,
            "x_mm": self.x,
            "edge1_mm": sec.edge1,
            "edge2_mm": sec.edge2,
            "width_mm": sec.width,
            "radius1_mm": sec.radius1,
            "radius2_mm": sec.radius2,
            "dv_mm": sec.vert_deflection,
            "dh_mm": sec.horz_deflection,
            "dS_N_per_mm": self.lateral_force_density,
            "dN_N_per_mm": self.vertical_force_density,
            "weight_mm": self.x_weights,
        }
        return {k: np.broadcast_to(np.asarray(v, float), (n,)) for k, v in cols.items()}

    def to_dataframe(self):
        """:meth:`section_table` as a pandas DataFrame (pandas is optional).

        Returns
        -------
        pandas.DataFrame
            One row per section.
        """
        return _pandas().DataFrame(self.section_table())

    def summary(self) -> dict[str, float | str]:
        """Scalar results with unit-carrying names (for tables, JSON, CSV).

        Returns
        -------
        dict
            The tire (:meth:`TireGeometry.describe`), surface, pressure_bar,
            camber_deg, slip_deg, lateral_mm, deflection_mm, sinkage_pct, length_mm,
            width_mm, area_mm2, vertical_force_N, lateral_force_N,
            net_force_orientation_deg, disk_offset_mm, flatness_mm.
        """
        return {
            **self.tire.describe(),
            "surface": self.surface.describe(),
            "pressure_bar": self.pressure / MPA_PER_BAR,
            "camber_deg": float(np.degrees(self.camber)),
            "slip_deg": float(np.degrees(self.slip)),
            "lateral_mm": self.lateral,
            "deflection_mm": self.deflection,
            "sinkage_pct": 100.0 * self.sinkage,
            "length_mm": self.length,
            "width_mm": self.width,
            "area_mm2": self.area,
            "vertical_force_N": self.vertical_force,
            "lateral_force_N": self.lateral_force,
            "net_force_orientation_deg": float(np.degrees(self.net_force_orientation)),
            "disk_offset_mm": self.disk_offset,
            "flatness_mm": self.flatness,
        }


def summary_html(title: str, values: dict) -> str:
    """An HTML table of ``values`` (names with units, numbers to 5 significant
    figures), escaped, for ``_repr_html_``.

    Parameters
    ----------
    title : str
    values : dict

    Returns
    -------
    str
    """
    import html

    def cell(v):
        return f"{v:.5g}" if isinstance(v, float) else html.escape(str(v))

    rows = "".join(
        f"<tr><th style='text-align:left'>{html.escape(str(k))}</th>"
        f"<td style='text-align:right'>{cell(v)}</td></tr>"
        for k, v in values.items()
    )
    return f"<table><caption>{html.escape(title)}</caption>{rows}</table>"


def _pandas():
    try:
        import pandas as pd
    except ImportError as exc:  # optional dependency
        raise ImportError("to_dataframe needs pandas: pip install pandas") from exc
    return pd


def _row(sol: SectionSolution, i: int, shape) -> SectionSolution:
    """Row ``i`` of a SectionSolution of (m, n) arrays."""
    pick = lambda a: np.broadcast_to(a, shape)[i]
    return SectionSolution(
        **{
            f.name: (
                tuple(pick(a) for a in getattr(sol, f.name))
                if isinstance(getattr(sol, f.name), tuple)
                else pick(getattr(sol, f.name))
            )
            for f in dataclasses.fields(sol)
        }
    )


def patch_from_arrays(
    case: LoadCase, out: PatchArrays, i: int, deflection: float, slip_offset: float
) -> ContactPatch:
    """The :class:`ContactPatch` of one case of a vectorized solve.

    Parameters
    ----------
    case : LoadCase
        The load case of row ``i``.
    out : PatchArrays
        Solved patches, arrays (m, n) and (m,).
    i : int
        Row of ``out``.
    deflection : float [mm]
        Wheel deflection of the case.
    slip_offset : float [mm]
        Lateral shift of the slip anchor (``ContactPatch.slip_offset``).

    Returns
    -------
    ContactPatch
        Arrays (n,); the outline a closed (2n + 1, 2) polygon [mm].
    """
    x1, y1 = (a[i] for a in out.edge1_xy)
    x2, y2 = (a[i] for a in out.edge2_xy)
    ring = np.concatenate([np.column_stack([x1, y1]), np.column_stack([x2, y2])[::-1]])
    ring = np.vstack([ring, ring[:1]])
    z1, z2 = (a[i] for a in out.edge_z)
    return ContactPatch(
        case=case,
        deflection=float(deflection),
        slip_offset=float(slip_offset),
        phi=out.phi[i],
        x=out.x[i],
        sections=_row(out.sections, i, out.phi.shape),
        outline=ring,
        centerline=np.column_stack([out.centre_xy[0][i], out.centre_xy[1][i]]),
        length=float(out.length[i]),
        width=float(out.width[i]),
        area=float(out.area[i]),
        vertical_force=float(out.vertical_force[i]),
        lateral_force=float(out.lateral_force[i]),
        disk_offset=float(out.offset[i]),
        flatness=float(max(np.abs(z1).max(), np.abs(z2).max())),
        surface_z=float(out.surface_z[i]),
        phi_ends=(float(out.rear[i, 0]), float(out.front[i, 0])),
        x_weights=out.x_weights[i],
    )
