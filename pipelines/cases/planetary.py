"""Reader of a double-helical planetary train (Part 1): gears, planets, member gap, errors of installment."""

from __future__ import annotations

from tca.errors import InputError
from tca.planetary.train import DoubleHelicalTrain, ShaftErrors

from pipelines.cases.reader import ARCMIN, read_gears
from pipelines.cases.schema import Table

__all__ = ["read_train", "read_installment"]

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
    return DoubleHelicalTrain(gears["sun"], gears["planet"], gears["ring"], n, gap)


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
