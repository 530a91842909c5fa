"""Structured hexahedral tooth bodies: six subvolumes per tooth, named sets, export."""

from .hexmesh import HEX_FACES, HexMesh, ReferencePoint

__all__ = ["HEX_FACES", "HexMesh", "ReferencePoint"]
