"""Rating standards: ISO 6336 (today part 3, the tooth-root form and stress-correction factors and sigma_F0).
"""

from tca.rating.root_stress import RootFactors, root_factors, sigma_f0, tooth_root

__all__ = ["RootFactors", "root_factors", "sigma_f0", "tooth_root"]
