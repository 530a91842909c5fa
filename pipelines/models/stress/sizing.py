r"""Element sizes of the loaded flanks from Hertz's contact (the formulas are in :mod:`pipelines.models.stress.scene`),
and the grading away from the zones (issue 26, item 2).

Grading away from the zones. The fillet stress (the largest nodal principal stress on the loaded teeth's fillets,
:mod:`pipelines.models.stress.headline`) converges with the element size along the fillet arc :math:`h_f` and the
thickness of the element layers normal to the fillet, on both sides of the tooth; it barely depends on the axial
spacing away from the contact zone, on the growth of the sizes along the profile and the axis away from the zones, or
on the coarse size of the rest (docs/benchmarks.md, "Third round: grading away from the zones" and "Fourth round: the
fillet target", measured on the crowned pair). With :math:`r` = ``refine``, sizes at refine 1 divided by r:

.. math::
    h_f = 0.045\,m \quad (G1), \qquad h_{z,max} = \max(h_{coarse},\ \min(2\,h_{coarse},\ 1.5\,m)) \quad (G2),
    \qquad q = 1.5 \quad (G4),

.. math::
    q_{s} = 1 + 0.3 / r \quad (G3), \qquad q_{d} = 1 + 0.5 / r \quad (G5), \qquad
    h(d) = \min(h_{coarse},\ h_c + (q_d - 1)\,d,\ h_f + (q_s - 1)\,d) \quad (G6)

(G1) the fillet arc of the loaded teeth (0.1 m before the third round, 0.05 m before the fourth), (G2) the largest
axial spacing of a graded member outside its zones (was the coarse size; 2 coarse sizes at refine >= 1, never beyond
the 1.5 m measured at refine 1, so coarser models keep their coarse size: at refine 0.3 a 5 m spacing moved the
conventional twin's torque balance past 1e-3), (G4) the growth of the flank profile and of the axial levels away from
the zones, ``mesh.growth`` (was 1.3: the zones keep the contact sizes, the pressure outside them is nil);
(G3) the growth of the layers under the loaded fillet (toward the mid-surface) and along its root, (G5) of the
layers under the contact (Hertz) and under the other flank and fillet of the loaded tooth (from ``back`` = h_f):
growth ratios refined like the sizes, the slope q - 1 of the size field divided by r (was 1.5 for both at every
refine); (G6) the layer size at depth d under the loaded flank and fillet, the finer of the Hertz field (contact
size h_c) and the fillet field (:mod:`mesher.body`, ``plan_tooth``). The layers under the fillet are graded like those
under the flank (:mod:`mesher.tooth`, Step 3).

Axial size of a line contact (G7). A contact's axial size resolves its pressure along the loaded line: a/6 of the
line's half-length a (an ellipse's pressure falls to zero over a). Along a line contact whose line load is uniform
(the smallest slice line load of the loaded estimate at least 0.9 of the largest: an aligned spur pair, a profile
modification) it is a/4: on the aligned FZG-type pair and a 22/37 pair the peak pressure and the fillet stress at a/4
are within 0.2 % of those at a/12, at 0.36-0.40 times the DOF (docs/benchmarks.md, "Fifth round: the axial size of
a uniform line contact"); a line load that varies along the face (misalignment: 1.2-1.7 % lower peak at a/4 with
2' of misalignment, 0.3 % at a/6; end relief) keeps a/6.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from fem.material import Material
from tca.errors import GeometryError, InputError
from tca.geometry.gear import Gear
from tca.pair.analysis import ContactKind

__all__ = ["HertzContact", "hertz_contact", "SizeRules", "ContactSizes", "contact_sizes", "zone_sizes", "unloaded_sizes",
           "NEIGHBOUR", "FILLET", "AXIAL_COARSE", "AXIAL_COARSE_MAX", "SECTION_GROWTH", "DEPTH_GROWTH", "GROWTH",
           "AXIAL_LINE", "UNIFORM_LINE", "SIZING"]

# ---------------------------------------------------------------------------------------------- Hertz and sizes
@dataclass(frozen=True)
class HertzContact:
    """Hertz estimate of one contact: semi-axes a >= b [mm], peak pressure p0 [MPa], normal load [N].

    ``line``: a line contact (the ellipse would be longer than the contact line): ``a`` is half the
    contact line's length and ``b`` the half-width of the band, ``w`` = load / (2 a) [N/mm].
    """

    a: float  # [mm]
    b: float  # [mm]
    p0: float  # [MPa]
    line: bool
    load: float  # [N]

    @property
    def w(self) -> float:
        """Load per unit length of the contact line [N/mm] (line contact; for an ellipse P / (2a))."""
        return self.load / (2.0 * self.a)

    def as_json(self) -> dict:
        """The summary's record (keys with units)."""
        return {"a_mm": self.a, "b_mm": self.b, "p0_mpa": self.p0, "line": self.line, "load_n": self.load}


