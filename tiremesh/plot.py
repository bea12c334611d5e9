"""Matplotlib figures of the model: a cross section (Figure 5-5).

matplotlib is imported inside the functions, so ``import tiremesh`` stays fast.
"""

from __future__ import annotations

import numpy as np

from .case import LoadCase
from .solver import ContactPatch, solve


def section_curve(sections, index: int = 0, n: int = 200):
    """Points of one solved Rotta section (section 5.1, Figure 5-5) in the section
    frame: bulge 1 from its bead to edge ``e1``, then bulge 2 from edge ``e2`` to its
    bead (the straight step between them is the flat contact).

    Parameters
    ----------
    sections : SectionSolution
        Solved sections (any shape).
    index : int
        Flat index of the section to draw.
    n : int
        Points per bulge.

    Returns
    -------
    x, z : (2n,) float [mm]
    """
    s = sections
    e1, e2, r1, r2 = (float(np.ravel(a)[index]) for a in (s.edge1, s.edge2, s.radius1, s.radius2))
    t1, t2 = float(np.ravel(s.angle1)[index]), float(np.ravel(s.angle2)[index])
    zg = float(np.ravel(np.broadcast_to(s.ground_z, np.shape(s.edge1)))[index])
    p1 = np.linspace(t1, 0.0, n)
    p2 = np.linspace(0.0, t2, n)
    x = np.concatenate([e1 - r1 * np.sin(p1), e2 + r2 * np.sin(p2)])
    z = np.concatenate([zg + r1 - r1 * np.cos(p1), zg + r2 - r2 * np.cos(p2)])
    return x, z


def plot_section(patch: ContactPatch | LoadCase, phi: float = 0.0, ax=None):
    """Plot the Rotta section at angle ``phi`` (Figure 5-5): undeformed circle, rim,
    bulges, flat contact and ground, with the edges and radii annotated.

    Parameters
    ----------
    patch : ContactPatch or LoadCase
        The solved patch, or a load case to solve.
    phi : float [rad]
        Section angle from bottom dead centre.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib.pyplot as plt

    if isinstance(patch, LoadCase):
        patch = solve(patch)
    sol, _ = patch.sections_at(np.array([phi]))
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 5.5))
    r0, gam = patch.tire.tire_radius, patch.camber
    t = np.linspace(0, 2 * np.pi, 400)
    ax.plot(r0 * np.cos(t), r0 * np.sin(t), ":", color="0.6", lw=1, label="undeformed")
    x, z = section_curve(sol)
    ax.plot(x, z, color="C3", lw=2, label="Rotta section")
    (xb1,), (zb1,) = np.ravel(sol.bead1[0]), np.ravel(sol.bead1[1])
    (xb2,), (zb2,) = np.ravel(sol.bead2[0]), np.ravel(sol.bead2[1])
    ax.plot([xb1, xb2], [zb1, zb2], color="C0", lw=4, solid_capstyle="round", label="rim")
    zg = float(np.ravel(sol.ground_z)[0])
    ax.axhline(zg, color="0.3", lw=1)
    e1, e2 = float(sol.edge1[0]), float(sol.edge2[0])
    ax.plot([e1, e2], [zg, zg], color="k", lw=4, label=f"contact {e2 - e1:.2f} mm")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm] (toward side 2, +y)")
    ax.set_ylabel("z [mm]")
    ax.set_title(
        f"section at phi = {np.degrees(phi):.2f} deg, camber {np.degrees(gam):.1f} deg\n"
        f"e1 = {e1:.3f} mm, e2 = {e2:.3f} mm, r1 = {float(sol.radius1[0]):.3f} mm, "
        f"r2 = {float(sol.radius2[0]):.3f} mm",
        fontsize=9,
    )
    ax.legend(loc="upper right", fontsize=8)
    return ax
