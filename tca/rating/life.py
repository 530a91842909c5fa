r"""Life factors of ISO 6336-2 (Z_NT) and ISO 6336-3 (Y_NT), method B, and the limited-life interpolation.

Number of load cycles of a gear: :math:`N_L = 60\,n\,L_h\,j` (speed :math:`n` [1/min], life :math:`L_h` [h],
:math:`j` contacts per revolution, e.g. the number of planets for a sun) (L1).

Each life curve is given by ISO as values at points: the static value up to :math:`N_{st}`, 1 at the reference
point :math:`N_{ref}` (and, for limited pitting, 1.3 at :math:`10^7`), and :math:`Z_{10}` at :math:`10^{10}`
(0.85, up to 1.0 for optimum lubrication, material, manufacturing and experience); between the points the factor is
a straight line in log-log, and beyond :math:`10^{10}` it keeps :math:`Z_{10}` (L2):

=================================================  ======  =====  ===========================  =======
curve (materials by ISO abbreviation)              N_st    Z_st   knee                         N_ref
=================================================  ======  =====  ===========================  =======
Z_NT: St, V, GGG (perl., bai.), GTS, Eh, IF        1e5     1.6                                 5e7
Z_NT: the same, limited pitting permitted          6e5     1.6    (1e7, 1.3)                   1e9
Z_NT: GG, GGG (ferr.), NT, NV (nitr.)              1e5     1.3                                 2e6
Z_NT: NV (nitrocar.)                               1e5     1.1                                 2e6
Y_NT: V, GGG (perl., bai.), GTS (perl.)            1e4     2.5                                 3e6
Y_NT: Eh, IF (root hardened)                       1e3     2.5                                 3e6
Y_NT: St, NT, NV (nitr.), GGG (ferr.), GG          1e3     1.6                                 3e6
Y_NT: NV (nitrocar.)                               1e3     1.1                                 3e6
=================================================  ======  =====  ===========================  =======

Earlier editions print these lines as power laws with rounded exponents (e.g. :math:`(5\cdot10^7/N_L)^{0.0306}`); the
point form differs from them by up to 4e-4. The point form is what the two sources of the tests apply:
ISO/TR 6336-30 Example 1 (σ_HP1 = 1338.48050 MPa needs Z_NT1 = 0.910054, the log-log value; the rounded exponent
gives 0.910258) and the KISSsoft reports (Z_NT = Y_NT = 0.850 beyond 10^10).

Limited life, method B: the other influence factors (Z_L, Z_v, Z_R; Y_δrelT, Y_RrelT, Y_X) are interpolated in the
same log-log way between their static values at :math:`N_{st}` and their reference values at :math:`N_{ref}` (L3);
beyond :math:`N_{ref}` they keep the reference value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.rating.errors import RatingInputError, check_range
from tca.rating.materials import MaterialKind

__all__ = ["LifeCurve", "contact_life_curve", "bending_life_curve", "life_factor", "load_cycles", "interpolate_life",
           "LONG_LIFE"]

LONG_LIFE = 1e10


@dataclass(frozen=True)
class LifeCurve:
    """A life curve (L2): static point, optional knee (limited pitting), reference point; ``name`` for notes."""

    name: str
    n_static: float
    z_static: float
    n_ref: float
    knee: tuple[float, float] | None = None  # (N, Z) between static and reference (Z_NT, limited pitting)


_K = MaterialKind
_CONTACT_1 = frozenset({_K.ST, _K.ST_CAST, _K.V_CARBON, _K.V_ALLOY, _K.GGG, _K.GTS, _K.EH, _K.IF})
_CONTACT_3 = frozenset({_K.GG, _K.GGG_FERRITIC, _K.NT, _K.NV_NITRIDED})
_BEND_1 = frozenset({_K.V_CARBON, _K.V_ALLOY, _K.GGG, _K.GTS})
_BEND_2 = frozenset({_K.EH, _K.IF})
_BEND_3 = frozenset({_K.ST, _K.ST_CAST, _K.NT, _K.NV_NITRIDED, _K.GGG_FERRITIC, _K.GG})


def contact_life_curve(kind: MaterialKind, limited_pitting: bool = False) -> LifeCurve:
    """Z_NT curve of ISO 6336-2 for a material kind."""
    kind = MaterialKind(kind)
    if kind in _CONTACT_1:
        if limited_pitting:
            return LifeCurve("ISO 6336-2 Z_NT, St/V/GGG/GTS/Eh/IF, limited pitting permitted", 6e5, 1.6, 1e9,
                             (1e7, 1.3))
        return LifeCurve("ISO 6336-2 Z_NT, St/V/GGG/GTS/Eh/IF", 1e5, 1.6, 5e7)
    if kind in _CONTACT_3:
        return LifeCurve("ISO 6336-2 Z_NT, GG/GGG(ferr.)/NT/NV(nitr.)", 1e5, 1.3, 2e6)
    return LifeCurve("ISO 6336-2 Z_NT, NV(nitrocar.)", 1e5, 1.1, 2e6)


def bending_life_curve(kind: MaterialKind) -> LifeCurve:
    """Y_NT curve of ISO 6336-3 for a material kind."""
    kind = MaterialKind(kind)
    if kind in _BEND_1:
        return LifeCurve("ISO 6336-3 Y_NT, V/GGG/GTS", 1e4, 2.5, 3e6)
    if kind in _BEND_2:
        return LifeCurve("ISO 6336-3 Y_NT, Eh/IF", 1e3, 2.5, 3e6)
    if kind in _BEND_3:
        return LifeCurve("ISO 6336-3 Y_NT, St/NT/NV(nitr.)/GGG(ferr.)/GG", 1e3, 1.6, 3e6)
    return LifeCurve("ISO 6336-3 Y_NT, NV(nitrocar.)", 1e3, 1.1, 3e6)


def load_cycles(speed: float, hours: float, contacts_per_revolution: int = 1) -> float:
    """N_L (L1) for ``speed`` [1/min] over ``hours`` [h]."""
    check_range("speed", speed, 0.0, lo_open=True)
    check_range("life_hours", hours, 0.0, lo_open=True)
    if isinstance(contacts_per_revolution, bool) or int(contacts_per_revolution) != contacts_per_revolution \
            or contacts_per_revolution < 1:
        raise RatingInputError("contacts_per_revolution", contacts_per_revolution, "an integer >= 1")
    return 60.0 * speed * hours * int(contacts_per_revolution)


def _loglog(n: float, n0: float, z0: float, n1: float, z1: float) -> float:
    """Straight line through (n0, z0), (n1, z1) in log-log, at n."""
    t = math.log(n / n0) / math.log(n1 / n0)
    return math.exp(math.log(z0) + t * (math.log(z1) - math.log(z0)))


def life_factor(curve: LifeCurve, cycles: float, long_life: float = 0.85) -> float:
    """Z_NT or Y_NT (L2) at ``cycles``; ``long_life`` = Z_10, the value at 10^10 cycles, in [0.85, 1]."""
    n = check_range("load_cycles", cycles, 0.0, lo_open=True)
    check_range("long_life", long_life, 0.85, 1.0, why="ISO 6336-2/-3: 0.85, up to 1.0 for optimum conditions")
    if n <= curve.n_static:
        return curve.z_static
    if curve.knee is not None and n <= curve.knee[0]:
        return _loglog(n, curve.n_static, curve.z_static, *curve.knee)
    start = curve.knee if curve.knee is not None else (curve.n_static, curve.z_static)
    if n <= curve.n_ref:
        return _loglog(n, start[0], start[1], curve.n_ref, 1.0)
    if n <= LONG_LIFE:
        return _loglog(n, curve.n_ref, 1.0, LONG_LIFE, long_life)
    return long_life


def interpolate_life(curve: LifeCurve, cycles: float, static_value: float, reference_value: float) -> float:
    """A factor (or product) between its static and reference values at ``cycles`` (L3)."""
    n = check_range("load_cycles", cycles, 0.0, lo_open=True)
    if n <= curve.n_static:
        return static_value
    if n >= curve.n_ref:
        return reference_value
    return _loglog(n, curve.n_static, static_value, curve.n_ref, reference_value)
