"""The gear stress model: the loaded estimate of a scene's meshes (:mod:`.loaded`) and its refined zones
(:mod:`.zones`), scene (:mod:`.scene`), element sizes (:mod:`.sizing`), FE model and solve
(:mod:`.model`), results (:mod:`.results`) and the run of a case through them (:mod:`.run`).

The case record and its reader are in :mod:`pipelines.cases.stress`.
"""

__all__: list[str] = []
