r"""Gear-level FE scenes at a TCA position: which teeth are meshed, where, and how finely (section 1.6).

A *scene* lists the parts to mesh — ``teeth`` teeth of one gear member centred on its loaded
tooth, placed in :math:`S_f` — the meshing interfaces between them and the supports of the bodies
(Fig. 1.7). It is built from tooth contact analysis only; :func:`pipelines.models.stress.run.run_stress`
meshes and solves it.

Contact at an angle: :func:`tca.pair.te.mesh_contact` (the one home of a pair's TE and contact at
any angle, with the ties of conjugate flanks resolved; re-exported here).

Models.

* ``pair``: driver (gear 1) fixed on its rim, driven gear rigid on its rim with only the rotation
  about its axis free and the torque :math:`-T` (against its sense of rotation, so that the loaded
  flanks close); the driver's reaction torque must be :math:`T N_1/N_2`.
* ``twin`` (Part 1, Numerical Example 1.3, Figs. 1.7–1.9): shaft 1 of the planetary train with the
  carrier at rest. Each member *k* = a, b is a single subgear drive (:func:`tca.planetary.subgear.subgear_pairs`,
  pair frames 1 and 2 mapped to :math:`S_f` by :math:`x_f = A_1^T(x + z_k e_z)` and
  :math:`x_f = A_2^T x + c_k`): sun member at :math:`\phi_1`; planet members either each at its own
  :math:`\phi_{2k}` from its sun mesh (``phase = 'assembled'``: members turned on the shaft in
  assembly, section 1.3 (2a), both touch the sun — Step 3 of section 1.4) or both at
  :math:`\max_k\phi_{2k}` (``'nominal'``: a one-piece planet as manufactured, the member that is
  behind keeps a backlash at the sun); ring at the angle of the member that leads,
  :math:`\max_k \Delta\phi_{3k}` (Eq. 1.15): the other member has a backlash at the ring. Bodies: the sun
  (members a, b, rims fixed), the twin planet (four parts — a and b, each on the sun side and on the
  ring side — tied to one reference node on the shaft axis, only the rotation free) and the ring
  (members a, b, rigid, rotation free, torque :math:`-T` about its axis). The sun's reaction torque
  must be :math:`T N_1/N_3`.

Element sizes (:func:`contact_sizes`). From the relative curvature of the two surfaces at the
contact point (:func:`tca.contact.ellipse.contact_ellipse`, :math:`K_2-K_1` with eigenvalues
:math:`\lambda_1 \le \lambda_2`, so :math:`A=\lambda_1/2`, :math:`B=\lambda_2/2`) and the normal load
:math:`P = T_{driven}/|((x-o_2)\times n)\cdot a_2|` (the whole torque on one contact), Hertz's
elliptical contact (Johnson, Contact Mechanics, eqs. 4.39–4.40; :math:`1/E^* = 2(1-\nu^2)/E`)

.. math::
    \frac{B}{A} = \frac{(a/b)^2 E(e) - K(e)}{K(e) - E(e)},\qquad
    a^3 = \frac{3P\,(K(e)-E(e))}{2\pi A E^* e^2},\qquad b = a\sqrt{1-e^2},\qquad p_0=\frac{3P}{2\pi ab},

(line contact — aligned involute gears, or an ellipse longer than the contact line
:math:`L = B/\cos\beta_b`, :func:`contact_length`: :math:`w = P/L`,
:math:`b=\sqrt{4wR/(\pi E^*)} = \sqrt{8wR/(\pi E')}`, :math:`R=1/\lambda_2`, :math:`p_0 = 2w/(\pi b)`,
:math:`a = L/2`, the major axis at the base helix angle :math:`\beta_b` from the axis, profile size
:math:`b/4`) sizes the loaded flanks: profile size :math:`b/3`, axial size
:math:`\min(a/6,\ b/(3|\sin\theta|))` (θ the major axis from the gear axis), kept over a zone of
half-lengths 1.2 × the ellipse's extent before growing (:class:`mesher.Focus` extents); all sizes
are divided by ``refine``. Edge and corner contacts (bounded surfaces) keep the profile size and
refine the axial levels toward the edge (size 2 × profile size, no zone), except, in the pair
model, a line contact inclined across the flank (a helical pair): under load it touches along the
whole line whatever the unloaded contact, so it keeps the line's sizes and its zone covers the whole
line, 2a, from the edge point (:func:`pipelines.models.stress.sizing.contact_sizes`). The twin model keeps
the edge rule there: with line zones its conventional design (edge contacts at the face ends) grows
from 79k to 458k DOF at refine 0.3, one tooth, and the torque balance its tests pin moves from
3.8e-4 to 9.7e-4 (nominal) and 4.7e-4 to 1.06e-3 (kinematic): a change to review with that model.

Sizing by the loaded estimate (``[mesh] sizing = "loaded"``, the default; issue 26). The sizes above put the
whole load on the unloaded TCA's contact point and mesh every neighbouring pair within reach like it. With the
estimator (:mod:`pipelines.models.stress.loaded`: the loaded TCA of each mesh at the scene's position on a coarse
flank grid, the twin's planet torque split between its members through the rigid planet) each mesh instead gets a
zone per pair of teeth that carries at least ``ZONE_SHARE`` (0.1) of its force
(:func:`pipelines.models.stress.zones.pair_zone`: extents covering the pair's loaded slices, each slice's Hertz
half-width :math:`b_i = p_i/\kappa_i` across the line); the part's profile and axial sizes are those of the most
loaded pair, :math:`b/3` (:math:`b/4` for a line contact) and :math:`\min(a/6,\ b/(3|\sin\theta|))` with
:math:`b` its half-width at its largest pressure and :math:`a` its loaded line's half-length, :math:`a/4` instead
of :math:`a/6` along a line contact whose line load is uniform (:func:`pipelines.models.stress.sizing.zone_sizes`,
(G7)). A pair below the share, or a mesh the estimate leaves
unloaded (a twin member with backlash), gets the neighbour mesh; where no pair but the zoned ones is within the
estimate's reach (``EstimateGrid.reach``, 50 µm of separation), by the estimate and by the unloaded TCA, the other
teeth's flanks are left coarse; the run flags a pair without a zone that the FE
loads beyond the share (:func:`pipelines.models.stress.run.unzoned_loads`) and, with ``[mesh] remesh = true``,
remeshes once with a zone there. Where the estimate fails the scene falls back to the sizes above and says so
(``position.loaded_estimate``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np

from mesher import Focus, ReferencePoint
from mesher.body import model_teeth
from mesher.placement import IDENTITY, Pose, gear_pose, loaded_tooth
from fem.material import Material
from tca.errors import GearfeError, InputError
from tca.geometry.gear import Gear
from tca.pair.gear_pair import GearPair
from tca.pair.analysis import ContactKind, PairTCAResult
from tca.planetary.train import DoubleHelicalTrain, ShaftErrors
from tca.pair.te import MeshContact, MeshTE, mesh_contact
from tca.contact.systems import PlacedFlank, foot_points
from tca.planetary.subgear import member_pose, subgear_pairs
from tca.numerics.transforms import rot_x, rot_z
from tca.units import ARCSEC

from pipelines.models.stress.loaded import EstimateGrid, Estimator, MeshLoad
from pipelines.models.stress.sizing import (ContactSizes, HertzContact, SizeRules, contact_sizes, hertz_contact, unloaded_sizes,
                                            zone_sizes)
from pipelines.models.stress.zones import ZONE_SHARE, Zone, pair_zone

__all__ = ["MeshContact", "mesh_contact", "contact_length", "Part", "Interface", "RigidBody", "Reaction",
           "Scene", "Placing", "TwinSetting", "pair_scene", "twin_scene", "PHASES", "mesh_interface"]

_SIDE = {1: "pos", -1: "neg"}


# ---------------------------------------------------------------------------------------------- scene
@dataclass(frozen=True, eq=False)
class Part:
    """A gear member's teeth around its loaded tooth, placed in S_f by x_f = R x + t (gear frame x)."""

    body: str
    label: str  # part label within its body ("" for a one-part body)
    gear: Gear
    centre: int  # loaded tooth (the gear's own index)
    focus: Focus
    sizes: ContactSizes
    R: np.ndarray
    t: np.ndarray
    others: tuple = ()  # (tooth, Focus) of neighbouring pairs within reach, meshed like the loaded tooth

    def set(self, name: str) -> str:
        """Full name of one of the part's sets, e.g. 'tooth3/flank_pos'."""
        return f"{self.body}/{self.label}/{name}" if self.label else f"{self.body}/{name}"

    @property
    def teeth(self) -> list[int]:
        return model_teeth(self.gear, self.sizes.teeth, self.centre)


