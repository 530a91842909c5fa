r"""Reader of a stress load case (``kind = "stress"``, or a pair file ``kind = "pair"``): every key checked, into
the record :class:`pipelines.models.stress.case.StressCase` (case-file keys in :mod:`pipelines.models.stress.run`).

One file per pair: a ``kind = "pair"`` file is read here as a stress case of ``model = "pair"`` (``model`` is
optional there), and ``gearfe tca`` reads a ``kind = "stress"`` pair file for its TCA (the load, position,
mesh and FE keys are checked and left unused). The load names its gear, exactly one of:

- ``driven_torque_nm`` (or ``torque_nm``, the same: the driven gear's, or the ring's in a twin case),
- ``driver_torque_nm`` (pair model): converted with the tooth ratio,
  :math:`T_	ext{driven} = T_	ext{driver}\,z_	ext{driven}/z_	ext{driver}` (S1, no losses).

Before any sizing or meshing the nominal unit load of the pair, :math:`w = F_t/(b\,m_n)` with
:math:`F_t = T_	ext{driven}/r_	ext{driven}` at the driven gear's pitch radius and :math:`b` the narrower face
(S2), must stay below :data:`UNIT_LOAD_MAX_MPA` (the nominal tooth-root stress :math:`\sigma_{F0}` is about
4-5 times w: 1500 MPa is some 7000 MPa in the root, beyond any steel); a torque above it is named, with the
value in N m it would have been if it was typed in N mm.
"""

from __future__ import annotations

import math

from fem.material import Material
from tca.errors import InputError
from tca.pair.checks import check_pair
from tca.pair.te import POSITIONS
from tca.planetary.train import ShaftErrors

from pipelines.cases.ltca_options import read_ltca_options
from pipelines.cases.reader import ARCMIN, read_gears, read_pair, read_tca_options
from pipelines.cases.schema import Table
from pipelines.cases.planetary import read_regulation_options, read_train
from pipelines.cases.rating import read_rating, with_rating
from pipelines.models.stress.case import MODELS, StressCase
from pipelines.models.stress.model import FESettings
from pipelines.models.stress.scene import PHASES
from pipelines.models.stress.sizing import GROWTH, SIZING, SizeRules

__all__ = ["read_stress_case", "read_train_stress", "read_unloaded_pair", "read_torque", "torque_record", "check_unit_load", "UNIT_LOAD_MAX_MPA", "TORQUE_KEYS"]

UNIT_LOAD_MAX_MPA = 1500.0  # largest nominal unit load F_t / (b m_n) of a stress case (S2)
TORQUE_KEYS = ("driven_torque_nm", "torque_nm", "driver_torque_nm")
TORQUE_MAX_NM = 1e7


def read_torque(case: Table, required: bool = True) -> tuple[str, float] | None:
    """(key, value [N m]) of the one torque key of a case (``driven_torque_nm``, ``torque_nm`` or
    ``driver_torque_nm``); None when absent and not required. InputError when two are given."""
    given = [k for k in TORQUE_KEYS if case.has(k)]
    if len(given) > 1:
        raise InputError(given[1], case.data[given[1]], f"exactly one of {', '.join(TORQUE_KEYS)} (not both {given[0]} "
                         f"and {given[1]}; torque_nm is the driven gear's)")
    if not given:
        if not required:
            return None
        raise InputError("driven_torque_nm", None, f"a torque in (0, {TORQUE_MAX_NM:g}] N m: one of "
                         f"{', '.join(TORQUE_KEYS)} (torque_nm is the driven gear's)", "missing: this command loads the pair")
    k = given[0]
    return k, case.get(k, float, lo=0.0, lo_open=True, hi=TORQUE_MAX_NM)


def torque_record(case: StressCase) -> dict:
    """The torques of a stress case with the gears they belong to, for every summary: the driven gear's (the ring's
    in a twin case) and, for a pair, the driver's (S1), with the pair checks' findings (``pair_geometry``: the centre
    distance and where it comes from, backlash, clearances, contact ratios, :func:`tca.pair.checks.check_pair`)."""
    if case.model == "train":  # the train LTCA's convention: the torque acts on the sun
        return {"torque_gear": case.train_case.sun.name, "sun_torque_nm": case.torque * 1e-3}
    if case.model != "pair":
        return {"torque_gear": case.train.ring.name, "driven_torque_nm": case.torque * 1e-3}
    g1, g2 = case.pair.gear1, case.pair.gear2
    return {"torque_gear": g2.name, "driven_torque_nm": case.torque * 1e-3,
            "driver_gear": g1.name, "driver_torque_nm": case.torque * 1e-3 * g1.teeth / g2.teeth,
            "pair_geometry": check_pair(case.pair).summary()}  # remembered from the reader's check