def _ratio(e: float) -> float:
    """B/A of an ellipse of eccentricity e (Johnson eq. 4.39)."""
    m = e * e
    K, Ee = ellipk(m), ellipe(m)
    return ((Ee / (1 - m)) - K) / (K - Ee)


_E_MAX = 1 - 1e-12  # largest eccentricity solved for; B/A beyond _ratio(_E_MAX) (~1e11) is a line contact


def hertz_contact(lam: tuple, load: float, material: Material, length: float) -> HertzContact:
    """Hertz contact of two bodies of one ``material`` (module docstring of :mod:`pipelines.models.stress.scene`).

    lam: eigenvalues (λ1, λ2) of the relative curvature [1/mm]; load [N]; ``length`` [mm]: the
    length of the contact line inside both flanks (the face width over cos β_b for a helical pair);
    an ellipse longer than it is a line contact, b = sqrt(4 w R / (π E*)) = sqrt(8 w R / (π E')),
    w = load / length, R = 1 / λ2, E* = E / (2 (1 - ν²)) = E' / 2, p0 = 2 w / (π b).
    """
    Es = material.E / (2.0 * (1.0 - material.nu**2))
    l1, l2 = sorted(float(x) for x in lam)
    if not (l2 > 0 and load > 0 and length > 0):
        raise GeometryError("contact", "not convex", f"relative curvatures {l1:.3g}, {l2:.3g} 1/mm and load {load:.3g} N: "
                            "the surfaces do not touch at a point or line (no Hertz estimate)")
    A, B = 0.5 * l1, 0.5 * l2
    if A > 0 and B / A < _ratio(_E_MAX):
        if B / A < 1 + 1e-9:
            a = b = (3 * load / (8 * A * Es)) ** (1 / 3)
        else:
            e = brentq(lambda e: _ratio(e) - B / A, 1e-6, _E_MAX, xtol=1e-14)
            m = e * e
            K, Ee = ellipk(m), ellipe(m)
            a = (3 * load * (K - Ee) / (2 * math.pi * A * Es * m)) ** (1 / 3)
            b = a * math.sqrt(1 - m)
        if a <= 0.5 * length:
            return HertzContact(a, b, 3 * load / (2 * math.pi * a * b), False, load)
    w = load / length
    b = math.sqrt(4 * w / (l2 * math.pi * Es))
    return HertzContact(0.5 * length, b, 2 * w / (math.pi * b), True, load)


NEIGHBOUR = 0.1  # default profile size on the other teeth's loaded flanks [module] (converged load share, see README)
FILLET = 0.045  # default size along the loaded teeth's fillets [module] (G1)
AXIAL_COARSE = 2.0  # largest axial spacing of a graded member outside its zones [coarse sizes] (G2)
AXIAL_COARSE_MAX = 1.5  # ... and never beyond this [module] unless the coarse size is (G2)
SECTION_GROWTH = 1.3  # growth of the layers under the loaded fillet and along its root at refine 1 (G3)
DEPTH_GROWTH = 1.5  # growth of the layers under the contact and under the other flank at refine 1 (G5)
GROWTH = 1.5  # default mesh.growth: the flank profile and the axial levels away from the zones (G4)
AXIAL_LINE = 4.0  # axial size of a line contact with a uniform line load [half-lengths of the loaded line] (G7)
UNIFORM_LINE = 0.9  # ... uniform: the smallest slice line load at least this fraction of the largest (G7)


C_PRIME = 14.0  # [N/(mm um)] single stiffness of a solid spur pair, ISO 6336-1 (order of magnitude of c')

