"""The gear stress model: scene (:mod:`.scene`), element sizes (:mod:`.sizing`), FE model and solve
(:mod:`.model`), results (:mod:`.results`) and the run of a case through them (:mod:`.run`).

The case record and its reader are in :mod:`pipelines.cases.stress`.
"""

__all__: list[str] = []
