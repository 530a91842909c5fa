"""Hexahedral model of a gear pair at a TCA position (or of one gear): mesh.vtu, mesh.inp, mesh.msh, summary.json.

A mesh case names its gear pair, either inline like a ``kind = "pair"`` TCA case (``[gears.*]``,
``driver``, ``driven``, optional ``center_distance_mm``, ``[misalignment]``, ``[tca]``) or by
``pair_case = "part1_sun_planet.toml"`` (relative to the mesh case, then ``pipelines/cases``), and adds::

    position = "max_te"          # TCA position: an index, "max_te" or "min_te"
    # gear = "sun"               # instead of a pair: one gear, no TCA, uniform coarse mesh
    [mesh]
    teeth = 3                    # teeth per gear model (Fig. 1.8)
    rim_depth_mm = 6.0           # rim below the root circle (default 3 modules)
    coarse_size_mm = 1.0         # element size where nothing happens (default 0.5 module)
    contact_size_mm = 0.25       # at the TCA contact point (default 0.125 module)
    fillet_size_mm = 0.5         # on the loaded tooth's fillets (default 2 x contact size)
    growth = 1.3                 # size ratio of neighbouring elements
    gap_mm = 10.0                # double-helical members separated by F (omit: single member)
    element_type = "C3D8I"       # in mesh.inp: C3D8 (default), C3D8I or C3D8R

Writes ``mesh.vtu`` (sets as point/cell data), ``mesh.inp`` (ABAQUS/CalculiX with *NSET, *ELSET,
*SURFACE), ``mesh.msh`` (gmsh) and ``summary.json``; nothing when the case is invalid.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from tca.errors import InputError

from pipelines.cases.kinds import read_case
from pipelines.cases.mesh import MeshInputs
from pipelines.jsonio import to_json
from pipelines.cli.outdir import staged_output

__all__ = ["add_args", "handle", "build_inputs", "check_mesh_size"]


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("case", help="mesh case file (TOML), e.g. pipelines/cases/mesh_part1_sun_planet.toml")
    p.add_argument("--out", required=True, help="output folder")


# peak memory of `gearfe mesh`: measured 0.22 GB at 40k elements, 0.28 GB at 69k (meshing and writing
# .vtu/.inp/.msh): 0.14 GB + 2 kB per element; twice that per element as the margin
MESH_GB_BASE, MESH_GB_PER_ELEMENT = 0.15, 4e-6


def check_mesh_size(inp: MeshInputs) -> float:
    """Estimated elements of the mesh (pipelines.models.stress.model's count); InputError naming the [mesh] key
    when its memory exceeds the limit (GEARFE_MAX_MEMORY_GB, default 80 % of the physical memory)."""
    from pipelines.models.stress.model import memory_limit_gb, part_elements

    o = inp.options
    gears = [inp.gear] if inp.gear is not None else [inp.pair.gear1, inp.pair.gear2]
    n = 0.0
    for g in gears:
        sz = o.sizes(g)
        if inp.gear is not None:  # one gear: a uniform coarse mesh
            sz = {**sz, "contact": sz["coarse"], "axial": sz["coarse"]}
        n += part_elements(g, sz, o.teeth) * (2 if o.gap is not None else 1)
    gb = MESH_GB_BASE + MESH_GB_PER_ELEMENT * n
    limit = memory_limit_gb()
    if gb > limit:
        # the key that refines most against its default (MeshOptions: coarse 0.5 m, contact 0.125 m, 3 teeth)
        m = min(g.module for g in gears)
        blame = {("mesh.teeth", o.teeth): o.teeth / 3}
        for k, v, ref, power in (("mesh.contact_size_mm", o.contact_size, 0.125 * m, 1),
                                 ("mesh.axial_contact_size_mm", o.axial_contact_size, 0.125 * m, 1),
                                 ("mesh.coarse_size_mm", o.coarse_size, 0.5 * m, 2)):
            if v is not None:
                blame[(k, v)] = (ref / v) ** power
        key, value = max(blame, key=blame.get)
        raise InputError(key, value, f"a mesh that fits in memory (limit {limit:.3g} GB, GEARFE_MAX_MEMORY_GB)",
                         f"estimated {n:.3g} elements, {gb:.3g} GB")
    return n


def build_inputs(inp: MeshInputs):
    """(HexMesh, summary extras, element type) of a mesh case already read."""
    from mesher import mesh_gear, mesh_pair

    if inp.gear is not None:
        return mesh_gear(inp.gear, inp.options), {"gear": inp.gear.name}, inp.element_type
    pm = mesh_pair(inp.pair, inp.position, inp.options, tca_options=inp.tca_options)
    p = pm.mesh.meta["position"]
    extra = {"driver": inp.driver, "driven": inp.driven, "position": p, "contact_node_gap_mm": pm.contact_node_gap,
             "contact_pairs": [list(x) for x in pm.mesh.contact_pairs]}
    return pm.mesh, extra, inp.element_type


def handle(args) -> int:
    from mesher import check_conformity, check_quality, write_inp, write_msh, write_vtu

    t0 = time.perf_counter()
    c0 = time.process_time()
    _, inputs = read_case(args.case, "mesh")  # every key checked before any work
    check_mesh_size(inputs)  # and the size of the mesh
    with staged_output(args.out) as tmp:
        tmp = Path(tmp)
        mesh, extra, et = build_inputs(inputs)
        t_mesh = time.perf_counter() - t0
        q = check_quality(mesh)
        conf = check_conformity(mesh)
        write_vtu(mesh, tmp / "mesh.vtu")
        names = write_inp(mesh, tmp / "mesh.inp", element_type=et)
        write_msh(mesh, tmp / "mesh.msh")
        bodies = {b: {"elements": int(np.sum(mesh.cell_body == i)),
                      "nodes": int(len(np.unique(mesh.cells[mesh.cell_body == i]))),
                      "volume_mm3": float(q.volume[mesh.cell_body == i].sum()),
                      "reference_point_mm": list(mesh.reference_points[b].point),
                      "axis": list(mesh.reference_points[b].axis),
                      **mesh.meta["bodies"].get(b, {})} for i, b in enumerate(mesh.bodies)}
        summary = {
            "case": str(args.case), "elements": mesh.n_cells, "nodes": mesh.n_points,
            "min_scaled_jacobian": float(q.min_scaled_jacobian.min()),
            "min_corner_scaled_jacobian": float(q.min_corner_scaled_jacobian.min()),
            "max_aspect_ratio": float(q.aspect_ratio.max()),
            "volume_mm3": float(q.volume.sum()), **conf, **extra, "bodies": bodies,
            "inp_element_type": et, "inp_set_names": names,
            "files": ["mesh.vtu", "mesh.inp", "mesh.msh", "summary.json"],
            "mesh_s": t_mesh, "elapsed_s": time.perf_counter() - t0, "cpu_s": time.process_time() - c0,
        }
        (tmp / "summary.json").write_text(json.dumps(summary, indent=2, default=to_json) + "\n")
    for k in ("elements", "nodes", "min_scaled_jacobian", "max_aspect_ratio", "contact_node_gap_mm", "elapsed_s"):
        if k in summary:
            v = summary[k]
            print(f"  {k:<22}  {v:.6g}" if isinstance(v, float) else f"  {k:<22}  {v}")
    print(f"results in {args.out}/")
    return 0
