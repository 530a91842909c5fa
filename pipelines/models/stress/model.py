r"""Mesh and FE model of a stress scene (Steps 4–6, Fig. 1.7) and its contact solve.

Each part of the scene is meshed by :func:`mesher.mesh_gear` around its loaded tooth (graded at the
TCA contact point with the scene's sizes and zone) and moved into S_f; parts of one body are joined
(:func:`mesher.join_parts`: the twin planet's four parts become one body whose rims are tied to one
reference node). Supports as Fig. 1.7: the fixed body's rims held, the rigid bodies' rims tied to
their reference nodes with only the rotation about the axis free, the torque on the driven body.

Contacts: for every interface and every modelled tooth pair (equal offsets from the loaded pair),
a :class:`fem.ContactPair` from the slave flank (the planet, or the driven gear of a pair) to the
master flank, seeded at the TCA point on the loaded pair, grouped per interface and member.

The solver keeps as contact candidates the slave nodes whose initial gap is below
``search_gap``; it checks afterwards that no other node penetrates, and when one does the solve
is repeated with the search gap doubled (up to ``max_search_gap``).

Resource estimate (before meshing, :func:`estimate_resources`). Every part's element distributions are
planned by the mesher itself (:func:`mesher.body.plan_gear`: the axial levels and the tooth plans of
:func:`mesher.mesh_gear`, the section topology, no node placed; about 40 ms a part), so the element
and node counts before meshing are those of the mesh that is built (issue 26: the fitted formula it
replaces, :func:`part_elements`, was 2-3 times low where a zone covers a helical contact line across
the whole flank — ``stress_helical_pair.toml`` at refine 0.5: 474k DOF estimated, 1.35M meshed — and
a run was killed by the kernel instead of refused; :func:`part_elements` remains the quick estimate
of ``gearfe mesh``). Peak memory of the sparse direct solve (PARDISO measured on a hexahedral box:
0.54 GB at 53k DOF, 8.2 GB at 499k DOF): :math:`M = 0.54\,(\mathrm{DOF}/53\,000)^{1.21}` GB. A model
whose estimate exceeds the limit (``GEARFE_MAX_MEMORY_GB``, default 80 % of the machine's physical
memory) is refused before meshing with an :class:`~tca.errors.InputError` naming the ``[mesh]`` key
that made it large; the meshed model is checked again before the solve (:func:`check_resources` with
``mesh``).

:func:`part_elements` (``gearfe mesh``): a part's structured mesh is axial layers times a transverse
section; along the face width :math:`F`, graded from the axial contact size :math:`h_a` (over a zone
of half-length :math:`e_z`) to the coarse size :math:`c` with growth :math:`q`,

.. math::  n_z = \min\Big(F/h_a,\; 2e_z/h_a + 2\ln(c/h_a)/\ln q + F/c\Big),

and the section of :math:`T` teeth, in sizes relative to the module (:math:`\bar c = c/m`,
:math:`\bar h = h_c/m`) is :math:`n_s = 155 + 33.7\,\bar c^{-2} + 7.5\,\bar h^{-1} + 37.6\,(T-1)\,\bar c^{-2}`
(a least-squares fit to 20 real part meshes), so :math:`N = n_z n_s`.
"""

from __future__ import annotations

import math

import numpy as np
import os
import dataclasses
from dataclasses import dataclass

from fem import STEEL, Body, ContactOptions, ContactPair, FEModel, Fixed, Material, Rigid, SolverOptions, solve
from fem.result import FEResult
from mesher import MeshOptions, join_parts, mesh_gear, merge_meshes
from mesher.body import plan_gear
from fem.mesh.hexmesh import HexMesh
from fem.errors import FEConvergenceError
from tca.errors import InputError

from pipelines.models.stress.scene import Interface, Scene

__all__ = ["FESettings", "mesh_scene", "fe_model", "solve_scene", "pair_name", "ResourceEstimate",
           "estimate_resources", "check_resources", "memory_limit_gb", "part_elements", "part_options"]

ELEMENTS = {"C3D8I": "hex8i", "C3D8": "hex8"}


