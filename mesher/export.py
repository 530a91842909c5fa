"""Export of a :class:`~fem.mesh.hexmesh.HexMesh` with meshio: VTU, ABAQUS/CalculiX ``.inp`` and gmsh ``.msh``.

* **VTU** — cell data ``body`` (index into the body names) and, per face set, ``faces:<name>``: a
  bit mask of the element's local faces in the set (bit f = local face f, ABAQUS S(f+1)); point
  data ``nodes:<name>`` (1 on the node set). Reference points are listed in ``field_data``.
* **INP** (ABAQUS, read by CalculiX) — written by meshio (``*NODE``, ``*ELEMENT``, ``*ELSET``,
  ``*NSET``; the element type is set to ``C3D8`` or ``C3D8I``), then ``*SURFACE, TYPE=ELEMENT`` blocks built on per-face element sets.
  Set names are upper-case ABAQUS names: ``sun/tooth0/flank_pos`` -> ``SUN_TOOTH0_FLANK_POS``
  (:func:`abaqus_name`); each body has an element set ``<BODY>`` and its reference point is an
  extra node (ids after the mesh nodes) in the node set ``<BODY>_REF``. Ids are compact (1..n),
  as CalculiX sizes its arrays by the largest id.
* **MSH** (gmsh 4.1) — written through the gmsh API: one discrete volume and physical group per
  body (hexahedra, gmsh type 5, same node order as VTK), one discrete surface of quadrangles and
  physical group per face set, named as in the mesh. gmsh also gives an independent element
  quality (:func:`gmsh_quality`, e.g. its scaled Jacobian 'minSJ' from Jacobian bounds).
"""

from __future__ import annotations

import contextlib
import re
import signal
from pathlib import Path

import meshio
import numpy as np

from tca.errors import InputError

from fem.mesh.hexmesh import HexMesh

__all__ = ["abaqus_name", "to_meshio", "write_vtu", "write_inp", "write_msh", "inp_names", "gmsh_quality", "gmsh_session"]


def abaqus_name(name: str) -> str:
    """ABAQUS-compatible set name: letters, digits and underscores, upper case, <= 80 characters."""
    s = re.sub(r"[^A-Za-z0-9_]", "_", name).upper()
    if not s or not s[0].isalpha():
        s = "S_" + s
    if len(s) > 80:
        raise InputError("set name", name, "at most 80 characters once written for ABAQUS")
    return s


def inp_names(mesh: HexMesh) -> dict[str, str]:
    """Set name in the mesh -> ABAQUS name; raises if two names collide."""
    names = list(mesh.bodies) + list(mesh.point_sets) + list(mesh.face_sets)
    out, seen = {}, {}
    for n in dict.fromkeys(names):
        a = abaqus_name(n)
        if a in seen and seen[a] != n:
            raise InputError("set name", n, f"a name distinct from {seen[a]!r} once written for ABAQUS ({a})")
        seen[a] = n
        out[n] = a
    return out


def to_meshio(mesh: HexMesh) -> meshio.Mesh:
    """meshio Mesh with bodies, node sets and face sets as point/cell data (see module docstring)."""
    cell_data = {"body": [mesh.cell_body.astype(np.int32)]}
    for name, fs in mesh.face_sets.items():
        mask = np.zeros(mesh.n_cells, np.int32)
        np.bitwise_or.at(mask, fs[:, 0], (1 << fs[:, 1]).astype(np.int32))
        cell_data[f"faces:{name}"] = [mask]
    point_data = {}
    for name, ps in mesh.point_sets.items():
        a = np.zeros(mesh.n_points, np.uint8)
        a[ps] = 1
        point_data[f"nodes:{name}"] = a
    field_data = {f"ref:{k}": np.array([*v.point, *v.axis]) for k, v in mesh.reference_points.items()}
    return meshio.Mesh(mesh.points, [("hexahedron", mesh.cells)], point_data=point_data, cell_data=cell_data,
                       field_data=field_data)


def write_vtu(mesh: HexMesh, path: str | Path) -> None:
    """VTU file (binary, zlib-compressed) of the mesh with its sets."""
    meshio.write(str(path), to_meshio(mesh), file_format="vtu")


