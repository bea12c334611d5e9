"""contactpatch.ruler.model: the model's patch as a region, Appendix C's ellipse
(section 5.4, Figure 5-15)."""

import pytest
from numpy.testing import assert_allclose

import contactpatch as cp
import tiremesh as tm


@pytest.fixture(scope="module")
def big_apple():
    tire = tm.TireGeometry.from_arc_length(128.2, 18.7)
    return tm.solve_patch(tire, 5.0, pressure=0.4)


def test_appendix_ellipse_figure_5_15(big_apple):
    # Figure 5-15 (section 5.4; configuration in published-values.md): the fitted
    # ellipse is 98.49 mm long, 9.783 mm wide, 756.8 mm^2 (Appendix C's fit_ellipse on
    # the patch edges and centre line, 151 sections per half over 15 degrees)
    patch = big_apple
    e = cp.appendix_ellipse(patch)
    assert_allclose([e.length, e.width, e.area], [98.49, 9.783, 756.8], rtol=0.01)
    assert_allclose([e.length, e.width, e.area], [98.49, 9.783, 756.8], rtol=1e-3)  # in fact
    assert_allclose(e.length / patch.length, 0.8295, atol=0.005)  # 82.95 % of the patch
    # the direct fit to the outline is a different (longer) ellipse: say which one
    m = cp.measure(patch, axis=0.0)
    assert m.ellipse_direct.length > 1.05 * e.length
    assert_allclose(m.area, patch.area, rtol=1e-4)


def test_patch_polygon_is_the_outline(big_apple):
    poly = cp.patch_polygon(big_apple)
    assert poly.is_valid
    assert_allclose(poly.area, big_apple.area, rtol=1e-4)  # polygon vs quadrature (Eq. 5-26)


def test_appendix_points_options(big_apple):
    pts = cp.appendix_points(big_apple, sections_per_half=21, last_angle_deg=10.0)
    assert pts.shape[1] == 2 and len(pts) % 4 == 0
    # (y, x): lateral within the patch width, forward within its length
    assert abs(pts[:, 0]).max() <= 0.5 * big_apple.width + 1e-9
    e = cp.appendix_ellipse(big_apple, sections_per_half=21, last_angle_deg=10.0)
    assert e and e.method == "appendix-lsq"
    with pytest.raises(cp.InvalidInput, match="sections_per_half"):
        cp.appendix_points(big_apple, sections_per_half=2)
    with pytest.raises(cp.InvalidInput, match="last_angle_deg"):
        cp.appendix_points(big_apple, last_angle_deg=90.0)
