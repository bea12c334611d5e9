"""The contact patch cut from the deformed-tire mesh (:func:`contactpatch.patch_from_mesh`)
against the solver's own patch, on every surface, including a surface kind defined
here alone (the :class:`tiremesh.Surface` protocol is all the packages need)."""

import itertools
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest
from numpy.testing import assert_allclose

import contactpatch as cp
import tiremesh as tm
from tests.tiremesh.mesh_cases import CASES, T37, solve_case
from tiremesh.export import patch_polydata
from tiremesh.mesh import build_mesh, support_mesh
from tiremesh.surface import curvature_drop


@pytest.fixture(scope="module", params=list(CASES))
def case(request):
    patch = solve_case(request.param)
    return request.param, patch, build_mesh(patch)


def test_patch_from_mesh_matches_solver_outline(case):
    # issue 3: mesh patch vs the solver's own outline, 0.5 % at default resolution
    _, patch, mesh = case
    geom = cp.patch_from_mesh(mesh, allow_multiple=False)
    m = cp.measure(geom, axis=0.0)
    assert_allclose(geom.area, patch.area, rtol=5e-3)
    assert_allclose(m.length, patch.length, rtol=5e-3)
    assert_allclose(m.width, patch.width, rtol=5e-3)
    # in fact far better: the patch edges are mesh vertices
    assert_allclose(
        [geom.area, m.length, m.width], [patch.area, patch.length, patch.width], rtol=2e-4
    )


def test_contact_faces_are_the_mesh_contact_faces(case):
    _, _, mesh = case
    assert np.array_equal(cp.contact_faces(mesh), mesh.face_contact)


def test_patch_from_mesh_error_shrinks_with_resolution():
    patch = tm.solve(T37, load=400.0, pressure=0.4, camber=math.radians(30), surface=tm.Drum(2500))
    errors = []
    for n_patch in (12, 24, 48, 96):
        geom = cp.patch_from_mesh(build_mesh(patch, n_around=3 * n_patch, n_patch=n_patch))
        errors.append(abs(geom.area / patch.area - 1))
    # polygon inscribed in a smooth outline: second order in the section spacing
    assert all(b < a / 3 for a, b in itertools.pairwise(errors)), errors


# -- a new surface kind, defined in this file alone ------------------------------


@dataclass(frozen=True)
class BigDrum(tm.SurfaceBase):
    """Outside of a cylinder of ``size`` mm across, written afresh from its curvature
    (no tiremesh.Drum code), unknown to every module of the packages."""

    size: float = 4000.0
    kind: ClassVar[str] = "bigdrum"

    @property
    def k(self) -> float:
        return 2.0 / self.size  # curvature [1/mm]

    @property
    def spec(self) -> str:
        return f"bigdrum:{self.size:g}"

    def describe(self) -> str:
        return f"big drum {self.size:g} mm"

    def drop(self, phi, wheel_radius):
        return curvature_drop(phi, wheel_radius, self.k)

    def height(self, x):
        # circle of radius 1/k through the origin, centre below: z = sqrt(R^2 - x^2) - R
        u = self.k * np.asarray(x, float)
        return -u * u / (self.k * (1.0 + np.sqrt(1.0 - u * u)))

    def gap(self, points):
        p = np.asarray(points, float)
        radius = 1.0 / self.k
        return np.sqrt(p[:, 0] ** 2 + (p[:, 2] + radius) ** 2) - radius

    def unroll(self, x):
        return np.arcsin(self.k * np.asarray(x, float)) / self.k

    def roll(self, s):
        return np.sin(self.k * np.asarray(s, float)) / self.k

    def stretch(self, x):
        u = self.k * np.asarray(x, float)
        return 1.0 / np.sqrt(1.0 - u * u)


ACCEPT = dict(camber=0.0), dict(camber=math.radians(25))


@pytest.fixture(scope="module", params=range(len(ACCEPT)), ids=["upright", "camber25"])
def big_and_drum(request):
    tire = tm.get_tire(8)
    kw = ACCEPT[request.param]
    new = tm.solve(tm.LoadCase(tire, pressure=0.4, load=400, surface=BigDrum(), **kw))
    ref = tm.solve(tm.LoadCase(tire, pressure=0.4, load=400, surface=tm.Drum(4000), **kw))
    return new, ref


def test_new_surface_is_a_surface():
    s = BigDrum()
    assert isinstance(s, tm.Surface)
    assert tm.parse_surface(s) is s
    x = np.linspace(-300, 300, 7)
    ref = tm.Drum(4000)
    for name in ("height", "unroll", "roll", "stretch"):
        assert_allclose(getattr(s, name)(x), getattr(ref, name)(x), rtol=1e-12, atol=1e-12)


def test_new_surface_solves_like_the_drum(big_and_drum):
    new, ref = big_and_drum
    assert new.surface == BigDrum() and new.vertical_force == pytest.approx(400.0, rel=1e-6)
    assert_allclose(
        [new.deflection, new.length, new.width, new.area, new.lateral_force],
        [ref.deflection, ref.length, ref.width, ref.area, ref.lateral_force],
        rtol=1e-12,
        atol=1e-12,
    )
    assert_allclose(new.outline, ref.outline, rtol=0, atol=1e-10)


def test_new_surface_meshes_like_the_drum(big_and_drum):
    new, ref = big_and_drum
    m_new, m_ref = build_mesh(new), build_mesh(ref)
    assert np.array_equal(m_new.mesh.faces, m_ref.mesh.faces)
    assert np.array_equal(m_new.face_contact, m_ref.face_contact)
    assert_allclose(m_new.mesh.vertices, m_ref.mesh.vertices, rtol=0, atol=1e-10)
    on = m_new.point_data["contact"].astype(bool)
    assert_allclose(m_new.surface_gap()[on], 0.0, atol=1e-9)
    slab_new, slab_ref = support_mesh(new), support_mesh(ref)
    assert_allclose(slab_new.vertices, slab_ref.vertices, rtol=0, atol=1e-10)
    outline_new, outline_ref = patch_polydata(m_new).points, patch_polydata(m_ref).points
    assert_allclose(outline_new, outline_ref, rtol=0, atol=1e-10)


def test_new_surface_patch_from_mesh_like_the_drum(big_and_drum):
    new, ref = big_and_drum
    cut = []
    for patch in (new, ref):
        geom = cp.patch_from_mesh(build_mesh(patch), allow_multiple=False)
        m = cp.measure(geom, axis=0.0)
        cut.append([m.length, m.width, geom.area])
    assert_allclose(cut[0], cut[1], rtol=1e-12)
    # and both agree with the solver's patch as on any surface
    assert_allclose(cut[0], [new.length, new.width, new.area], rtol=2e-4)
