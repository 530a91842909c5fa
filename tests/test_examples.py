"""The scripts in examples/ run from Python alone and give the physics they claim (as scikit-fem tests its examples).

Each example is imported as a module and its ``main`` run on a small setting; each check names its source.
"""

import importlib.util
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def load(name: str):
    spec = importlib.util.spec_from_file_location(f"examples_{name}", EXAMPLES / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def test_pair_tca_crowned_is_parabolic_and_involute_has_edge_contact():
    res = load("pair_tca").main(d_gamma_arcmin=3.0)
    crowned, involute = res["double-crowned"], res["involute"]
    # report section 1.5 / Fig. 1.6: the double-crowned planet keeps a parabolic TE and no edge contact under
    # a 3 arcmin shaft-angle error; the involute pair gets edge contact
    assert not crowned["edge_contact"] and involute["edge_contact"]
    # parabolic to within 1 % of its amplitude (the crowning is parabolic to first order; measured 0.4 %)
    assert crowned["parabola_rms_arcsec"] < 0.01 * crowned["te_pp_arcsec"]


def test_mesh_pair_puts_the_tca_contact_point_on_both_meshes(tmp_path):
    model, q = load("mesh_pair").main(tmp_path, contact_size_mm=0.5)
    # the contact point is a node of both gears, evaluated from the exact surfaces at the TCA parameters:
    # they coincide to the TCA residual (1e-10 mm) plus rounding
    assert model.contact_node_gap < 1e-9
    assert q.min_scaled_jacobian.min() > 0.0
    assert (tmp_path / "mesh.vtu").stat().st_size > 0 and (tmp_path / "mesh.inp").stat().st_size > 0


def test_stress_pair_balances_the_torque_through_the_contact(tmp_path):
    s = load("stress_pair").main(tmp_path, refine=0.3)
    # equilibrium: the fixed sun reacts T N1/N2 (41/34) of the planet's 156 N m (Newton's third law across the
    # contact, frictionless, to the FE's torque balance; measured 4e-4 at refine 0.35)
    assert s["reaction_torque_nm"] == pytest.approx(156.0 * 41 / 34, rel=2e-3)
    assert (tmp_path / "result.vtu").is_file()


def test_misalignment_sweep_crowned_absorbs_the_error_involute_is_linear_in_it():
    rows = load("misalignment_sweep").main(d_gamma=(0.0, 1.5, 3.0))
    te = {(r["design"], r["d_gamma_arcmin"]): r for r in rows}
    # conjugate involute helicoids transmit exactly when aligned (closed form: zero TE)
    assert te["involute", 0.0]["te_pp_arcsec"] < 1e-3 and not te["involute", 0.0]["edge_contact"]
    # crossed axes: edge contact and a TE first order in the error (twice the error, twice the TE, within 5 %)
    assert te["involute", 3.0]["edge_contact"]
    assert te["involute", 3.0]["te_pp_arcsec"] / te["involute", 1.5]["te_pp_arcsec"] == pytest.approx(2.0, rel=0.05)
    # report section 1.5: the double crowning absorbs the misalignment: no edge contact, amplitude within 5 %
    for g in (1.5, 3.0):
        assert not te["double-crowned", g]["edge_contact"]
        assert te["double-crowned", g]["te_pp_arcsec"] == pytest.approx(te["double-crowned", 0.0]["te_pp_arcsec"],
                                                                        rel=0.05)