SIZING = ("loaded", "tca")  # zones sized by the loaded estimate (pipelines.models.stress.loaded) or the unloaded TCA


@dataclass(frozen=True)
class SizeRules:
    """Element sizes of the models [mm, or multiples of the module m]; every size is divided by ``refine``.

    None: the Hertz-based contact sizes of the module docstring, ``coarse`` = 0.75 m,
    ``fillet`` = FILLET m (G1), ``neighbour`` = NEIGHBOUR m (profile size on the loaded side of the
    other teeth, :func:`mesher.body.plan_tooth`; divided by ``refine`` only when ``refine`` > 1),
    rim depth 3 m. Default ``refine`` = 1: the cheapest
    level of ``benchmarks.stress`` with the maximum von Mises stress within 5 % (README,
    "Stress speed vs error").
    """

    refine: float = 1.0
    teeth: int = 3
    rim_depth: float | None = None
    coarse: float | None = None
    contact: float | None = None
    axial: float | None = None
    fillet: float | None = None
    neighbour: float | None = None
    growth: float = GROWTH
    zone: float = 1.2
    neighbour_reach: float | None = None  # [mm] neighbouring pairs closer than this (TCA) get a focus; None: reach()
    sizing: str = "loaded"  # 'loaded': zones from the loaded estimate; 'tca': from the unloaded TCA (before issue 26)
    remesh: bool = False  # remesh once when the FE loads a pair the estimate left unloaded (pipelines.models.stress.run)
    axial_coarse: float | None = None  # [mm] largest axial spacing outside the zones (before refine); None: (G2)
    section_growth: float | None = None  # growth under the loaded fillet and along its root; None: (G3)
    depth_growth: float | None = None  # growth under the contact and the other flank; None: (G5)
    axial_growth: float | None = None  # growth of the axial levels away from the zones; None: growth (G4)
    back: float | None = None  # [mm] layer under the loaded tooth's other flank and fillet (before refine); None: h_f

    def __post_init__(self):
        if not (0.1 <= self.refine <= 10.0):
            raise InputError("mesh.refine", self.refine, "in [0.1, 10] (element sizes are divided by it)")
        if not (isinstance(self.teeth, int) and not isinstance(self.teeth, bool) and 1 <= self.teeth <= 9):
            raise InputError("mesh.teeth", self.teeth, "an integer in [1, 9] (teeth per gear part)")
        for k in ("rim_depth", "coarse", "contact", "axial", "fillet", "neighbour"):
            v = getattr(self, k)
            if v is not None and not (v > 0 and math.isfinite(v)):
                raise InputError(f"mesh.{'rim_depth' if k == 'rim_depth' else k + '_size'}_mm", v, "> 0 mm")
        if not (1.05 <= self.growth <= 3.0):
            raise InputError("mesh.growth", self.growth, "in [1.05, 3]")
        if not (0.0 <= self.zone <= 5.0):
            raise InputError("mesh.zone", self.zone, "in [0, 5] (zone half-lengths over the Hertz ellipse's)")
        if self.neighbour_reach is not None and not (0.0 <= self.neighbour_reach <= 1.0):
            raise InputError("mesh.neighbour_reach_um", self.neighbour_reach * 1e3, "in [0, 1000] um")
        if self.sizing not in SIZING:
            raise InputError("mesh.sizing", self.sizing, "one of " + ", ".join(repr(x) for x in SIZING))
        if not isinstance(self.remesh, bool):
            raise InputError("mesh.remesh", self.remesh, "true or false")
        if self.axial_coarse is not None and not (self.axial_coarse > 0 and math.isfinite(self.axial_coarse)):
            raise InputError("mesh.axial_coarse_size_mm", self.axial_coarse, "> 0 mm")
        for k in ("section_growth", "depth_growth", "axial_growth"):
            v = getattr(self, k)
            if v is not None and not (1.05 <= v <= 3.0):
                raise InputError(f"mesh.{k}", v, "in [1.05, 3]")
        if self.back is not None and not (self.back > 0 and math.isfinite(self.back)):
            raise InputError("mesh.back_size_mm", self.back, "> 0 mm")

    def reach(self, load: float, face_width: float) -> float:
        r"""Separation [mm] below which a neighbouring pair of teeth is meshed like the loaded one.

        ``neighbour_reach`` if set, else three times the approach of a pair under the whole normal load
        P [N] estimated with ISO 6336-1's single stiffness :math:`c' = 14` N/(mm µm) over the face width
        b [mm]: :math:`3P/(c' b)`. A pair within it may close under load and carry part of it; a
        localized (crowned) contact is more compliant than the full-face line contact c′ describes,
        hence the factor (the crowned pair of docs/ltca.md approaches by about twice P/(c′b)).
        """
        if self.neighbour_reach is not None:
            return self.neighbour_reach
        return 3.0 * load / (C_PRIME * 1e3 * face_width)


