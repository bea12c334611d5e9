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

The support surface enters only through its :class:`~tiremesh.surface.Surface`
methods (``height``, ``gap``, ``roll``), so any surface, including one defined
outside the package, meshes the same way.

:func:`build_mesh` runs in named steps, each with a small frozen result:
:func:`mesh_resolution` (:class:`MeshResolution`), :func:`plan_sections`
(:class:`SectionPlan`), :func:`section_rings` (:class:`SectionRings` of
:class:`RingBlock`), :func:`place_vertices` (:class:`PlacedVertices`),
:func:`tire_faces` and :func:`close_beads`.

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

from . import validate as v
from .case import LoadCase
from .errors import InvalidParameter, TireModelError
from .solver import ContactPatch


@dataclass(frozen=True)
class TireMesh:
    """A deformed-tire surface mesh and its per-vertex data.

    Attributes
    ----------
    mesh : trimesh.Trimesh
        Vertices in the ground frame [mm] (x forward, y lateral, z up).
    point_data : dict of (n_vertices,) arrays
        ``radial_deformation`` [mm], ``lateral_displacement`` [mm], ``contact`` (0/1),
        ``footprint`` (0/1, only for a rounded footprint: :func:`footprint_points`),
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
        """Number of triangles."""
        return len(self.mesh.faces)

    def surface_gap(self, points=None) -> np.ndarray:
        """Height of points above the support surface (``surface.gap``).

        Parameters
        ----------
        points : (n, 3) float [mm], optional
            Ground-frame points; default: the mesh vertices.

        Returns
        -------
        (n,) float [mm]
            Positive above the surface, negative below.
        """
        pts = self.mesh.vertices if points is None else np.asarray(points, float)
        return self.patch.surface.gap(pts)

    def section_arc_lengths(self) -> np.ndarray:
        """Bead-to-bead polyline length of every section along the mesh.

        Returns
        -------
        (n_sections,) float [mm]
            Close to the carcass arc length ``s0`` (the carcass does not stretch).
        """
        return _ring_lengths(self)


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


def as_patch(source) -> ContactPatch:
    """The :class:`ContactPatch` to mesh.

    Parameters
    ----------
    source : ContactPatch or LoadCase
        A solved patch (returned as is) or a load case (solved with
        :func:`tiremesh.solve`).

    Returns
    -------
    ContactPatch

    Raises
    ------
    InvalidParameter
        ``source`` is neither.
    """
    if isinstance(source, ContactPatch):
        return source
    if isinstance(source, LoadCase):
        from .solver import solve

        return solve(source)
    raise InvalidParameter(
        "patch", type(source).__name__, "a tiremesh.ContactPatch or a tiremesh.LoadCase"
    )


@dataclass(frozen=True)
class MeshResolution:
    """Validated mesh resolution (see :func:`build_mesh`).

    Attributes
    ----------
    n_around : int
        Sections around the whole wheel.
    n_patch : int
        Of which between (and including) the patch ends.
    bulge_points : int
        Segments along each side bulge (``K``).
    contact_points : int
        Segments across the contact segment (``kc``).
    """

    n_around: int
    n_patch: int
    bulge_points: int
    contact_points: int


def mesh_resolution(n_around=720, n_patch=None, bulge_points=32, contact_points=12):
    """Check the resolution arguments of :func:`build_mesh`.

    Parameters
    ----------
    n_around : int [-]
        Sections around the whole wheel, 16 .. 100000.
    n_patch : int [-], optional
        Of which between (and including) the patch ends, 3 .. ``n_around - 8``
        (default ``n_around // 3``).
    bulge_points : int [-]
        Segments along each side bulge, 4 .. 10000.
    contact_points : int [-]
        Segments across the contact segment, 2 .. 10000.

    Returns
    -------
    MeshResolution

    Raises
    ------
    InvalidParameter
        A value that is not an integer in its range.
    """
    n_around = v.integer("n_around", n_around, 16, 100_000)
    n_patch = v.integer("n_patch", n_around // 3 if n_patch is None else n_patch, 3, n_around - 8)
    return MeshResolution(
        n_around,
        n_patch,
        v.integer("bulge_points", bulge_points, 4, 10_000),
        v.integer("contact_points", contact_points, 2, 10_000),
    )


@dataclass(frozen=True)
class SectionPlan:
    """Section angles around the wheel, in mesh order.

    Attributes
    ----------
    rear : float [rad]
        Rear patch end (a section of zero width).
    contact : (n_patch - 2,) float [rad]
        Contact sections strictly between the ends, uniformly spaced.
    front : float [rad]
        Front patch end.
    free : (n_around - n_patch,) float [rad]
        Free (undeformed) sections, forward from the front end round to the rear
        end (``rear + 2 pi``).
    """

    rear: float
    contact: np.ndarray = field(repr=False)
    front: float
    free: np.ndarray = field(repr=False)


def plan_sections(patch: ContactPatch, res: MeshResolution) -> SectionPlan:
    """Place ``res.n_patch`` sections uniformly between the exact patch ends and the
    others uniformly around the rest of the wheel.

    Parameters
    ----------
    patch : ContactPatch
        Supplies the patch-end angles ``phi_ends`` [rad].
    res : MeshResolution

    Returns
    -------
    SectionPlan
    """
    rear, front = patch.phi_ends
    contact = np.linspace(rear, front, res.n_patch)[1:-1]
    n_free = res.n_around - res.n_patch
    free = np.linspace(front, rear + 2 * np.pi, n_free + 2)[1:-1]
    return SectionPlan(rear, contact, front, free)


@dataclass(frozen=True)
class RingBlock:
    """Vertex rings of a block of n sections in their section frames.

    Attributes
    ----------
    x, z : (n, m) float [mm]
        Section-frame coordinates.
    s : (n, m) float [mm]
        Carcass arc coordinate from bead 1.
    contact : (n, m) bool
        Vertices on the support surface.
    phi : (n,) float [rad]
        Section angles.
    """

    x: np.ndarray = field(repr=False)
    z: np.ndarray = field(repr=False)
    s: np.ndarray = field(repr=False)
    contact: np.ndarray = field(repr=False)
    phi: np.ndarray = field(repr=False)


@dataclass(frozen=True)
class SectionRings:
    """The four ring blocks of the mesh, in vertex order (``K`` bulge and ``kc``
    contact segments, :class:`MeshResolution`).

    Attributes
    ----------
    rear : RingBlock
        The rear end section, (1, 2K + 1): the bulges meet at the touching point.
    contact : RingBlock
        Sections between the ends, (n_patch - 2, 2K + kc + 1).
    front : RingBlock
        The front end section, (1, 2K + 1).
    free : RingBlock
        Undeformed sections beyond the patch, (n_around - n_patch, 2K + 1).
    """

    rear: RingBlock
    contact: RingBlock
    front: RingBlock
    free: RingBlock

    def blocks(self) -> tuple[RingBlock, RingBlock, RingBlock, RingBlock]:
        """The four blocks in the order of the mesh vertices.

        Returns
        -------
        tuple of RingBlock
            ``(rear, contact, front, free)``.
        """
        return self.rear, self.contact, self.front, self.free


def section_rings(
    patch: ContactPatch, plan: SectionPlan, res: MeshResolution, centreline=None
) -> SectionRings:
    """Section-frame rings: Rotta sections in the patch (ends of width zero), the
    undeformed torus beyond it (shifted sideways by ``centreline`` if given).

    Parameters
    ----------
    patch : ContactPatch
    plan : SectionPlan
        Section angles [rad].
    res : MeshResolution
    centreline : (s, dh) of (k,) float [mm], optional
        Lateral displacement ``dh`` of the tread centre line at arc length ``s``
        along the wheel (section 5.8); 0 outside its range.

    Returns
    -------
    SectionRings

    Raises
    ------
    TireModelError
        A section between the patch ends is out of contact (split patch).
    """
    K, kc = res.bulge_points, res.contact_points
    tire = patch.tire
    ends, _ = patch.sections_at(np.array([plan.rear, plan.front]))
    sol_c, _ = patch.sections_at(plan.contact)
    if np.any(sol_c.width <= 0):
        raise TireModelError("a section between the patch ends is out of contact (split patch)")
    xc, zc, sc, kcon = _contact_rings(sol_c, K, kc)
    xt, zt, st, tcon = _tip_rings(ends, K)
    n_free = len(plan.free)
    xf, zf, sf, fcon = _free_rings(
        n_free, K, tire.tire_radius, tire.arc_length, tire.rim_angle, patch.camber
    )
    if centreline is not None:
        xf = xf + _centreline_shift(patch, plan, centreline)[:, None]
    return SectionRings(
        rear=RingBlock(xt[:1], zt[:1], st[:1], tcon[:1], np.array([plan.rear])),
        contact=RingBlock(xc, zc, sc, kcon, plan.contact),
        front=RingBlock(xt[1:], zt[1:], st[1:], tcon[1:], np.array([plan.front])),
        free=RingBlock(xf, zf, sf, fcon, plan.free),
    )


def _centreline_shift(patch: ContactPatch, plan: SectionPlan, centreline) -> np.ndarray:
    """Sideways shift [mm] of the free sections by the centre line beyond the patch."""
    cs_, cdh = (np.asarray(a, float) for a in centreline)
    R = patch.tire.wheel_radius
    phi_f, rear, front = plan.free, plan.rear, plan.front
    # free sections run forward from the front end; beyond half a turn, backward from the rear
    ahead = phi_f - front < np.pi
    s_pos = np.where(
        ahead, patch.x[-1] + R * (phi_f - front), patch.x[0] - R * (rear + 2 * np.pi - phi_f)
    )
    return np.interp(s_pos, cs_, cdh, left=0.0, right=0.0)


@dataclass(frozen=True)
class PlacedVertices:
    """Mesh vertices in the ground frame and their data.

    Attributes
    ----------
    vertices : (N, 3) float [mm]
    contact : (N,) bool
    radial, lateral : (N,) float [mm]
        Radial deformation and lateral displacement of each carcass point.
    section : (N,) int
        Section index around the wheel.
    phi : (n_sections,) float [rad]
    rings : tuple of (n_i, m_i) int arrays
        Vertex indices of each block of :class:`SectionRings`, in order.
    """

    vertices: np.ndarray = field(repr=False)
    contact: np.ndarray = field(repr=False)
    radial: np.ndarray = field(repr=False)
    lateral: np.ndarray = field(repr=False)
    section: np.ndarray = field(repr=False)
    phi: np.ndarray = field(repr=False)
    rings: tuple = field(repr=False)


def place_vertices(patch: ContactPatch, rings: SectionRings) -> PlacedVertices:
    """Map every ring to the ground frame; sections in contact are translated onto the
    support surface (by at most the patch ``flatness``) and their contact vertices
    snapped to it.

    Parameters
    ----------
    patch : ContactPatch
        Supplies the ground map (:meth:`ContactPatch.to_ground`) and the surface.
    rings : SectionRings

    Returns
    -------
    PlacedVertices
        Vertices (N, 3) [mm] and per-vertex radial deformation and lateral
        displacement (N,) [mm].
    """
    tire = patch.tire
    r0, s0, gam = tire.tire_radius, tire.arc_length, patch.camber
    surface = patch.surface
    pts, data, con, sec, phis, idx = [], [], [], [], [], []
    start, first = 0, 0
    for b in rings.blocks():
        n, m = b.x.shape
        X, Y, Z = patch.to_ground(b.x, b.z, b.phi[:, None])
        if b.contact.any():  # translate sections in contact onto the surface (<= flatness)
            gap = np.where(b.contact, Z - surface.height(X), 0.0)
            Z = Z - (gap.sum(axis=1) / b.contact.sum(axis=1))[:, None]
        pts.append(np.stack([X, Y, Z], -1).reshape(-1, 3))
        # per-vertex displacement against the same carcass point undeformed
        ux, uz = _undeformed(b.s, r0, s0, gam)
        _, UY, _ = patch.to_ground(ux, uz, b.phi[:, None])
        data.append(np.stack([(r0 - np.hypot(b.x, b.z)).ravel(), (Y - UY).ravel()], -1))
        con.append(b.contact.ravel())
        sec.append(np.repeat(np.arange(first, first + n), m))
        phis.append(b.phi)
        idx.append(start + np.arange(n * m).reshape(n, m))
        start += n * m
        first += n
    vertices = np.concatenate(pts)
    contact = np.concatenate(con)
    # contact vertices exactly onto the support surface (the residual tilt across one
    # section is a tiny fraction of the patch `flatness`)
    vertices[contact, 2] = surface.height(vertices[contact, 0])
    ds = np.concatenate(data)
    return PlacedVertices(
        vertices,
        contact,
        ds[:, 0],
        ds[:, 1],
        np.concatenate(sec),
        np.concatenate(phis),
        tuple(idx),
    )


def tire_faces(patch: ContactPatch, placed: PlacedVertices, res: MeshResolution) -> np.ndarray:
    """Triangles of the tire surface, oriented outward (away from each section's
    centre, the air side inside).

    Parameters
    ----------
    patch : ContactPatch
        Supplies the section centres in the ground frame.
    placed : PlacedVertices
    res : MeshResolution

    Returns
    -------
    faces : (n_faces, 3) int
        Vertex indices into ``placed.vertices``.
    """
    K, kc = res.bulge_points, res.contact_points
    rt, rc, ft, rf = placed.rings[0][0], placed.rings[1], placed.rings[2][0], placed.rings[3]
    faces = np.concatenate(
        [
            _quads(rc[:-1], rc[1:]) if len(rc) > 1 else np.empty((0, 3), int),
            _transition(rc[0], rt, K, kc, tip_after=False),
            _transition(rc[-1], ft, K, kc, tip_after=True),
            _quads(ft, rf[0]),
            _quads(rf[:-1], rf[1:]),
            _quads(rf[-1], rt),
        ]
    )
    phi = placed.phi
    centre = np.stack(patch.to_ground(np.zeros_like(phi), np.zeros_like(phi), phi), -1)
    tri = placed.vertices[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    away = tri.mean(axis=1) - centre[placed.section[faces[:, 0]]]
    if np.sum(np.einsum("ij,ij->i", normal, away) > 0) < 0.5 * len(faces):
        faces = faces[:, ::-1]
    return faces


def bead_lines(placed: PlacedVertices) -> np.ndarray:
    """Vertex indices of the two bead lines, in order around the wheel.

    Parameters
    ----------
    placed : PlacedVertices

    Returns
    -------
    beads : (2, n_sections) int
        Row 0 the bead of side 1, row 1 that of side 2.
    """
    rt, rc, ft, rf = placed.rings[0][0], placed.rings[1], placed.rings[2][0], placed.rings[3]
    first = np.concatenate([[rt[0]], rc[:, 0], [ft[0]], rf[:, 0]])
    last = np.concatenate([[rt[-1]], rc[:, -1], [ft[-1]], rf[:, -1]])
    return np.stack([first, last])


def close_beads(vertices, faces, beads) -> np.ndarray:
    """Triangles of a rim band joining the two bead lines (winding consistent with
    ``faces``), making the mesh watertight.

    Parameters
    ----------
    vertices : (N, 3) float [mm]
    faces : (n_faces, 3) int
        The tire surface (:func:`tire_faces`).
    beads : (2, n_sections) int
        Bead-line vertex indices (:func:`bead_lines`).

    Returns
    -------
    band : (2 n_sections, 3) int
    """
    import trimesh

    b1, b2 = beads[0], beads[1]
    n1, n2 = np.roll(b1, -1), np.roll(b2, -1)  # next section, wrapping around
    band = np.concatenate([np.column_stack([b1, n1, n2]), np.column_stack([b1, n2, b2])])
    mesh0 = trimesh.Trimesh(vertices, np.concatenate([faces, band]), process=False)
    return band if mesh0.is_winding_consistent else band[:, ::-1]


def footprint_points(patch: ContactPatch, vertices, contact) -> np.ndarray:
    """Contact vertices inside the print footprint the load case asks for.

    The mesh's contact faces are the Rotta patch (section 5.2); with a rounded
    footprint (:mod:`tiremesh.footprint`, beyond the dissertation, 7.3.1) the print
    leaves out its pointed tips. A contact vertex belongs to the print when its
    ground position (unrolled along a drum or disk) lies inside the footprint
    outline. The print's narrow rim beyond the Rotta patch sides (about 0.3 mm with
    the default parameters) has no mesh vertex on the ground; renders draw the
    footprint outline itself.

    Parameters
    ----------
    patch : ContactPatch
    vertices : (n, 3) float [mm]
        Mesh vertices (x forward, y lateral, z up).
    contact : (n,) bool
        Vertices on the support surface.

    Returns
    -------
    (n,) uint8
        1 on contact vertices inside the footprint, else 0.
    """
    import shapely

    outline = shapely.Polygon(patch.footprint.outline)
    x = patch.surface.unroll(vertices[:, 0])
    inside = shapely.contains_xy(outline.buffer(1e-9), x, vertices[:, 1])
    return (inside & np.asarray(contact, bool)).astype(np.uint8)


def build_mesh(
    patch: ContactPatch | LoadCase,
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
    patch : ContactPatch or LoadCase
        Solver result (:func:`tiremesh.solve`), or a load case to solve first.
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

    Examples
    --------
    >>> import tiremesh as tm
    >>> from tiremesh.mesh import build_mesh
    >>> case = tm.LoadCase(tm.get_tire(8), pressure=0.4, load=400.0)
    >>> build_mesh(case, n_around=60).n_faces > 0
    True
    """
    import trimesh

    patch = as_patch(patch)
    res = mesh_resolution(n_around, n_patch, bulge_points, contact_points)
    rings = section_rings(patch, plan_sections(patch, res), res, centreline)
    placed = place_vertices(patch, rings)
    faces = tire_faces(patch, placed, res)
    face_contact = np.all(placed.contact[faces], axis=1)
    beads = bead_lines(placed)
    if close_rim:
        band = close_beads(placed.vertices, faces, beads)
        face_contact = np.concatenate([face_contact, np.zeros(len(band), bool)])
        faces = np.concatenate([faces, band])
    point_data = {
        "radial_deformation": placed.radial,
        "lateral_displacement": placed.lateral,
        "contact": placed.contact.astype(np.uint8),
        "section": placed.section.astype(np.int32),
    }
    if patch.case.footprint.kind != "rotta":
        point_data["footprint"] = footprint_points(patch, placed.vertices, placed.contact)
    return TireMesh(
        mesh=trimesh.Trimesh(vertices=placed.vertices, faces=faces, process=False),
        point_data=point_data,
        face_contact=face_contact,
        patch=patch,
        section_phi=placed.phi,
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
    patch: ContactPatch | LoadCase,
    *,
    extent: float | None = None,
    thickness: float | None = None,
    sink: float = 0.0,
    resolution: int = 240,
):
    """Mesh of the support surface under the patch (for renders), as a slab.

    Built from the surface protocol alone: the top profile runs along the surface at
    arc lengths ``s`` (``x = surface.roll(s)``, ``z = surface.height(x)``), lowered by
    ``sink`` along the profile normal; the bottom lies ``thickness`` further along the
    normal. Flat ground and the disk (a plane; the disk's track is curved, not its
    surface) give a box, a drum a thick cylinder segment of its radius.

    Parameters
    ----------
    patch : ContactPatch or LoadCase
    extent : float [mm], optional
        Half-length along the surface (default 0.6 x the wheel radius).
    thickness : float [mm], optional
        Slab thickness below the surface (default the tire radius).
    sink : float [mm]
        Lower the top face by this much (renders use a fraction of a mm so the contact
        faces, which lie exactly on the surface, do not z-fight with it).
    resolution : int
        Segments along the surface (a curved surface's facets must stay well below
        the patch).

    Returns
    -------
    trimesh.Trimesh
        Watertight, normals outward.
    """

    patch = as_patch(patch)
    R, r0 = patch.tire.wheel_radius, patch.tire.tire_radius
    ext = 0.6 * R if extent is None else float(v.positive("extent", extent, unit="mm"))
    th = r0 if thickness is None else float(v.positive("thickness", thickness, unit="mm"))
    n = v.integer("resolution", resolution, 2, 100_000)
    top, bot = _slab_profile(patch.surface, ext, th, float(sink), n)
    return _extrude_profile(np.concatenate([top, bot[::-1]]), 4.0 * r0, n + 1)


