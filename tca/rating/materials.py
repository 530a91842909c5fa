r"""Gear materials and the allowable stress numbers of ISO 6336-5 (method B).

ISO 6336-5 gives the endurance limits for contact, :math:`\sigma_{H\lim}`, and the nominal bending stress number
:math:`\sigma_{F\lim}` (the allowable bending number is :math:`\sigma_{FE} = Y_{ST}\sigma_{F\lim}`, :math:`Y_{ST} = 2`)
as straight lines in the surface hardness :math:`x` (HBW or HV10, per material) for three material qualities
ML, MQ, ME (ISO 6336-5 Figures 1-14 and their table of coefficients):

.. math::
    \sigma_{H\lim} = A_H\,x + B_H,\qquad \sigma_{F\lim} = A_F\,x + B_F,\qquad x_{\min} \le x \le x_{\max} \quad (M1)

:data:`ISO_6336_5_TABLE` holds the rows as frozen :class:`StressNumbers` records. Provenance of the numbers: the
coefficients follow ISO 6336-5 (2003 table, carried into the 2016 edition as far as the author knows) as
transcribed for this package. The ISO text itself was not available to this project, so each row says in
``checked`` what independent public source it was cross-checked against:

* "fyp-website": the ME rows as transcribed in the public repository ``waa552/fyp-website`` (``data.js``);
* "KISSsoft 03/2017": case-hardened MQ (σ_Hlim = 1500, σ_Flim = 430 MPa, 18CrNiMo7-6, core >= 25 HRC,
  Jominy J12 < 28 HRC) as printed in the KISSsoft reports of ``gfsReboucas/Drivetrain`` (@NREL_5MW/*.rtf);
* "" (empty): not cross-checked; review against ISO 6336-5 before relying on it.

A material not in the table (or a quality it does not list, or a hardness outside the row's range) raises
:class:`~.errors.RatingInputError`; any other material is given with explicit σ_Hlim, σ_Flim (source "input").
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from tca.rating.errors import RatingInputError, check_range
from tca.rating.factors import Source

__all__ = ["MaterialKind", "Quality", "StressNumbers", "Material", "ISO_6336_5_TABLE", "iso_material",
           "SURFACE_HARDENED", "STEEL_YOUNGS_MODULUS"]

STEEL_YOUNGS_MODULUS = 206000.0  # E_st of ISO 6336-1's stiffness [MPa]


class MaterialKind(str, Enum):
    """Material groups of ISO 6336 (their abbreviations are the values)."""

    ST = "St"  # normalized low carbon wrought steel
    ST_CAST = "St (cast)"  # cast steel
    GTS = "GTS (perl.)"  # black malleable cast iron, pearlitic
    GGG = "GGG (perl., bai.)"  # nodular cast iron, pearlitic or bainitic
    GGG_FERRITIC = "GGG (ferr.)"  # nodular cast iron, ferritic
    GG = "GG"  # grey cast iron
    V_CARBON = "V (carbon)"  # through-hardened wrought carbon steel
    V_ALLOY = "V (alloy)"  # through-hardened wrought alloy steel
    EH = "Eh"  # case-hardened wrought steel
    IF = "IF"  # flame or induction hardened wrought steel (root hardened)
    NT = "NT (nitr.)"  # nitriding steel, nitrided
    NV_NITRIDED = "NV (nitr.)"  # through-hardening steel, nitrided
    NV_NITROCARBURIZED = "NV (nitrocar.)"  # through-hardening steel, nitrocarburized

    @property
    def through_hardened(self) -> bool:
        """V in ISO 6336's tables (carbon or alloy)."""
        return self in (MaterialKind.V_CARBON, MaterialKind.V_ALLOY)


SURFACE_HARDENED = frozenset({MaterialKind.EH, MaterialKind.IF, MaterialKind.NT, MaterialKind.NV_NITRIDED,
                              MaterialKind.NV_NITROCARBURIZED})


class Quality(str, Enum):
    """Material quality grades of ISO 6336-5."""

    ML = "ML"
    MQ = "MQ"
    ME = "ME"


@dataclass(frozen=True)
class StressNumbers:
    """One row of ISO 6336-5's coefficients (M1): σ_Hlim = a_h x + b_h, σ_Flim = a_f x + b_f [MPa]."""

    kind: MaterialKind
    quality: Quality
    hardness_unit: str  # "HBW" or "HV10"
    a_h: float
    b_h: float
    h_range: tuple[float, float]  # validity range of x for σ_Hlim
    a_f: float
    b_f: float
    f_range: tuple[float, float]  # validity range of x for σ_Flim
    figure: str  # ISO 6336-5 figures (contact/bending)
    checked: str = ""  # independent source the row was cross-checked against ("" = none)
    condition: str = ""  # extra condition of the row (core hardness ...)

    def __post_init__(self):
        for key in ("h_range", "f_range"):
            lo, hi = getattr(self, key)
            if not 0 < lo < hi:
                raise RatingInputError(f"StressNumbers.{key}", (lo, hi), "0 < x_min < x_max")