@dataclass(frozen=True)
class ContactSizes:
    """Element sizes and refined zone of one loaded flank [mm] (:class:`mesher.MeshOptions` fields)."""

    coarse: float
    contact: float  # profile size at the contact
    axial: float  # axial size at the contact
    fillet: float
    neighbour: float  # profile size on the other teeth's loaded flanks
    rim: float  # rim depth
    growth: float
    extent_u: float  # zone half-length along the profile
    extent_z: float  # zone half-length along the axis
    teeth: int = 3
    axial_coarse: float | None = None  # largest axial spacing outside the zones (G2); None: coarse
    section_growth: float | None = None  # growth under the loaded fillet and along its root (G3); None: growth
    axial_growth: float | None = None  # growth of the axial levels away from the zones (G4); None: growth
    depth_growth: float | None = None  # growth under the contact and the other flank (G5); None: section_growth
    back: float | None = None  # layer under the loaded tooth's other flank and fillet; None: fillet


def contact_sizes(rules: SizeRules, gear: Gear, hz: HertzContact, angle: float, kind: int,
                  inclined_lines: bool = False) -> ContactSizes:
    """Sizes and zone of one loaded flank (module docstring of :mod:`pipelines.models.stress.scene`).

    A line contact is sized as an ellipse with ``a`` half the contact line, its major axis at the base
    helix angle β_b from the axis: on a spur gear the zone spans the face at one profile position; on a
    helical gear it covers the inclined line, (B/2) tan β_b + b either side of the point along the profile.
    ``inclined_lines`` (the pair model): a helical line contact whose TCA contact is an edge is sized so too.
    """
    m = gear.module
    a, b = hz.a, hz.b
    s, c = abs(math.sin(angle)), abs(math.cos(angle))
    if hz.line:  # the contact line of an involute helicoid: inclined by the base helix angle across the flank
        beta_b = math.atan(math.tan(gear.helix) * gear.r_b / gear.r_p)
        s, c = math.sin(beta_b), math.cos(beta_b)
    # an inclined (helical) contact line crosses the whole profile and is touched along its length under load
    # whatever the unloaded TCA contact: with ``inclined_lines`` it is sized as a line for every kind, and where
    # the TCA point is an edge (a tip, a face end: the line may run from it to its other end) the zone covers the
    # whole line, 2a, from it. (With the edge rule's zone of b about the point the rest of the line lay in
    # elements graded up to the coarse size: the full FE of ltca_helical_crowned.toml was 15.6 % too compliant.)
    # On a spur gear the line runs along the axis at one profile position: the edge rule's zone covers it, and
    # its axial levels refine toward the edge.
    inclined_edge = inclined_lines and hz.line and s > 1e-12 and kind != ContactKind.SURFACE
    surface = kind == ContactKind.SURFACE or inclined_edge
    # a line contact's band is resolved one step finer (b/4: nodal peak within 5 % of Hertz at refine 1, docs)
    contact = rules.contact if rules.contact is not None else b / (4.0 if hz.line else 3.0)
    if rules.axial is not None:
        axial = rules.axial
    elif surface:
        axial = min(a / 6.0, b / (3.0 * s) if s > 1e-12 else math.inf)
    else:
        axial = 2.0 * contact
    half = 2.0 * a if inclined_edge else a  # half-length of the zone along the line
    ext_u = rules.zone * (half * s + b * c) if surface else rules.zone * b
    ext_z = rules.zone * (half * c + b * s) if surface else 0.0
    return _sizes(rules, m, contact, axial, ext_u, ext_z)


def _coarse(rules: SizeRules, m: float) -> float:
    return (rules.coarse if rules.coarse is not None else 0.75 * m) / rules.refine


