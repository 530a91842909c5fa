"""Bad input raises FEInputError naming field, value and valid range; non-convergence is reported."""

import dataclasses

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fem import Body, ContactOptions, ContactPair, Fixed, Material, Rigid, solve
from fem.verification import block_chain, hertz_line
from fem.errors import FEConvergenceError, FEInputError


@pytest.fixture(scope="module")
def chain():
    return block_chain(n=2)


def test_unknown_set_name(chain):
    mesh, model, _ = chain
    bodies = (dataclasses.replace(model.bodies[0], supports=(Fixed("base/nowhere"),)),) + model.bodies[1:]
    with pytest.raises(FEInputError, match="base/nowhere") as e:
        solve(mesh, dataclasses.replace(model, bodies=bodies))
    assert "supports[0].set" in str(e.value)


def test_body_without_support(chain):
    mesh, model, _ = chain
    bodies = (Body("base", ()),) + model.bodies[1:]
    with pytest.raises(FEInputError, match="at least one Fixed or Rigid support"):
        solve(mesh, dataclasses.replace(model, bodies=bodies))


def test_mesh_body_missing_from_model(chain):
    mesh, model, _ = chain
    with pytest.raises(FEInputError, match="every body"):
        solve(mesh, dataclasses.replace(model, bodies=model.bodies[1:], contacts=model.contacts[:1]))


def test_unknown_contact_surface(chain):
    mesh, model, _ = chain
    bad = (ContactPair("top/ymin", "mid/top_face"),)
    with pytest.raises(FEInputError, match=r"contacts\['top/ymin'\].master"):
        solve(mesh, dataclasses.replace(model, contacts=bad))


def test_unknown_reference_point(chain):
    mesh, model, _ = chain
    bodies = model.bodies[:2] + (dataclasses.replace(model.bodies[2], supports=(Rigid("top/ymax", "nowhere"),)),)
    with pytest.raises(FEInputError, match="nowhere"):
        solve(mesh, dataclasses.replace(model, bodies=bodies))


@settings(max_examples=25, deadline=None)
@given(st.floats(max_value=0.0, allow_nan=False))
def test_nonpositive_penalty(v):
    with pytest.raises(FEInputError, match="penalty_factor"):
        ContactOptions(penalty_factor=v)


@given(st.floats(allow_nan=False, allow_infinity=False).filter(lambda x: not -1.0 < x < 0.5))
def test_poisson_ratio_range(nu):
    with pytest.raises(FEInputError, match=r"nu"):
        Material(2e5, nu)


def test_bad_rigid_dof_name():
    with pytest.raises(FEInputError, match="free"):
        Rigid("x/rim", "x", free=("rotz",))


def test_torque_on_held_rotation():
    with pytest.raises(FEInputError, match="torque"):
        Rigid("x/rim", "x", free=("ux",), torque=1.0)


def test_active_set_iteration_limit():
    mesh, model, _ = hertz_line(elements_per_halfwidth=5.0)
    model = dataclasses.replace(model, contact=ContactOptions(max_iterations=2))
    with pytest.raises(FEConvergenceError, match="contact active set"):
        solve(mesh, model)


def test_candidate_zone_too_small():
    mesh, model, _ = hertz_line(elements_per_halfwidth=5.0)
    pair = dataclasses.replace(model.contacts[0], search_gap=1e-7)
    with pytest.raises(FEConvergenceError, match="search_gap"):
        solve(mesh, dataclasses.replace(model, contacts=(pair,)))
