"""gearfe against CalculiX on the same gear scenes (issue 13): job.inp, the reader, the crosscheck command.

The CalculiX runs are skipped without ccx (apt-get install calculix-ccx). The models are the
smallest that carry a localized contact (C3D8, refine 0.3): a crowned helical pair with a shaft
angle error (one tooth each) and a spur sun on a lead-crowned planet (three teeth each) at the
position of minimum TE, where two tooth pairs share the load. (An aligned spur pair without lead
crowning has line contact, which ``gearfe stress`` does not size yet: its Hertz sizing fails.)
The spur scene's run is a peer run of make bench (marker bench); the crowned one stays in make test.
Targets of the issue: contact force and reaction torque 0.5 %, load shares 0.02, fillet stress
3 %, maximum von Mises 5 %, peak contact pressure 10 %; where CalculiX and gearfe differ by more,
the test asserts the target under a strict xfail carrying the measured value (docs/deviations.md).
"""

import json
import re
import shutil

import numpy as np
import pytest

from pipelines.cli import main
from pipelines.calculix.frd import read_dat_totals, read_frd

from tests.support.shipped import shipped_data, write_case

CCX = shutil.which("ccx")
needs_ccx = pytest.mark.skipif(CCX is None, reason="CalculiX (ccx) not installed: apt-get install calculix-ccx")

CASE = "pipelines/cases/stress_pair_small.toml"


def _case(tmp_path, name, **over):
    """The shipped small crowned-pair case with C3D8, refine 0.3 and overrides, written as TOML."""
    o = {"mesh": {"refine": 0.3, "teeth": over.pop("teeth", 1)}, "fe": {"element": "C3D8"}}
    if over.pop("spur", False):
        data = shipped_data(CASE)
        o.update({f"gears.{k}.helix_deg": 0.0 for k in data["gears"]})
        o.update({"misalignment": {"d_gamma_arcmin": 0.0}, "title": "spur sun driving a lead-crowned planet, aligned"})
    return write_case(tmp_path, name, shipped_data(CASE, {**o, **over}))


@pytest.fixture(scope="module")
def crowned(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("crowned")
    out = tmp / "out"
    assert main(["stress", str(_case(tmp, "crowned")), "--out", str(out), "--inp"]) == 0
    return out


def test_job_deck_has_every_part_of_the_scene(crowned):
    deck = (crowned / "job.inp").read_text()
    summary = json.loads((crowned / "summary.json").read_text())
    n_el = summary["elements"]
    elements = deck.split("*ELEMENT, TYPE=C3D8\n")[1].split("*")[0].splitlines()
    assert [int(e.split(",")[0]) for e in elements] == list(range(1, n_el + 1))
    ref, rot = map(int, re.search(r"\*RIGID BODY, NSET=PLANET_RIM, REF NODE=(\d+), ROT NODE=(\d+)", deck).groups())
    # compact ids: mesh nodes 1..n, then the reference and the rotation node of the one rigid body
    node_ids = [int(x) for x in re.findall(r"^(\d+), [-0-9.e+]+, [-0-9.e+]+, [-0-9.e+]+$", deck.split("*ELEMENT")[0], re.M)]
    node_ids += [int(x) for x in re.findall(r"^(\d+), [-0-9.e+]+, [-0-9.e+]+, [-0-9.e+]+$", deck.split("*NSET, NSET=PLANET_ROT")[0].split("gearfe (pipelines.calculix.job)")[1], re.M)]
    assert sorted(node_ids) == list(range(1, rot + 1)) and ref < rot
    assert re.search(r"\*BOUNDARY\nSUN_RIM, 1, 1, 0\.", deck)
    # the planet axis is tilted by the 3 arcmin shaft error: its held rotations need an equation
    assert "*EQUATION" in deck
    assert deck.count("*CONTACT PAIR, INTERACTION=") == 1
    assert "PLANET_TOOTH0_FLANK_NEG, SUN_TOOTH0_FLANK_POS" in deck
    # the torque as the generalized force of the moment T e3 on the rotation node's free DOF:
    # T = 156 N m about the planet axis e3 = (0, sin 3', -cos 3') (closed form of the tilt)
    m = re.search(r"\*CLOAD\n(\d+), (\d), (\S+)\n", deck)
    node, dof, value = int(m.group(1)), int(m.group(2)), float(m.group(3))
    assert node == rot and dof == 3
    e3z = -np.cos(np.radians(3.0 / 60.0))
    assert value * e3z == pytest.approx(-156.0e3, rel=1e-12)
    # the penalty slope of the pair: s f E / h_min, f = 100, E = 2.068e5 MPa (case defaults), s from the solve
    K = float(re.search(r"PRESSURE-OVERCLOSURE=LINEAR\n(\S+)\n", deck).group(1))
    h = 100.0 * 2.068e5 * summary["fe"]["penalty_scale"] / K
    assert 0.05 < h < 2.0  # [mm] an element thickness of this coarse mesh


def test_crosscheck_without_ccx_names_the_install_command(crowned, monkeypatch, capsys, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path))
    assert main(["crosscheck", str(crowned)]) == 2
    err = capsys.readouterr().err
    assert "apt-get install calculix-ccx" in err and len(err.strip().splitlines()) == 1
    assert not (crowned / "crosscheck.md").exists()


