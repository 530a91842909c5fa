"""ISO 6336-3 method B (tca.iso6336) against the generated tooth: the root chord s_Fn and fillet radius ρ_F.

ISO's s_Fn and ρ_F are closed forms of the trochoid cut by the basic rack's tip rounding; the
gear's own fillet surface (tca.profile: envelope of the rack-cutter) is an independent path to the
same two numbers: the fillet point whose tangent makes 30° with the tooth centre line, its chord
2|y| and its radius of curvature. Y_F and Y_S themselves are not compared with published worked
values (ISO/TR 6336-30 has worked examples; they were not consulted here): they are checked through
the quantities they are built from, their trends, and the FE root stress
(tests/pipelines/test_standard_gears.py).
"""

import math

import numpy as np
import pytest

from tca.errors import InputError
from tca.gear import Gear
from tca.iso6336 import root_factors, sigma_f0


def _generated(g: Gear) -> tuple[float, float]:
    """(s_Fn, ρ_F) [mm] of the generated fillet at its 30° tangent, transverse section z = 0 of a spur gear."""
    srf = g.surface(1, "fillet")
    u = np.linspace(*srf.u_range, 20001)
    sp = srf.evaluate(u, np.zeros_like(u))
    d1, d2 = sp.r_u[:, :2], sp.r_uu[:, :2]
    ang = np.degrees(np.arctan2(np.abs(d1[:, 1]), np.abs(d1[:, 0])))  # tangent against the centre line (x axis)
    i = int(np.argmin(np.abs(ang - 30.0)))
    kappa = np.abs(d1[i, 0] * d2[i, 1] - d1[i, 1] * d2[i, 0]) / np.linalg.norm(d1[i]) ** 3
    return 2 * abs(sp.r[i, 1]), 1.0 / kappa


@pytest.mark.parametrize("z, x", [(19, 0.0), (24, 0.0), (16, 0.2), (40, -0.2)])
def test_root_chord_and_fillet_radius_match_the_generated_tooth(z, x):
    g = Gear("g", z, 4.5, math.radians(20), 14.0, profile_shift=x)
    rf = root_factors(g, 1.5)
    s_fn, rho = _generated(g)
    # the sampled 30° point is within 1e-3 deg of the exact one: 1e-4 relative on the chord, 1e-3 on the radius
    assert rf.s_fn == pytest.approx(s_fn, rel=1e-4)
    assert rf.rho_f == pytest.approx(rho, rel=1e-3)


def test_factors_in_their_published_ranges_and_trends():
    """ISO 6336-3 figures: Y_F falls and Y_S rises with z; positive shift lowers Y_F (standard rack, load at D)."""
    yf = [root_factors(Gear("g", z, 4.5, math.radians(20), 14.0), 1.55).y_f for z in (19, 25, 40, 80)]
    ys = [root_factors(Gear("g", z, 4.5, math.radians(20), 14.0), 1.55).y_s for z in (19, 25, 40, 80)]
    assert all(a > b for a, b in zip(yf, yf[1:])) and all(a < b for a, b in zip(ys, ys[1:]))
    assert 1.2 < min(yf) and max(yf) < 2.2 and 1.6 < min(ys) and max(ys) < 2.4
    shifted = root_factors(Gear("g", 18, 4.5, math.radians(20), 14.0, profile_shift=0.4), 1.55).y_f
    assert shifted < yf[0]


def test_sigma_f0_is_linear_in_torque_and_rejects_what_method_b_does_not_cover():
    g = Gear("g", 19, 4.5, math.radians(20), 14.0)
    assert sigma_f0(g, 2e5, 1.57) == pytest.approx(2 * sigma_f0(g, 1e5, 1.57), rel=1e-12)
    with pytest.raises(InputError, match="eps_alpha"):
        root_factors(g, 2.3)
    with pytest.raises(InputError, match="internal"):
        root_factors(Gear("r", 60, 4.5, math.radians(20), 14.0, internal=True), 1.5)
