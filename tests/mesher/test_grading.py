"""1D graded distributions of element sizes (mesher.grading)."""

import numpy as np
import pytest

from mesher.grading import SizeField, count, distribute
from tca.errors import InputError


def test_uniform_size_gives_equal_elements():
    # 10 mm at 0.7 mm: ceil(10 / 0.7) = 15 equal elements
    assert count(10.0, SizeField(0.7)) == 15
    f = distribute(10.0, SizeField(0.7))
    np.testing.assert_allclose(np.diff(f), 1 / 15, rtol=1e-12)


@pytest.mark.parametrize("focus", [0.0, 3.3, 7.0, 10.0])
def test_graded_elements_respect_target_size_and_growth(focus):
    h = SizeField(1.0, 0.1, focus, 1.25)
    x = 10.0 * distribute(10.0, h, pin=True)
    le = np.diff(x)
    # equidistribution of 1/h: each element is at most the largest target size on it
    # (0.2 % allowance: the integral of 1/h is a 2049-point trapezoid rule)
    hmax = np.maximum(h(x[:-1]), h(x[1:]))
    assert np.all(le <= hmax * 1.002)
    # neighbours differ by at most the growth ratio (5 % allowance for the rounding of counts at a pin)
    r = le[1:] / le[:-1]
    assert np.all(np.maximum(r, 1 / r) <= 1.25 * 1.05)
    # the focus is a node, and the elements touching it are within one growth step of the target
    k = int(np.argmin(np.abs(x - focus)))
    assert abs(x[k] - focus) < 1e-12
    touching = le[max(k - 1, 0):k + 1]
    assert np.all(touching <= 0.1 * 1.25 * 1.002)


def test_focus_near_an_end_is_served_by_the_end_node():
    # a focus 0.01 mm from the end (less than half the 0.1 mm target) must not create a sliver
    h = SizeField(1.0, 0.1, 9.99, 1.25)
    x = 10.0 * distribute(10.0, h, pin=True)
    assert np.diff(x).min() > 0.05
    assert not np.any(np.abs(x - 9.99) < 1e-12)


def test_size_field_rejects_bad_input():
    with pytest.raises(InputError, match="contact_size"):
        SizeField(1.0, 2.0, 0.0)
    with pytest.raises(InputError, match="growth"):
        SizeField(1.0, 0.5, 0.0, growth=5.0)