def _slab_profile(surface, extent: float, thickness: float, sink: float, n: int):
    """(n + 1, 2) top and bottom ``(x, z)`` of the slab under the surface profile."""
    s = np.linspace(-extent, extent, n + 1)
    ds = s[1] - s[0]
    s_ext = np.concatenate([[s[0] - ds], s, [s[-1] + ds]])
    x = surface.roll(s_ext)
    prof = np.column_stack([x, surface.height(x)])
    # central chords: for a circular profile exactly tangent at the middle point
    t = prof[2:] - prof[:-2]
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    normal = np.column_stack([-t[:, 1], t[:, 0]])  # up, out of the surface
    on = prof[1:-1]
    return on - sink * normal, on - (sink + thickness) * normal


def _extrude_profile(prof, half_y: float, k: int):
    """Closed slab from a closed (x, z) profile of ``k`` top then ``k`` bottom points,
    extruded over ``-half_y .. half_y``."""
    import trimesh

    m = len(prof)
    verts = np.concatenate(
        [np.column_stack([prof[:, 0], np.full(m, y), prof[:, 1]]) for y in (-half_y, half_y)]
    )
    ring = np.arange(m)
    sides = _quads(np.append(ring, 0)[None, :], np.append(ring + m, m)[None, :])
    # end caps: the profile is a simple polygon; fan-free strip triangulation
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
    """A simple rim for renders: the bead lines joined by a rim bed sunk toward the
    axle.

    Parameters
    ----------
    tire_mesh : TireMesh
    depth : float [mm]
        Depth of the rim bed below the bead lines.

    Returns
    -------
    trimesh.Trimesh
        Open band (4 n_sections vertices [mm]), ground frame.
    """
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


__all__ = [
    "MeshResolution",
    "PlacedVertices",
    "RingBlock",
    "SectionPlan",
    "SectionRings",
    "TireMesh",
    "as_patch",
    "bead_lines",
    "build_mesh",
    "close_beads",
    "mesh_resolution",
    "place_vertices",
    "plan_sections",
    "rim_mesh",
    "section_rings",
    "support_mesh",
    "tire_faces",
]
