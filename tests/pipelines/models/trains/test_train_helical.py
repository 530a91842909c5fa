"""A user's helical single-member train (docs/trains.md): the isostatic reader takes helical gears for gearfe ltca,
and the loaded TCA meets the closed forms in their helical (transverse) form.

The small train of test_train_solve.py (24/21/66, m_n = 2 mm, b = 10 mm, three planets in phase) with β = 15°:
sun right-hand, planet and ring left-hand, coarse flank grids."""

import math

import numpy as np
import pytest

from tca.errors import InputError
from tca.geometry.gear import Gear

from pipelines.cases.kinds import KINDS, read_checked
from pipelines.models.trains.geometry import TrainErrors, single_layout
from pipelines.models.trains.model import build_train_model
from pipelines.models.trains.options import TrainOptions
from pipelines.models.trains.run import solve_run
from tests.pipelines.models.trains.test_train_solve import PSI, T, path_stiffness, pin
from tests.support.shipped import shipped_table

BETA = math.radians(15.0)


def helical_gears():
    d = math.radians
    return (Gear("sun", 24, 2.0, d(20), 10, helix=BETA, hand=1), Gear("planet", 21, 2.0, d(20), 10, helix=BETA, hand=-1),
            Gear("ring", 66, 2.0, d(20), 10, helix=BETA, hand=-1, internal=True, addendum=0.95))


@pytest.fixture(scope="module")
def helical():
    return build_train_model(single_layout(*helical_gears(), 3), TrainOptions(torques=(T,), profile_size=1.0,
                                                                             axial_size=2.5))


def test_helical_train_equal_shares_and_single_pin_error(helical):
    """In phase: every share 1/n (0.5 %). One tangential pin error e, sun held: K_γ - 1 linear in e (2 %) and equal
    to Eq. (T6) in the transverse plane (5 %): the opening a = 2 e cos α_wt along the transverse line of action,
    k the transverse path stiffness dP_t/du_t of the train's own meshes (P_t = s T / r_b1, u_t = r_b1 ω_1)."""
    r = solve_run(helical, TrainErrors(), T, PSI)
    assert np.abs(r.sun_share * 3 - 1).max() < 0.005
    e, psi = 0.5e-3, PSI[:1]
    k1 = solve_run(helical, pin(e), T, psi).k_gamma - 1
    k2 = solve_run(helical, pin(2 * e), T, psi).k_gamma - 1
    assert k2 / k1 == pytest.approx(2.0, rel=0.02)
    at = helical.layout.sun.transverse_pressure_angle
    a = np.array([2 * e * math.cos(at), 0.0, 0.0])
    closed = 3 * path_stiffness(helical, psi[0]) * float((a.mean() - a).max()) * helical.layout.sun.r_b / T
    assert k1 == pytest.approx(closed, rel=0.05)


def _helical_part3(hands=("right", "left", "left"), helix=(15.0, 15.0, 15.0), **top):
    t = shipped_table("part3_indexing", top)
    for g, h, b in zip(("sun", "planet", "ring"), hands, helix):
        t.data["gears"][g].update({"helix_deg": b, "hand": h})
    return t


def test_isostatic_reader_takes_helical_gears_for_ltca():
    c = read_checked(_helical_part3(), KINDS["isostatic"], "ltca")
    assert c.sun.helix == pytest.approx(BETA) and (c.sun.hand, c.planet.hand, c.ring.hand) == (1, -1, -1)
    assert c.planet.r_p == pytest.approx(43 * 4.0 / (2 * math.cos(BETA)))  # normal module 4 mm
    assert c.errors.pins[0] == pytest.approx((0.0, 0.02))  # the case's indexing error kept


@pytest.mark.parametrize("kw, key", [({"hands": ("right", "right", "right")}, "gears.planet.hand"),
                                     ({"hands": ("right", "left", "right")}, "gears.ring.hand"),
                                     ({"helix": (15.0, 15.0, 12.0)}, "gears.ring.helix_deg")])
def test_helical_train_bad_input(kw, key):
    with pytest.raises(InputError, match=key.replace(".", r"\.")):
        read_checked(_helical_part3(**kw), KINDS["isostatic"], "ltca")