@dataclass(frozen=True)
class FESettings:
    """Material, element, solver and contact settings of a stress case."""

    material: Material = STEEL  # E = 2.068e5 MPa, nu = 0.29 (Numerical Example 1.3)
    element: str = "C3D8I"
    solver: str = "auto"
    penalty_factor: float = 100.0
    max_penetration: float = 1e-4  # [mm]
    quadrature: int = 2
    penalty_check_tol: float = 0.01  # peak-pressure change allowed when the penalty doubles
    search_gap: float = 0.03  # [mm]
    max_search_gap: float = 0.5  # [mm]
    points: str = "gauss"  # contact constraints: 'gauss' (per Gauss point) or 'nodes' (averaged per slave node)

    def __post_init__(self):
        if self.element not in ELEMENTS:
            raise InputError("fe.element", self.element, "one of " + ", ".join(repr(e) for e in ELEMENTS))
        SolverOptions(solver=self.solver)
        self.contact_options()
        if not (0 < self.search_gap <= self.max_search_gap <= 5.0):
            raise InputError("fe.search_gap_mm", self.search_gap, f"in (0, max_search_gap_mm = {self.max_search_gap:g}] mm, "
                             "max_search_gap_mm <= 5")

    def contact_options(self) -> ContactOptions:
        return ContactOptions(penalty_factor=self.penalty_factor, max_penetration=self.max_penetration,
                              quadrature=self.quadrature, penalty_check_tol=self.penalty_check_tol,
                              points=self.points)


# element-count model of the module docstring, fitted to real meshes
_SECTION = (155.0, 33.7, 7.5, 37.6)  # n_s = a + b / cbar^2 + c / hbar + d (T - 1) / cbar^2
_NODES_PER_ELEMENT = 1.15
_MEM_GB_REF, _DOF_REF, _MEM_EXP = 0.54, 53_000.0, 1.21


@dataclass(frozen=True)
class ResourceEstimate:
    """Estimated size of a stress model before meshing."""

    elements: int
    dofs: int
    memory_gb: float  # peak memory of the direct solve [GB]


def _count(L: float, h: float, c: float, ext: float, q: float) -> float:
    """Elements along a length L graded from h (over +-ext) to c with growth q (module docstring)."""
    h = min(h, c)
    return min(L / h, 2 * ext / h + 2 * math.log(c / h) / math.log(max(q, 1.01)) + L / c)


def part_elements(gear, sizes: dict, teeth: int, extent_z: float = 0.0, zones: tuple = ()) -> float:
    """Elements of one part's mesh (module docstring) from its sizes [mm] (keys coarse, contact, axial, growth).

    ``zones``: (z, extent_z) [mm] of every focus when there are several (refined neighbouring teeth): the
    axial layers of the first grow by the ratio of the integrals of 1/h over the face for the smallest
    of all their size fields (the mesher's :class:`mesher.grading.MinField`) and for the first alone,
    and each further focus adds a graded tooth section."""
    a, b, c_, d = _SECTION
    m, c = gear.module, sizes["coarse"]
    h, q, F = min(sizes["axial"], c), sizes["growth"], gear.face_width
    if len(zones) > 1:  # the calibrated count of the first zone, times the growth of the layer integral
        x = np.linspace(-0.5 * F, 0.5 * F, 4001)

        def layers(zs):
            size = np.full_like(x, c)
            for z, e in zs:
                size = np.minimum(size, h + (q - 1.0) * np.maximum(np.abs(x - z) - e, 0.0))
            return float(np.sum(0.5 * (1 / size[1:] + 1 / size[:-1]) * np.diff(x)))

        nz = _count(F, h, c, extent_z, q) * layers(zones) / layers(zones[:1])
    else:
        nz = _count(F, h, c, extent_z, q)
    cbar, hbar = c / m, min(sizes["contact"], c) / m
    extra = max(len(zones) - 1, 0)
    return nz * (a + b / cbar**2 + (1 + extra) * c_ / hbar + d * (teeth - 1) / cbar**2)


def part_options(p) -> MeshOptions:
    """The mesher's options of a scene part (its sizes)."""
    s = p.sizes
    return MeshOptions(teeth=s.teeth, rim_depth=s.rim, coarse_size=s.coarse, contact_size=s.contact, fillet_size=s.fillet,
                       growth=s.growth, axial_contact_size=s.axial, neighbour_size=s.neighbour,
                       axial_coarse_size=s.axial_coarse, section_growth=s.section_growth, axial_growth=s.axial_growth,
                       back_size=s.back, depth_growth=s.depth_growth)


