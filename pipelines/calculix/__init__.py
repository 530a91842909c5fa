"""CalculiX cross-check: the ABAQUS/CalculiX job of a stress scene, the .frd/.dat reader, the comparison.
"""


__all__ = []
