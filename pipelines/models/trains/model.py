r"""The loaded-TCA model of a train: the meshes' TCAs, the flank compliances, the slices of every mesh phase.

Build (once). One pair TCA per distinct pair of the layout (:mod:`pipelines.models.trains.geometry`: a pair
serves every planet with the same errors); one condensed flank compliance per gear body and loaded side
(:func:`pipelines.models.ltca.compliance.flank_compliance`: the sun's +1 flank, the planet's −1 flank (sun
side) and +1 flank (ring side), the ring's −1 flank), reused by every planet; a twin's member b is the mirror
image of member a, so its compliance is member a's reflected (:class:`MirroredFlank`). The two flanks of a
planet are condensed separately: the coupling of its sun-side and ring-side teeth through the planet's rim
is neglected, like the coupling of the meshes of different planets through the sun's or the ring's body.

Slices (per mesh phase, cached). In the carrier frame every mesh has the mesh frequency of the train: with
P positions per mesh cycle and the planets' phase offsets multiples of 1/(P n) of a pitch, each distinct
pair only ever sees P n phases (P when P N_1/n is an integer), whatever the number of carrier revolutions.
Its slices (:func:`pipelines.models.ltca.contact.contact_lines`) are computed once per phase and reused.

Separations at q = 0 (Eq. T1 of :mod:`pipelines.models.trains.solver`). ``contact_lines`` gives each slice's
separation g_s at the mesh's own TCA configuration, driven body turned by the mesh's unloaded TE
:math:`\Delta\phi_2` from nominal. At q = 0 the driven body is nominal: turned back by :math:`\Delta\phi_2`,
which opens slice s by :math:`\Delta\phi_2\,m_{2,s}`, :math:`m_{2,s} = ((\mathbf x_s - \mathbf o_2)\times\mathbf n_s)\cdot\mathbf a_2`
(the pair frame's driven axis), so

.. math:: c_s = g_s - \Delta\phi_2\,m_{2,s} - \mathbf n_s\cdot\mathbf e_{A} + \mathbf n_s\cdot\mathbf e_{B},     \qquad (T4)

the last terms the prescribed translations of the driver's and the driven body's teeth (errors entered as
offsets, :func:`pipelines.models.trains.geometry.offsets`).

A regulated member of a twin is mounted turned by its sun-contact angle :math:`\delta_k`
(:mod:`pipelines.models.trains.geometry`): its slices' c take the rigid motion of a planet rotation
:math:`\delta_k`, :math:`c \leftarrow c - B_{\omega_i}\delta_k`.

Rigid rows (Eq. T1) in the carrier frame: the sun turns about :math:`+z_f` through the origin, planet i about
its own axis through its pin (:attr:`TrainLayout.planet_axis`), the ring is held; translations of the sun
(floating, or on a support of finite stiffness) and of the planets (elastic pins) in the plane of the train.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from tca.errors import InputError
from tca.pair.analysis import run_pair_tca
from tca.pair.te import MeshTE, mesh_contact

from pipelines.models.ltca.compliance import FlankGrid, flank_compliance, strip_constant, weber_constant
from pipelines.models.ltca.contact import ContactLines, SliceLaw, contact_lines, teeth_in_reach
from pipelines.models.stress.model import ELEMENTS
from pipelines.models.trains.geometry import MeshSite, TrainErrors, TrainLayout, offsets
from pipelines.models.trains.options import TrainOptions
from pipelines.models.trains.solver import MeshBlock, RigidSystem

__all__ = ["DofMap", "MirroredFlank", "SliceSet", "TrainModel", "build_train_model", "PHASE_DIGITS"]

PHASE_DIGITS = 9  # a mesh phase (fraction of a pitch) is a cache key to 1e-9


class MirroredFlank:
    """A flank compliance seen through the reflection z -> -z of its gear frame (a twin's member b)."""

    def __init__(self, base):
        self.base = base
        self.teeth = base.teeth
        self.points = base.points * np.array([1.0, 1.0, -1.0])
        self.C = base.C
        self.info = {**base.info, "mirror_of": base.gear.name}
        self.gear = base.gear

    def locate(self, x, slack: float = 1e-9):
        return self.base.locate(np.asarray(x, float) * np.array([1.0, 1.0, -1.0]), slack)


@dataclass(frozen=True)
class DofMap:
    """Indices of the rigid DOFs in q: the sun's rotation (0), its translations, the planets' rotations and
    translations (-1 where a DOF is not free)."""

    sun_rot: int
    sun_t: tuple  # (ix, iy) or ()
    planet_rot: tuple  # per planet
    planet_t: tuple  # per planet (ix, iy) or ()
    size: int

    @classmethod
    def build(cls, planets: int, sun_t: bool, planet_t: bool) -> "DofMap":
        k = 1
        st = ()
        if sun_t:
            st, k = (1, 2), 3
        pr = tuple(range(k, k + planets))
        k += planets
        pt = ()
        if planet_t:
            pt = tuple((k + 2 * i, k + 2 * i + 1) for i in range(planets))
            k += 2 * planets
        return cls(0, st, pr, pt, k)


@dataclass(frozen=True, eq=False)
class SliceSet:
    """The slices of one distinct pair at one phase: the pair LTCA's contact lines and the separations at q = 0
    without offsets (Eq. T4)."""

    lines: ContactLines
    c0: np.ndarray  # (S,) [mm]
    te: float  # unloaded TE of the mesh [rad]
    build_s: float


@dataclass(frozen=True, eq=False)
class SiteRows:
    """A site's slices in S_f at one phase: rigid rows, normals, torque arms about the sun and ring axes."""

    B: np.ndarray  # (S, nq)
    normal: np.ndarray  # (S, 3)
    sun_arm: np.ndarray  # (S,) ((x - 0) x n) . e_z [mm]
    ring_arm: np.ndarray  # (S,) torque on the ring about -e_z per unit load [mm]
    points: np.ndarray  # (S, 3) in S_f


@dataclass(frozen=True, eq=False)
class TrainModel:
    """TCAs, flank compliances and the caches of slices (module docstring)."""

    layout: TrainLayout
    opts: TrainOptions
    mte: dict  # key -> MeshTE
    flanks: dict  # (gear name, side) -> FlankCompliance or MirroredFlank
    sizes: tuple  # (profile, axial, slice) [mm]
    local: float  # the flattening constant c
    dof: DofMap
    teeth: int
    build: dict  # timings [s] and sizes
    turn: dict = field(default_factory=dict)  # member key -> screw turn δ_k of a regulated member [rad]
    _slices: dict = field(default_factory=dict, repr=False)
    _rows: dict = field(default_factory=dict, repr=False)

    # ------------------------------------------------------------------ slices
    def phase(self, site: MeshSite, psi1: float) -> float:
        """The site's mesh phase at ψ1: fraction of a driver pitch from its TCA grid's start, in [0, 1)."""
        m = self.mte[site.key]
        fr = ((self.layout.driver_angle(site, psi1) - m.phi0) / m.pitch) % 1.0
        fr = round(fr, PHASE_DIGITS)
        return 0.0 if fr >= 1.0 else fr

    def slices(self, key, frac: float) -> SliceSet:
        """The slices of pair ``key`` at phase ``frac`` (cached)."""
        hit = self._slices.get((key, frac))
        if hit is not None:
            return hit
        t0 = time.perf_counter()
        pair = self.layout.pairs[key]
        m = self.mte[key]
        phi = m.phi0 + frac * m.pitch
        fl = (self._flank(pair.gear1, pair.side1), self._flank(pair.gear2, pair.side2))
        L = contact_lines(pair, m, phi, fl, self.sizes[2], self.opts.reach, self.opts.material)
        if L.dropped:
            raise InputError("ltca.teeth", self.teeth, f"more modelled teeth: pairs of teeth within reach of the "
                             f"{self.layout.labels[key]} lie outside the model at phase {frac:.4f}")
        _, m2 = pair.mounts()
        arm2 = np.einsum("ij,j->i", np.cross(L.x - m2.origin, L.normal), m2.axis)
        s = SliceSet(L, L.gap - L.te * arm2, L.te, time.perf_counter() - t0)
        self._slices[(key, frac)] = s
        return s

    def rows(self, site: MeshSite, frac: float) -> SiteRows:
        """The rigid rows of a site's slices at a phase (cached)."""
        hit = self._rows.get((site, frac))
        if hit is not None:
            return hit
        L = self.slices(site.key, frac).lines
        x, n = L.x, L.normal
        if site.mirror:
            x, n = x * np.array([1.0, 1.0, -1.0]), n * np.array([1.0, 1.0, -1.0])
        R, t = site.frame.R, site.frame.t
        xf, nf = x @ R.T + t, n @ R.T
        i = site.planet
        o, a = self.layout.planet_origin[i], self.layout.planet_axis[i]
        d = self.dof
        B = np.zeros((len(xf), d.size))
        planet_arm = np.einsum("ij,j->i", np.cross(xf - o, nf), a)
        sun_arm = np.cross(xf, nf)[:, 2]
        if site.kind == "sun":  # sun (driver) pushes planet i (driven)
            B[:, d.sun_rot] = sun_arm
            if d.sun_t:
                B[:, list(d.sun_t)] = nf[:, :2]
            B[:, d.planet_rot[i]] = -planet_arm
            if d.planet_t:
                B[:, list(d.planet_t[i])] = -nf[:, :2]
        else:  # planet i (driver) pushes the ring (held)
            B[:, d.planet_rot[i]] = planet_arm
            if d.planet_t:
                B[:, list(d.planet_t[i])] = nf[:, :2]
        r = SiteRows(B, nf, sun_arm, -sun_arm, xf)
        self._rows[(site, frac)] = r
        return r

    def build_phases(self) -> float:
        """Build the slices and rigid rows of every mesh phase the run will meet (one mesh cycle of positions: the
        phases repeat every cycle), so that a position costs only its coupled solve; the seconds taken (also in
        ``build['phases_s']``)."""
        t0 = time.perf_counter()
        P, N1 = self.opts.positions_per_cycle, self.layout.sun.teeth
        for ps in 2 * math.pi * np.arange(P) / (P * N1):
            for site in self.layout.sites:
                fr = self.phase(site, float(ps))
                self.slices(site.key, fr)
                self.rows(site, fr)
        dt = time.perf_counter() - t0
        self.build["phases_s"] = self.build.get("phases_s", 0.0) + dt
        return dt

    @property
    def cached_phases(self) -> int:
        """Distinct (pair, phase) slice sets built so far."""
        return len(self._slices)

    def with_options(self, opts: TrainOptions) -> "TrainModel":
        """The same TCAs, flank compliances and slices under other supports (sun axis, sun support, pins): the
        rigid DOFs are rebuilt, the slices reused (they do not depend on the supports)."""
        floating = opts.sun_axis == "floating" or opts.sun_support is not None
        dof = DofMap.build(self.layout.planets, floating, opts.pin_stiffness is not None)
        return replace(self, opts=opts, dof=dof, _slices=self._slices, _rows={})

    def _flank(self, gear, side):
        return self.flanks[(gear.name, side)]

    # ------------------------------------------------------------------ one position
    def blocks(self, psi1: float, errors: TrainErrors, torque: float):
        """The MeshBlock of every site at ψ1 [rad] with the errors' offsets; (blocks, rows, slice sets)."""
        off = offsets(self.layout, errors, psi1)
        out, rows, sets = [], [], []
        n = self.layout.planets
        rb = self.layout.sun.r_b
        for site in self.layout.sites:
            fr = self.phase(site, psi1)
            ss = self.slices(site.key, fr)
            r = self.rows(site, fr)
            L = ss.lines
            nxy = r.normal[:, :2]
            if site.kind == "sun":
                c = ss.c0 - nxy @ off["sun"] + nxy @ off["planets"][site.planet]
            else:
                c = ss.c0 - nxy @ off["planets"][site.planet] + nxy @ off["ring"]
            dk = self.turn.get(site.key[0], 0.0)
            if dk:  # the member mounted turned by its screw turn: a planet rotation of its teeth
                c = c - r.B[:, self.dof.planet_rot[site.planet]] * dk
            L0 = max(float(np.ptp(L.xi[L.pair == 0])) if (L.pair == 0).any() else 0.0, L.ds)
            members = len(self.layout.members)
            out.append(MeshBlock(L.W, c, r.B, SliceLaw(L.length, L.radius, L.depth), L.kappa,
                                 torque / (n * members * rb) / L0))
            rows.append(r)
            sets.append(ss)
        return out, rows, sets

    def rigid(self, torque: float) -> RigidSystem:
        """K, f and residual scales for a torque T [N mm] on the sun."""
        d = self.dof
        K = np.zeros((d.size, d.size))
        f = np.zeros(d.size)
        f[d.sun_rot] = torque
        scale = np.full(d.size, torque)
        force = torque / self.layout.sun.r_b
        if d.sun_t:
            scale[list(d.sun_t)] = force
            if self.opts.sun_support is not None:
                K[d.sun_t, d.sun_t] = self.opts.sun_support
        for pt in d.planet_t:
            scale[list(pt)] = force
            K[pt, pt] = self.opts.pin_stiffness
        return RigidSystem(K, f, scale)


def _u_mid(mte: MeshTE, which: int) -> float:
    r = mte.result
    i = int(np.argmax(r.te[:-1] if len(r.te) > 1 else r.te))
    return float(mesh_contact(r, float(r.phi1[i])).params[0 if which == 1 else 2])


def build_train_model(layout: TrainLayout, opts: TrainOptions, say=None) -> TrainModel:
    """TCAs of the distinct pairs and the flank compliances of the bodies (module docstring)."""
    t0 = time.perf_counter()
    one = replace(opts.tca, cycles=1)  # every mesh is periodic: one cycle
    mte = {}
    for key, pair in layout.pairs.items():
        mte[key] = MeshTE.from_result(run_pair_tca(pair, one))
    turn = {}
    if layout.regulated:
        u = np.arange(40) / 40.0
        for (gk, kind), m1 in mte.items():
            if kind == "sun":
                turn[gk] = float(np.mean(m1(m1.phi0 + m1.pitch * u)))
    t_tca = time.perf_counter() - t0
    if say is not None:
        say(f"build: {len(mte)} pair TCAs in {t_tca:.1f} s")
    g0 = layout.sun
    hu, hz, ds = opts.sizes(g0.module, min(g.face_width for g in (layout.sun, layout.planet, layout.ring)))
    teeth = opts.teeth
    P = opts.positions_per_cycle
    psi = 2 * math.pi * np.arange(P) / (P * layout.sun.teeth)  # the phases repeat every mesh cycle
    for key, pair in layout.pairs.items():
        m = mte[key]
        phis = sorted({m.phi0 + m.pitch * (((layout.driver_angle(s, float(p)) - m.phi0) / m.pitch) % 1.0)
                       for s in layout.sites if s.key == key for p in psi})
        teeth = max(teeth, teeth_in_reach(pair, m, np.array(phis), ds, opts.reach, opts.teeth))
    if teeth > 9:
        raise InputError("ltca.reach_um", opts.reach * 1e3, f"a reach whose pairs of teeth fit a model of at most 9 "
                         f"teeth per gear (they span {teeth})")
    t1 = time.perf_counter()
    # bodies and loaded sides: member a's gears condensed, member b's mirrored
    need = {}
    for key, pair in layout.pairs.items():
        for g, side, which in ((pair.gear1, pair.side1, 1), (pair.gear2, pair.side2, 2)):
            need.setdefault((g.name, side), (g, _u_mid(mte[key], which)))
    flanks = {}
    element = ELEMENTS[opts.element]
    for (name, side), (g, u) in sorted(need.items(), key=lambda kv: kv[0][0].endswith("_b")):
        base = name[:-2] if name.endswith("_b") else None
        if base is not None and (base, side) in flanks:
            flanks[(name, side)] = MirroredFlank(flanks[(base, side)])
            continue
        fc = flank_compliance(g, side, FlankGrid(teeth, hu, hz, hz, u), opts.material, element, opts.solver)
        flanks[(name, side)] = fc
        if say is not None:
            say(f"build: {name} flank {side:+d}: {fc.info['elements']} elements, {fc.info['dofs']} DOF, "
                f"{fc.info['flank_nodes']} flank nodes condensed in {fc.info['total_s']:.1f} s")
    for (name, side), (g, u) in need.items():  # member b without a condensed member a (not expected)
        if (name, side) not in flanks:
            flanks[(name, side)] = flank_compliance(g, side, FlankGrid(teeth, hu, hz, hz, u), opts.material, element,
                                                    opts.solver)
    t_fc = time.perf_counter() - t1
    c_loc = strip_constant(opts.material) if opts.local == "strip" else weber_constant(opts.material.nu)
    floating = opts.sun_axis == "floating" or opts.sun_support is not None
    dof = DofMap.build(layout.planets, floating, opts.pin_stiffness is not None)
    build = {"tca_s": t_tca, "compliance_s": t_fc, "total_s": time.perf_counter() - t0, "pairs": len(mte),
             "bodies": len([f for f in flanks.values() if not isinstance(f, MirroredFlank)])}
    build["member_turn_arcsec"] = {layout.labels[(k, "sun")]: v / (math.pi / 648000) for k, v in turn.items()}
    return TrainModel(layout, opts, mte, flanks, (hu, hz, ds), c_loc, dof, teeth, build, turn)
