"""Degrees of freedom of planar planetary trains (section 3.2, Eqs. 3.1-3.3)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from tca.isostatic.dof import TrainConstraints, count_dof
from tca.errors import InputError
from tca.geometry.gear import Gear
from tca.isostatic.analysis import run_isostatic_tca
from tca.isostatic.subtrain import JT_CENTRES, Members, subtrain_eval
from tca.isostatic.train import IsostaticTrain


@pytest.mark.parametrize("case,kw,planets,c0", [
    (1, dict(), 1, 8),                                               # Eq. (3.1): 9 + 3 Np = 8 + 4 Np
    (2, dict(sun_axis_free=True), 3, 6),                             # Eq. (3.2): 9 + 3 Np = 6 + 4 Np
    (3, dict(sun_axis_free=True, carrier_axis_free=True), 5, 4),     # Eq. (3.3): 9 + 3 Np = 4 + 4 Np
])
def test_report_cases_give_1_3_5_planets(case, kw, planets, c0):
    d = count_dof(TrainConstraints(planets, **kw))
    assert d.isostatic_planets == planets
    assert d.dof == 9 + 3 * planets
    assert d.constraints == c0 + 4 * planets == d.dof
    assert d.mobility == 0
    # the report's tables of constraints, row by row
    rows = dict(d.rows)
    assert rows["(ii) sun angle"] == 1 and rows["(iv) ring axis and angle"] == 3
    assert rows["(i) sun axis"] == (0 if case > 1 else 2)
    assert rows["(iii) carrier axis"] == (0 if case == 3 else 2)
    assert rows["(v) planets pinned"] == rows["(vi) tangency with sun and ring"] == 2 * planets


def test_states_of_non_isostatic_trains():
    assert count_dof(TrainConstraints(3)).state == "hyperstatic"  # case 1 constraints, 3 planets: N_f - N_c = -2
    assert count_dof(TrainConstraints(3)).mobility == -2
    assert count_dof(TrainConstraints(2, sun_axis_free=True)).state == "under-constrained"
    assert count_dof(TrainConstraints(3, ring_axis_free=True)).state == "isostatic"  # Note 2
    assert count_dof(TrainConstraints(3, carrier_axis_free=True)).state == "isostatic"


@given(st.integers(1, 12), st.booleans(), st.booleans(), st.booleans())
def test_count_is_consistent(n, sun, car, ring):
    if sun and car and ring:
        with pytest.raises(InputError, match="grounded"):
            TrainConstraints(n, sun, car, ring)
        return
    d = count_dof(TrainConstraints(n, sun, car, ring))
    # section 3.2 (Eqs. 3.1-3.3): 3 planar DOF per member (sun, carrier, ring: 9, and each planet), and the
    # constraints row by row: (i) sun axis 2, (ii) sun angle 1, (iii) carrier axis 2, (iv) ring axis and angle
    # 3 (its angle only, 1, with a floating ring axis: Note 2), (v)+(vi) 4 per planet
    assert d.dof == 9 + 3 * n
    assert d.constraints == (0 if sun else 2) + 1 + (0 if car else 2) + (1 if ring else 3) + 4 * n
    # identities of the count, kept beside the closed forms above
    assert d.dof - d.constraints == d.isostatic_planets - n  # one planet adds 3 DOF and 4 constraints
    assert d.constraints == sum(v for _, v in d.rows)


@pytest.mark.parametrize("bad", [dict(n_planets=0), dict(n_planets=2.0), dict(n_planets=3, planets_pinned=False)])
def test_bad_constraints_are_rejected(bad):
    with pytest.raises(InputError):
        TrainConstraints(**bad)


def test_case_3_is_isostatic_by_count_but_singular():
    # The count of section 3.2 gives 5 planets for a floating sun and carrier, but translations of
    # any member change the loop backlash as first harmonics of the planet angles: rank 3 < 5. The
    # Jacobian of Eq. (3.22) w.r.t. the 4 floating coordinates, computed by the simulation's own
    # implicit differentiation, has two singular values at round-off level (< 1e-12 of the largest),
    # while case 2 (one floating axis, 3 planets) is regular (ratio > 0.1).
    d = math.radians
    sun, pl = Gear("sun", 40, 3.0, d(20), 30), Gear("planet", 20, 3.0, d(20), 30)
    ring = Gear("ring", 80, 3.0, d(20), 30, internal=True)
    c3 = TrainConstraints(5, sun_axis_free=True, carrier_axis_free=True)
    assert count_dof(c3).state == "singular" and count_dof(c3).first_order_rank == 3
    ratios = {}
    for free, n in ((("sun", "carrier"), 5), (("sun",), 3)):
        tr = IsostaticTrain(sun, (pl,) * n, ring, TrainConstraints(n, sun_axis_free=True,
                                                                  carrier_axis_free="carrier" in free))
        fl = tr.flanks()
        # the ideal configuration at phi1 = 0.3 from the (case 2) solver and, for case 3, the rigid one
        ref = run_isostatic_tca(tr.with_(constraints=TrainConstraints(n)) if n == 5 else tr, np.array([0.3]))
        m = Members(np.repeat(ref.phi1, n), tr.theta, tr.pins, np.zeros((n, 2)), ref.teeth.reshape(n, 4),
                    np.zeros((n, 3, 2)))
        x = np.c_[ref.params.reshape(n, 4), ref.phi2.reshape(n), ref.phi_c_planets.reshape(n)]
        F, J = subtrain_eval(tr, fl, m, x)
        assert np.abs(F).max() < 1e-10
        cols = [0, 1, 2, 3][: 2 * len(free)]
        dX = -np.linalg.solve(J, np.broadcast_to(JT_CENTRES[:, cols], (n, 6, len(cols))))
        dG = dX[:-1, 5, :] - dX[1:, 5, :]
        sv = np.linalg.svd(dG, compute_uv=False)
        ratios[n] = sv[-1] / sv[0]
    assert ratios[5] < 1e-12
    assert ratios[3] > 0.1
    with pytest.raises(InputError, match="singular"):
        run_isostatic_tca(IsostaticTrain(sun, (pl,) * 5, ring, c3), np.array([0.0]))
