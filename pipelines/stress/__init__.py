"""The gear stress model: case (:mod:`.case`), scene (:mod:`.scene`), element sizes (:mod:`.sizing`),
FE model and solve (:mod:`.model`), results (:mod:`.results`), the run (:mod:`.run`) and sweeps (:mod:`.sweep`)."""

from pipelines.stress.case import MODELS, REGULATION, StressCase, read_stress_case
from pipelines.stress.run import build_scene, run_stress

__all__ = ["MODELS", "REGULATION", "StressCase", "read_stress_case", "build_scene", "run_stress"]
