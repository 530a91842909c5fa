"""Part 1: the double-helical one-stage planetary train, TCA of its subgear drives with the carrier at rest,
twin subgear drives, the integrated TE and the regulation of backlash by axial displacement of planets.
"""

from tca.planetary.train import DoubleHelicalTrain, ShaftErrors
from tca.planetary.subgear import SubgearTE, run_subgear_tca
from tca.planetary.regulation import RegulationOptions, TrainRegulation, regulate_train, twin_te, integrated_te

__all__ = ["DoubleHelicalTrain", "ShaftErrors", "SubgearTE", "run_subgear_tca", "RegulationOptions", "TrainRegulation",
           "regulate_train", "twin_te", "integrated_te"]