def test_crosscheck_of_a_folder_without_job_is_bad_input(tmp_path, capsys):
    assert main(["crosscheck", str(tmp_path)]) == 2
    assert "--inp" in capsys.readouterr().err


def test_frd_reader_is_strict(tmp_path):
    good = ("    1C\n  100CL  101 1.00000E+00           2                     0    1           1\n"
            " -4  DISP        4    1\n -5  D1          1    2    1    0\n -5  D2          1    2    2    0\n"
            " -5  D3          1    2    3    0\n -5  ALL         1    2    0    0    1ALL\n"
            " -1         1 1.00000E+00-2.00000E+00 3.00000E-01\n -1         2 0.00000E+00 0.00000E+00 5.00000E+00\n"
            " -3\n 9999\n")
    (tmp_path / "a.frd").write_text(good)
    b = read_frd(tmp_path / "a.frd")["DISP"]
    np.testing.assert_array_equal(b.nodes, [1, 2])
    np.testing.assert_array_equal(b.field(3), [[1.0, -2.0, 0.3], [0.0, 0.0, 5.0], [0.0, 0.0, 0.0]])
    (tmp_path / "b.frd").write_text(good.replace("           2                     0", "           3                     0"))
    with pytest.raises(Exception, match="2 node records, header says 3"):
        read_frd(tmp_path / "b.frd")
    (tmp_path / "c.dat").write_text("\n total force (fx,fy,fz) for set SUN_RIM and time  0.1E+01\n\n"
                                    "        1.0E+00  2.0E+00 -3.0E+00\n\n")
    np.testing.assert_array_equal(read_dat_totals(tmp_path / "c.dat")["SUN_RIM"], [1.0, 2.0, -3.0])


def _rows(folder):
    assert main(["crosscheck", str(folder)]) == 0
    return {r["quantity"]: r for r in json.loads((folder / "crosscheck.json").read_text())["rows"]}


@pytest.fixture(scope="module")
def crowned_check(crowned):
    if CCX is None:
        pytest.skip("CalculiX (ccx) not installed: apt-get install calculix-ccx")
    return _rows(crowned)


@needs_ccx
@pytest.mark.parametrize("q", ["contact force [N]", "reaction torque [N m]"])
def test_crowned_pair_equilibrium_matches_calculix(crowned_check, q):
    # target of issue 13: 0.5 %
    assert abs(crowned_check[q]["difference"]) <= 0.005


@needs_ccx
def test_crowned_pair_fillet_stress_matches_calculix(crowned_check):
    # target of issue 13: 3 %
    assert abs(crowned_check["fillet max principal [MPa]"]["difference"]) <= 0.03


@needs_ccx
def test_crowned_pair_max_von_mises_matches_calculix(crowned_check):
    # target of issue 13: 5 %. Measured -0.5 % (sun) and +0.9 % (planet) with gearfe's contact constraints at the
    # Gauss points (issue 14), the integration points of CalculiX's surface-to-surface contact; -15 % / -7 % with
    # gearfe's earlier node-averaged gaps
    for k, r in crowned_check.items():
        if k.startswith("max von Mises"):
            assert abs(r["difference"]) <= 0.05, (k, r)


@needs_ccx
@pytest.mark.xfail(strict=True, reason="measured +717 % at refine 0.3 (CalculiX 20.8 GPa against gearfe 2.55 GPa; "
                   "Hertz 2.3 GPa): CalculiX's nodal CPRESS of surface-to-surface contact is extrapolated from "
                   "integration points and does not integrate to the contact force (sum of CPRESS*A is 3x the "
                   "force at refine 0.5); gearfe's is the nodal force over its area")
