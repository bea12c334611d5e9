"""Explicit 3D surface mesh of the deformed tire (sections 5.2, 5.3; Figure 5-13).

The whole tire (360 degrees) is a ring of radial cross sections: inside the contact
patch the Rotta sections of the solver (bulge 1, flat contact segment, bulge 2),
beyond it the undeformed torus. Every section carries the same number of vertices
on each bulge, so neighbouring sections triangulate as quads; contact sections
also carry the contact segment, which fans into the single touching point of the
two end sections (the exact patch ends, where the width is zero). The patch edges
are therefore mesh vertices, and the contact faces lie on the support surface: each
section in contact is translated vertically onto it and its contact vertices are
snapped to it (a move of at most the patch's ``flatness``, the small non-flatness of
the 3D Rotta patch of a cambered tire, Figure 5-9).

Topology (vertex ring of one section, from bead 1 to bead 2)::

    contact section : bulge1[0..K] | contact[1..kc-1] | bulge2[0..K]   (2K + kc + 1)
    other section   : bulge1[0..K] | bulge2[1..K]                      (2K + 1)

Vertex data: ``radial_deformation`` (how far the carcass moved toward its section
centre, mm; negative where a bulge swells), ``lateral_displacement`` (ground ``y``
displacement of each carcass point, mm), ``contact`` (1 on the support surface),
``section`` (section index around the wheel).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _validate as v
from .patch import ContactPatch
from .surface import Drum


@dataclass(frozen=True)
class TireMesh:
    """A deformed-tire surface mesh and its per-vertex data.

    Attributes
    ----------
    mesh : trimesh.Trimesh
        Vertices in the ground frame [mm] (x forward, y lateral, z up).
    point_data : dict of (n_vertices,) arrays
        ``radial_deformation`` [mm], ``lateral_displacement`` [mm], ``contact`` (0/1),
        ``section`` (index around the wheel).
    face_contact : (n_faces,) bool
        Faces of the contact patch (built on the support surface).
    patch : ContactPatch
        The solver result the mesh was built from.
    section_phi : (n_sections,) float [rad]
        Section angles around the wheel.
    bead_vertices : (2, n_sections) int
        Vertex indices of the bead lines (the mesh's only open boundary, unless
        ``closed``).
    closed : bool
        Whether a rim band closes the beads (the mesh then encloses the air).
    """

    mesh: object
    point_data: dict = field(repr=False)
    face_contact: np.ndarray = field(repr=False)
    patch: ContactPatch = field(repr=False)
    section_phi: np.ndarray = field(repr=False)
    bead_vertices: np.ndarray = field(repr=False)
    closed: bool = False

    @property
    def n_faces(self) -> int:
        return len(self.mesh.faces)

    def surface_gap(self, points=None) -> np.ndarray:
        """Height of points (default: the vertices) above the support surface [mm]."""
        pts = self.mesh.vertices if points is None else np.asarray(points, float)
        return surface_gap(self.patch.surface, pts)

    def section_arc_lengths(self) -> np.ndarray:
        """Bead-to-bead polyline length of every section along the mesh [mm]."""
        return _ring_lengths(self)


def surface_gap(surface, points) -> np.ndarray:
    """Distance of ``points`` (n, 3) [mm] above the support surface (flat, disk: the
    plane z = 0; drum: the cylinder of the drum radius whose top line is x = z = 0)."""
    p = np.asarray(points, float)
    if isinstance(surface, Drum):
        rd = 0.5 * surface.diameter
        return np.hypot(p[:, 0], p[:, 2] + rd) - rd
    return p[:, 2].copy()


def surface_height(surface, x) -> np.ndarray:
    """Height z of the support surface at forward position ``x`` [mm]."""
    x = np.asarray(x, float)
    if isinstance(surface, Drum):
        rd = 0.5 * surface.diameter
        return -(x * x) / (rd + np.sqrt(np.maximum(rd * rd - x * x, 0.0)))
    return np.zeros_like(x)


def _undeformed(s, r0, s0, camber):
    """Section-frame position of carcass arc coordinate s (from bead 1) on the
    undeformed, cambered section circle."""
    sig = (s - 0.5 * s0) / r0
    x, z = r0 * np.sin(sig), -r0 * np.cos(sig)
    c, sn = np.cos(camber), np.sin(camber)
    return c * x + sn * z, -sn * x + c * z


def _contact_rings(sol, K: int, kc: int):
    """Section-frame points (n, 2K+kc+1) and arc coordinates of contact sections."""
    u = np.linspace(0.0, 1.0, K + 1)
    e1, e2 = sol.edge1[:, None], sol.edge2[:, None]
    r1, r2 = sol.radius1[:, None], sol.radius2[:, None]
    t1, t2 = sol.angle1[:, None], sol.angle2[:, None]
    zg = np.broadcast_to(sol.ground_z, sol.edge1.shape)[:, None]
    psi1 = t1 * (1.0 - u)  # bead -> edge
    b1x, b1z = e1 - r1 * np.sin(psi1), zg + r1 - r1 * np.cos(psi1)
    s_b1 = r1 * t1 * u
    w = e2 - e1
    v = np.linspace(0.0, 1.0, kc + 1)[1:-1]
    cx, cz = e1 + w * v, np.broadcast_to(zg, (len(e1), kc - 1))
    s_c = r1 * t1 + w * v
    psi2 = t2 * u  # edge -> bead
    b2x, b2z = e2 + r2 * np.sin(psi2), zg + r2 - r2 * np.cos(psi2)
    s_b2 = r1 * t1 + w + r2 * psi2
    xs = np.concatenate([b1x, cx, b2x], axis=1)
    zs = np.concatenate([b1z, cz, b2z], axis=1)
    ss = np.concatenate([s_b1, s_c, s_b2], axis=1)
    contact = np.zeros(xs.shape, bool)
    contact[:, K : K + kc + 1] = True
    return xs, zs, ss, contact


def _tip_rings(sol, K: int):
    """Rings of the two end sections (width 0: bulges meet at the touching point)."""
    xs, zs, ss, _ = _contact_rings(sol, K, 1)  # kc = 1: no interior contact points
    keep = np.r_[0 : K + 1, K + 2 : 2 * K + 2]
    contact = np.zeros((len(xs), 2 * K + 1), bool)
    contact[:, K] = True
    return xs[:, keep], zs[:, keep], ss[:, keep], contact


def _free_rings(n: int, K: int, r0, s0, theta0, camber):
    """Undeformed sections split at the lowest point of the cambered circle."""
    low = r0 * (np.pi - 0.5 * theta0 + camber)  # arc from bead 1 to the lowest point
    u = np.linspace(0.0, 1.0, K + 1)
    s = np.concatenate([low * u, low + (s0 - low) * u[1:]])
    xs, zs = _undeformed(s, r0, s0, camber)
    shape = (n, len(s))
    return (
        np.broadcast_to(xs, shape),
        np.broadcast_to(zs, shape),
        np.broadcast_to(s, shape),
        np.zeros(shape, bool),
    )


def _quads(a, b):
    """Triangles between two equal rings of vertex indices a, b (..., m)."""
    a0, a1, b0, b1 = a[..., :-1], a[..., 1:], b[..., :-1], b[..., 1:]
    t1 = np.stack([a0, a1, b1], axis=-1)
    t2 = np.stack([a0, b1, b0], axis=-1)
    return np.concatenate([t1.reshape(-1, 3), t2.reshape(-1, 3)])


def _transition(contact_ring, tip_ring, K: int, kc: int, tip_after: bool):
    """Faces between a contact ring and an end-section ring (the contact fans in)."""
    A, B = contact_ring, tip_ring
    faces = [
        _quads(A[: K + 1], B[: K + 1]),
        _quads(A[K + kc : 2 * K + kc + 1], B[K : 2 * K + 1]),
        np.column_stack([A[K : K + kc], A[K + 1 : K + kc + 1], np.full(kc, B[K])]),
    ]
    f = np.concatenate(faces)
    return f if tip_after else f[:, ::-1]


def build_mesh(
    patch: ContactPatch,
    *,
    n_around: int = 720,
    n_patch: int | None = None,
    bulge_points: int = 32,
    contact_points: int = 12,
    close_rim: bool = False,
    centreline=None,
) -> TireMesh:
    """Build the deformed tire as a triangle mesh.

    Parameters
    ----------
    patch : ContactPatch
        Solver result (``tiremesh.solve`` / ``solve_patch``).
    n_around : int
        Sections around the whole wheel (>= 16).
    n_patch : int, optional
        How many of them lie inside the contact patch, uniformly spaced between the
        exact ends (default ``n_around // 3``: the patch is meshed finer).
    bulge_points : int
        Segments along each side bulge (>= 4).
    contact_points : int
        Segments across the flat contact segment (>= 2).
    close_rim : bool
        Close the bead lines with a rim band (watertight mesh enclosing the air).
    centreline : (s, dh) arrays [mm], optional
        Lateral displacement of the tread centre line beyond the patch along the
        wheel (e.g. ``LateralResult.s, LateralResult.dh``, section 5.8): the free
        sections are shifted sideways by it, so meshes and renders show the
        deformation that decays away from the patch.

    Returns
    -------
    TireMesh
    """
    import trimesh

    if not isinstance(patch, ContactPatch):
        from .errors import InvalidParameter

        raise InvalidParameter("patch", type(patch).__name__, "a tiremesh.ContactPatch")
    n_around = v.integer("n_around", n_around, 16, 100_000)
    n_patch = v.integer("n_patch", n_around // 3 if n_patch is None else n_patch, 3, n_around - 8)
    K = v.integer("bulge_points", bulge_points, 4, 10_000)
    kc = v.integer("contact_points", contact_points, 2, 10_000)

    tire = patch.tire
    r0, s0, theta0, gam = tire.tire_radius, tire.arc_length, tire.rim_angle, patch.camber
    rear, front = patch.phi_ends
    # sections: rear end, n_patch - 2 contact sections, front end, then the free tire
    phi_c = np.linspace(rear, front, n_patch)[1:-1]
    n_free = n_around - n_patch
    phi_f = np.linspace(front, rear + 2 * np.pi, n_free + 2)[1:-1]
    ends, _ = patch.sections_at(np.array([rear, front]))
    sol_c, _ = patch.sections_at(phi_c)
    if np.any(sol_c.width <= 0):
        from .errors import TireModelError

        raise TireModelError("a section between the patch ends is out of contact (split patch)")

    xc, zc, sc, kcon = _contact_rings(sol_c, K, kc)
    xt, zt, st, tcon = _tip_rings(ends, K)
    xf, zf, sf, fcon = _free_rings(n_free, K, r0, s0, theta0, gam)
    if centreline is not None:
        cs_, cdh = (np.asarray(a, float) for a in centreline)
        R = tire.wheel_radius
        # free sections run forward from the front end; beyond half a turn, backward from the rear
        ahead = phi_f - front < np.pi
        s_pos = np.where(
            ahead, patch.x[-1] + R * (phi_f - front), patch.x[0] - R * (rear + 2 * np.pi - phi_f)
        )
        shift = np.interp(s_pos, cs_, cdh, left=0.0, right=0.0)
        xf = xf + shift[:, None]

    nc = len(phi_c)
    # vertex blocks: [rear tip | contact sections | front tip | free sections]
    blocks = [
        (xt[:1], zt[:1], st[:1], tcon[:1], np.array([rear])),
        (xc, zc, sc, kcon, phi_c),
        (xt[1:], zt[1:], st[1:], tcon[1:], np.array([front])),
        (xf, zf, sf, fcon, phi_f),
    ]
    pts, data_s, data_con, data_sec, phis, rings = [], [], [], [], [], []
    start, sec = 0, 0
    for bx, bz, bs, bcon, bphi in blocks:
        n, m = bx.shape
        bphi = np.broadcast_to(np.atleast_1d(bphi), (n,))
        X, Y, Z = patch.to_ground(bx, bz, bphi[:, None])
        if bcon.any():  # translate sections in contact onto the surface (<= flatness)
            gap = np.where(bcon, Z - surface_height(patch.surface, X), 0.0)
            Z = Z - (gap.sum(axis=1) / bcon.sum(axis=1))[:, None]
        pts.append(np.stack([X, Y, Z], -1).reshape(-1, 3))
        # per-vertex displacement against the same carcass point undeformed
        ux, uz = _undeformed(bs, r0, s0, gam)
        _, UY, _ = patch.to_ground(ux, uz, bphi[:, None])
        data_s.append(np.stack([(r0 - np.hypot(bx, bz)).ravel(), (Y - UY).ravel()], -1))
        data_con.append(bcon.ravel())
        data_sec.append(np.repeat(np.arange(sec, sec + n), m))
        phis.append(bphi)
        rings.append(start + np.arange(n * m).reshape(n, m))
        start += n * m
        sec += n
    vertices = np.concatenate(pts)
    contact = np.concatenate(data_con)
    # contact vertices exactly onto the support surface (the residual tilt across one
    # section is a tiny fraction of the patch `flatness`)
    vertices[contact, 2] = surface_height(patch.surface, vertices[contact, 0])
    rt, rc, ft, rf = rings[0][0], rings[1], rings[2][0], rings[3]

    faces = [
        _quads(rc[:-1], rc[1:]) if nc > 1 else np.empty((0, 3), int),
        _transition(rc[0], rt, K, kc, tip_after=False),
        _transition(rc[-1], ft, K, kc, tip_after=True),
        _quads(ft, rf[0]),
        _quads(rf[:-1], rf[1:]),
        _quads(rf[-1], rt),
    ]
    faces = np.concatenate(faces)
    face_contact = np.all(contact[faces], axis=1)

    # orient outward: normals point away from each section's centre
    centre = np.concatenate(
        [np.stack(patch.to_ground(np.zeros_like(p), np.zeros_like(p), p), -1) for p in phis]
    )
    sec_of_vertex = np.concatenate(data_sec)
    tri = vertices[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    away = tri.mean(axis=1) - centre[sec_of_vertex[faces[:, 0]]]
    if np.sum(np.einsum("ij,ij->i", normal, away) > 0) < 0.5 * len(faces):
        faces = faces[:, ::-1]

    # bead vertices of every section, in order around the wheel
    first = np.concatenate([[rt[0]], rc[:, 0], [ft[0]], rf[:, 0]])
    last = np.concatenate([[rt[-1]], rc[:, -1], [ft[-1]], rf[:, -1]])
    beads = np.stack([first, last])
    if close_rim:
        b1, b2 = beads[0], beads[1]
        n1, n2 = np.roll(b1, -1), np.roll(b2, -1)  # next section, wrapping around
        band = np.concatenate([np.column_stack([b1, n1, n2]), np.column_stack([b1, n2, b2])])
        mesh0 = trimesh.Trimesh(vertices, np.concatenate([faces, band]), process=False)
        if not mesh0.is_winding_consistent:
            band = band[:, ::-1]
        face_contact = np.concatenate([face_contact, np.zeros(len(band), bool)])
        faces = np.concatenate([faces, band])

    mesh = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
    ds = np.concatenate(data_s)
    point_data = {
        "radial_deformation": ds[:, 0],
        "lateral_displacement": ds[:, 1],
        "contact": contact.astype(np.uint8),
        "section": sec_of_vertex.astype(np.int32),
    }
    section_phi = np.concatenate(phis)
    return TireMesh(
        mesh=mesh,
        point_data=point_data,
        face_contact=face_contact,
        patch=patch,
        section_phi=section_phi,
        bead_vertices=beads,
        closed=close_rim,
    )


def _ring_lengths(tm_: TireMesh) -> np.ndarray:
    sec = tm_.point_data["section"]
    v = tm_.mesh.vertices
    same = sec[1:] == sec[:-1]
    seg = np.linalg.norm(np.diff(v, axis=0), axis=1)
    return np.bincount(sec[1:][same], weights=seg[same], minlength=sec.max() + 1)


def support_mesh(
    patch: ContactPatch,
    *,
    extent: float | None = None,
    thickness: float | None = None,
    sink: float = 0.0,
    resolution: int = 240,
):
    """Mesh of the support surface under the patch (for renders), as a slab.

    Flat ground and the disk (a plane; the disk's track is curved, not its surface)
    give a box; a drum gives a thick cylinder segment of its radius.

    Parameters
    ----------
    extent : float [mm], optional
        Half-size along x (default 0.6 x the wheel radius).
    thickness : float [mm], optional
        Slab thickness below the surface (default the tire radius).
    sink : float [mm]
        Lower the top face by this much (renders use a fraction of a mm so the contact
        faces, which lie exactly on the surface, do not z-fight with it).
    resolution : int
        Segments along x (the drum's facets must stay well below the patch).
    """
    import trimesh

    R, r0 = patch.tire.wheel_radius, patch.tire.tire_radius
    ext = 0.6 * R if extent is None else float(v.positive("extent", extent, unit="mm"))
    th = r0 if thickness is None else float(v.positive("thickness", thickness, unit="mm"))
    n = v.integer("resolution", resolution, 2, 100_000)
    half_y = 4.0 * r0
    if isinstance(patch.surface, Drum):
        rd = 0.5 * patch.surface.diameter
        ang = np.linspace(-ext / rd, ext / rd, n + 1)
        top = np.column_stack([(rd - sink) * np.sin(ang), (rd - sink) * np.cos(ang) - rd])
        bot = np.column_stack(
            [(rd - sink - th) * np.sin(ang), (rd - sink - th) * np.cos(ang) - rd]
        )
    else:
        x = np.linspace(-ext, ext, n + 1)
        top = np.column_stack([x, np.full_like(x, -sink)])
        bot = np.column_stack([x, np.full_like(x, -sink - th)])
    prof = np.concatenate([top, bot[::-1]])  # closed profile in (x, z)
    m = len(prof)
    verts = np.concatenate(
        [np.column_stack([prof[:, 0], np.full(m, y), prof[:, 1]]) for y in (-half_y, half_y)]
    )
    ring = np.arange(m)
    sides = _quads(np.append(ring, 0)[None, :], np.append(ring + m, m)[None, :])
    # end caps: the profile is a simple polygon; fan-free strip triangulation
    k = n + 1
    cap = np.concatenate(
        [
            np.column_stack([ring[: k - 1], ring[1:k], ring[m - 1 : m - k : -1][: k - 1]]),
            np.column_stack(
                [
                    ring[1:k],
                    ring[m - 2 : m - k - 1 : -1][: k - 1],
                    ring[m - 1 : m - k : -1][: k - 1],
                ]
            ),
        ]
    )
    faces = np.concatenate([sides, cap[:, ::-1], cap + m])
    mesh = trimesh.Trimesh(verts, faces, process=False)
    mesh.fix_normals()
    return mesh


def rim_mesh(tire_mesh: TireMesh, *, depth: float = 12.0):
    """A simple rim for renders: the bead lines joined by a rim bed sunk ``depth`` mm
    toward the axle."""
    import trimesh

    v_ = tire_mesh.mesh.vertices
    b1, b2 = v_[tire_mesh.bead_vertices[0]], v_[tire_mesh.bead_vertices[1]]
    # toward the axle: from the bead-line midpoint, the axle is at the wheel-plane origin
    axle = np.array([0.0, 0.0, -tire_mesh.patch.surface_z])
    mid = 0.5 * (b1 + b2)
    inward = axle - mid
    inward /= np.linalg.norm(inward, axis=1, keepdims=True)
    c1, c2 = b1 + depth * inward, b2 + depth * inward
    rings = [b1, c1, c2, b2]
    n = len(b1)
    verts = np.concatenate(rings)
    idx = np.arange(len(verts)).reshape(4, n)
    idx = np.concatenate([idx, idx[:, :1]], axis=1)  # close around the wheel
    faces = np.concatenate([_quads(idx[i], idx[i + 1]) for i in range(3)])
    return trimesh.Trimesh(verts, faces, process=False)


__all__ = ["TireMesh", "build_mesh", "rim_mesh", "support_mesh", "surface_gap", "surface_height"]
