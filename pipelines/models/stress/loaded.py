r"""The loaded estimate of a scene before it is meshed: which pairs of teeth carry load at the analysed
position, how much, and over which contact lines (issue 26, "model only what a scene needs").

Every mesh of a scene (the pair's one; the twin drive's four: sun–planet and planet–ring of members a
and b) is solved by the loaded TCA of :mod:`pipelines.models.ltca` at the scene's position: the condensed
flank compliances of both gears (:func:`pipelines.models.ltca.compliance.flank_compliance`) on a coarse
grid (:class:`EstimateGrid`), the contact lines of the pairs of teeth within reach
(:func:`pipelines.models.ltca.contact.contact_lines`) and their loads
(:func:`pipelines.models.ltca.contact.solve_contact`). Per loaded pair of teeth it gives the force, the
line load :math:`w` and the Hertz half-width of the slice with the largest pressure,

.. math:: b = p/\kappa = \sqrt{2 w / (\pi \kappa)},\qquad \kappa = p_0/b \text{ of the slice's curvatures},

and the points of its loaded slices (the extent of its contact under load). The stress scene sizes
each refined zone from these (:mod:`pipelines.models.stress.scene`) instead of the whole load on the
unloaded TCA's contact point; a pair that the estimate leaves unloaded gets the neighbour mesh.

Twin drive (Part 1). The twin planet is one rigid body: its two sun meshes turn it by one angle, and
its two ring meshes see one relative rotation of the ring. So the sun-side split of the planet torque
:math:`T_2 = T N_2/N_3` between members a and b solves

.. math:: \delta_a(T_a) + g_a = \delta_b(T_2 - T_a) + g_b,\qquad 0 \le T_a \le T_2,

with :math:`\delta_k(T)` the elastic rotation of member k's mesh under torque T (the loaded TCA of
that mesh alone, :math:`\delta_k(0) = 0`) and :math:`g_k` its backlash (the planet angle still to turn
before member k touches: zero for both in the assembled phase); a member that stays open gets
nothing. The ring side is split the same way with the ring torque T and the ring backlashes. The
elastic rotations are those of each mesh with the other gear held (the LTCA's): the sun and ring
sides decouple through the rigid planet.

Costs (2-core machine, Table 1.1 sun and crowned planet): the default grid (0.5 m profile, 1.5 m
axial) condenses a three-tooth gear in about 1 s; a position costs 0.1–0.3 s; member b's flanks are
the mirror images of member a's (:func:`mirrored`), so a twin drive condenses four flanks.
Against the LTCA's own default grid (0.15 m x 0.5 m), measured on ``stress_pair_small`` at its maximum TE (one
pair) and at φ1 = −5.71° (two pairs): shares 0.525/0.475 against 0.534/0.466 (the FE's converged 0.545/0.455,
tests/pipelines/models/stress/test_stress_neighbours.py), half-widths within 0.7 %, 2.1 % and 6.0 %; the finer
grid costs 80–90 s instead of 6–10 s (the shared 2-core machine, under load).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.optimize import brentq

from fem.material import Material
from tca.pair.gear_pair import GearPair
from tca.pair.te import MeshTE

from pipelines.models.ltca.compliance import FlankCompliance, FlankGrid, flank_compliance, strip_constant
from pipelines.models.ltca.contact import ContactLines, contact_lines, solve_contact

__all__ = ["EstimateGrid", "PairLoad", "MeshLoad", "Compliances", "Estimator", "mirrored", "mesh_lines", "mesh_load",
           "split_torque", "LOADED_SHARE"]

LOADED_SHARE = 1e-3  # a pair carrying less than this fraction of its mesh's force counts as unloaded (round-off)


@dataclass(frozen=True)
class EstimateGrid:
    """Grid of the loaded estimate: flank grid sizes in multiples of the module (the axial size at most
    ``axial_per_face`` of the face width), slice length [module], reach [mm] of the pairs considered."""

    profile: float = 0.5
    axial: float = 1.5
    axial_per_face: float = 1.0 / 8.0
    slice: float = 0.5
    reach: float = 0.05

    def sizes(self, module: float, face_width: float) -> tuple[float, float, float]:
        """(profile, axial, slice) [mm]."""
        return (self.profile * module, min(self.axial * module, self.axial_per_face * face_width), self.slice * module)


@dataclass(frozen=True, eq=False)
class PairLoad:
    """One pair of teeth under load in the estimate (pair frame of its mesh; the reference pair at the pair's
    own angles, as :class:`pipelines.models.ltca.contact.ContactLines`)."""

    branch: int  # TCA branch k' (teeth -k' mod N)
    teeth: tuple  # (driver tooth, driven tooth), the gears' own indices
    force: float  # [N]
    share: float  # of the mesh's force
    w: float  # line load of the slice with the largest pressure [N/mm]
    b: float  # Hertz half-width there [mm]
    p: float  # its pressure [MPa]
    points: np.ndarray  # (n, 3) loaded slice points [mm]
    lengths: np.ndarray  # (n,) their slice lengths [mm]
    widths: np.ndarray  # (n,) their Hertz half-widths p/κ [mm]
    phi: tuple  # (driver, driven) angles [rad] of the reference pair where the slices are given

    def as_json(self) -> dict:
        return {"teeth": list(self.teeth), "force_n": self.force, "share": self.share, "line_load_n_per_mm": self.w,
                "half_width_mm": self.b, "pressure_mpa": self.p, "slices": int(len(self.points))}


@dataclass(frozen=True, eq=False)
class MeshLoad:
    """The estimate of one mesh at the scene's position: its torque [N mm] on the driven gear, the elastic
    rotation [rad] of the driven gear, the loaded pairs (most loaded first) and the teeth of every pair within reach."""

    torque: float
    rotation: float
    pairs: tuple
    in_reach: tuple
    backlash: float = 0.0  # [rad] of the driven gear, before this mesh touches (twin members)

    def of(self, teeth) -> PairLoad | None:
        """The loaded pair on these (driver, driven) teeth, or None."""
        t = tuple(int(x) for x in teeth)
        return next((p for p in self.pairs if p.teeth == t), None)

    @property
    def loaded(self) -> bool:
        return bool(self.pairs)

    def as_json(self) -> dict:
        return {"torque_nm": self.torque * 1e-3, "elastic_rotation_urad": self.rotation * 1e6,
                "backlash_urad": self.backlash * 1e6, "pairs": [p.as_json() for p in self.pairs],
                "pairs_in_reach": [list(t) for t in self.in_reach]}


@lru_cache(maxsize=8)
def _strip(E: float, nu: float) -> float:
    return strip_constant(Material(E, nu))


def mirrored(fc: FlankCompliance, gear) -> FlankCompliance:
    """The compliance of ``gear``, the mirror image of ``fc.gear`` in its plane z = 0 (a double-helical member b):
    points and normals mirrored, the same compliance matrix."""
    flip = np.array([1.0, 1.0, -1.0])
    return dataclasses.replace(fc, gear=gear, points=fc.points * flip, normals=fc.normals * flip)


class Compliances:
    """Condensed flank compliances of the gears of a scene, built once per (gear, side); a gear that is the
    mirror image of one already built (double-helical member b) reuses its compliance (:func:`mirrored`)."""

    def __init__(self, grid: EstimateGrid, material: Material, element: str, solver: str, teeth: int):
        self.grid, self.material, self.element, self.solver, self.teeth = grid, material, element, solver, teeth
        self._built: list = []  # (gear, side, FlankCompliance)
        self.build_s = 0.0
        self.condensed = 0  # flank compliances built (mirror images not counted)

    def of(self, gear, side: int, u_mid: float, mirror_of=None) -> FlankCompliance:
        for g, s, fc in self._built:
            if g is gear and s == side:
                return fc
        if mirror_of is not None:
            for g, s, fc in self._built:
                if g is mirror_of and s == side:
                    out = mirrored(fc, gear)
                    self._built.append((gear, side, out))
                    return out
        t0 = time.perf_counter()
        hu, hz, _ = self.grid.sizes(gear.module, gear.face_width)
        fc = flank_compliance(gear, side, FlankGrid(self.teeth, hu, hz, hz, u_mid), self.material, self.element, self.solver)
        self.build_s += time.perf_counter() - t0
        self.condensed += 1
        self._built.append((gear, side, fc))
        return fc


def mesh_lines(pair: GearPair, mte: MeshTE, phi: float, flanks: tuple, grid: EstimateGrid, material: Material) -> ContactLines:
    """Contact lines of the pairs of teeth within reach of a mesh at driver angle ``phi`` [rad]."""
    m = max(pair.gear1.module, pair.gear2.module)
    B = min(pair.gear1.face_width, pair.gear2.face_width)
    return contact_lines(pair, mte, phi, flanks, grid.sizes(m, B)[2], grid.reach, material)


def mesh_load(pair: GearPair, lines: ContactLines, torque: float, material: Material, backlash: float = 0.0) -> MeshLoad:
    """Loads of one mesh under ``torque`` [N mm] on its driven gear (module docstring); an unloaded mesh
    (torque 0) has no loaded pairs."""
    p1 = 2 * math.pi / pair.gear1.teeth
    reach = tuple(tuple(int(x) for x in t) for t in lines.teeth)
    if not torque > 0:
        return MeshLoad(0.0, 0.0, (), reach, backlash)
    s = solve_contact(lines, torque, material, _strip(material.E, material.nu))
    total = float(s.F.sum())
    pairs = []
    for i in np.argsort(-s.pair_force):
        f = float(s.pair_force[i])
        if not f > LOADED_SHARE * total:
            continue
        sel = (lines.pair == i) & (s.F > 0)
        j = int(np.argmax(np.where(sel, s.pressure, -np.inf)))
        w = float(s.F[j] / lines.length[j])
        p = float(s.pressure[j])
        kk = int(lines.branches[i])
        phr = float(lines.phi1) - kk * p1  # the reference pair's angles where the slices lie (ltca.contact.pair_slices)
        pairs.append(PairLoad(kk, reach[i], f, f / total, w, p / float(lines.kappa[j]), p, lines.x[sel].copy(),
                              lines.length[sel].copy(), s.pressure[sel] / lines.kappa[sel],
                              (phr, pair.ratio * phr + float(lines.te))))
    return MeshLoad(float(torque), float(s.delta), tuple(pairs), reach, backlash)


def _rotation(lines: ContactLines, torque: float, material: Material) -> float:
    """Elastic rotation [rad] of the driven gear of a mesh under ``torque`` [N mm] (0 at no load)."""
    if not torque > 0:
        return 0.0
    return float(solve_contact(lines, torque, material, _strip(material.E, material.nu)).delta)


def split_torque(lines: tuple, backlash: tuple, torque: float, material: Material) -> tuple[float, float]:
    """Torques [N mm] of two meshes in parallel on one rigid body (module docstring): their elastic rotations
    plus backlashes [rad] equal, the torques summing to ``torque``; a mesh that stays open gets 0."""
    ga, gb = backlash

    def f(ta):
        return _rotation(lines[0], ta, material) + ga - _rotation(lines[1], torque - ta, material) - gb

    lo, hi = f(0.0), f(torque)
    if lo >= 0.0:
        return 0.0, torque
    if hi <= 0.0:
        return torque, 0.0
    ta = brentq(f, 0.0, torque, xtol=1e-6 * torque, rtol=1e-8)
    return float(ta), float(torque - ta)



class Estimator:
    """The loaded estimate of the meshes of one scene (module docstring): flank compliances built once, contact
    lines and loads per mesh, timings for the summary."""

    def __init__(self, grid: EstimateGrid, material: Material, element: str, solver: str, teeth: int,
                 forced: dict | None = None):
        self.grid, self.material = grid, material
        self.compliances = Compliances(grid, material, element, solver, teeth)
        self.solve_s = 0.0
        self.forced = dict(forced or {})  # (interface, member) -> teeth (j1, j2) to refine whatever the estimate (a remesh)

    def lines(self, pair: GearPair, mte: MeshTE, phi: float, params: tuple, mirror_of: tuple = (None, None)) -> ContactLines:
        """Contact lines of a mesh at driver angle ``phi`` [rad]; ``params`` (u1, v1, u2, v2) of its TCA contact
        (the flank grids' centres); ``mirror_of``: gears of which the mesh's gears are mirror images, if any."""
        fc1 = self.compliances.of(pair.gear1, pair.side1, params[0], mirror_of[0])
        fc2 = self.compliances.of(pair.gear2, pair.side2, params[2], mirror_of[1])
        t0 = time.perf_counter()
        out = mesh_lines(pair, mte, phi, (fc1, fc2), self.grid, self.material)
        self.solve_s += time.perf_counter() - t0
        return out

    def load(self, pair: GearPair, lines: ContactLines, torque: float, backlash: float = 0.0) -> MeshLoad:
        t0 = time.perf_counter()
        out = mesh_load(pair, lines, torque, self.material, backlash)
        self.solve_s += time.perf_counter() - t0
        return out

    def split(self, lines: tuple, backlash: tuple, torque: float) -> tuple[float, float]:
        t0 = time.perf_counter()
        out = split_torque(lines, backlash, torque, self.material)
        self.solve_s += time.perf_counter() - t0
        return out

    def record(self) -> dict:
        """Grid and costs for the summary."""
        g = self.grid
        return {"grid": {"profile_module": g.profile, "axial_module": g.axial, "axial_per_face": g.axial_per_face,
                         "slice_module": g.slice, "reach_um": g.reach * 1e3},
                "flanks_condensed": self.compliances.condensed,
                "build_s": self.compliances.build_s, "solve_s": self.solve_s}
