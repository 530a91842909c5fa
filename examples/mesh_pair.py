"""A hexahedral model of a gear pair placed at a TCA position, from Python (report section 1.6, Step 5).

The pair is read from a shipped case file (Table 1.1 sun and double-crowned planet, 3 arcmin shaft
angle error) and meshed at the position of maximum transmission error: both gears in the fixed frame,
the TCA contact point a node of both meshes, named face sets for the flanks, fillets and rims.
Writes ``mesh.vtu`` (ParaView) and ``mesh.inp`` (CalculiX/ABAQUS) when given a folder.

Run: ``python examples/mesh_pair.py [OUT_DIR]``
"""

import sys
from pathlib import Path

from mesher import MeshOptions, check_conformity, check_quality, mesh_pair, write_inp, write_vtu
from pipelines.cases import CASES_DIR, load_case, read_gears, read_misalignment
from tca import GearPair


def main(out: Path | None = None, contact_size_mm: float | None = None):
    case = load_case(CASES_DIR / "part1_sun_planet.toml")
    gears = read_gears(case)
    pair = GearPair(gears["sun"], gears["planet"], read_misalignment(case.table("misalignment")))
    model = mesh_pair(pair, "max_te", MeshOptions(teeth=3, contact_size=contact_size_mm))
    q = check_quality(model.mesh)  # raises on an inverted element
    check_conformity(model.mesh)  # raises on a duplicate node or a hanging face
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        write_vtu(model.mesh, out / "mesh.vtu")
        write_inp(model.mesh, out / "mesh.inp")
    return model, q


if __name__ == "__main__":
    model, q = main(Path(sys.argv[1]) if len(sys.argv) > 1 else None)
    m = model.mesh
    print(f"{m.n_cells} hexahedra, {m.n_points} nodes, bodies {m.bodies}; loaded teeth {model.loaded_teeth}")
    print(f"contact point {model.contact_point.round(4)} mm; gap between the two contact nodes "
          f"{model.contact_node_gap:.1e} mm; worst scaled Jacobian {q.min_scaled_jacobian.min():.3f}")
