"""Part 3: the isostatic planetary train: DOF counting, planar flanks, subtrain equations, switching of
pairs by backlash, the multi-body TCA with floating members, and its closed forms.
"""

from tca.isostatic.train import PlanetPlacement, IsostaticTrain
from tca.isostatic.dof import DOFCount, TrainConstraints, count_dof
from tca.isostatic.result import IsostaticResult

__all__ = ["PlanetPlacement", "IsostaticTrain", "DOFCount", "TrainConstraints", "count_dof", "IsostaticResult"]