@dataclass(frozen=True, eq=False)
class Interface:
    """A meshing pair of members: driver flank side1 of `driver` against side2 of `driven`."""

    name: str  # e.g. 'sun-planet'
    member: str  # 'a', 'b'
    driver: Part
    driven: Part
    side1: int
    side2: int
    contact: MeshContact
    point: np.ndarray  # TCA contact point in S_f [mm]
    normal: np.ndarray  # unit normal out of the driver's tooth in S_f
    hertz: HertzContact
    slave: str  # 'driver' or 'driven'
    load: MeshLoad | None = None  # the loaded estimate of this mesh (None: sized by the unloaded TCA)
    zones: tuple = ()  # Zone of every loaded pair of teeth (loaded estimate)

    def tooth_pairs(self) -> list[tuple[int, int, int]]:
        """(offset q, driver tooth, driven tooth): equal offsets from the loaded pair meet."""
        t1, t2 = self.driver.teeth, self.driven.teeth
        c1, c2 = t1.index(self.driver.centre), t2.index(self.driven.centre)
        return [(q - c1, t1[q], t2[q - c1 + c2]) for q in range(len(t1)) if 0 <= q - c1 + c2 < len(t2)]


class RigidBody(NamedTuple):
    """A body held rigid on its rim by a reference node on its axis, the rotation about it free (and, for a floating
    train sun, its translations ``ux``, ``uy``)."""

    ref: ReferencePoint
    torque: float  # applied about the reference axis [N mm]
    free: tuple = ("rz",)  # the free DOFs of the reference node (fem.Rigid)


