"""Hertz contact of crossed cylinders: relative curvatures, ellipse orientation, semi-axes and p0 (issue 13).

Independent sources:

* Curvatures (Johnson, Contact Mechanics, section 4.2): cylinders of radii R1, R2 whose axes cross at
  angle theta have A + B = (1/R1 + 1/R2)/2 and B - A = (1/2) sqrt(1/R1^2 + 1/R2^2 + 2 cos(2 theta)/(R1 R2)),
  the separation being A x^2 + B y^2 in the principal axes (``tca.contact.ellipse`` gives lambda = 2A, 2B).
* Orientation (Mohr's circle of the relative curvature tensor K in the axes of cylinder 1):
  tan 2 psi = 2 k12 / (k11 - k22); the major axis is the direction of the smaller normal curvature.
* Semi-axes (Hertz, in the ellipsoidal-potential form, e.g. Johnson eq. 3.60 with the load
  P = (2/3) p0 pi a b): A = (3P / (4 pi E*)) int_0^inf dw / sqrt((a^2+w)^3 (b^2+w) w) and
  B = (3P / (4 pi E*)) int_0^inf dw / sqrt((a^2+w) (b^2+w)^3 w), 1/E* = 2 (1 - nu^2)/E, evaluated
  by quadrature -- not the complete elliptic integrals K(e), E(e) that ``hertz_contact`` solves.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from fem.material import Material
from pipelines.models.stress.sizing import hertz_contact
from tca.contact.ellipse import contact_ellipse
from tca.geometry.surfaces import SurfacePoints

E, NU, P = 2.068e5, 0.29, 3000.0  # [MPa], [-], [N]


def _cylinders(R1, R2, theta):
    """Body 1 below (axis x, radius R1), body 2 above (axis at theta in the tangent plane), touching at 0."""
    x, y, z = np.eye(3)
    d = np.array([math.cos(theta), math.sin(theta), 0.0])
    dp = np.cross(z, d)
    zero = np.zeros(3)
    sp1 = SurfacePoints(zero, x, y, zero, zero, -z / R1, z)  # r = u x + R1 sin(v/R1) y + R1 (cos(v/R1) - 1) z
    sp2 = SurfacePoints(zero, d, dp, zero, zero, z / R2, -z)  # r = u d + R2 sin(v/R2) d' + R2 (1 - cos(v/R2)) z
    return sp1, sp2


@pytest.mark.parametrize("R1, R2, theta_deg", [(20.0, 30.0, 30.0), (20.0, 30.0, 60.0), (15.0, 40.0, 80.0)])
def test_crossed_cylinders_against_hertz(R1, R2, theta_deg):
    th = math.radians(theta_deg)
    sp1, sp2 = _cylinders(R1, R2, th)
    a_app, b_app, ang, lam = contact_ellipse(sp1, sp2, 0.005, np.array([1.0, 0.0, 0.0]))
    # relative curvatures (Johnson 4.2)
    s = 0.5 * (1 / R1 + 1 / R2)
    dlt = 0.5 * math.sqrt(1 / R1**2 + 1 / R2**2 + 2 * math.cos(2 * th) / (R1 * R2))
    A, B = 0.5 * (s - dlt), 0.5 * (s + dlt)  # A + B = s, B - A = dlt
    np.testing.assert_allclose(np.sort(lam), [2 * A, 2 * B], rtol=1e-12)
    # orientation of the major axis (Mohr's circle), modulo pi
    k11, k22, k12 = math.sin(th) ** 2 / R2, 1 / R1 + math.cos(th) ** 2 / R2, -math.sin(th) * math.cos(th) / R2
    psi = 0.5 * math.atan2(2 * k12, k11 - k22)
    kn = lambda p: k11 * math.cos(p) ** 2 + 2 * k12 * math.sin(p) * math.cos(p) + k22 * math.sin(p) ** 2  # noqa: E731
    if kn(psi) > kn(psi + math.pi / 2):
        psi += math.pi / 2
    diff = (float(ang) - psi + math.pi / 2) % math.pi - math.pi / 2
    assert abs(diff) < 1e-10
    # semi-axes and p0 against Hertz's potential integrals
    h = hertz_contact(tuple(lam), P, Material(E, NU), length=100.0)
    a, b = h.a, h.b
    assert not h.line and a > b
    Es = E / (2 * (1 - NU**2))
    c = 3 * P / (4 * math.pi * Es)
    IA = quad(lambda w: 1 / math.sqrt((a * a + w) ** 3 * (b * b + w) * w), 0, np.inf, limit=200)[0]
    IB = quad(lambda w: 1 / math.sqrt((a * a + w) * (b * b + w) ** 3 * w), 0, np.inf, limit=200)[0]
    assert c * IA == pytest.approx(A, rel=1e-6)
    assert c * IB == pytest.approx(B, rel=1e-6)
    assert h.p0 == pytest.approx(3 * P / (2 * math.pi * a * b), rel=1e-12)
