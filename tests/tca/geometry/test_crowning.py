"""Longitudinal crowning by a plunging disk (tca.geometry.modifications.crowning): the generated surface against the
exact envelope of the disk and its first-order depth."""

import math

import numpy as np
import pytest

from tca.errors import GeometryError
from tca.geometry.gear import Gear
from tca.geometry.modifications.crowning import DiskPlunge, _Disk
from tca.report_data import table_1_1_planet

d = math.radians


def _plunge_depth(g: Gear, side: int, u, z):
    """Removed material along the normal, the plunge parameter l and e_r . n at (u, z)."""
    sigma = g.helicoid(side)
    space = side * math.pi / g.teeth
    disk = _Disk(sigma, g.plunge, space)
    w = disk.contact_line(u)
    l = z - w
    e0 = sigma.evaluate(u, z)
    e1 = g.surface(side).evaluate(u, z)
    dev = np.einsum("ij,ij->i", e0.r - e1.r, e0.n)
    ang = space + g.k_screw * l
    er = np.stack([np.cos(ang), np.sin(ang), 0 * l], -1)
    pc = sigma.evaluate(u, w).r  # on the line of contact with the disk
    rho = np.linalg.norm(np.cross(pc - disk.C, disk.a), axis=-1)  # radius of the disk there
    return dev, l, np.abs(np.einsum("ij,ij->i", er, e0.n)), rho


def test_longitudinal_crowning_spur_equals_exact_disk_envelope():
    # Spur planet: every circle of the disk (radius rho, in a plane containing the gear axis) moves on
    # the plunge parabola x_c = E0 - a_pl l^2 (Eq. 1.6), so the depth at axial position z is exactly
    # max_l [a_pl l^2 + sqrt(rho^2 - (z - l)^2) - rho] along e_r. This is a_pl z^2 / (1 - 2 a_pl rho)
    # to leading order: the disk's own curvature amplifies the plunge (1.67x for r_D = 100 mm,
    # a_pl = 0.002). Tolerance 1e-6 relative (the Chebyshev fit is < 1e-9 mm).
    a_pl = 0.002
    g = Gear("planet", 34, 2.0, d(20), 30, parabola_neg=0.005, plunge=DiskPlunge(100, a_pl))
    u = np.array([-1.5, 0.0, 1.5])
    for z in (-14.0, -7.0, 5.0, 14.0):
        dev, l, ern, rho = _plunge_depth(g, -1, u, np.full(3, z))
        for k in range(3):
            ls = np.linspace(z - 0.999 * rho[k], z + 0.999 * rho[k], 200001)
            exact = np.max(a_pl * ls**2 + np.sqrt(rho[k] ** 2 - (z - ls) ** 2) - rho[k])
            assert dev[k] / ern[k] == pytest.approx(exact, rel=1e-6)


def test_longitudinal_crowning_depth_is_a_pl_l2_to_first_order():
    # Helical planet: the depth along the normal is a_pl l^2 (e_r . n) to first order in a_pl r_D;
    # with a_pl r_D = 2e-3 the second-order term is below 1 % (issue 2's tolerance).
    g = Gear("planet", 34, 2.0, d(20), 30, helix=d(10), hand=-1, parabola_neg=0.005, plunge=DiskPlunge(100, 2e-5))
    u = np.array([-1.0, 0.0, 1.0])
    for z in (-14.0, -8.0, 8.0, 14.0):
        dev, l, ern, _ = _plunge_depth(g, -1, u, np.full(3, z))
        assert np.allclose(dev, 2e-5 * l**2 * ern, rtol=0.01)


def test_plunge_more_curved_than_the_disk_is_rejected():
    # 2 a_pl rho >= 1: the plunge path is more curved than the disk, which would cut its own track
    with pytest.raises(GeometryError, match="plunging"):
        Gear("planet", 34, 2.0, d(20), 30, plunge=DiskPlunge(100, 0.006)).surface(1)


def test_crowned_surface_interpolation_error_is_bounded():
    g = table_1_1_planet()
    for side in (1, -1):
        assert g.surface(side).fit_error < 1e-9