class Reaction(NamedTuple):
    """The support whose reaction torque checks the equilibrium of a scene."""

    body: str  # the body held on its rims
    point: tuple  # a point of its axis [mm]
    axis: tuple  # unit axis
    expected: float  # expected support torque about the axis [N mm]


@dataclass(frozen=True, eq=False)
class Scene:
    """Everything needed to mesh and solve one position (see module docstring)."""

    model: str
    parts: tuple
    interfaces: tuple
    fixed: str  # body held on its rims
    rigid: dict  # body -> RigidBody
    reaction: Reaction
    ratio: float  # expected reaction torque / applied torque
    info: dict = field(default_factory=dict)  # position, TE, regulation (JSON-ready)


def _load(pair: GearPair, c: MeshContact, torque: float) -> float:
    """Normal load [N] transmitting `torque` [N mm] to the driven gear through the contact point."""
    _, m2 = pair.mounts()
    arm = abs(float(np.cross(c.point - m2.origin, c.normal) @ m2.axis))
    return abs(torque) / arm


@dataclass(frozen=True, eq=False)
class Placing:
    """Where a meshing pair goes in a scene: interface name and member, the bodies and part labels of driver
    and driven, which side is the slave, and the frame of the pair in S_f."""

    name: str  # e.g. 'sun-planet'
    member: str  # 'a', 'b'
    bodies: tuple  # (driver body, driven body)
    labels: tuple = ("", "")  # part labels within the bodies ('' for a one-part body)
    slave: str = "driven"
    frame: Pose = IDENTITY
    inclined_lines: bool = False  # size a helical line contact as a line whatever its TCA kind (sizing.contact_sizes)


def mesh_interface(at: Placing, pair: GearPair, c: MeshContact, torque: float, rules: SizeRules, mat: Material,
               load: MeshLoad | None = None, forced: tuple = ()) -> Interface:
    """Driver and driven parts of one mesh at its contact (placed by mesher.placement), sized by the loaded estimate
    ``load`` of the mesh (:func:`_loaded_parts`) or, without it, by Hertz's contact of the whole load at the TCA point."""
    hz = hertz_contact(c.curvature, _load(pair, c, torque), mat, contact_length(pair))
    g1, g2 = pair.gear1, pair.gear2
    m1, m2 = pair.mounts()
    u1, v1, u2, v2 = c.params
    zones = ()
    if load is None:
        s1 = contact_sizes(rules, g1, hz, c.angle, c.kind, at.inclined_lines)
        s2 = contact_sizes(rules, g2, hz, c.angle, c.kind, at.inclined_lines)
        # both flanks get the finer of the two size sets (master and slave equally fine at the contact)
        fine = {k: min(getattr(s1, k), getattr(s2, k)) for k in ("contact", "axial")}
        s1, s2 = replace(s1, **fine), replace(s2, **fine)
        foci = [Focus(pair.side1, u1, v1, s1.extent_u, s1.extent_z), Focus(pair.side2, u2, v2, s2.extent_u, s2.extent_z)]
        others = [(), ()]
    else:
        (s1, s2), foci, others, zones = _loaded_parts(pair, c, rules, load, hz.line, forced)
    parts = []
    for i, (g, mount, phi, sz) in enumerate(((g1, m1, c.phi1, s1), (g2, m2, c.phi2, s2))):
        pose = gear_pose(mount, phi, at.frame)
        parts.append(Part(at.bodies[i], at.labels[i], g, loaded_tooth(g, c.k), foci[i], replace(sz, teeth=rules.teeth),
                          pose.R, pose.t, others[i]))
    point = at.frame.R @ c.point + at.frame.t
    normal = at.frame.R @ c.normal
    return Interface(at.name, at.member, parts[0], parts[1], pair.side1, pair.side2, c, point, normal, hz, at.slave,
                     load, zones)


