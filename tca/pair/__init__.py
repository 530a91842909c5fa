"""TCA of a gear pair: mounts and misalignments, the reference pair, bounded and relieved surfaces, run-out,
transitions between pairs of teeth, the result, and the TE and contact at any angle (:mod:`tca.pair.te`).
"""

from tca.pair.gear_pair import GearPair, Misalignment
from tca.pair.analysis import ContactKind, PairTCAResult, TCAOptions, ellipse_outlines, run_pair_tca, solve_reference_pair
from tca.pair.te import MeshContact, MeshTE, PathOfContact, mesh_contact, path_of_contact, position_angle

__all__ = ["GearPair", "Misalignment", "ContactKind", "PairTCAResult", "TCAOptions", "ellipse_outlines", "run_pair_tca", "solve_reference_pair", "MeshContact", "MeshTE", "PathOfContact", "mesh_contact", "path_of_contact", "position_angle"]