def test_crowned_pair_peak_pressure_matches_calculix(crowned_check):
    # target of issue 13: 10 %
    assert abs(crowned_check["peak contact pressure [MPa]"]["difference"]) <= 0.10


@pytest.fixture(scope="module")
def spur_check(tmp_path_factory):
    if CCX is None:
        pytest.skip("CalculiX (ccx) not installed: apt-get install calculix-ccx")
    tmp = tmp_path_factory.mktemp("spur")
    out = tmp / "out"
    case = _case(tmp, "spur", spur=True, teeth=3, position="min_te")
    assert main(["stress", str(case), "--out", str(out), "--inp"]) == 0
    return out, _rows(out)


@pytest.mark.bench  # the second peer run (three teeth each, ~60 s): make bench
@needs_ccx
@pytest.mark.parametrize("q", ["contact force [N]", "reaction torque [N m]"])
def test_spur_pair_equilibrium_matches_calculix(spur_check, q):
    # target of issue 13: 0.5 %
    assert abs(spur_check[1][q]["difference"]) <= 0.005


@pytest.mark.bench  # the second peer run (three teeth each, ~60 s): make bench
@needs_ccx
def test_spur_pair_fillet_stress_matches_calculix(spur_check):
    # target of issue 13: 3 %
    assert abs(spur_check[1]["fillet max principal [MPa]"]["difference"]) <= 0.03


@pytest.mark.bench  # the second peer run (three teeth each, ~60 s): make bench
@needs_ccx
def test_spur_pair_shares_two_tooth_pairs_like_calculix(spur_check):
    # measured 0.500/0.500 (gearfe, Gauss-point contact constraints) against 0.506/0.494 (CalculiX CF): 0.006
    # apart; gearfe's earlier node-averaged gaps gave 0.462/0.538 (0.045 apart)
    out, rows = spur_check
    shares = json.loads((out / "summary.json").read_text())["load_share"]["sun-planet"]["teeth"]
    # the position of minimum TE is a transition: two pairs carry load (at least 20 % each)
    assert sorted(shares.values())[-2] > 0.2
    # target of issue 13: load shares within 0.02 (absolute)
    for k, r in rows.items():
        if k.startswith("load share"):
            assert abs(r["difference"]) <= 0.02, (k, r)


@pytest.mark.parametrize("axis", [(0.0, 0.0, 1.0), (0.3, -0.2, 0.93), (0.9, 0.1, 0.4), (0.0, 1.0, 0.0)])
def test_rotation_node_constraints_leave_only_the_axis_free(axis):
    # the held rotations about e1, e2 (fem.constraints.axis_frame) as *BOUNDARY/*EQUATION lines: their null
    # space must be the axis e3, and the torque on the independent DOF must do the work T phi for theta = e3 phi
    from fem.constraints import axis_frame
    from pipelines.calculix.job import _node_dofs

    R = axis_frame(axis)
    T = 1234.5
    bnd, eqs, cl = _node_dofs(7, R, [0, 1], np.zeros(2), T * R[:, 2])
    rows = []
    for b in bnd:
        _, d, _, v = b.split(", ")
        row = np.zeros(3)
        row[int(d) - 1] = 1.0
        rows.append(row)
        assert float(v) == 0.0
    for e in eqs:
        lines = e.splitlines()
        assert int(lines[0]) == len(lines) - 1
        row = np.zeros(3)
        for term in lines[1:]:
            node, d, c = term.split(", ")
            assert int(node) == 7
            row[int(d) - 1] = float(c)
        rows.append(row)
    C = np.array(rows)
    assert C.shape == (2, 3)
    np.testing.assert_allclose(C @ R[:, 2], 0.0, atol=1e-12)  # the axis is free
    assert np.linalg.matrix_rank(C) == 2  # and only the axis
    theta = R[:, 2] * 0.01
    work = sum(float(line.split(", ")[2]) * theta[int(line.split(", ")[1]) - 1] for line in cl)
    assert work == pytest.approx(T * 0.01, rel=1e-12)
    dependent = {int(b.split(", ")[1]) for b in bnd} | {int(e.splitlines()[1].split(", ")[1]) for e in eqs}
    assert not dependent & {int(line.split(", ")[1]) for line in cl}  # no load on a constrained DOF