def write_inp(mesh: HexMesh, path: str | Path, element_type: str = "C3D8") -> dict[str, str]:
    """ABAQUS/CalculiX input deck (mesh part); returns the mesh-name -> ABAQUS-name map.

    ``element_type``: ``C3D8`` (full integration) or ``C3D8I`` (incompatible modes, as in the report).
    """
    if element_type not in ("C3D8", "C3D8I", "C3D8R"):
        raise InputError("element_type", element_type, "'C3D8', 'C3D8I' or 'C3D8R'")
    names = inp_names(mesh)
    refs = list(mesh.reference_points.items())
    pts = mesh.points
    if refs:
        pts = np.concatenate([pts, np.array([v.point for _, v in refs], float)])
    cell_sets = {names[b]: [mesh.body_cells(b)] for b in mesh.bodies}
    surf_lines = []
    for name, fs in mesh.face_sets.items():
        a = names[name]
        lines = [f"*SURFACE, NAME={a}, TYPE=ELEMENT"]
        for f in np.unique(fs[:, 1]):
            es = f"{a}_S{f + 1}"
            if len(es) > 80 or es in cell_sets:
                raise InputError("face set", name, "a name that leaves room for the per-face element sets")
            cell_sets[es] = [np.unique(fs[fs[:, 1] == f, 0])]
            lines.append(f"{es}, S{f + 1}")
        surf_lines.append("\n".join(lines) + "\n")
    point_sets = {names[k]: v for k, v in mesh.point_sets.items()}
    for i, (b, _) in enumerate(refs):
        point_sets[abaqus_name(b) + "_REF"] = np.array([mesh.n_points + i])
    m = meshio.Mesh(pts, [("hexahedron", mesh.cells)], point_sets=point_sets, cell_sets=cell_sets)
    meshio.abaqus.write(str(path), m, float_fmt=".13e")  # CalculiX reads numbers of at most 20 characters
    with open(path, "r+") as fh:  # meshio names hexahedra C3D8RH (hybrid, reduced): set the element type
        text = fh.read()
        if text.count("*ELEMENT, TYPE=C3D8RH") != 1:
            raise InputError("meshio abaqus writer", "element header", "one '*ELEMENT, TYPE=C3D8RH' block")
        fh.seek(0)
        fh.write(text.replace("*ELEMENT, TYPE=C3D8RH", f"*ELEMENT, TYPE={element_type}", 1))
        fh.write("".join(surf_lines))
        fh.truncate()
    return names


def _keep_sigpipe(before) -> None:
    """Put back the SIGPIPE disposition Python had: gmsh.initialize resets SIGPIPE to its default (terminate) in
    the C library, so that a later write to a closed pipe (a reader gone, a child process that died) kills the
    whole process silently instead of raising BrokenPipeError (seen: a test worker killed by SIGPIPE, exit status
    13). Only the main thread may set a handler; elsewhere it is left as gmsh set it."""
    if before is None:
        return
    with contextlib.suppress(ValueError):
        signal.signal(signal.SIGPIPE, before)


@contextlib.contextmanager
def gmsh_session():
    """gmsh initialized for the block (quiet, no signal handlers, SIGPIPE as before); finalized if we initialized
    it."""
    import gmsh

    own = not gmsh.isInitialized()
    before = signal.getsignal(signal.SIGPIPE) if hasattr(signal, "SIGPIPE") else None
    if own:
        gmsh.initialize(interruptible=False)
        _keep_sigpipe(before)
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        yield gmsh
    finally:
        if own:
            gmsh.finalize()
            _keep_sigpipe(before)


def load_gmsh(gmsh, mesh: HexMesh, face_sets: bool = True) -> dict[str, int]:
    """Put the mesh into the current gmsh model: one discrete volume and physical group per body,
    one discrete surface of quadrangles and physical group per face set. Returns element tag offsets."""
    gmsh.model.add("gearfe")
    node_tags = np.arange(1, mesh.n_points + 1, dtype=np.uint64)
    etag = 1
    for b, body in enumerate(mesh.bodies):
        v = gmsh.model.addDiscreteEntity(3)
        cells = mesh.body_cells(body)
        nodes = np.unique(mesh.cells[cells])
        gmsh.model.mesh.addNodes(3, v, node_tags[nodes], mesh.points[nodes].ravel())
        tags = np.arange(etag, etag + len(cells), dtype=np.uint64)
        gmsh.model.mesh.addElementsByType(v, 5, tags, (mesh.cells[cells] + 1).astype(np.uint64).ravel())
        etag += len(cells)
        gmsh.model.setPhysicalName(3, gmsh.model.addPhysicalGroup(3, [v]), body)
    if face_sets:
        for name in mesh.face_sets:
            s = gmsh.model.addDiscreteEntity(2)
            q = mesh.face_nodes(name)
            tags = np.arange(etag, etag + len(q), dtype=np.uint64)
            gmsh.model.mesh.addElementsByType(s, 3, tags, (q + 1).astype(np.uint64).ravel())
            etag += len(q)
            gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, [s]), name)
    return {"elements": etag - 1}


def write_msh(mesh: HexMesh, path: str | Path) -> None:
    """gmsh 4.1 mesh file written by gmsh: hexahedra per body, quadrangles per face set, physical names."""
    with gmsh_session() as gmsh:
        load_gmsh(gmsh, mesh)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        gmsh.write(str(path))
        gmsh.model.remove()


def gmsh_quality(mesh: HexMesh, measure: str = "minSJ") -> np.ndarray:
    """Element quality of the hexahedra computed by gmsh ('minSJ', 'minSICN', 'volume', ...)."""
    with gmsh_session() as gmsh:
        load_gmsh(gmsh, mesh, face_sets=False)
        tags = np.arange(1, mesh.n_cells + 1, dtype=np.uint64)
        q = np.asarray(gmsh.model.mesh.getElementQualities(tags, measure))
        gmsh.model.remove()
    return q
