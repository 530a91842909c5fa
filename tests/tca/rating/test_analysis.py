"""Load factors from a loaded TCA (tca.rating.analysis): (A1) and (A2) against distributions whose factors are known."""

import numpy as np
import pytest

from tca.rating import Source
from tca.rating.analysis import AnalysisFactors, face_load_from_slices, transverse_from_shares, with_analysis
from tca.rating.errors import RatingInputError
from tca.rating.factors import Given


def slices(w, b=40.0, n=400, positions=1):
    """Slices of a line load w(z) [N/mm] over [-b/2, b/2], repeated at ``positions`` positions."""
    z = -0.5 * b + b * (np.arange(n) + 0.5) / n
    f = w(z) * b / n
    return np.repeat(np.arange(positions), n), np.tile(z, positions), np.tile(f, positions)


def test_uniform_line_load_gives_one():
    fl = face_load_from_slices(*slices(lambda z: 100.0 + 0 * z), 40.0, 20)
    assert fl.k_h_beta == pytest.approx(1.0, abs=1e-12) and fl.instantaneous == pytest.approx(1.0, abs=1e-12)


def test_linear_line_load_gives_its_max_over_mean():
    """w = w_m (1 + k z/(b/2)): the bin at the loaded end averages 1 + k (1 - 1/N) of the mean (exact for N bins)."""
    k, n = 0.6, 20
    fl = face_load_from_slices(*slices(lambda z: 100.0 * (1 + k * z / 20.0)), 40.0, n)
    assert fl.k_h_beta == pytest.approx(1 + k * (1 - 1 / n), rel=1e-9)
    assert np.argmax(fl.line_load) == n - 1


def test_slices_longer_than_the_bins_are_spread_over_them():
    """Slices 1.125 mm long on a 14 mm face cut into 14 bins: by their centres some bins get none (aliasing), spread
    over their lengths every bin gets the uniform line load (K_Hβ = 1)."""
    n = int(14.0 / 1.125) + 1
    z = -7.0 + 1.125 * (np.arange(n) + 0.5)
    z = z[z < 7.0]
    f = np.full(len(z), 100.0 * 1.125)
    f[-1] = 100.0 * (7.0 - (z[-1] - 0.5625))  # the last slice is cut by the face end
    e = np.full(len(z), 0.5625)
    e[-1] = 0.5 * (7.0 - (z[-1] - 0.5625))
    z[-1] = 7.0 - e[-1]
    aliased = face_load_from_slices(np.zeros(len(z)), z, f, 14.0, 14)
    spread = face_load_from_slices(np.zeros(len(z)), z, f, 14.0, 14, e)
    assert aliased.k_h_beta > 1.1
    assert spread.k_h_beta == pytest.approx(1.0, abs=1e-9)


def test_moving_lines_average_over_the_cycle():
    """Helical-like: at each position the load sits on part of the face (instantaneous ratio 2), but over the cycle
    every section is loaded equally: K_Hβ = 1, the instantaneous value reported beside it."""
    b, n_pos = 40.0, 8
    pos, z, f = [], [], []
    for j in range(n_pos):
        zz = -0.5 * b + (np.arange(200) + 0.5) * b / 200
        on = ((zz + 0.5 * b + j * b / n_pos) % b) < 0.5 * b
        pos.append(np.full(on.sum(), j)), z.append(zz[on]), f.append(np.full(on.sum(), 1.0))
    fl = face_load_from_slices(np.concatenate(pos), np.concatenate(z), np.concatenate(f), b, n_pos)
    assert fl.k_h_beta == pytest.approx(1.0, abs=1e-12)
    assert fl.instantaneous == pytest.approx(2.0, rel=1e-12)


def test_transverse_factor_of_a_spur_mesh_cycle():
    """Spur: single contact (share 1 on length b) governs; double contact 0.6/0.4 stays below it: K_Hα = 1.
    A pair carrying 0.9 of the load where ISO's ideal gives it 0.5 *and* in single contact: (A2) from the largest."""
    b = 14.0
    shares = np.array([[1.0, 0.0], [0.6, 0.4], [0.4, 0.6]])
    lengths = np.array([[b, 0.0], [b, b], [b, b]])
    t = transverse_from_shares(shares, lengths)
    assert t.k_h_alpha == pytest.approx(1.0) and t.unlimited == pytest.approx(1.0)
    # helical-like: two pairs always in contact (lengths 10 + 10 mm): one carrying 0.7 -> 0.7/10 over 1/20 = 1.4
    t = transverse_from_shares(np.array([[0.5, 0.5], [0.7, 0.3]]), np.array([[10.0, 10.0], [10.0, 10.0]]))
    assert t.k_h_alpha == pytest.approx(1.4)
    # never below 1: at every position the shares sum to 1, so some pair carries at least 1/ΣL per unit length
    rng = np.random.default_rng(3)
    for _ in range(200):
        s = rng.random((5, 3)) * (rng.random((5, 3)) > 0.3) + 1e-3
        s /= s.sum(axis=1, keepdims=True)
        assert transverse_from_shares(s, rng.random((5, 3)) * 10 + 0.1).unlimited >= 1.0 - 1e-12


def test_bad_inputs():
    with pytest.raises(RatingInputError):
        face_load_from_slices([0], [0.0], [0.0], 10.0, 4)
    with pytest.raises(RatingInputError):
        face_load_from_slices([0, 1], [0.0], [1.0], 10.0, 4)
    with pytest.raises(RatingInputError):
        transverse_from_shares(np.ones((2, 2)), np.ones((2, 3)))
    with pytest.raises(RatingInputError):
        AnalysisFactors(k_h_beta=1.2)


def test_with_analysis_replaces_iso_methods():
    from tests.tca.rating.test_api import base_case

    from tca.rating import rate

    f = AnalysisFactors(k_h_beta=Given(1.3, Source.GEARFE, "ltca"), k_h_alpha=Given(1.1, Source.GEARFE, "ltca"))
    r = rate(with_analysis(base_case(), f))
    assert r.pinion.factors["K_Hbeta"].value == 1.3 and r.pinion.factors["K_Hbeta"].source is Source.GEARFE
    assert r.pinion.factors["K_Falpha"].value == 1.1 and r.face_load is None
