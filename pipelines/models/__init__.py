"""Gear models on top of tca, mesher and fem: the stress scene (:mod:`.stress`) and the loaded TCA (:mod:`.ltca`).
"""


__all__ = []
