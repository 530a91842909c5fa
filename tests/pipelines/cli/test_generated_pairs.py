"""Generated pairs through ``gearfe tca`` and ``gearfe stress`` (issue 24, item 2): each runs or is refused before any
work by the pair checks (tca.pair.checks, one InputError line, exit status 2, no files).

:func:`generated_pair` draws a pair file from a seed: spur and helical up to 40 deg, external and internal,
profile shifts, lead crownings, tip reliefs, end reliefs, small misalignments, without or with a centre distance.
What runs must be plausible: a finite TE; the stress model's load shares in [0, 1] summing to 1 and its
reaction torque balancing the applied one within 1 %. The 32 seeds run under ``make bench`` (marker ``bench``,
some ten minutes on two cores); ``make test`` runs two of them through ``gearfe tca``.
"""

import json
import math
import random
import re

import pytest

from pipelines.cli import main

from tests.support.tomlw import dumps

SEEDS = list(range(32))
GEAR_ERROR = re.compile(r"error: \w+: (undercut|pointed tooth|singular point|interference)")
FAST = [1, 2]


def generated_pair(seed: int) -> dict:
    """A pair file (data) drawn from ``seed`` (module docstring); the torque a nominal unit load of 20-120 MPa."""
    rnd = random.Random(seed)
    internal = rnd.random() < 0.25
    m = rnd.choice([1.5, 2.0, 3.0, 4.5, 5.0])
    alpha = rnd.choice([17.5, 20.0, 20.0, 22.5, 25.0])
    beta = 0.0 if rnd.random() < 0.4 else round(rnd.uniform(5.0, 40.0), 1)
    z1 = rnd.randint(14, 40)
    z2 = z1 + rnd.randint(20, 60) if internal else rnd.randint(z1, 4 * z1)
    b = round(min(rnd.uniform(6.0, 14.0) * m, 120.0), 1)
    x1 = round(rnd.uniform(-0.1, 0.6), 2)
    x2 = round(rnd.uniform(-0.2, 0.5), 2) if not internal else round(rnd.uniform(0.0, 0.5), 2)

    def gear(z, x, hand):
        g = {"teeth": z, "module_mm": m, "pressure_angle_deg": alpha, "face_width_mm": b, "profile_shift": x}
        if beta:
            g.update(helix_deg=beta, hand=hand)
        return g

    h1 = rnd.choice(["right", "left"])
    h2 = h1 if internal else ("left" if h1 == "right" else "right")
    p, w = gear(z1, x1, h1), gear(z2, x2, h2)
    if internal:
        w.update(internal=True, addendum=0.6)
    mod = rnd.choice(["none", "crowning", "tip_relief", "end_relief"])
    if mod == "crowning" and not internal:
        p["crowning"] = {"c_beta_um": round(rnd.uniform(5.0, 20.0), 1)}
    elif mod == "tip_relief":
        p["tip_relief"] = {"amount_um": round(rnd.uniform(5.0, 20.0), 1),
                           "start_roll_mm": round(0.5 * z1 * m * math.cos(math.radians(alpha)) * math.tan(math.radians(alpha)) + m, 2),
                           "kind": rnd.choice(["linear", "parabolic"])}
    elif mod == "end_relief":
        p["end_relief"] = {"amount_um": round(rnd.uniform(5.0, 20.0), 1), "length_mm": round(0.15 * b, 1)}
    r2 = 0.5 * z2 * m / math.cos(math.radians(beta))
    torque = round(rnd.uniform(20.0, 120.0) * b * m * r2 * 1e-3, 1)  # [N m] on the driven gear
    data = {"kind": "pair", "title": f"generated pair {seed}", "driver": "p", "driven": "w", "driven_torque_nm": torque,
            "gears": {"p": p, "w": w}, "tca": {"cycles": 1, "steps_per_cycle": 12},
            "mesh": {"refine": 0.4, "teeth": 3}}
    if rnd.random() < 0.5:
        data["misalignment"] = {"d_gamma_arcmin": round(rnd.uniform(-2.0, 2.0), 2)}
    return data


def _run(tmp_path, capsys, command: str, seed: int):
    f = tmp_path / "pair.toml"
    f.write_text(dumps(generated_pair(seed)) + "\n")
    out = tmp_path / command
    rc = main([command, str(f), "--out", str(out)])
    err = [line for line in capsys.readouterr().err.splitlines() if "error" in line]
    if rc == 2:  # refused: by a check before any work (a key out of range, a gear that cannot be cut), one line
        assert len(err) == 1 and (" is invalid: expected " in err[0] or GEAR_ERROR.search(err[0])), err
        assert not out.exists()
        return None
    assert rc == 0, err
    return json.loads((out / "summary.json").read_text())


def _tca(tmp_path, capsys, seed):
    s = _run(tmp_path, capsys, "tca", seed)
    if s is not None:
        assert math.isfinite(s["te_peak_to_peak_arcsec"]) and s["max_residual_mm"] < 1e-8
    return s


@pytest.mark.parametrize("seed", FAST)
def test_generated_pair_tca(tmp_path, capsys, seed):
    _tca(tmp_path, capsys, seed)


@pytest.mark.bench
@pytest.mark.parametrize("seed", SEEDS)
def test_generated_pair_tca_and_stress(tmp_path, capsys, seed, monkeypatch):
    monkeypatch.setenv("GEARFE_MAX_MEMORY_GB", "10")
    if _tca(tmp_path, capsys, seed) is None:
        return
    s = _run(tmp_path, capsys, "stress", seed)
    if s is None:
        return
    assert abs(s["torque_balance_error"]) < 0.01
    for name, share in s["load_share"].items():
        for part in ("members", "teeth"):
            v = list(share[part].values())
            assert all(0.0 <= x <= 1.0 for x in v) and abs(sum(v) - 1.0) < 1e-6, (name, part, share)