def estimate_resources(scene: Scene) -> ResourceEstimate:
    """Element, DOF and memory estimate of the scene's model before meshing: the mesher's own plan of every part
    (:func:`mesher.body.plan_gear`: its element distributions without the nodes, exact counts in ~40 ms a part)."""
    plans = [plan_gear(p.gear, part_options(p), centre=p.centre, focus=p.focus, others=p.others) for p in scene.parts]
    return _resources(sum(q.cells for q in plans), 3 * sum(q.nodes for q in plans))


def _resources(elements: float, dofs: float) -> ResourceEstimate:
    """Elements, DOF and the peak memory of the direct solve (module docstring)."""
    return ResourceEstimate(int(elements), int(dofs), float(_MEM_GB_REF * (dofs / _DOF_REF) ** _MEM_EXP))


def memory_limit_gb() -> float:
    """The memory a model may take [GB]: ``GEARFE_MAX_MEMORY_GB``, or 80 % of the physical memory."""
    env = os.environ.get("GEARFE_MAX_MEMORY_GB")
    if env is not None:
        try:
            v = float(env)
        except ValueError:
            v = float("nan")
        if not (v > 0 and math.isfinite(v)):
            raise InputError("GEARFE_MAX_MEMORY_GB", env, "a positive number of GB")
        return v
    try:
        return 0.8 * os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 1e9
    except (ValueError, OSError, AttributeError):  # not POSIX: no limit known
        return math.inf


def check_resources(scene: Scene, rules, limit_gb: float | None = None, mesh: HexMesh | None = None) -> ResourceEstimate:
    """The estimate, or an InputError naming the [mesh] key that made the model too large.

    ``rules`` is the case's :class:`pipelines.models.stress.sizing.SizeRules`; the key blamed is the
    user-set one that refines the most (``refine`` cubed; a contact size below the default
    Hertz-based one, squared; ...), ``mesh.refine`` when none was set. With ``mesh`` the check
    is made on its real size (before the solve): the estimate is calibrated on localized contacts
    and is 2-3 times low where a zone covers a helical contact line across the whole flank
    (``stress_helical_pair.toml`` at refine 0.5: 474k DOF estimated, 1.35M meshed).
    """
    est = estimate_resources(scene) if mesh is None else _resources(mesh.n_cells, 3 * mesh.n_points)
    limit = memory_limit_gb() if limit_gb is None else limit_gb
    if est.memory_gb <= limit:
        return est
    m = min(p.gear.module for p in scene.parts)
    blame = {"mesh.refine": rules.refine ** 3 if rules.refine > 1 else 0.0}
    for key, attr, ref, power in (("mesh.contact_size_mm", "contact", 0.1 * m, 2),
                                  ("mesh.axial_contact_size_mm", "axial", 0.3 * m, 1),
                                  ("mesh.coarse_size_mm", "coarse", 0.75 * m, 3),
                                  ("mesh.fillet_size_mm", "fillet", 0.1 * m, 2)):
        v = getattr(rules, attr)
        if v is not None:
            blame[key] = (ref / v) ** power
    key = max(blame, key=blame.get)
    value = {"mesh.refine": rules.refine, "mesh.contact_size_mm": rules.contact,
             "mesh.axial_contact_size_mm": rules.axial, "mesh.coarse_size_mm": rules.coarse,
             "mesh.fillet_size_mm": rules.fillet}[key]
    raise InputError(key, value, f"a model that fits in memory (limit {limit:.3g} GB, GEARFE_MAX_MEMORY_GB)",
                     f"{'estimated' if mesh is None else 'meshed:'} {est.elements:.3g} elements, {est.dofs:.3g} DOF, "
                     f"{est.memory_gb:.3g} GB")