def _loaded_parts(pair: GearPair, c: MeshContact, rules: SizeRules, load: MeshLoad, line: bool, forced: tuple = ()):
    """Sizes, main foci, further foci and zones of both gears of a mesh from its loaded estimate.

    ``forced``: teeth (j1, j2) of pairs the estimate left unloaded and the FE loaded (a remesh,
    :func:`pipelines.models.stress.run.run_stress`): each gets a zone like the most loaded pair's, at its own place.

    Every pair of teeth carrying at least ``ZONE_SHARE`` of the mesh's force gets a zone
    (:func:`pipelines.models.stress.zones.pair_zone`): the pair in contact around its TCA point, another around the
    point of :func:`neighbour_params`; a more lightly loaded pair gets the neighbour mesh. The gears' sizes come from
    the most loaded pair (:func:`pipelines.models.stress.sizing.zone_sizes`: its half-width and line), the other zones
    are meshed alike over their own extents. A mesh the estimate leaves unloaded keeps its focus
    at the TCA point with the neighbour mesh (:func:`pipelines.models.stress.sizing.unloaded_sizes`).
    """
    g1, g2 = pair.gear1, pair.gear2
    main_teeth = (loaded_tooth(g1, c.k), loaded_tooth(g2, c.k))
    by_branch = {o.k: o for o in c.others}
    zones = []
    for pl in load.pairs:
        if pl.share < ZONE_SHARE:  # lightly loaded: the neighbour mesh (the FE's share is checked, run._warnings)
            continue
        if pl.teeth == main_teeth:
            centre, angle = c.params, c.angle
        else:
            o = by_branch.get(pl.branch)
            centre = neighbour_params(pair, c, o, math.inf) if o is not None else None
            if centre is None:
                centre = _slice_centre(pair, pl)
            angle = c.angle
        zones.append(pair_zone(pair, pl, centre, rules.zone, angle))
    if zones:
        ref = max(zones, key=lambda z: z.share)
        for teeth in forced:
            if tuple(teeth) == main_teeth:  # the pair in contact: at its TCA point
                centre = c.params
            else:
                o = next((o for o in c.others if ((-o.k) % g1.teeth, (-o.k) % g2.teeth) == tuple(teeth)), None)
                centre = neighbour_params(pair, c, o, math.inf) if o is not None else None
            if centre is not None and all(z.teeth != tuple(teeth) for z in zones):
                zones.append(replace(ref, teeth=tuple(teeth), centre=tuple(centre), share=0.0))
    u1, v1, u2, v2 = c.params
    if not zones:
        sizes = (unloaded_sizes(rules, g1), unloaded_sizes(rules, g2))
        return sizes, [Focus(pair.side1, u1, v1), Focus(pair.side2, u2, v2)], [(), ()], ()
    top = max(zones, key=lambda z: z.share)
    shape = ((top.b, top.a, top.s, top.uniform),)  # the most loaded pair's sizes; the other zones are meshed alike
    main = next((z for z in zones if z.teeth == main_teeth), None)
    sizes, foci, others = [], [], []
    for i, (g, side, (u, v)) in enumerate(((g1, pair.side1, (u1, v1)), (g2, pair.side2, (u2, v2)))):
        eu, ez = main.extents[i] if main is not None else (0.0, 0.0)
        sizes.append(zone_sizes(rules, g, line, shape, eu, ez))
        foci.append(Focus(side, u, v, eu, ez))
        others.append(tuple((z.teeth[i], Focus(side, z.centre[2 * i], z.centre[2 * i + 1], *z.extents[i]))
                            for z in zones if z.teeth != main_teeth))
    fine = {k: min(getattr(sizes[0], k), getattr(sizes[1], k)) for k in ("contact", "axial")}
    sizes = [replace(sz, **fine) for sz in sizes]
    zoned = {z.teeth for z in zones}
    if set(load.in_reach) <= zoned and c.next_gap > EstimateGrid.reach and all(
            o.gap > EstimateGrid.reach or o.kind == ContactKind.NONE for o in c.others
            if ((-o.k) % g1.teeth, (-o.k) % g2.teeth) not in zoned):
        # no other pair within the estimate's reach (50 um, several elastic approaches), by the estimate or by the
        # unloaded TCA (kind NONE: a tangency of the extended surfaces, whose gap is only a lower bound, is left to
        # the estimate's working areas): the other teeth's flanks cannot close under load, no neighbour mesh (issue 26)
        sizes = [replace(sz, neighbour=sz.coarse) for sz in sizes]
    return tuple(sizes), foci, others, tuple(zones)


