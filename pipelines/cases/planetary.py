"""Reader of a double-helical planetary train (Part 1): gears, planets, member gap, errors of installment."""

from __future__ import annotations

from dataclasses import dataclass

from tca.errors import InputError
from tca.planetary.train import DoubleHelicalTrain, ShaftErrors

from tca.units import ARCSEC

from tca.pair.gear_pair import GearPair

from pipelines.cases.reader import ARCMIN, check_mesh, read_gears
from pipelines.models.stress.case import REGULATION
from pipelines.cases.schema import Table

__all__ = ["read_train", "check_train_meshes", "read_installment", "RegulationSettings", "read_regulation_options"]


@dataclass(frozen=True)
class RegulationSettings:
    """The ``[regulation]`` table: the iteration of Step 3 (tolerance [rad], iterations) and, in stress cases,
    the mode, the given axial displacements dz [mm] of members a, b and the members' phase ('' = default)."""

    tol: float = 1e-3 * ARCSEC
    max_iterations: int = 12
    mode: str = "tca"
    dz: tuple = (0.0, 0.0)
    member_phase: str = ""


def read_regulation_options(t: Table | None, stress: bool = False, phases: tuple = ()) -> RegulationSettings:
    """``[regulation]`` of a planetary (``tol_arcsec``, ``max_iterations``) or, with ``stress``, a twin stress case
    (also ``mode``, ``dz_a_mm``, ``dz_b_mm``, ``member_phase`` among ``phases``); the one reader of that table."""
    if t is None:
        return RegulationSettings()
    mode, dz, phase = "tca", (0.0, 0.0), ""
    if stress:
        mode = t.get("mode", str, "tca", choices=REGULATION)
        phase = t.get("member_phase", str, "", choices=("",) + tuple(phases))
        if mode == "given":
            dz = (t.get("dz_a_mm", float, lo=-1000.0, hi=1000.0), t.get("dz_b_mm", float, lo=-1000.0, hi=1000.0))
        else:
            for k in ("dz_a_mm", "dz_b_mm"):
                if t.has(k):
                    raise InputError(f"regulation.{k}", t.data[k], "set only with mode = 'given'")
    tol = t.get("tol_arcsec", float, 1e-3, lo=1e-6, hi=10.0)
    maxit = t.get("max_iterations", int, 12, lo=2, hi=50)
    t.done()
    return RegulationSettings(tol * ARCSEC, maxit, mode, dz, phase)

def read_train(case: Table) -> DoubleHelicalTrain:
    """Train from the case: gears sun, planet, ring; ``planets``; ``member_gap_mm``."""
    gears = read_gears(case)
    for name in ("sun", "planet", "ring"):
        if name not in gears:
            raise InputError(f"gears.{name}", None, "a gear table (the train needs sun, planet and ring)")
    extra = sorted(set(gears) - {"sun", "planet", "ring"})
    if extra:
        raise InputError(f"gears.{extra[0]}", extra[0], "one of 'sun', 'planet', 'ring'")
    for name, g in gears.items():
        if g.runout > 0:  # the Part 1 train repeats each mesh's reference pair (tca.planetary.subgear.MeshTE)
            raise InputError(f"gears.{name}.runout_um", g.runout * 1e3, "0 in a Part 1 planetary case (run-out is "
                             "analysed by pair cases and by isostatic cases, kind = 'isostatic')")
    n = case.get("planets", int, lo=1, hi=20)
    gap = case.get("member_gap_mm", float, lo=0.0, hi=1000.0)
    train = DoubleHelicalTrain(gears["sun"], gears["planet"], gears["ring"], n, gap)
    check_train_meshes(train.sun, train.planet, train.ring, train.center_distance, gears)
    return train


def check_train_meshes(sun, planet, ring, center_distance: float, gears: dict) -> None:
    """The pair checks (:func:`pipelines.cases.reader.check_mesh`) of a train's sun-planet and planet-ring meshes
    at the carrier's centre distance, before any work."""
    check_mesh(GearPair(sun, planet, center_distance=center_distance), gears, where="the sun-planet mesh")
    check_mesh(GearPair(planet, ring, center_distance=center_distance), gears, where="the planet-ring mesh")


def _floats(t: Table, key: str, n: int, lo: float, hi: float) -> list[float]:
    v = t.get(key, list, [0.0] * n)
    name = f"{t.path}.{key}"
    if len(v) != n:
        raise InputError(name, v, f"a list of {n} numbers (one per planet shaft)")
    for x in v:
        if isinstance(x, bool) or not isinstance(x, (int, float)) or not (lo <= x <= hi):
            raise InputError(name, v, f"numbers in [{lo:g}, {hi:g}]")
    return [float(x) for x in v]


def read_installment(t: Table | None, n: int) -> list[ShaftErrors]:
    """Errors of installment per shaft from ``[installment]`` (none: an error-free train)."""
    if t is None:
        return [ShaftErrors() for _ in range(n)]
    dex = _floats(t, "d_ex_um", n, -1000.0, 1000.0)
    dg = _floats(t, "d_gamma_arcmin", n, -60.0, 60.0)
    t.done()
    return [ShaftErrors(d_ex=x * 1e-3, d_gamma=g * ARCMIN) for x, g in zip(dex, dg)]
