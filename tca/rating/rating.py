r"""The rating of a gear pair to ISO 6336-1/-2/-3/-5 (method B), from a :class:`RatingCase` to a :class:`PairRating`.

Order of evaluation (each step's equations are in the module named):

1. geometry (:mod:`.geometry` G1-G10), nominal tangential force :math:`F_t = 2T_1/d_1` and circumferential speed
   :math:`v = \pi d_1 n_1/60000` at the reference circle;
2. accuracy (:mod:`.accuracy`, ISO 1328-1:1995), running-in (:mod:`.running_in`), stiffness (:mod:`.stiffness`);
3. K_v (:mod:`.dynamics`), K_Hβ, K_Fβ (:mod:`.face_load`), K_Hα, K_Fα (:mod:`.transverse_load`);
4. contact (:mod:`.contact`) and root (:mod:`.bending`) stresses, their limits with the life factors
   (:mod:`.life`), and the safeties :math:`S_H = \sigma_{HG}/\sigma_H`, :math:`S_F = \sigma_{FG}/\sigma_F`.

Any of K_v, K_Hβ, K_Hα, K_Fβ, K_Fα, K_γ and the single stiffness c' can be passed in with :class:`~.factors.Given`
(source "input", or "gearfe" for values from gearfe's own analysis: K_Hβ from loaded TCA, K_Hα, K_γ of a planetary
train); ``dataclasses.replace(case, k_h_beta=Given(...))`` rates the same case the other way. A passed-in K_Hβ still
gives K_Fβ by (F4); a passed-in K_Hα gives K_Fα = K_Hα (method B equates them) unless K_Fα is passed too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

from tca.rating.accuracy import EDITION, tolerances
from tca.rating.bending import (deep_tooth_factor, helix_factor, notch_sensitivity, notch_sensitivity_static, rim_factor,
                      size_factor, surface_factor)
from tca.rating.contact import (ContactFactors, contact_factors, lubricant_factors, nominal_contact_stress, roughness_factor,
                      work_hardening_factor)
from tca.rating.dynamics import (DynamicFactor, MeshKind, ToothDeviations, dynamic_factor, reduced_mass,
                                 running_in_tip_relief)
from tca.rating.errors import RatingInputError, RatingWarning, check_range
from tca.rating.face_load import FaceLoad, ShaftData, face_load_factor, root_face_load_factor
from tca.rating.factors import Factor, Given, Source
from tca.rating.geometry import PairData, PairGeometry, pair_geometry
from tca.rating.life import bending_life_curve, contact_life_curve, interpolate_life, life_factor, load_cycles
from tca.rating.materials import SURFACE_HARDENED, Material
from tca.rating.running_in import helix_allowance, profile_allowance
from tca.rating.stiffness import GearBody, MeshStiffness, mesh_stiffness
from tca.rating.transverse_load import TransverseLoad, transverse_load_factors

__all__ = ["GearRatingData", "Operation", "RatingCase", "GearRating", "PairRating", "rate"]


@dataclass(frozen=True)
class GearRatingData:
    """What the rating needs of one gear besides its geometry.

    ``form_factor`` Y_F, ``stress_correction`` Y_S and ``notch_parameter`` q_s (load at the outer point of single
    contact, ISO 6336-3 method B) come from gearfe's tooth analysis (``form_source`` "gearfe") or from the user.
    Roughness Rz [µm]; ``tip_relief`` C_a [µm] (``None``: running-in C_ay); ``rim_thickness`` s_R [mm] (``None``:
    solid, Y_B = 1); ``contacts_per_revolution`` (a sun meshing with 3 planets: 3); ``mean_stress_factor`` Y_M.
    """

    material: Material
    accuracy_grade: int
    flank_roughness: float
    root_roughness: float
    form_factor: float
    stress_correction: float
    notch_parameter: float
    tip_relief: float | None = None
    rim_thickness: float | None = None
    contacts_per_revolution: int = 1
    mean_stress_factor: float = 1.0
    form_source: Source = Source.INPUT

    def __post_init__(self):
        if not isinstance(self.material, Material):
            raise RatingInputError("material", type(self.material).__name__, "a Material record")
        if isinstance(self.accuracy_grade, bool) or int(self.accuracy_grade) != self.accuracy_grade \
                or not 0 <= self.accuracy_grade <= 12:
            raise RatingInputError("accuracy_grade", self.accuracy_grade, "an integer in [0, 12] (ISO 1328-1:1995)")
        check_range("flank_roughness", self.flank_roughness, 0.0, 40.0, lo_open=True)
        check_range("root_roughness", self.root_roughness, 0.0, 40.0)
        check_range("form_factor", self.form_factor, 0.5, 6.0, why="Y_F of ISO 6336-3")
        check_range("stress_correction", self.stress_correction, 1.0, 4.0, why="Y_S of ISO 6336-3")
        check_range("notch_parameter", self.notch_parameter, 1.0, 8.0, hi_open=True, why="ISO 6336-3: 1 <= q_s < 8")
        if self.tip_relief is not None:
            check_range("tip_relief", self.tip_relief, 0.0, 500.0)
        if isinstance(self.contacts_per_revolution, bool) or int(self.contacts_per_revolution) != \
                self.contacts_per_revolution or self.contacts_per_revolution < 1:
            raise RatingInputError("contacts_per_revolution", self.contacts_per_revolution, "an integer >= 1")
        check_range("mean_stress_factor", self.mean_stress_factor, 0.7, 1.0, why="Y_M: 0.7 reversed .. 1 one-way")
        object.__setattr__(self, "form_source", Source(self.form_source))
        if self.form_source is Source.ISO:
            raise RatingInputError("form_source", "iso", "'input' or 'gearfe' (Y_F, Y_S are inputs of this library)")


@dataclass(frozen=True)
class Operation:
    """Load and service: pinion torque T_1 [N mm], pinion speed n_1 [1/min] (relative to the carrier in a planetary
    stage), required life [h], application factor K_A, lubricant viscosity ν40 [mm²/s]."""

    torque: float
    speed: float
    life_hours: float
    viscosity_40: float
    application_factor: float = 1.0

    def __post_init__(self):
        check_range("torque", self.torque, 0.0, lo_open=True, why="the pinion torque magnitude [N mm]")
        check_range("speed", self.speed, 0.0, lo_open=True, why="pinion speed [1/min]")
        check_range("life_hours", self.life_hours, 0.0, lo_open=True, why="required life [h]")
        check_range("viscosity_40", self.viscosity_40, 1.0, 10000.0, why="ν40 [mm²/s]")
        check_range("application_factor", self.application_factor, 1.0, 4.0, why="K_A of ISO 6336-1")


@dataclass(frozen=True)
class RatingCase:
    """Everything a rating needs. ``k_*``/``c_prime`` left ``None`` are computed by ISO 6336-1 (K_γ: taken as 1)."""

    pair: PairData
    pinion: GearRatingData
    wheel: GearRatingData
    operation: Operation
    mesh: MeshKind = MeshKind.PAIR
    planets: int = 1
    sun_is_pinion: bool = True
    gear_body: GearBody = GearBody()
    shaft: ShaftData = ShaftData()
    min_safety_contact: float = 1.0
    min_safety_bending: float = 1.0
    long_life_contact: float = 0.85
    long_life_bending: float = 0.85
    limited_pitting: bool = False
    k_gamma: Given | None = None
    k_v: Given | None = None
    k_h_beta: Given | None = None
    k_f_beta: Given | None = None
    k_h_alpha: Given | None = None
    k_f_alpha: Given | None = None
    c_prime: Given | None = None

    def __post_init__(self):
        object.__setattr__(self, "mesh", MeshKind(self.mesh))
        if not isinstance(self.pair, PairData):
            raise RatingInputError("pair", type(self.pair).__name__, "a PairData record")
        if self.mesh is MeshKind.PLANET_RING and not self.pair.internal:
            raise RatingInputError("mesh", self.mesh.value, "an internal pair (PairData.internal=True)")
        if self.pair.internal and self.mesh is MeshKind.SUN_PLANET:
            raise RatingInputError("mesh", self.mesh.value, "'pair' or 'planet-ring' for an internal pair")
        if isinstance(self.planets, bool) or int(self.planets) != self.planets or not 1 <= self.planets <= 20:
            raise RatingInputError("planets", self.planets, "an integer in [1, 20]")
        check_range("min_safety_contact", self.min_safety_contact, 0.5, 5.0)
        check_range("min_safety_bending", self.min_safety_bending, 0.5, 5.0)
        check_range("long_life_contact", self.long_life_contact, 0.85, 1.0)
        check_range("long_life_bending", self.long_life_bending, 0.85, 1.0)
        limits = {"k_gamma": (1.0, 3.0), "k_v": (1.0, 5.0), "k_h_beta": (1.0, 10.0), "k_f_beta": (1.0, 10.0),
                  "k_h_alpha": (1.0, 5.0), "k_f_alpha": (1.0, 5.0), "c_prime": (1.0, 50.0)}
        for key, (lo, hi) in limits.items():
            g = getattr(self, key)
            if g is None:
                continue
            if not isinstance(g, Given):
                raise RatingInputError(key, g, "a Given record (value, source, note) or None")
            if key == "k_gamma" and g.source is Source.GEARFE:
                hi = 2.0 * 20  # computed by a loaded train: up to 2n (a twin member carrying the whole torque)
            check_range(key, g.value, lo, hi)


@dataclass(frozen=True)
class GearRating:
    """Stresses [MPa], safeties and all factors of one gear; ``factors`` maps a factor name to its :class:`Factor`."""

    name: str
    sigma_h0: float
    sigma_h: float
    sigma_hg: float
    sigma_hp: float
    s_h: float
    sigma_f0: float
    sigma_f: float
    sigma_fg: float
    sigma_fp: float
    s_f: float
    load_cycles: float
    factors: Mapping[str, Factor]


@dataclass(frozen=True)
class PairRating:
    """Rating of a pair: geometry, intermediate results, both gears and the warnings of failed assumptions."""

    geometry: PairGeometry
    tangential_force: float  # F_t [N]
    circumferential_speed: float  # v [m/s]
    stiffness: MeshStiffness | None
    dynamics: DynamicFactor | None
    face_load: FaceLoad | None
    transverse_load: TransverseLoad | None
    contact: ContactFactors
    pinion: GearRating
    wheel: GearRating
    factors: Mapping[str, Factor]  # factors of the pair (K_*, Z_H, Z_E, ...)
    warnings: tuple[RatingWarning, ...] = field(default=())


def _f(value: float, note: str, source: Source = Source.ISO) -> Factor:
    return Factor(float(value), source, note)


def rate(case: RatingCase) -> PairRating:
    """Rate ``case`` (module docstring); raises :class:`RatingInputError`, returns warnings in the result."""
    geom = pair_geometry(case.pair)
    warnings: list[RatingWarning] = list(geom.warnings)
    op = case.operation
    g = (case.pinion, case.wheel)
    mat = (case.pinion.material, case.wheel.material)
    d1 = geom.reference_diameter[0]
    f_t = 2.0 * op.torque / d1
    v = math.pi * d1 * op.speed / 60000.0
    b = geom.common_face_width
    pair_f: dict[str, Factor] = {}

    pair_f["K_A"] = _f(op.application_factor, "application factor (ISO 6336-1 clause 6, given)", Source.INPUT)
    if case.k_gamma is None:
        pair_f["K_gamma"] = _f(1.0, "mesh load factor taken as 1 (no planet load sharing given)", Source.INPUT)
    else:
        pair_f["K_gamma"] = case.k_gamma.factor("mesh load factor (given)")
    k_a, k_g = op.application_factor, pair_f["K_gamma"].value
    w = f_t * k_a * k_g / b  # line load of (D4), (S2)

    # accuracy and running-in
    tol = [tolerances(g[i].accuracy_grade, geom.reference_diameter[i], geom.normal_module, geom.face_width[i],
                      geom.transverse_pressure_angle) for i in (0, 1)]
    f_pb = max(t.f_pb for t in tol)
    f_fa = max(t.f_f_alpha for t in tol)
    f_beta = max(t.F_beta for t in tol)
    y_alpha = profile_allowance(mat[0], mat[1], f_pb, v)
    y_f = profile_allowance(mat[0], mat[1], f_fa, v)

    # stiffness
    stiff = mesh_stiffness(geom, w, e1=mat[0].youngs_modulus, e2=mat[1].youngs_modulus, body=case.gear_body)
    warnings.extend(stiff.warnings)
    if case.c_prime is None:
        c_prime, c_ga = stiff.c_prime, stiff.c_gamma_alpha
        pair_f["c_prime"] = _f(c_prime, "single stiffness c' [N/(mm µm)], ISO 6336-1 method B (S1)-(S3)")
    else:
        c_prime = case.c_prime.value
        c_ga = c_prime * (0.75 * geom.eps_alpha + 0.25)
        pair_f["c_prime"] = case.c_prime.factor("single stiffness c' [N/(mm µm)], given")
    c_gb = 0.85 * c_ga
    pair_f["c_gamma_alpha"] = _f(c_ga, "mesh stiffness c_γα = c'(0.75 ε_α + 0.25) (S4)", pair_f["c_prime"].source)

    # K_v
    dyn = None
    if case.k_v is None:
        m_red = reduced_mass(geom, (mat[0].density, mat[1].density), case.mesh, case.planets, case.sun_is_pinion)
        c_a = [g[i].tip_relief if g[i].tip_relief is not None else running_in_tip_relief(mat[i].sigma_h_lim)
               for i in (0, 1)]
        dyn = dynamic_factor(geom, pinion_speed=op.speed, line_load=w, c_prime=c_prime, c_gamma_alpha=c_ga,
                             reduced_mass=m_red, deviations=ToothDeviations(f_pb - y_alpha, f_fa - y_f,
                                                                            0.5 * (c_a[0] + c_a[1])))
        warnings.extend(dyn.warnings)
        relief = "given" if all(x.tip_relief is not None for x in g) else "running-in C_ay (D11) where not given"
        pair_f["K_v"] = _f(dyn.k_v, f"ISO 6336-1 method B, {dyn.speed_range} range, N = {dyn.resonance_ratio:.4f} "
                           f"(D3)-(D10); f_pb = {f_pb:.2f}, f_fα = {f_fa:.2f} µm ({EDITION}), C_a = "
                           f"{0.5 * (c_a[0] + c_a[1]):.2f} µm ({relief})")
    else:
        pair_f["K_v"] = case.k_v.factor("dynamic factor (given)")
    k_v = pair_f["K_v"].value

    # K_Hβ, K_Fβ
    face = None
    if case.k_h_beta is None:
        face = face_load_factor(mean_line_load=w * k_v, pinion_diameter=d1, face_width=b, c_gamma_beta=c_gb,
                                total_helix_deviation=f_beta, shaft=case.shaft,
                                running_in=lambda fbx: helix_allowance(mat[0], mat[1], fbx, v))
        shaft_note = "" if case.shaft.pinion_offset else "; pinion centred between bearings (s = 0)"
        pair_f["K_Hbeta"] = _f(face.k_h_beta, f"ISO 6336-1 method C (F1)-(F3): f_sh = {face.f_sh:.2f}, f_ma = "
                               f"{case.shaft.mesh_misalignment:g}, F_βy = {face.f_beta_y:.2f} µm" + shaft_note)
    else:
        pair_f["K_Hbeta"] = case.k_h_beta.factor("face load factor (given)")
    k_hb = pair_f["K_Hbeta"].value
    if case.k_f_beta is None:
        k_fb = root_face_load_factor(k_hb, geom.face_width, geom.tooth_depth)
        pair_f["K_Fbeta"] = _f(k_fb, f"K_Hβ^N_F (F4) from K_Hβ ({pair_f['K_Hbeta'].source.value}), smaller b/h "
                               f"of b/h = {geom.face_width[0] / geom.tooth_depth[0]:.3f}, "
                               f"{geom.face_width[1] / geom.tooth_depth[1]:.3f}")
    else:
        pair_f["K_Fbeta"] = case.k_f_beta.factor("face load factor, root (given)")
    k_fb = pair_f["K_Fbeta"].value

    # contact factors (needed by the K_Hα limit)
    cf = contact_factors(geom, (mat[0].youngs_modulus, mat[1].youngs_modulus), (mat[0].poisson, mat[1].poisson))

    # K_Hα, K_Fα
    trans = None
    if case.k_h_alpha is None:
        trans = transverse_load_factors(eps_alpha=geom.eps_alpha, eps_gamma=geom.eps_gamma, z_eps=cf.z_eps,
                                        c_gamma_alpha=c_ga, f_pb=f_pb, f_falpha=f_fa, y_alpha=y_alpha,
                                        line_load_h=w * k_v * k_hb)
        clip = "; limited to 1" if trans.unlimited < 1.0 else ""
        pair_f["K_Halpha"] = _f(trans.k_h_alpha, f"ISO 6336-1 method B (T1)-(T4), unlimited {trans.unlimited:.4f}"
                                + clip)
        k_fa_val, k_fa_note, k_fa_src = trans.k_f_alpha, "ISO 6336-1 method B (T1)-(T4)" + clip, Source.ISO
    else:
        pair_f["K_Halpha"] = case.k_h_alpha.factor("transverse load factor (given)")
        k_fa_val, k_fa_src = case.k_h_alpha.value, case.k_h_alpha.source
        k_fa_note = "K_Fα = K_Hα (method B equates them; K_Hα given)"
    if case.k_f_alpha is None:
        pair_f["K_Falpha"] = _f(k_fa_val, k_fa_note, k_fa_src)
    else:
        pair_f["K_Falpha"] = case.k_f_alpha.factor("transverse load factor, root (given)")
    k_ha, k_fa = pair_f["K_Halpha"].value, pair_f["K_Falpha"].value

    pair_f["Z_H"] = _f(cf.z_h, "zone factor (H3)")
    pair_f["Z_E"] = _f(cf.z_e, "elasticity factor (H4)")
    pair_f["Z_eps"] = _f(cf.z_eps, "contact ratio factor (H5)")
    pair_f["Z_beta"] = _f(cf.z_beta, "helix angle factor (H6)")
    pair_f["Z_B"] = _f(cf.z_b, f"single pair contact factor, pinion (H7), (H8); M_1 = {cf.m1:.4f}")
    pair_f["Z_D"] = _f(cf.z_d, "single pair contact factor, wheel: 1 for an internal wheel (H8)" if geom.internal
                       else f"single pair contact factor, wheel (H7), (H8); M_2 = {cf.m2:.4f}")
    sigma_h0 = nominal_contact_stress(geom, f_t, cf)
    k_h = k_a * k_g * k_v * k_hb * k_ha
    k_f = k_a * k_g * k_v * k_fb * k_fa

    s_lim = min(mat[0].sigma_h_lim, mat[1].sigma_h_lim)
    gears = []
    for i, name in enumerate(("pinion", "wheel")):
        gi, mi = g[i], mat[i]
        speed = op.speed / (geom.gear_ratio if i else 1.0)
        n_l = load_cycles(speed, op.life_hours, gi.contacts_per_revolution)
        fac = dict(pair_f)
        # contact
        z_bd = cf.z_b if i == 0 else cf.z_d
        fac.pop("Z_D" if i == 0 else "Z_B")
        sigma_h = z_bd * sigma_h0 * math.sqrt(k_h)
        c_curve = contact_life_curve(mi.kind, case.limited_pitting)
        z_nt = life_factor(c_curve, n_l, case.long_life_contact)
        # Z_L, Z_v, Z_R of the pair, with the lower σ_Hlim of the two materials (H11), (H12)
        zl, zv = lubricant_factors(s_lim, op.viscosity_40, v)
        zr = roughness_factor(s_lim, g[0].flank_roughness, g[1].flank_roughness, geom.relative_curvature)
        limited = n_l < c_curve.n_ref
        tag = f" at N_L = {n_l:.4g} (L3, interpolated to 1 at {c_curve.n_static:g})" if limited else ""
        zl_n, zv_n, zr_n = (interpolate_life(c_curve, n_l, 1.0, z) for z in (zl, zv, zr))
        mate = mat[1 - i]
        if mi.kind not in SURFACE_HARDENED and mate.kind in SURFACE_HARDENED:
            if mi.brinell_hardness is None:
                raise RatingInputError(f"{name}.material.brinell_hardness", None,
                                       "HB of the through-hardened gear (Z_W, ISO 6336-2)")
            z_w = work_hardening_factor(mi.brinell_hardness)
            zw_note = f"work hardening factor (H13), HB = {mi.brinell_hardness:g} (hardness-only form)"
        else:
            z_w, zw_note = 1.0, "work hardening factor: 1 (no soft gear against a surface-hardened mate)"
        z_x = 1.0
        sigma_hg = mi.sigma_h_lim * z_nt * zl_n * zv_n * zr_n * z_w * z_x
        fac["sigma_Hlim"] = _f(mi.sigma_h_lim, mi.note or "endurance limit (contact), given", mi.source)
        fac["Z_NT"] = _f(z_nt, f"{c_curve.name} (L2), N_L = {n_l:.4g}, Z(10^10) = {case.long_life_contact:g}")
        fac["Z_L"] = _f(zl_n, f"lubricant factor (H10), ν40 = {op.viscosity_40:g} mm²/s, σ_Hlim = {s_lim:g} "
                              "(lower of the pair)" + tag)
        fac["Z_v"] = _f(zv_n, f"velocity factor (H10), v = {v:.4f} m/s (reference circle)" + tag)
        fac["Z_R"] = _f(zr_n, f"roughness factor (H12), Rz = {g[0].flank_roughness:g}/{g[1].flank_roughness:g} µm, "
                              f"ρ_red = {geom.relative_curvature:.3f} mm" + tag)
        fac["Z_W"] = _f(z_w, zw_note)
        fac["Z_X"] = _f(z_x, "size factor (flank) taken as 1 (ISO 6336-2 method B)")
        # bending
        b_f = min(geom.face_width[i], geom.face_width[1 - i] + 2.0 * geom.normal_module)
        y_b = helix_factor(geom.eps_beta, geom.helix_angle)
        y_rim = rim_factor(gi.rim_thickness, geom.tooth_depth[i], geom.normal_module, geom.internal and i == 1)
        y_dt = deep_tooth_factor(geom.eps_alpha_n, gi.accuracy_grade)
        sigma_f0 = f_t / (b_f * geom.normal_module) * gi.form_factor * gi.stress_correction * y_b * y_rim * y_dt
        sigma_f = sigma_f0 * k_f
        b_curve = bending_life_curve(mi.kind)
        y_nt = life_factor(b_curve, n_l, case.long_life_bending)
        yd_ref = notch_sensitivity(mi, gi.notch_parameter)
        yr_ref = surface_factor(mi, gi.root_roughness)
        yx_ref = size_factor(mi, geom.normal_module)
        b_limited = n_l < b_curve.n_ref
        if b_limited:
            yd = interpolate_life(b_curve, n_l, notch_sensitivity_static(mi, gi.stress_correction), yd_ref)
            yr = interpolate_life(b_curve, n_l, 1.0, yr_ref)
            yx = interpolate_life(b_curve, n_l, 1.0, yx_ref)
            btag = f" at N_L = {n_l:.4g} (L3, interpolated to the static value at {b_curve.n_static:g})"
        else:
            yd, yr, yx, btag = yd_ref, yr_ref, yx_ref, ""
        sigma_fg = mi.sigma_f_lim * 2.0 * y_nt * yd * yr * yx * gi.mean_stress_factor
        fac["sigma_Flim"] = _f(mi.sigma_f_lim, mi.note or "nominal bending stress number, given", mi.source)
        fac["Y_F"] = _f(gi.form_factor, "form factor (ISO 6336-3 method B, from the tooth analysis)", gi.form_source)
        fac["Y_S"] = _f(gi.stress_correction, "stress correction factor (ISO 6336-3 method B)", gi.form_source)
        fac["Y_beta"] = _f(y_b, "helix angle factor (B2)")
        fac["Y_B"] = _f(y_rim, "rim thickness factor (B3)" if gi.rim_thickness is not None
                        else "rim thickness factor: 1 (solid gear, no rim thickness given)")
        fac["Y_DT"] = _f(y_dt, f"deep tooth factor (B4), ε_αn = {geom.eps_alpha_n:.3f}, grade {gi.accuracy_grade}")
        fac["Y_ST"] = _f(2.0, "stress correction factor of the test gear, Y_ST = 2")
        fac["Y_NT"] = _f(y_nt, f"{b_curve.name} (L2), N_L = {n_l:.4g}, Y(10^10) = {case.long_life_bending:g}")
        fac["Y_deltarelT"] = _f(yd, f"relative notch sensitivity (B6), q_s = {gi.notch_parameter:g}" + btag)
        fac["Y_RrelT"] = _f(yr, f"relative surface factor (B8), Rz = {gi.root_roughness:g} µm" + btag)
        fac["Y_X"] = _f(yx, f"size factor (B9), m_n = {geom.normal_module:g} mm" + btag)
        fac["Y_M"] = _f(gi.mean_stress_factor, "mean stress factor (given; 1 = one-way bending)", Source.INPUT)
        gears.append(GearRating(
            name=name, sigma_h0=sigma_h0, sigma_h=sigma_h, sigma_hg=sigma_hg,
            sigma_hp=sigma_hg / case.min_safety_contact, s_h=sigma_hg / sigma_h, sigma_f0=sigma_f0, sigma_f=sigma_f,
            sigma_fg=sigma_fg, sigma_fp=sigma_fg / case.min_safety_bending, s_f=sigma_fg / sigma_f, load_cycles=n_l,
            factors=MappingProxyType(fac)))

    return PairRating(geometry=geom, tangential_force=f_t, circumferential_speed=v, stiffness=stiff, dynamics=dyn,
                      face_load=face, transverse_load=trans, contact=cf, pinion=gears[0], wheel=gears[1],
                      factors=MappingProxyType(pair_f), warnings=tuple(warnings))