def _driven_torque(key: str, value: float, pair) -> float:
    """The driven gear's torque [N mm] from the torque key (S1), its unit load checked (S2)."""
    g1, g2 = pair.gear1, pair.gear2
    T = value * 1e3 * (g2.teeth / g1.teeth if key == "driver_torque_nm" else 1.0)
    check_unit_load(key, value, value, T, pair)
    return T


def check_unit_load(key: str, shown, value: float, T: float, pair) -> None:
    """InputError naming ``key`` (``shown`` as written) when the driven torque T [N mm] (``value`` [N m] as given, on
    the driver for ``driver_torque_nm``) exceeds the unit load (S2)."""
    g1, g2 = pair.gear1, pair.gear2
    r2 = 0.5 * g2.teeth * g2.module / math.cos(g2.beta_ref)
    w = T / r2 / (min(g1.face_width, g2.face_width) * g2.module)
    if w > UNIT_LOAD_MAX_MPA:
        hint = f"{value:g} looks like N mm: {value * 1e-3:g} N m?" if w * 1e-3 <= UNIT_LOAD_MAX_MPA else "no steel carries it"
        raise InputError(key, shown, f"a torque whose nominal unit load F_t/(b m_n) <= {UNIT_LOAD_MAX_MPA:g} MPa: "
                         f"<= {value * UNIT_LOAD_MAX_MPA / w:.4g} N m on {g1.name if key == 'driver_torque_nm' else g2.name}",
                         f"F_t/(b m_n) = {w:.4g} MPa; {hint}")


def _um(v: float | None) -> float | None:
    return None if v is None else v * 1e-3


def _read_mesh(t: Table | None) -> SizeRules:
    if t is None:
        return SizeRules()
    pos = dict(lo=0.0, lo_open=True)
    r = SizeRules(
        refine=t.get("refine", float, 1.0, lo=0.1, hi=10.0),  # default chosen by benchmarks.stress
        teeth=t.get("teeth", int, 3, lo=1, hi=9),
        rim_depth=t.get("rim_depth_mm", float, None, **pos),
        coarse=t.get("coarse_size_mm", float, None, **pos),
        contact=t.get("contact_size_mm", float, None, **pos),
        axial=t.get("axial_contact_size_mm", float, None, **pos),
        fillet=t.get("fillet_size_mm", float, None, **pos),
        neighbour=t.get("neighbour_size_mm", float, None, **pos),
        growth=t.get("growth", float, GROWTH, lo=1.05, hi=3.0),
        zone=t.get("zone", float, 1.2, lo=0.0, hi=5.0),
        neighbour_reach=_um(t.get("neighbour_reach_um", float, None, lo=0.0, hi=1000.0)),
        sizing=t.get("sizing", str, "loaded", choices=SIZING),
        remesh=t.get("remesh", bool, False),
    )
    t.done()
    return r


E_RANGE_MPA = (1e3, 1e6)  # engineering gear materials: polymers (~2e3 MPa) to carbides (~6e5 MPa)


def _youngs(t: Table) -> float:
    """Young's modulus [MPa], refused outside E_RANGE_MPA with a hint at the unit (GPa, Pa)."""
    e = t.get("youngs_modulus_mpa", float, 2.068e5, lo=0.0, lo_open=True)
    lo, hi = E_RANGE_MPA
    if not lo <= e <= hi:
        hint = (f"{e:g} looks like GPa: {e * 1e3:g} MPa?" if 0.1 <= e < lo else
                f"{e:g} looks like Pa: {e * 1e-6:g} MPa?" if 1e8 <= e <= 1e13 else "not a plausible stiffness")
        raise InputError(t._key("youngs_modulus_mpa"), e, f"a Young's modulus in MPa in [{lo:g}, {hi:g}] (steel 2.068e5)",
                         hint)
    return e