def _rows(kind, unit, fig, h_range, f_range, coeffs, checked=None, condition=None):
    """Rows of one material for ML, MQ, ME from {quality: (a_h, b_h, a_f, b_f)}."""
    out = []
    for q, (ah, bh, af, bf) in coeffs.items():
        hr = h_range[q] if isinstance(h_range, dict) else h_range
        fr = f_range[q] if isinstance(f_range, dict) else f_range
        out.append(StressNumbers(kind, Quality(q), unit, ah, bh, hr, af, bf, fr, fig,
                                 (checked or {}).get(q, ""), (condition or {}).get(q, "")))
    return out


_FYP = "fyp-website (ME row)"
ISO_6336_5_TABLE: tuple[StressNumbers, ...] = tuple(
    _rows(MaterialKind.ST, "HBW", "Figures 1, 2", (110, 210), (110, 210),
          {"ML": (1.000, 190, 0.455, 69), "MQ": (1.000, 190, 0.455, 69), "ME": (1.520, 250, 0.386, 147)},
          {"ME": _FYP})
    + _rows(MaterialKind.ST_CAST, "HBW", "Figures 1, 2", (140, 210), (140, 210),
            {"ML": (0.986, 131, 0.313, 62), "MQ": (0.986, 131, 0.313, 62), "ME": (1.143, 237, 0.254, 137)},
            {"ME": _FYP})
    + _rows(MaterialKind.GGG, "HBW", "Figures 3 b), 4 b)", (175, 300), (175, 300),
            {"ML": (1.434, 211, 0.350, 119), "MQ": (1.434, 211, 0.350, 119), "ME": (1.500, 250, 0.380, 134)})
    + _rows(MaterialKind.GG, "HBW", "Figures 3 c), 4 c)", (150, 240), (150, 240),
            {"ML": (1.033, 132, 0.256, 8), "MQ": (1.033, 132, 0.256, 8), "ME": (1.465, 122, 0.200, 53)})
    + _rows(MaterialKind.V_CARBON, "HV10", "Figures 5, 6", (135, 210), (135, 210),
            {"ML": (0.963, 283, 0.250, 108), "MQ": (0.925, 360, 0.240, 163), "ME": (0.838, 432, 0.283, 202)},
            {"ME": _FYP})
    + _rows(MaterialKind.V_ALLOY, "HV10", "Figures 5, 6", {"ML": (200, 360), "MQ": (200, 360), "ME": (200, 390)},
            {"ML": (200, 360), "MQ": (200, 360), "ME": (200, 390)},
            {"ML": (1.313, 188, 0.423, 104), "MQ": (1.313, 373, 0.425, 187), "ME": (2.213, 260, 0.358, 231)},
            {"ME": _FYP})
    + _rows(MaterialKind.EH, "HV10", "Figures 9, 10", (660, 800), (660, 800),
            {"ML": (0.0, 1300, 0.0, 312), "MQ": (0.0, 1500, 0.0, 430), "ME": (0.0, 1650, 0.0, 525)},
            {"MQ": "KISSsoft 03/2017 (MQ)", "ME": _FYP},
            {"MQ": "core hardness >= 25 HRC, Jominy J12 < 28 HRC (bending)"})
    + _rows(MaterialKind.IF, "HV10", "Figures 11, 12", {"ML": (485, 615), "MQ": (485, 615), "ME": (500, 615)},
            {"ML": (485, 615), "MQ": (485, 615), "ME": (500, 615)},
            {"ML": (0.740, 602, 0.305, 76), "MQ": (0.541, 882, 0.138, 290), "ME": (0.505, 1013, 0.271, 237)},
            {"ME": _FYP})
    + _rows(MaterialKind.NT, "HV10", "Figures 13 a), 14 a)", (650, 900), (650, 900),
            {"ML": (0.0, 1125, 0.0, 270), "MQ": (0.0, 1250, 0.0, 420), "ME": (0.0, 1450, 0.0, 468)},
            {"ME": _FYP})
    + _rows(MaterialKind.NV_NITRIDED, "HV10", "Figures 13 b), 14 b)", (450, 650), (450, 650),
            {"ML": (0.0, 788, 0.0, 258), "MQ": (0.0, 998, 0.0, 363), "ME": (0.0, 1217, 0.0, 432)},
            {"ME": _FYP})
    + _rows(MaterialKind.NV_NITROCARBURIZED, "HV10", "Figures 13 c), 14 c)", (450, 650), (450, 650),
            {"ML": (0.0, 650, 0.0, 224), "MQ": (0.0, 850, 0.0, 310), "ME": (0.0, 950, 0.0, 388)},
            {"ME": _FYP})
)