def _sizes(rules: SizeRules, m: float, contact: float, axial: float, ext_u: float, ext_z: float) -> ContactSizes:
    """The sizes of a part from its contact and axial sizes at refine 1 [mm] and its zone (not refined) [mm]."""
    r = rules.refine
    coarse = _coarse(rules, m)
    contact = min(max(contact, 0.005 * m), coarse * r) / r
    axial = min(max(axial, contact * r), coarse * r) / r
    fillet = min((rules.fillet if rules.fillet is not None else FILLET * m) / r, coarse)
    # a resolution of the flank geometry (facet sag against the elastic approach), not of a stress gradient:
    # coarser models (refine < 1) keep it, finer ones refine it too
    neighbour = min((rules.neighbour if rules.neighbour is not None else NEIGHBOUR * m) / max(r, 1.0), coarse)
    return ContactSizes(coarse, contact, axial, fillet, neighbour, rules.rim_depth if rules.rim_depth is not None else 3.0 * m,
                        rules.growth, ext_u, ext_z, rules.teeth,
                        max(rules.axial_coarse / r if rules.axial_coarse is not None else
                            max(coarse, min(AXIAL_COARSE * coarse, AXIAL_COARSE_MAX * m)), axial),
                        section_growth=rules.section_growth if rules.section_growth is not None else
                        _refined(SECTION_GROWTH, r), axial_growth=rules.axial_growth,
                        depth_growth=rules.depth_growth if rules.depth_growth is not None else
                        _refined(DEPTH_GROWTH, r),
                        back=min(rules.back / r, coarse) if rules.back is not None else fillet)


def _refined(q: float, r: float) -> float:
    """A growth ratio q at refine 1 at refine r: the slope q - 1 of the size field divided by r like the sizes
    (G3, G5), within the mesher's [1.05, 3]."""
    return min(max(1.0 + (q - 1.0) / r, 1.05), 3.0)


def zone_sizes(rules: SizeRules, gear: Gear, line: bool, zones: tuple, ext_u: float, ext_z: float) -> ContactSizes:
    """Sizes of a part whose zones come from the loaded estimate (:mod:`pipelines.models.stress.loaded`).

    ``zones``: (b, a, s, u) of every loaded pair of teeth: the Hertz half-width b [mm] of its loaded contact, the
    half-length a [mm] of its loaded line, the sine s of the line's angle from the axis and the uniformity u of its
    line load (w_min / w_max over the loaded slices; 1 if not known). The part's profile size is the smallest b/3
    (b/4 for a line contact), its axial size the smallest min(a/6, b/(3 s)), a/4 instead of a/6 on a line contact
    whose u >= 0.9 (G7) (one size per part: the mesher grades every zone of it alike); ``ext_u``, ``ext_z`` [mm]:
    the main zone's half-lengths (over its loaded slices, times ``rules.zone``:
    :mod:`pipelines.models.stress.zones`)."""
    b = min(z[0] for z in zones)
    contact = rules.contact if rules.contact is not None else b / (4.0 if line else 3.0)

    def along(z) -> float:  # the axial size a zone needs
        bb, a, s = z[:3]
        uniform = z[3] if len(z) > 3 else 1.0
        k = AXIAL_LINE if line and uniform >= UNIFORM_LINE else 6.0
        return min(a / k, bb / (3.0 * s) if s > 1e-12 else math.inf)

    axial = rules.axial if rules.axial is not None else min(along(z) for z in zones)
    return _sizes(rules, gear.module, contact, axial, ext_u, ext_z)


def unloaded_sizes(rules: SizeRules, gear: Gear) -> ContactSizes:
    """Sizes of a part whose mesh the loaded estimate leaves unloaded (a twin member with backlash): its loaded
    tooth's flank at the neighbour size (so that the FE can still close it), no zone, the rest coarse."""
    m, r = gear.module, rules.refine
    coarse = _coarse(rules, m)
    nb = min((rules.neighbour if rules.neighbour is not None else NEIGHBOUR * m) / max(r, 1.0), coarse)
    sz = _sizes(rules, m, nb * r, coarse * r, 0.0, 0.0)
    return dataclasses.replace(sz, contact=nb, axial=coarse, fillet=coarse)
