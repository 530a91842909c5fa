"""Contact pressure at 3 elements per Hertz half-width (issue 14): Gauss-point constraints and recovery.

References: Hertz (Johnson, Contact Mechanics, ch. 4) through fem.verification's closed forms.
The half-width is the Hertz-equivalent one of the nodal forces (fem.contact.contact_patch): for the
elliptic line pressure int x^2 p dx / P = a^2 / 4, for the semi-ellipsoid int x^2 p dA / P = a^2 / 5.
"""

import numpy as np
import pytest
import scipy.sparse as sp

from fem import ContactOptions, solve
from fem.contact.faces import surface_mass
from fem.contact.patch import contact_patch
from fem.verification import ModelSetup, hertz_line, hertz_point
from fem.errors import FEInputError


@pytest.fixture(scope="module")
def line3():
    mesh, model, ref = hertz_line(elements_per_halfwidth=3.0)
    return mesh, model, ref, solve(mesh, model)


@pytest.fixture(scope="module")
def point3():
    mesh, model, ref = hertz_point(elements_per_radius=3.0)
    return mesh, model, ref, solve(mesh, model)


def test_hertz_line_peak_at_three_per_halfwidth(line3):
    mesh, model, ref, r = line3
    pair = r.pairs[0]
    # issue 14: within 3 % at 3 elements per half-width (measured -0.3 %; the nodal-gap formulation
    # of issue 6 gives +7.8 % here, test below)
    assert abs(pair.max_pressure / ref["p0"] - 1.0) < 0.03
    # equilibrium: the Gauss-point forces carry the applied load (round-off)
    assert pair.force == pytest.approx(ref["force"], rel=1e-9)
    assert r.info.penalty_change < model.contact.penalty_check_tol


def test_hertz_line_half_width_from_moments(line3):
    mesh, model, ref, r = line3
    assert r.contact_force.sum() == pytest.approx(ref["force"], rel=1e-9)
    # half-width of the elliptic pressure with the same load and second moment about the symmetry plane x = 0
    patch = contact_patch(mesh.points, r.contact_force, (0.0, 1.0, 0.0), centre=(0.0, 0.0, 0.0), kind="line",
                          major=(0.0, 0.0, 1.0))
    # issue 14: within 10 % (measured +3.6 %); the tributary-area width is +13 % (edge quantization h/2)
    assert abs(patch.semi_axes[1] / ref["a"] - 1.0) < 0.10


def test_hertz_point_peak_and_radius_at_three_per_radius(point3):
    mesh, model, ref, r = point3
    pair = r.pairs[0]
    # issue 14: within 3 % at 3 elements per contact radius (measured -0.2 %; nodal gaps: +5.8 %)
    assert abs(pair.max_pressure / ref["p0"] - 1.0) < 0.03
    assert 4.0 * pair.force == pytest.approx(ref["load"], rel=1e-9)
    # quarter model: second moments about the symmetry planes x = 0 and y = 0; both semi-axes are the radius
    patch = contact_patch(mesh.points, r.contact_force, (0.0, 0.0, 1.0), centre=(0.0, 0.0, 0.0), major=(1.0, 0.0, 0.0))
    # issue 14: within 10 % (measured +3 %, +3 %)
    assert np.all(np.abs(np.array(patch.semi_axes) / ref["a"] - 1.0) < 0.10)


@pytest.mark.xfail(strict=True, reason="measured +7.8 %: one averaged gap per slave node cannot open the node "
                   "at the contact edge, the load moves inward (the reason for Gauss-point constraints)")
def test_hertz_line_nodal_gaps_at_three_per_halfwidth():
    mesh, model, ref = hertz_line(elements_per_halfwidth=3.0, setup=ModelSetup(contact=ContactOptions(points="nodes")))
    assert abs(solve(mesh, model).pairs[0].max_pressure / ref["p0"] - 1.0) < 0.03


def test_surface_mass_integrates_area_and_moments():
    """Row sums of the consistent face mass are the tributary areas; 1^T M 1 the area (exact for bilinear faces)."""
    x = np.linspace(0.0, 2.0, 4)
    X, Y = np.meshgrid(x, x, indexing="ij")
    pts = np.stack([X.ravel(), Y.ravel(), 0.1 * X.ravel() * Y.ravel()], axis=1)  # a hyperbolic paraboloid: curved faces
    idx = np.arange(16).reshape(4, 4)
    faces = np.stack([idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()], axis=1)
    M = surface_mass(pts, faces)
    # area of z = 0.1 x y over [0, 2]^2 by a fine midpoint rule (independent of the face quadrature)
    s = (np.arange(2000) + 0.5) / 1000.0
    U, V = np.meshgrid(s, s, indexing="ij")
    area = np.sum(np.sqrt(1.0 + (0.1 * V) ** 2 + (0.1 * U) ** 2)) * 1e-6
    # the bilinear faces are the surface itself (z = 0.1 x y is bilinear in x, y); 2x2 Gauss points integrate
    # the smooth area element |x_u x x_v| of each face (measured 2.4e-8 against the midpoint rule)
    assert M.sum() == pytest.approx(area, rel=1e-5)
    assert sp.issparse(M) and abs(M - M.T).max() < 1e-14 * abs(M).max()  # symmetric up to summation round-off


def test_contact_patch_of_an_exact_hertz_distribution():
    """Nodal forces of the exact semi-ellipsoid on a fine grid give back its semi-axes (quadrature error only)."""
    a, b = 3.0, 1.0
    x = np.linspace(-a, a, 601)
    y = np.linspace(-b, b, 201)
    X, Y = np.meshgrid(x, y, indexing="ij")
    p = np.sqrt(np.clip(1.0 - (X / a) ** 2 - (Y / b) ** 2, 0.0, None))
    th = 0.3  # rotated in the tangent plane z = 0
    R = np.array([[np.cos(th), -np.sin(th), 0.0], [np.sin(th), np.cos(th), 0.0], [0.0, 0.0, 1.0]])
    pts = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1) @ R.T + (1.0, 2.0, 3.0)
    patch = contact_patch(pts, p.ravel() * (x[1] - x[0]) * (y[1] - y[0]), (0.0, 0.0, 1.0))
    assert patch.semi_axes == pytest.approx((a, b), rel=2e-3)
    assert abs(np.dot(patch.directions[0], R[:, 0])) == pytest.approx(1.0, abs=1e-6)
    assert patch.centre == pytest.approx((1.0, 2.0, 3.0), abs=1e-9)
    with pytest.raises(FEInputError, match="kind"):
        contact_patch(pts, p.ravel(), (0.0, 0.0, 1.0), kind="area")


def test_points_option_is_validated():
    with pytest.raises(FEInputError, match="contact.points"):
        ContactOptions(points="faces")