@dataclass(frozen=True)
class Material:
    """A gear material: allowable numbers [MPa] and the properties the factors of ISO 6336 need.

    ``sigma_f_lim`` is the nominal bending stress number σ_Flim (σ_FE = 2 σ_Flim). ``yield_strength`` (σ_S for St,
    σ_0.2 for V, GTS, GGG) feeds the relative notch sensitivity Y_δrelT; ``tensile_strength`` (σ_B) does for GG;
    ``brinell_hardness`` (HB) feeds the work hardening factor Z_W of a through-hardened wheel.
    ``source``: ISO when built from :data:`ISO_6336_5_TABLE` by :func:`iso_material`, else INPUT.
    """

    kind: MaterialKind
    sigma_h_lim: float
    sigma_f_lim: float
    quality: Quality | None = None
    hardness: float | None = None
    hardness_unit: str = ""
    brinell_hardness: float | None = None
    yield_strength: float | None = None
    tensile_strength: float | None = None
    youngs_modulus: float = STEEL_YOUNGS_MODULUS
    poisson: float = 0.3
    density: float = 7.83e-6  # [kg/mm³]
    source: Source = Source.INPUT
    note: str = ""

    def __post_init__(self):
        object.__setattr__(self, "kind", MaterialKind(self.kind))
        if self.quality is not None:
            object.__setattr__(self, "quality", Quality(self.quality))
        object.__setattr__(self, "source", Source(self.source))
        check_range("sigma_h_lim", self.sigma_h_lim, 100.0, 2500.0)
        check_range("sigma_f_lim", self.sigma_f_lim, 10.0, 1000.0)
        for key, lo, hi in (("brinell_hardness", 50.0, 800.0), ("yield_strength", 100.0, 3000.0),
                            ("tensile_strength", 100.0, 3000.0)):
            v = getattr(self, key)
            if v is not None:
                check_range(key, v, lo, hi)
        check_range("youngs_modulus", self.youngs_modulus, 1000.0, 500000.0)
        check_range("poisson", self.poisson, 0.0, 0.5, hi_open=True)
        check_range("density", self.density, 1e-7, 2e-5)

    @property
    def sigma_fe(self) -> float:
        """Allowable stress number (bending) σ_FE = Y_ST σ_Flim, Y_ST = 2 [MPa]."""
        return 2.0 * self.sigma_f_lim


def _row(kind: MaterialKind, quality: Quality) -> StressNumbers:
    for r in ISO_6336_5_TABLE:
        if r.kind is kind and r.quality is quality:
            return r
    have = sorted({f"{r.kind.value}" for r in ISO_6336_5_TABLE})
    raise RatingInputError("material", f"{kind.value} {quality.value}", f"one of {have} with ML, MQ or ME")


def iso_material(kind: MaterialKind | str, quality: Quality | str, hardness: float, **properties) -> Material:
    """Material with σ_Hlim, σ_Flim from ISO 6336-5 (M1) at surface ``hardness`` (HBW or HV10 as the row says).

    ``properties`` are the other :class:`Material` fields (yield strength, E, ...).
    """
    try:
        kind = MaterialKind(kind)
    except ValueError:
        raise RatingInputError("material.kind", kind, f"one of {[k.value for k in MaterialKind]}") from None
    try:
        quality = Quality(quality)
    except ValueError:
        raise RatingInputError("material.quality", quality, "'ML', 'MQ' or 'ME'") from None
    r = _row(kind, quality)
    check_range(f"hardness ({r.hardness_unit}, {kind.value} {quality.value}, contact)", hardness, *r.h_range)
    check_range(f"hardness ({r.hardness_unit}, {kind.value} {quality.value}, bending)", hardness, *r.f_range)
    note = (f"ISO 6336-5 {r.figure}, {quality.value}: σ_Hlim = {r.a_h:g} x + {r.b_h:g}, σ_Flim = {r.a_f:g} x + "
            f"{r.b_f:g}, x = {hardness:g} {r.hardness_unit}" + (f"; {r.condition}" if r.condition else "")
            + (f"; cross-checked: {r.checked}" if r.checked else "; row not cross-checked against a second source"))
    hb = properties.pop("brinell_hardness", hardness if r.hardness_unit == "HBW" else None)
    return Material(kind, r.a_h * hardness + r.b_h, r.a_f * hardness + r.b_f, quality, float(hardness),
                    r.hardness_unit, brinell_hardness=hb, source=Source.ISO, note=note, **properties)