def _read_fe(t: Table | None) -> FESettings:
    if t is None:
        return FESettings()
    f = FESettings(
        material=Material(_youngs(t), t.get("poisson_ratio", float, 0.29, lo=-1.0, hi=0.5, lo_open=True, hi_open=True)),
        element=t.get("element", str, "C3D8I", choices=("C3D8I", "C3D8")),
        solver=t.get("solver", str, "auto", choices=("auto", "pardiso", "superlu")),
        penalty_factor=t.get("penalty_factor", float, 100.0, lo=0.0, lo_open=True, hi=1e6),
        max_penetration=t.get("max_penetration_mm", float, 1e-4, lo=0.0, lo_open=True, hi=0.1),
        quadrature=t.get("quadrature", int, 2, choices=(0, 2, 3, 4)),
        penalty_check_tol=t.get("penalty_check_tol", float, 0.01, lo=0.0, hi=1.0, lo_open=True, hi_open=True),
        search_gap=t.get("search_gap_mm", float, 0.03, lo=0.0, lo_open=True, hi=5.0),
        max_search_gap=t.get("max_search_gap_mm", float, 0.5, lo=0.0, lo_open=True, hi=5.0),
    )
    t.done()
    return f


def _read_position(case: Table):
    given = [k for k in ("position", "phi1_deg", "roll_deg") if case.has(k)]
    if len(given) > 1:
        raise InputError(given[1], case.data[given[1]], f"one of position, phi1_deg, roll_deg, not both {given[0]} and {given[1]}")
    phi1 = math.radians(case.get("phi1_deg", float, lo=-3600.0, hi=3600.0)) if case.has("phi1_deg") else None
    roll = math.radians(case.get("roll_deg", float, lo=0.0, hi=180.0)) if case.has("roll_deg") else None
    v = case.data.get("position", "max_te")
    if isinstance(v, int) and not isinstance(v, bool):
        pos = case.get("position", int)
    elif isinstance(v, str):
        pos = case.get("position", str, "max_te", choices=POSITIONS)
    else:
        raise InputError("position", v, ", ".join(repr(p) for p in POSITIONS) + " or an integer index of the TCA positions")
    return pos, phi1, roll


def read_unloaded_pair(case: Table):
    """(pair, TCA options, rating spec or None) of a pair file without a torque (gearfe tca, gearfe rate): its
    position, ``[mesh]`` and ``[fe]`` keys are checked as :func:`read_stress_case` checks them, and not used;
    ``[rating]`` then gives the torque it rates (docs/cases.md)."""
    kind = case.get("kind", str, "stress", choices=("stress", "pair"))
    if kind == "stress" or case.has("model"):
        case.get("model", str, "pair", choices=("pair",))
    case.get("title", str, "")
    _read_position(case)
    tca = read_tca_options(case.table("tca", required=False))
    _read_mesh(case.table("mesh", required=False))
    _read_fe(case.table("fe", required=False))
    pair, _, _ = read_pair(case, read_gears(case))
    spec = read_rating(case.table("rating", required=False), (pair.gear1.name, pair.gear2.name), case_has_torque=False)
    return pair, tca, spec


