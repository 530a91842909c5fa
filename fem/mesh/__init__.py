"""The hexahedral mesh type of the FE engine and simple structured meshes for its verification.
"""

from fem.mesh.hexmesh import HEX_FACES, HexMesh, ReferencePoint, merge_meshes

__all__ = ["HEX_FACES", "HexMesh", "ReferencePoint", "merge_meshes"]
