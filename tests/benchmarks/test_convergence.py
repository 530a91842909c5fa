"""Richardson extrapolation: exact on a power law, order recovered, non-monotone sequences refused."""

import pytest

from benchmarks.convergence import richardson
from tca.errors import InputError


@pytest.mark.parametrize("p", [1.0, 2.0, 1.37])
def test_power_law_is_extrapolated_exactly(p):
    h = [0.8, 0.4, 0.2, 0.1]
    f = [10.0 + 3.0 * x**p for x in h]
    r = richardson(h, f)
    assert r.order == pytest.approx(p, rel=1e-9)
    assert r.value == pytest.approx(10.0, rel=1e-12)
    assert r.errors[-1] == pytest.approx(3.0 * 0.1**p / 10.0, rel=1e-9)


def test_non_monotone_sequence_is_refused():
    with pytest.raises(InputError, match="monotonically"):
        richardson([0.4, 0.2, 0.1], [1.0, 1.2, 1.1])
