"""Loaded TCA of a gear pair from condensed flank compliances (``gearfe ltca``, docs/ltca.md).

:mod:`.compliance` condenses each gear's flank compliance once from its hexahedral model (FE global
part at the tooth centre plane, Weber's Hertzian flattening as the local part); :mod:`.contact`
builds the contact lines of the pairs of teeth within reach from the TCA and solves the contact
problem with torque balance; :mod:`.run` drives positions and torques and writes the results.
The ``[ltca]`` table of a case is read by :mod:`pipelines.cases.ltca`.
"""

__all__: list[str] = []