def _slice_centre(pair: GearPair, pl) -> tuple:
    """(u1, v1, u2, v2) [mm] of the loaded slice nearest the force-weighted centre of a pair's slices."""
    m1, m2 = pair.mounts()
    x = pl.points[int(np.argmin(np.linalg.norm(pl.points - pl.points.mean(0), axis=1)))][None, :]
    out = []
    for i, f in enumerate((PlacedFlank(pair.gear1, pair.side1, m1), PlacedFlank(pair.gear2, pair.side2, m2))):
        area = f.gear.area(f.side)
        _, _, uv = foot_points(f, (0.5 * (area.u_form + area.u_tip), 0.0), pl.phi[i], x)
        out += [float(uv[0, 0]), float(uv[0, 1])]
    return tuple(out)


def contact_length(pair: GearPair) -> float:
    """Length [mm] of one contact line across the common face width: B / cos β_b (β_b the base helix angle)."""
    g = pair.gear1
    beta_b = math.atan(math.tan(g.helix) * g.r_b / g.r_p)
    return min(pair.gear1.face_width, pair.gear2.face_width) / math.cos(beta_b)


def _kind_name(k: int) -> str:
    return ContactKind.names.get(int(k), str(k))


def _clamp(area, uv) -> np.ndarray:
    """(u, v) [mm] moved onto a working area (profile parameter between form circle and tip, v on the face)."""
    return np.array([min(max(uv[0], area.u_form), area.u_tip), min(max(uv[1], area.z_min), area.z_max)])


def neighbour_params(pair: GearPair, c: MeshContact, o, extent: float) -> tuple | None:
    """(u1, v1, u2, v2) [mm] of the refined zones of a neighbouring pair of teeth (a
    :class:`tca.pair.te.NeighbourContact`), at one place in space on both flanks; None where no such
    place exists (the two points, each on its working area, further apart than ``extent`` [mm], the
    zone's half-length along the profile: e.g. a ring's tip edge whose foot on the pinion lies below
    the pinion's form circle — that pair touches, if at all, in the fillet, which is not refined).

    A contact of the TCA (surface, edge, corner) is used as it is. Where the extended surfaces touch
    outside a working area (beyond a tip, below a form circle, off the face) the pair can touch only
    along a boundary: the point is moved onto the working area of the gear whose tip it passes (else
    of the one it lies further outside), and the other gear's zone is centred on the foot of that
    point on its flank (:func:`tca.contact.systems.foot_points`), at the angles where the loaded pair touches.
    Conjugate flanks make every such pair "touch" with gap 0; the zones then still sit where the
    pair's boundary meets the other flank, so master and slave are refined at the same place.
    """
    if o.kind in (ContactKind.SURFACE, ContactKind.EDGE, ContactKind.CORNER):
        return tuple(o.params)
    g1, g2 = pair.gear1, pair.gear2
    m1, m2 = pair.mounts()
    phr = c.phi1 - o.k * 2 * math.pi / g1.teeth
    ph = (phr, pair.ratio * phr + c.te)
    fl = (PlacedFlank(g1, pair.side1, m1), PlacedFlank(g2, pair.side2, m2))
    uv = (np.array(o.params[:2], float), np.array(o.params[2:], float))
    cons = [fl[i].constraints(fl[i].surface.evaluate(uv[i][:1], uv[i][1:]), uv[i][:1])[0] for i in (0, 1)]
    tip = [cons[i][1] > 0 for i in (0, 1)]
    a = 0 if tip[0] and not tip[1] else 1 if tip[1] and not tip[0] else int(np.argmax([max(cons[0]), max(cons[1])]))
    b = 1 - a
    areas = (g1.area(pair.side1), g2.area(pair.side2))
    out = [None, None]
    out[a] = _clamp(areas[a], uv[a])
    x, _, _ = fl[a].world(out[a][:1], out[a][1:], np.array([ph[a]]))
    _, ok, uvf = foot_points(fl[b], uv[b], ph[b], x.r)
    out[b] = _clamp(areas[b], uvf[0] if ok[0] else uv[b])
    y, _, _ = fl[b].world(out[b][:1], out[b][1:], np.array([ph[b]]))
    if not np.linalg.norm(y.r[0] - x.r[0]) <= extent:
        return None
    return (float(out[0][0]), float(out[0][1]), float(out[1][0]), float(out[1][1]))


