"""A pair's TCA is computed once per process for inputs of equal value (tca.pair.memo)."""

import math
from dataclasses import dataclass, field

import numpy as np
import pytest

from tca.geometry.gear import Gear
from tca.pair.analysis import TCAOptions, run_pair_tca
from tca.pair.gear_pair import GearPair
from tca.pair.memo import Memo, Unkeyable, fingerprint

d = math.radians
OPTS = TCAOptions(cycles=1, steps_per_cycle=8)


def spur(teeth2=35, shift=0.0):
    return GearPair(Gear("pinion", 21, 2.0, d(20), 20), Gear("gear", teeth2, 2.0, d(20), 20, profile_shift=shift))


def test_an_equal_pair_built_anew_gets_the_stored_result_a_different_one_is_computed():
    r = run_pair_tca(spur(), OPTS)
    assert run_pair_tca(spur(), OPTS) is r  # equal values, other objects
    assert run_pair_tca(spur(), TCAOptions(cycles=1, steps_per_cycle=12)) is not r
    other = run_pair_tca(spur(shift=0.1), OPTS)
    assert other is not r and other.pair.gear2.profile_shift == 0.1
    # the stored result is shared: it cannot be changed in place by a caller
    with pytest.raises(ValueError, match="read-only"):
        r.te[0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        r.reference.x[0, 0] = 1.0


def test_fingerprint_follows_values_not_lazy_caches():
    a, b = spur(), spur()
    a.gear1.surface(1), a.gear1.rack  # fill the gear's lazy caches (a compare=False field, a cached property): same key
    assert fingerprint(a) == fingerprint(b)
    assert fingerprint(spur(shift=1e-12)) != fingerprint(b)
    assert fingerprint((1,)) != fingerprint((True,)) and fingerprint((1,)) != fingerprint((1.0,))
    assert fingerprint(np.zeros(3)) != fingerprint(np.zeros((3, 1)))
    with pytest.raises(Unkeyable):
        fingerprint(lambda x: x)


def test_memo_keeps_the_last_results_and_computes_unkeyable_inputs():
    calls = []

    @dataclass(frozen=True)
    class Box:
        v: float
        _cache: dict = field(default_factory=dict, compare=False)

    m = Memo(lambda b: calls.append(b) or np.full(2, getattr(b, "v", 0.0)), size=2)
    x = m(Box(1.0))
    assert m(Box(1.0)) is x and len(calls) == 1 and not x.flags.writeable
    m(Box(2.0)), m(Box(3.0))  # Box(1.0) leaves the store (size 2)
    m(Box(1.0))
    assert len(calls) == 4
    m(object()), m(object())  # no fingerprint: computed every time
    assert len(calls) == 6 and (m.hits, m.misses) == (1, 6)


def test_a_shared_folder_joins_processes(tmp_path):
    """Two memos sharing a folder stand for two processes (the suite's workers): the second reads the first's
    result from its file; a key with a nan is not shared; no temporary file is left."""
    calls = []

    def compute(v):
        calls.append(v)
        return np.array([v, 2.0 * v])

    first, second = Memo(compute), Memo(compute)
    first.share(tmp_path)
    second.share(tmp_path)
    a = first(1.5)
    b = second(1.5)
    assert calls == [1.5] and np.array_equal(a, b) and b is not a and not b.flags.writeable
    assert (second.hits, second.misses) == (1, 0)
    assert second(1.5) is b  # then from its own store
    assert len(list(tmp_path.iterdir())) == 1 and not list(tmp_path.glob(".*"))
    first(float("nan")), second(float("nan"))  # nan never matches: computed by each, not written
    assert len(calls) == 3 and len(list(tmp_path.iterdir())) == 1
    alone = Memo(compute)  # not shared: computes
    alone(1.5)
    assert len(calls) == 4


def test_a_pair_tca_read_from_the_shared_folder_equals_the_computed_one(tmp_path):
    """A pair's TCA written by one memo and read back by another: equal pair and options, equal arrays."""
    first, second = Memo(run_pair_tca), Memo(run_pair_tca)
    first.share(tmp_path)
    second.share(tmp_path)
    r = first(spur(), OPTS)
    s = second(spur(), OPTS)
    assert (second.hits, second.misses) == (1, 0) and s is not r
    assert s.pair == r.pair and s.options == r.options
    for f in ("phi1", "phi2", "te", "transitions"):
        assert np.array_equal(getattr(s, f), getattr(r, f)), f
        assert not getattr(s, f).flags.writeable, f
