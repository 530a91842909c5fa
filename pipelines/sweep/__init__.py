"""Sweeps of load cases: the stress points of a grid (positions, torques) and their scalar results.
"""


__all__ = []
