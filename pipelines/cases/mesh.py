"""Reader of a mesh case (``gearfe mesh``; ``kind = "mesh"``, which a mesh file may leave out).

A mesh case names its gear pair, either inline like a ``kind = "pair"`` TCA case (``[gears.*]``,
``driver``, ``driven``, optional ``center_distance_mm``, ``[misalignment]``, ``[tca]``) or by
``pair_case = "part1_sun_planet.toml"`` (relative to the mesh case, then ``pipelines/cases``); its keys
are listed in :mod:`pipelines.cli.mesh`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from tca.errors import InputError

from pipelines.cases.reader import CASES_DIR, load_case, read_gears, read_pair, read_tca_options
from pipelines.cases.schema import Table

__all__ = ["read_mesh_options", "read_mesh_case", "read_mesh_table", "MeshInputs"]


def read_mesh_options(t: Table | None):
    """MeshOptions and the .inp element type from a ``[mesh]`` table."""
    from mesher import MeshOptions

    if t is None:
        return MeshOptions(), "C3D8"
    o = MeshOptions(
        teeth=t.get("teeth", int, 3, lo=1, hi=2000),
        rim_depth=t.get("rim_depth_mm", float, None, lo=0.0, lo_open=True),
        coarse_size=t.get("coarse_size_mm", float, None, lo=0.0, lo_open=True),
        contact_size=t.get("contact_size_mm", float, None, lo=0.0, lo_open=True),
        fillet_size=t.get("fillet_size_mm", float, None, lo=0.0, lo_open=True),
        growth=t.get("growth", float, 1.3, lo=1.0, hi=3.0),
        gap=t.get("gap_mm", float, None, lo=0.0),
    )
    et = t.get("element_type", str, "C3D8", choices=("C3D8", "C3D8I", "C3D8R"))
    t.done()
    return o, et


def _pair_source(case: Table, path: Path) -> Table:
    """The table holding the pair definition: the case itself or the file named by pair_case."""
    ref = case.get("pair_case", str, None)
    if ref is None:
        return case
    if case.has("gears"):
        raise InputError("pair_case", ref, "either pair_case or inline [gears], not both")
    for base in (path.parent, CASES_DIR):
        p = base / ref
        if p.is_file():
            src = load_case(p)
            src.get("kind", str, "pair", choices=("pair",))
            src.get("title", str, "")
            return src
    raise InputError("pair_case", ref, f"a pair case file in {path.parent} or {CASES_DIR}")


@dataclass(frozen=True)
class MeshInputs:
    """A mesh case read in full (every key checked) before any meshing."""

    options: object  # mesher.MeshOptions
    element_type: str
    gear: object = None  # tca.geometry.gear.Gear when one gear is meshed
    pair: object = None  # tca.pair.gear_pair.GearPair otherwise
    driver: str = ""
    driven: str = ""
    position: object = "max_te"
    tca_options: object = None


def read_mesh_table(case: Table) -> MeshInputs:
    """Read and check every key of a mesh case loaded from its file (``case.source``) without meshing."""
    return read_mesh_case(case, Path(case.source) if case.source is not None else Path("case.toml"))


def read_mesh_case(case: Table, path: Path) -> MeshInputs:
    """Read and check every key of a mesh case (unknown keys included) without meshing; ``pair_case`` is
    looked up beside ``path``, then among the shipped cases."""
    case.get("kind", str, "mesh", choices=("mesh",))
    case.get("title", str, "")
    gear_name = case.get("gear", str, None)
    src = _pair_source(case, path)
    gears = read_gears(src)
    opts, et = read_mesh_options(case.table("mesh", required=False))
    if gear_name is not None:
        if gear_name not in gears:
            raise InputError("gear", gear_name, "one of " + ", ".join(repr(g) for g in gears))
        for k in ("driver", "driven", "center_distance_mm", "misalignment", "tca", "position"):
            if case.has(k):
                raise InputError(k, case.data[k], "no pair keys in a case that meshes one gear (gear = ...)")
        case.done()
        return MeshInputs(opts, et, gear=gears[gear_name])
    pair, driver, driven = read_pair(src, gears)
    tca_opts = read_tca_options(src.table("tca", required=False))
    if case.has("position") and isinstance(case.data["position"], int) and not isinstance(case.data["position"], bool):
        pos = case.get("position", int)  # range-checked against the TCA positions by mesh_pair
    else:
        pos = case.get("position", str, "max_te", choices=("max_te", "min_te"))
    if src is not case:
        src.done()
    case.done()
    return MeshInputs(opts, et, pair=pair, driver=driver, driven=driven, position=pos, tca_options=tca_opts)
