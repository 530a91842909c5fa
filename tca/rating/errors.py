"""Errors and warnings of the rating: each names the key, the value and what would be valid.

:class:`RatingInputError` is a :class:`tca.errors.InputError` (a ``ValueError``): the command line prints
it as one line (``key = value is invalid: expected valid``) with exit status 2.
:class:`RatingWarning` is returned (never raised) when a case lies outside an assumption of ISO 6336
but can still be rated (ε_α < 1, β > 30°, ...): the rating is computed and the warning names the
failed assumption.
"""

from __future__ import annotations

from dataclasses import dataclass

from tca.errors import InputError

__all__ = ["RatingInputError", "RatingWarning", "check_range"]


class RatingInputError(InputError):
    """A value outside the range ISO 6336 (or this library) allows: names key, value and range."""

    def __init__(self, key: str, value, valid: str, why: str = ""):
        super().__init__(key, value, valid, why)

    @property
    def key(self) -> str:
        """The key, under the name the rating's docstrings use (``field`` of :class:`tca.errors.InputError`)."""
        return self.field


@dataclass(frozen=True)
class RatingWarning:
    """A failed assumption of ISO 6336: ``code`` is stable (for tests, filters), ``message`` is for people."""

    code: str
    message: str

    def __str__(self) -> str:
        return f"{self.code}: {self.message}"


def check_range(key: str, value: float, lo: float | None = None, hi: float | None = None, *,
                lo_open: bool = False, hi_open: bool = False, why: str = "") -> float:
    """Return ``value`` if it lies in the interval, else raise :class:`RatingInputError`.

    The bounds are closed unless ``lo_open``/``hi_open``; ``None`` leaves a side unbounded. NaN never passes.
    """
    v = float(value)
    ok = v == v  # NaN fails
    if ok and lo is not None:
        ok = v > lo if lo_open else v >= lo
    if ok and hi is not None:
        ok = v < hi if hi_open else v <= hi
    if not ok:
        left = "-inf" if lo is None else f"{lo:g}"
        right = "inf" if hi is None else f"{hi:g}"
        interval = ("(" if lo_open or lo is None else "[") + f"{left}, {right}" + (")" if hi_open or hi is None else "]")
        raise RatingInputError(key, value, f"in {interval}", why)
    return v
