"""Factor records: where each number of a rating comes from.

Every influence factor of a rating is reported as a :class:`Factor` (value, :class:`Source`, note):

* ``Source.ISO``: computed by the method of ISO 6336 that the factor's note names;
* ``Source.INPUT``: given by the user (application factor K_A, a measured K_Hβ, Y_F from a drawing...);
* ``Source.GEARFE``: computed by gearfe's own analysis and passed in (K_Hβ from loaded TCA, K_Hα, K_γ of a
  planetary train). The library never produces this source itself; it carries what the caller says.

A caller passes a factor in with :class:`Given`; where a factor is taken as 1 or simplified, its note says so.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

__all__ = ["Source", "Factor", "Given"]


class Source(str, Enum):
    """Origin of a factor value."""

    ISO = "iso"
    INPUT = "input"
    GEARFE = "gearfe"


@dataclass(frozen=True)
class Factor:
    """One influence factor of a rating: its value, where it came from and what was assumed."""

    value: float
    source: Source
    note: str = ""

    def __post_init__(self):
        if not isinstance(self.source, Source):
            object.__setattr__(self, "source", Source(self.source))
        v = float(self.value)
        if v != v:
            from tca.rating.errors import RatingInputError

            raise RatingInputError("factor.value", self.value, "a finite number")


@dataclass(frozen=True)
class Given:
    """A factor passed in by the caller instead of the ISO method: ``source`` is INPUT or GEARFE."""

    value: float
    source: Source = Source.INPUT
    note: str = ""

    def __post_init__(self):
        from tca.rating.errors import RatingInputError

        src = Source(self.source)
        if src is Source.ISO:
            raise RatingInputError("given.source", src.value, "'input' or 'gearfe' (ISO values are computed, not given)")
        object.__setattr__(self, "source", src)
        v = float(self.value)
        if not (v == v and abs(v) != float("inf")):
            raise RatingInputError("given.value", self.value, "a finite number")

    def factor(self, default_note: str = "") -> Factor:
        """The :class:`Factor` this given value becomes in a result."""
        return Factor(float(self.value), self.source, self.note or default_note)