def mesh_scene(scene: Scene) -> HexMesh:
    """All parts meshed, placed and joined into the scene's bodies (one mesh)."""
    bodies: dict[str, list] = {}
    for p in scene.parts:
        m = mesh_gear(p.gear, part_options(p), centre=p.centre, focus=p.focus, others=p.others).transformed(p.R, p.t)
        bodies.setdefault(p.body, []).append((p, m))
    refs = {b: rb.ref for b, rb in scene.rigid.items()}
    meshes = []
    for body, items in bodies.items():
        if len(items) == 1 and not items[0][0].label:
            p, m = items[0]
            if m.bodies[0] != body:
                raise InputError("parts", (m.bodies[0], body), "a one-part body named after its gear")
            if body in refs:
                m = HexMesh(m.points, m.cells, m.cell_body, m.bodies, m.point_sets, m.face_sets, {body: refs[body]},
                            (), m.meta)
            meshes.append(m)
        else:
            from mesher import ReferencePoint

            ref = refs.get(body, ReferencePoint((0.0, 0.0, 0.0), (0.0, 0.0, 1.0)))
            meshes.append(join_parts([(p.label, m) for p, m in items], body, ref))
    pairs = []
    for itf in scene.interfaces:
        for _, j1, j2 in itf.tooth_pairs():
            pairs.append((itf.driver.set(f"tooth{j1}/flank_{_side(itf.side1)}"), itf.driven.set(f"tooth{j2}/flank_{_side(itf.side2)}")))
    meta = {"bodies": {k: v for m in meshes for k, v in m.meta.get("bodies", {}).items()}, "model": scene.model}
    return merge_meshes(meshes, contact_pairs=pairs, meta=meta)


def _side(s: int) -> str:
    return "pos" if s > 0 else "neg"


def pair_name(itf: Interface, j1: int, j2: int) -> str:
    """Contact pair name: '<interface>/<member>/<driver><j1>-<driven><j2>' (own tooth indices)."""
    return f"{itf.name}/{itf.member}/{itf.driver.gear.name}{j1}-{itf.driven.gear.name}{j2}"


def fe_model(scene: Scene, fe: FESettings, search_gap: float | None = None) -> FEModel:
    """Bodies with the supports of Fig. 1.7, contact pairs per tooth pair, fillet sets of all teeth."""
    mat = fe.material
    gap = fe.search_gap if search_gap is None else search_gap
    bodies = []
    names = []
    for p in scene.parts:
        if p.body not in names:
            names.append(p.body)
    for b in names:
        if b == scene.fixed:
            bodies.append(Body(b, (Fixed(f"{b}/rim"),), mat))
        else:
            torque = scene.rigid[b].torque
            bodies.append(Body(b, (Rigid(f"{b}/rim", b, free=scene.rigid[b].free, torque=torque),), mat))
    contacts = []
    for itf in scene.interfaces:
        for q, j1, j2 in itf.tooth_pairs():
            s1 = itf.driver.set(f"tooth{j1}/flank_{_side(itf.side1)}")
            s2 = itf.driven.set(f"tooth{j2}/flank_{_side(itf.side2)}")
            slave, master = (s2, s1) if itf.slave == "driven" else (s1, s2)
            cp = tuple(float(x) for x in itf.point) if q == 0 else None
            contacts.append(ContactPair(slave, master, name=pair_name(itf, j1, j2), group=f"{itf.name}/{itf.member}",
                                        search_gap=gap, contact_point=cp))
    fillets = []
    for p in scene.parts:
        for j in p.teeth:
            fillets += [p.set(f"tooth{j}/fillet_pos"), p.set(f"tooth{j}/fillet_neg")]
    return FEModel(tuple(bodies), tuple(contacts), fe.contact_options(),
                   SolverOptions(solver=fe.solver, element=ELEMENTS[fe.element]), tuple(fillets))


def solve_scene(scene: Scene, mesh: HexMesh, fe: FESettings, progress=None) -> tuple[FEResult, FEModel, list]:
    """Solve, doubling the search gap while nodes outside the candidate set penetrate; (result, model, attempts)."""
    gap = fe.search_gap
    attempts = []
    while True:
        model = fe_model(scene, fe, gap)
        try:
            r = solve(mesh, model)
            attempts.append({"search_gap_mm": gap, "ok": True, "total_s": r.info.timings["total_s"]})
            return r, model, attempts
        except FEConvergenceError as exc:
            if "outside the candidate set" not in str(exc.where) or 2 * gap > fe.max_search_gap:
                raise
            attempts.append({"search_gap_mm": gap, "ok": False, "why": str(exc)})
            gap *= 2
            if progress is not None:
                progress(f"solve: a node outside the contact candidates penetrates; search gap raised to {gap:g} mm")
