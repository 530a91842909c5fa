"""One body made of several disconnected gear parts (Fig. 1.7: rigid surfaces of several members).

The report's three-body models tie the rims of all members of a gear to one reference node: the
twin planet is four three-tooth parts (members a and b, each meshing with the sun and with the
ring) that form one rigid body 2; the double-helical sun and ring are two parts each. A part is a
single-body :class:`HexMesh` (e.g. from :func:`mesher.mesh_gear`, already placed in S_f);
:func:`join_parts` renames its sets ``<part body>/<set>`` to ``<body>/<label>/<set>``, adds the
unions ``<body>/<set>`` of the rim sets (``rim``, ``rim_side1``, ``rim_side2``, ``rim_bottom``) and
of the end faces, and gives the body one reference point. Parts share no nodes.
"""

from __future__ import annotations

import numpy as np

from tca.errors import InputError

from fem.mesh.hexmesh import HexMesh, ReferencePoint

__all__ = ["join_parts", "UNION_SETS"]

UNION_SETS = ("rim", "rim_side1", "rim_side2", "rim_bottom", "end_zmin", "end_zmax")


def join_parts(parts, body: str, reference: ReferencePoint, meta: dict | None = None) -> HexMesh:
    """Single-body meshes ``parts = [(label, mesh), ...]`` joined into one body ``body`` (see module docstring)."""
    parts = list(parts)
    if not parts:
        raise InputError("parts", parts, "at least one (label, mesh) part")
    labels = [lab for lab, _ in parts]
    if len(set(labels)) != len(labels) or any(not lab or "/" in lab for lab in labels):
        raise InputError("parts.label", labels, "distinct non-empty labels without '/'")
    pts, cells, psets, fsets = [], [], {}, {}
    union_p: dict[str, list] = {}
    union_f: dict[str, list] = {}
    part_meta = {}
    n0 = c0 = 0
    for label, m in parts:
        if len(m.bodies) != 1:
            raise InputError(f"parts[{label!r}]", m.bodies, "a mesh of one body")
        old = m.bodies[0]
        pts.append(m.points)
        cells.append(m.cells + n0)
        for k, v in m.point_sets.items():
            rest = k.split("/", 1)[1] if k.startswith(old + "/") else k
            psets[f"{body}/{label}/{rest}"] = v + n0
            if rest in UNION_SETS:
                union_p.setdefault(rest, []).append(v + n0)
        for k, v in m.face_sets.items():
            rest = k.split("/", 1)[1] if k.startswith(old + "/") else k
            fsets[f"{body}/{label}/{rest}"] = v + np.array([c0, 0])
            if rest in UNION_SETS:
                union_f.setdefault(rest, []).append(v + np.array([c0, 0]))
        part_meta[label] = dict(m.meta.get("bodies", {}).get(old, {}))
        n0 += m.n_points
        c0 += m.n_cells
    for k, v in union_p.items():
        psets[f"{body}/{k}"] = np.concatenate(v)
    for k, v in union_f.items():
        fsets[f"{body}/{k}"] = np.concatenate(v)
    info = {"bodies": {body: {"parts": part_meta}}}
    info.update(meta or {})
    return HexMesh(np.concatenate(pts), np.concatenate(cells), np.zeros(c0, np.int64), (body,), psets, fsets,
                   {body: reference}, (), info)
