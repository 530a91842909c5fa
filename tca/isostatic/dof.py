r"""Degrees of freedom and constraints of a planar planetary train (section 3.2, Eqs. 3.1–3.3).

Every member of the planar mechanism is a rigid body with three DOF (two translations, one
rotation): sun, carrier, ring and :math:`N_p` planets give :math:`N_f = 9 + 3N_p`.
Constraints:

==========================================  ================
(i)   axis of the sun fixed                 2 (0 when free)
(ii)  angular position of the sun given     1
(iii) axis of the carrier fixed             2 (0 when free)
(iv)  axis and angle of the ring given      3 (1 when its axis is free, Note 2)
(v)   each planet pinned to the carrier     :math:`2N_p`
(vi)  each planet in tangency with sun
      and ring                              :math:`2N_p`
==========================================  ================

so :math:`N_c = c_0 + 4N_p` with :math:`c_0 = 1 + 2[\text{sun fixed}] + 2[\text{carrier fixed}]
+ 1 + 2[\text{ring fixed}]`. The train is *isostatic* when :math:`N_f = N_c`, i.e. for
:math:`N_p = 9 - c_0` planets: case 1 (everything fixed) 1 planet (Eq. 3.1), case 2 (sun free)
3 planets (Eq. 3.2), case 3 (sun and carrier free) 5 planets (Eq. 3.3). With more planets the
train is hyperstatic (over-constrained: not all planets can touch in the presence of errors),
with fewer it has free motions (under-constrained: the position of a floating member is not
determined).

The count is structural; the geometry can make constraints dependent. To first order, the backlash
of the loop sun–planet *i*–ring changes with a translation :math:`\mathbf e` of the sun, the carrier
or the ring as :math:`\mathbf e\cdot R(q_i)\,\mathbf w` (a fixed vector :math:`\mathbf w` per member, see
:mod:`tca.isostatic.linear`): a first harmonic of the planet's angle :math:`q_i`, whichever member
floats; the carrier's rotation changes every loop alike. The Jacobian of the loop closures with
respect to the floating unknowns therefore has rank :math:`\min(N_p,\ 1 + 2\,[\text{any axis free}])`,
not :math:`1 + 2n_{free}`. With one floating axis (case 2) and three planets it is regular; with two
floating axes (case 3, five planets) it has rank 3 < 5: a combined translation of the two floating
members leaves every loop unchanged (the positions are not determined) and the second harmonic
of the planets' errors cannot be absorbed (generic errors leave planets out of contact). The
simulation verifies this numerically (the Jacobian of Eq. 3.22 is singular to round-off) and
refuses such set-ups; :attr:`DOFCount.first_order_rank` reports it.
"""

from __future__ import annotations

from dataclasses import dataclass

from tca.errors import InputError

__all__ = ["TrainConstraints", "DOFCount", "count_dof"]


@dataclass(frozen=True)
class TrainConstraints:
    """Constraint choices of a planar planetary train (section 3.2)."""

    n_planets: int
    sun_axis_free: bool = False
    carrier_axis_free: bool = False
    ring_axis_free: bool = False  # Note 2: the ring may float instead of the sun
    planets_pinned: bool = True  # Note 3: unpinned planets are not considered by the report

    def __post_init__(self):
        if not (isinstance(self.n_planets, int) and not isinstance(self.n_planets, bool) and 1 <= self.n_planets <= 12):
            raise InputError("planets.count", self.n_planets, "an integer in [1, 12]")
        if not self.planets_pinned:
            raise InputError("planets_pinned", False, "true (section 3.2, Note 3: unpinned planets are not considered)")
        for name in ("sun_axis_free", "carrier_axis_free", "ring_axis_free"):
            if not isinstance(getattr(self, name), bool):
                raise InputError(name, getattr(self, name), "true or false")
        if self.sun_axis_free and self.carrier_axis_free and self.ring_axis_free:
            raise InputError("ring_axis_free", True, "false when the sun and carrier axes float",
                             "Note 1 of section 3.2: at least one member must be grounded, or the whole train "
                             "could translate")

    @property
    def free_centres(self) -> tuple[str, ...]:
        """Members whose axis floats, in the order sun, carrier, ring."""
        return tuple(n for n, f in (("sun", self.sun_axis_free), ("carrier", self.carrier_axis_free),
                                    ("ring", self.ring_axis_free)) if f)


@dataclass(frozen=True)
class DOFCount:
    """DOF N_f, constraints N_c, mobility N_f - N_c and the isostatic number of planets."""

    dof: int
    constraints: int
    isostatic_planets: int
    rows: tuple[tuple[str, int], ...]  # the report's table of constraints, (condition, count)
    n_planets: int = 1
    n_free: int = 0  # floating axes

    @property
    def first_order_rank(self) -> int:
        """Rank of the loop closures w.r.t. the carrier angle and the floating centres (module docstring)."""
        return min(self.n_planets, 1 + (2 if self.n_free else 0))

    @property
    def singular(self) -> bool:
        """Structurally isostatic but with dependent constraints (two or more floating axes)."""
        return self.mobility == 0 and self.first_order_rank < 1 + 2 * self.n_free

    @property
    def mobility(self) -> int:
        """N_f - N_c: 0 isostatic, > 0 under-constrained (free motions), < 0 hyperstatic."""
        return self.dof - self.constraints

    @property
    def state(self) -> str:
        m = self.mobility
        if m == 0:
            return "singular" if self.singular else "isostatic"
        return "under-constrained" if m > 0 else "hyperstatic"

    def as_dict(self) -> dict:
        return {"dof": self.dof, "constraints": self.constraints, "mobility": self.mobility, "state": self.state,
                "isostatic_planets": self.isostatic_planets, "first_order_rank": self.first_order_rank,
                "table": {k: v for k, v in self.rows}}


def count_dof(c: TrainConstraints) -> DOFCount:
    """DOF and constraints of the train (section 3.2); isostatic N_p from 9 + 3 N_p = c_0 + 4 N_p."""
    n = c.n_planets
    rows = (
        ("(i) sun axis", 0 if c.sun_axis_free else 2),
        ("(ii) sun angle", 1),
        ("(iii) carrier axis", 0 if c.carrier_axis_free else 2),
        ("(iv) ring axis and angle", 1 if c.ring_axis_free else 3),
        ("(v) planets pinned", 2 * n),
        ("(vi) tangency with sun and ring", 2 * n),
    )
    dof = 9 + 3 * n
    nc = sum(v for _, v in rows)
    c0 = nc - 4 * n
    return DOFCount(dof, nc, 9 - c0, rows, n, len(c.free_centres))