def pair_scene(pair: GearPair, result: PairTCAResult, phi1: float, torque: float, rules: SizeRules,
               mat: Material, estimator: Estimator | None = None) -> Scene:
    """Driver fixed, driven gear rigid (rotation free, torque -T about its axis) at driver angle phi1 [rad].

    With an ``estimator`` (``[mesh] sizing = "loaded"``) the zones come from the loaded estimate of the mesh
    (:mod:`pipelines.models.stress.loaded`); without it, or where the estimate fails (said in ``info``), from the
    unloaded TCA: the whole load at the TCA point, and every pair within ``rules.reach`` meshed like it."""
    c = mesh_contact(result, phi1)
    g1, g2 = pair.gear1, pair.gear2
    at = Placing(f"{g1.name}-{g2.name}", "a", (g1.name, g2.name), inclined_lines=True)
    load, failed = None, None
    if estimator is not None:
        try:
            lines = estimator.lines(pair, MeshTE.from_result(result), phi1, c.params)
            load = estimator.load(pair, lines, torque)
        except GearfeError as exc:  # the unloaded TCA's sizes, and the summary says why
            failed = str(exc)
    itf = mesh_interface(at, pair, c, torque, rules, mat, load, estimator.forced.get((at.name, at.member), ()) if estimator else ())
    reach = rules.reach(_load(pair, c, torque), min(g1.face_width, g2.face_width))
    near = []
    if load is None:
        modelled = set(itf.driver.teeth), set(itf.driven.teeth)
        near = [o for o in c.others if o.gap <= reach and (-o.k) % g1.teeth in modelled[0]
                and (-o.k) % g2.teeth in modelled[1]] if reach > 0 else []
    if near:  # neighbouring pairs that may close under load: refined around their own contact points
        fd, fn = itf.driver.focus, itf.driven.focus
        pars = [neighbour_params(pair, c, o, max(fd.extent_u, fn.extent_u)) for o in near]
        near, pars = [o for o, q in zip(near, pars) if q is not None], [q for q in pars if q is not None]
        d = replace(itf.driver, others=tuple(((-o.k) % g1.teeth, replace(fd, u=q[0], z=q[1])) for o, q in zip(near, pars)))
        n = replace(itf.driven, others=tuple(((-o.k) % g2.teeth, replace(fn, u=q[2], z=q[3])) for o, q in zip(near, pars)))
        itf = replace(itf, driver=d, driven=n)
    m1, m2 = pair.mounts()
    ratio = g1.teeth / g2.teeth
    gaps = {((-o.k) % g1.teeth, (-o.k) % g2.teeth): o for o in c.others}
    refined = ([{"pair": [(-o.k) % g1.teeth, (-o.k) % g2.teeth], "gap_um": o.gap * 1e3, "kind": _kind_name(o.kind)} for o in near]
               if load is None else
               [{"pair": list(z.teeth), "gap_um": gaps[z.teeth].gap * 1e3 if z.teeth in gaps else None,
                 "kind": _kind_name(gaps[z.teeth].kind) if z.teeth in gaps else None, "share": z.share}
                for z in itf.zones if z.teeth != (itf.driver.centre, itf.driven.centre)])
    info = {"phi1_deg": math.degrees(phi1), "phi2_deg": math.degrees(c.phi2), "te_arcsec": c.te / ARCSEC,
            "active_pair": c.k, "kind": _kind_name(c.kind), "on_tca_grid": c.exact,
            "instantaneous_ratio": c.ratio, "te_slope": c.slope, "next_pair_gap_um": c.next_gap * 1e3,
            "loaded_teeth": {g1.name: itf.driver.centre, g2.name: itf.driven.centre},
            "neighbour_reach_um": reach * 1e3, "refined_neighbours": refined,
            "loaded_estimate": _estimate_record(estimator, (itf,), failed)}
    return Scene("pair", (itf.driver, itf.driven), (itf,), g1.name,
                 {g2.name: RigidBody(ReferencePoint(tuple(m2.origin), tuple(m2.axis)), -abs(torque))},
                 Reaction(g1.name, tuple(m1.origin), tuple(m1.axis), abs(torque) * ratio), ratio, info)


def _twin_loads(estimator: Estimator, train: DoubleHelicalTrain, subs: dict, pairs: dict, per: dict, at: tuple,
                own12: dict) -> dict:
    """(interface, member) -> MeshLoad of the four meshes of a twin drive (module docstring of
    :mod:`pipelines.models.stress.loaded`). ``at``: sun angle in the pair frame, the ring's angle (of the leading
    member), the planet torque and the ring torque [N mm]; ``own12``: each member's sun contact at its own planet angle."""
    ph1, phi3_lead, T_planet, T_ring = at
    N2 = train.planet.teeth
    mirror = {"a": (None, None, None), "b": train.gears("a")}
    L12, L23, g12, g23 = {}, {}, {}, {}
    for k in ("a", "b"):
        p1, p2 = pairs[k]
        c12, c23, _ = per[k]
        sun, planet, ring = mirror[k]
        L12[k] = estimator.lines(p1, subs[k].mesh12, ph1, c12.params, (sun, planet))
        L23[k] = estimator.lines(p2, subs[k].mesh23, c12.phi2 + math.pi + math.pi / N2, c23.params, (planet, ring))
        g12[k] = max(c12.phi2 - own12[k].phi2, 0.0)  # planet angle to turn back before member k touches the sun
        g23[k] = max(phi3_lead - c23.phi2, 0.0)  # ring angle to turn back before member k touches the ring
    t12 = estimator.split((L12["a"], L12["b"]), (g12["a"], g12["b"]), T_planet)
    t23 = estimator.split((L23["a"], L23["b"]), (g23["a"], g23["b"]), T_ring)
    out = {}
    for i, k in enumerate(("a", "b")):
        p1, p2 = pairs[k]
        out[("sun-planet", k)] = estimator.load(p1, L12[k], t12[i], g12[k])
        out[("planet-ring", k)] = estimator.load(p2, L23[k], t23[i], g23[k])
    return out


