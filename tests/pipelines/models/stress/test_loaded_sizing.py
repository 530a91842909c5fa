"""Zones sized by the loaded estimate (issue 26): the FE's check of the pairs left without a zone, and the remesh.

At φ1 = −5.71° of ``stress_pair_small`` two pairs share the load (0.455/0.545 in the FE, test_stress_neighbours).
With the zone threshold raised to 0.5 (monkeypatched: the shipped 0.1 zones both) the estimate zones only the
pair that carries more, the FE loads the other beyond 0.1 of the mesh's force, and the run must say so; with
``[mesh] remesh = true`` it remeshes once with a zone on that pair, after which no pair is left unzoned.
"""

import pytest

import pipelines.models.stress.scene as scene_module
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress

from tests.support.shipped import shipped_table


def case(remesh):
    return read_stress_case(shipped_table("stress_pair_small", {"position": None, "phi1_deg": -5.71, "mesh.refine": 0.3,
                                                                "mesh.remesh": remesh}))


@pytest.fixture
def half(monkeypatch):
    monkeypatch.setattr(scene_module, "ZONE_SHARE", 0.5)


def test_a_loaded_pair_without_a_zone_is_flagged(tmp_path, half):
    s = run_stress(case(False), tmp_path / "flag").summary
    zoned = [z["pair"] for z in s["position"]["loaded_estimate"]["meshes"]["sun-planet/a"]["zones"]]
    assert len(zoned) == 1
    flagged = [w for w in s["warnings"] if "no refined zone" in w]
    assert len(flagged) == 1 and s["position"]["remeshed"] is None


def test_remesh_puts_a_zone_on_it(tmp_path, half):
    s = run_stress(case(True), tmp_path / "remesh").summary
    first = s["position"]["remeshed"]
    assert first is not None and len(first["pairs"]["sun-planet/a"]) == 1
    zoned = [z["pair"] for z in s["position"]["loaded_estimate"]["meshes"]["sun-planet/a"]["zones"]]
    assert len(zoned) == 2 and not any("no refined zone" in w for w in s["warnings"])
    assert s["dofs"] > first["dofs"]
