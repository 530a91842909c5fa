"""ISO 6336 (parts 1, 2, 3, 5; method B) load capacity rating of cylindrical gear pairs.

The tooth-root form factor Y_F, stress-correction factor Y_S and sigma_F0 of the generated tooth are
:mod:`tca.rating.root_stress`; the rest of the rating is the standard's method on numbers.

Data flow: :class:`PairData` (+ :class:`GearRatingData` per gear, :class:`Operation`) -> :class:`RatingCase` ->
:func:`rate` -> :class:`PairRating` (a :class:`GearRating` per gear: σ_H0, σ_H, σ_HP, S_H, σ_F0, σ_F, σ_FP, S_F and
a mapping factor name -> :class:`Factor` (value, source "iso"/"input"/"gearfe", note)). Factors computed elsewhere
(K_Hβ from loaded TCA, K_Hα, K_γ) are passed in with :class:`Given`. Units: mm, N, MPa, rad.
"""

from tca.rating.accuracy import Tolerances, tolerances
from tca.rating.dynamics import DynamicFactor, MeshKind
from tca.rating.errors import RatingInputError, RatingWarning
from tca.rating.face_load import FaceLoad, ShaftData
from tca.rating.factors import Factor, Given, Source
from tca.rating.geometry import DEG, GearBlank, PairData, PairGeometry, pair_geometry
from tca.rating.life import load_cycles
from tca.rating.materials import ISO_6336_5_TABLE, Material, MaterialKind, Quality, StressNumbers, iso_material
from tca.rating.root_stress import RootFactors, root_factors, sigma_f0, tooth_root
from tca.rating.rating import GearRating, GearRatingData, Operation, PairRating, RatingCase, rate
from tca.rating.stiffness import GearBody, MeshStiffness
from tca.rating.transverse_load import TransverseLoad

__all__ = [
    "RootFactors", "root_factors", "sigma_f0", "tooth_root",
    "DEG", "DynamicFactor", "FaceLoad", "Factor", "GearBlank", "GearBody", "GearRating", "GearRatingData", "Given",
    "ISO_6336_5_TABLE", "Material", "MaterialKind", "MeshKind", "MeshStiffness", "Operation", "PairData",
    "PairGeometry", "PairRating", "Quality", "RatingCase", "RatingInputError", "RatingWarning", "ShaftData",
    "Source", "StressNumbers", "Tolerances", "TransverseLoad", "iso_material", "load_cycles", "pair_geometry",
    "rate", "tolerances",
]