def _estimate_record(estimator: Estimator | None, itfs: tuple, failed: str | None) -> dict:
    """The summary's record of the loaded estimate: mode, grid and costs, per mesh its loads and zones."""
    if estimator is None:
        return {"sizing": "tca"}
    rec = {"sizing": "loaded" if failed is None else "tca", **estimator.record()}
    if failed is not None:
        rec["failed"] = failed
        return rec
    rec["meshes"] = {f"{i.name}/{i.member}": {**i.load.as_json(),
                                               "zones": [{"pair": list(z.teeth), "share": z.share, "half_width_mm": z.b,
                                                          "line_half_length_mm": z.a,
                                                          "extents_mm": [list(e) for e in z.extents]} for z in i.zones],
                                               "forced": [list(t) for t in estimator.forced.get((i.name, i.member), ())]}
                     for i in itfs}
    return rec


PHASES = ("assembled", "nominal")


@dataclass(frozen=True)
class TwinSetting:
    """The state of shaft 1 of a twin drive: its errors of installment, the axial regulation dz [mm] of
    members a and b, and the members' phase (:func:`twin_scene`)."""

    errors: ShaftErrors = field(default_factory=ShaftErrors)
    dz: tuple = (0.0, 0.0)
    phase: str = "assembled"


def twin_scene(train: DoubleHelicalTrain, subs: dict, setting: TwinSetting, phi1: float, torque: float,
               rules: SizeRules, mat: Material, estimator: Estimator | None = None) -> Scene:
    """Twin subgear drive of shaft 1 at sun angle phi1 [rad]: sun fixed, twin planet and ring rigid (module docstring).

    With an ``estimator`` the four meshes are sized by their loaded estimates, the planet torque split between the
    members through the rigid planet (:mod:`pipelines.models.stress.loaded`); without it, or where the estimate
    fails, every mesh is sized for the whole torque of its interface at its TCA point.

    ``subs``: member -> :class:`tca.planetary.subgear.SubgearTE` of shaft 1 (its meshes are used).
    ``setting.phase``: 'assembled' — each member turned on the shaft so that it touches the sun at phi1
    (members regulated in assembly, section 1.3 (2a); the four-point assumption of Step 3);
    'nominal' — the members at one angle as manufactured (a one-piece conventional planet): the
    member whose sun mesh leads turns the planet, the other keeps a backlash at the sun too.
    """
    errors, dz, phase = setting.errors, setting.dz, setting.phase
    if phase not in PHASES:
        raise InputError("regulation.member_phase", phase, "one of " + ", ".join(repr(p) for p in PHASES))
    i = 0
    th = train.carrier_angle(i)
    N1, N2, N3 = train.sun.teeth, train.planet.teeth, train.ring.teeth
    E_c = train.center_distance
    A1 = rot_z(-th)
    A2 = rot_x(math.pi) @ rot_z(-th)
    zm = train.member_offset
    ph1 = phi1 - th
    pairs, c12s = {}, {}
    for k in ("a", "b"):
        pairs[k] = subgear_pairs(train, i, k, errors, dz[0 if k == "a" else 1])
        c12s[k] = mesh_contact(subs[k].mesh12.result, ph1)
    if phase == "nominal":  # one planet angle: the sun pushes the member that is ahead
        phi2 = max(c.phi2 for c in c12s.values())
        c12s = {k: replace(c, phi2=phi2) for k, c in c12s.items()}
    per = {}
    for k in ("a", "b"):
        c12 = c12s[k]
        ph2p = c12.phi2 + math.pi + math.pi / N2
        c23 = mesh_contact(subs[k].mesh23.result, ph2p)
        # ring TE through this member (tca.planetary.subgear.compose_te), shaft 1
        te3 = c23.phi2 - th + math.pi / N3 - (N1 / N3) * phi1 - math.pi * (N2 + 2) / N3
        te3 = (te3 + math.pi / N3) % (2 * math.pi / N3) - math.pi / N3
        per[k] = (c12, c23, te3)
    lead = max(per, key=lambda k: per[k][2])
    phi3_lead = per[lead][1].phi2
    parts, itfs = [], []
    T_planet = abs(torque) * N2 / N3  # torque through the sun mesh if one member carried all
    loads, failed = {}, None
    if estimator is not None:
        try:
            loads = _twin_loads(estimator, train, subs, pairs, per, (ph1, phi3_lead, T_planet, abs(torque)),
                                {k: mesh_contact(subs[k].mesh12.result, ph1) for k in ("a", "b")})
        except GearfeError as exc:
            loads, failed = {}, str(exc)
    members = {}
    r2, r3 = train.planet.r_p, train.ring.r_p
    for k in ("a", "b"):
        p1, p2 = pairs[k]
        c12, c23, te3 = per[k]
        own12 = mesh_contact(subs[k].mesh12.result, ph1)
        zk = train.member_sign(k) * zm
        F1 = Pose(A1.T, A1.T @ np.array([0.0, 0.0, zk]))
        c_nom = np.array([E_c * math.cos(th), E_c * math.sin(th), zk])
        F2 = Pose(A2.T, c_nom)
        forced = estimator.forced if estimator is not None else {}
        s_itf = mesh_interface(Placing("sun-planet", k, ("sun", "planet"), (k, f"{k}_sun"), "driven", F1), p1, c12, T_planet,
                           rules, mat, loads.get(("sun-planet", k)), forced.get(("sun-planet", k), ()))
        # the ring turns with the member that leads: the other member keeps its backlash at the ring
        r_itf = mesh_interface(Placing("planet-ring", k, ("planet", "ring"), (f"{k}_ring", k), "driver", F2), p2,
                           replace(c23, phi2=phi3_lead), abs(torque), rules, mat, loads.get(("planet-ring", k)),
                           forced.get(("planet-ring", k), ()))
        itfs += [s_itf, r_itf]
        parts += [s_itf.driver, s_itf.driven, r_itf.driver, r_itf.driven]
        members[k] = {"te3_arcsec": te3 / ARCSEC, "te12_arcsec": own12.te / ARCSEC, "te23_arcsec": c23.te / ARCSEC,
                      "sun_backlash_um": (c12.phi2 - own12.phi2) * r2 * 1e3,
                      "ring_backlash_um": (phi3_lead - c23.phi2) * r3 * 1e3,
                      "dz_mm": dz[0 if k == "a" else 1], "phi2_deg": math.degrees(c12.phi2),
                      "sun_mesh": {"kind": _kind_name(own12.kind), "active_pair": own12.k, "on_tca_grid": own12.exact,
                                   "instantaneous_ratio": own12.ratio, "te_slope": own12.slope,
                                   "next_pair_gap_um": own12.next_gap * 1e3},
                      "ring_mesh": {"kind": _kind_name(c23.kind), "active_pair": c23.k, "on_tca_grid": c23.exact,
                                    "instantaneous_ratio": c23.ratio, "te_slope": c23.slope,
                                    "next_pair_gap_um": c23.next_gap * 1e3},
                      "loaded_teeth": {"sun": s_itf.driver.centre, "planet_sun_side": s_itf.driven.centre,
                                       "planet_ring_side": r_itf.driver.centre, "ring": r_itf.driven.centre}}
    # the twin planet: reference node on the shaft axis, midway between the members' nominal planes
    oa, _ = member_pose(train, i, "a", errors, 0.0)
    ob, R0 = member_pose(train, i, "b", errors, 0.0)
    planet_ref = ReferencePoint(tuple(0.5 * (oa + ob)), tuple(R0[:, 2]))
    ring_ref = ReferencePoint((0.0, 0.0, 0.0), (0.0, 0.0, -1.0))  # the ring turns positively about -z_f
    ratio = N1 / N3
    info = {"phi1_deg": math.degrees(phi1), "te3_arcsec": per[lead][2] / ARCSEC, "leading_member": lead, "member_phase": phase,
            "ring_angle_deg": math.degrees(phi3_lead), "members": members, "shaft": i + 1,
            "d_ex_um": errors.d_ex * 1e3, "d_gamma_arcmin": math.degrees(errors.d_gamma) * 60,
            "loaded_estimate": _estimate_record(estimator, tuple(itfs), failed)}
    return Scene("twin", tuple(parts), tuple(itfs), "sun",
                 {"planet": RigidBody(planet_ref, 0.0), "ring": RigidBody(ring_ref, -abs(torque))},
                 Reaction("sun", (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), abs(torque) * ratio), ratio, info)
