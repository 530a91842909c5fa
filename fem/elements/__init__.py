"""Element stiffness matrices, one module per element (today the 8-node hexahedron, C3D8 and C3D8I-like).
"""

from fem.elements.hex8 import HexGeometry, ElementMatrices, hex8_matrices, hex_geometry

__all__ = ["HexGeometry", "ElementMatrices", "hex8_matrices", "hex_geometry"]