def read_stress_case(case: Table, ltca: bool = True) -> StressCase:
    """A :class:`StressCase` from a case table (module docstring); every key is checked, unknown keys rejected.
    ``ltca``: an ``[ltca]`` table (one file per pair) is checked too, and left unused (gearfe ltca reads it itself)."""
    kind = case.get("kind", str, "stress", choices=("stress", "pair"))
    # model 'train' is read from an isostatic train case (read_train_stress), the file gearfe ltca takes
    model = (case.get("model", str, "pair", choices=("pair",)) if kind == "pair"
             else case.get("model", str, choices=tuple(m for m in MODELS if m != "train")))
    title = case.get("title", str, "")
    tkey, tval = read_torque(case)
    if model == "twin" and tkey == "driver_torque_nm":
        raise InputError(tkey, tval, "torque_nm or driven_torque_nm in a twin case (the ring's torque)")
    torque = tval * 1e3
    pos, phi1, roll = _read_position(case)
    tca = read_tca_options(case.table("tca", required=False))
    mesh = _read_mesh(case.table("mesh", required=False))
    fe = _read_fe(case.table("fe", required=False))
    if model == "pair":
        for k in ("planets", "member_gap_mm", "shaft", "regulation"):
            if case.has(k):
                raise InputError(k, case.data[k], "no planetary-train keys in a 'pair' case")
        pair, _, _ = read_pair(case, read_gears(case))
        torque = _driven_torque(tkey, tval, pair)
        for g in (pair.gear1, pair.gear2):
            if g.runout > 0:  # the FE scene places a periodic pair (tca.planetary.subgear.MeshTE): refuse, not ignore
                raise InputError(f"gears.{g.name}.runout_um", g.runout * 1e3, "0 in a stress case (run-out is analysed "
                                 "by gearfe tca; the FE model places the teeth of a pair without it)")
        out = StressCase("pair", torque, title, pair=pair, position=pos, phi1=phi1, roll=roll, tca=tca, mesh=mesh, fe=fe)
    else:
        for k in ("driver", "driven", "center_distance_mm", "misalignment"):
            if case.has(k):
                raise InputError(k, case.data[k], "no pair keys in a 'twin' case (the train fixes the meshes)")
        train = read_train(case)
        st = case.table("shaft", required=False)
        errors = ShaftErrors()
        if st is not None:
            errors = ShaftErrors(d_ex=st.get("d_ex_um", float, 0.0, lo=-1000.0, hi=1000.0) * 1e-3,
                                 d_gamma=st.get("d_gamma_arcmin", float, 0.0, lo=-60.0, hi=60.0) * ARCMIN)
            st.done()
        ro = read_regulation_options(case.table("regulation", required=False), stress=True, phases=PHASES)
        if tca.steps_per_cycle % train.planets:
            raise InputError("tca.steps_per_cycle", tca.steps_per_cycle, f"a multiple of the number of planets n = {train.planets}")
        out = StressCase("twin", torque, title, train=train, errors=errors, regulation=ro.mode, dz=ro.dz,
                         regulation_tol=ro.tol, regulation_maxiter=ro.max_iterations, member_phase=ro.member_phase, position=pos, phi1=phi1, roll=roll, tca=tca,
                         mesh=mesh, fe=fe)
    out = with_rating(case, out)  # [rating]: ISO 6336 (pipelines.cases.rating)
    if ltca and case.has("ltca"):
        read_ltca_options(case.table("ltca"), out.torque)
    case.done()
    return out


def read_train_stress(case: Table) -> StressCase:
    """A stress case of ``model = "train"`` from an isostatic train case (``kind = "isostatic"``, the file
    ``gearfe ltca`` takes; :func:`pipelines.cases.trains.read_isostatic_ltca` reads and checks its train, errors and
    ``[ltca]`` tables): the FE of the whole train at one position of the train LTCA's run, loaded by the first of
    ``[ltca] torques_nm`` on the sun (the LTCA's conventions: ring held, carrier output). Its own keys::

        [stress]
        position = 0            # index j of the LTCA's positions: psi1 = 2 pi j / (positions_per_cycle N1)
        psi1_deg = 0.0          # or the sun's angle relative to the carrier [deg] (not both)
        [mesh] ...              # as a stress case (refine, teeth, sizes, sizing)
        [fe] ...

    The FE's pins and the sun's support are rigid: ``[ltca] pin_stiffness_n_per_um`` and ``sun_support_n_per_um``
    are refused here (the sun is held on its axis or floats, ``[train] sun_axis``)."""
    from pipelines.cases.trains import read_isostatic_ltca

    case.get("kind", str, choices=("isostatic",))
    mesh = _read_mesh(case.table("mesh", required=False))
    fe = _read_fe(case.table("fe", required=False))
    st = case.table("stress", required=False)
    position, psi1 = 0, None
    if st is not None:
        if st.has("position") and st.has("psi1_deg"):
            raise InputError("stress.psi1_deg", st.data["psi1_deg"], "left out when stress.position is given (one of them)")
        position = st.get("position", int, 0, lo=0, hi=100000)
        if st.has("psi1_deg"):
            psi1 = math.radians(st.get("psi1_deg", float, lo=-3600.0, hi=3600.0))
        st.done()
    tc = read_isostatic_ltca(case)
    for key, v in (("ltca.pin_stiffness_n_per_um", tc.opts.pin_stiffness), ("ltca.sun_support_n_per_um", tc.opts.sun_support)):
        if v is not None:
            raise InputError(key, v * 1e-3, "left out for gearfe stress (the FE's planet pins and sun support are rigid)")
    torque = tc.opts.torques[0]
    out = StressCase("train", torque, tc.title, position=position, phi1=psi1, mesh=mesh, fe=fe, train_case=tc)
    case.done()
    return out
