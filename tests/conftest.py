"""Test-session setup: images are rendered off screen (EGL, no display), as the ``gearfe`` command does;
the fixture ``shipped`` gives a shipped case with overrides (:mod:`tests.support.shipped`)."""

import types

import pytest

from pipelines.render import offscreen

from tests.support import shipped as _shipped

offscreen()


# `make test` runs two workers, one test file each (-n 2 --dist loadfile --no-loadscope-reorder), in the order
# collected: the heaviest files go first so that the run does not end with one worker alone on a long file.
# Seconds per file from `pytest --durations=0` (2-core machine); a file not listed keeps its place after these.
HEAVY_FILES = {
    "tests/pipelines/report/test_compare.py": 100,
    "tests/pipelines/sweep/test_sweep_stress.py": 20,
    "tests/pipelines/models/stress/test_stress.py": 55,
    "tests/pipelines/models/ltca/test_ltca.py": 40,
    "tests/pipelines/models/stress/test_stress_neighbours.py": 35,
    "tests/tca/planetary/test_regulation.py": 32,
    "tests/pipelines/report/test_report_layout.py": 30,
    "tests/pipelines/models/stress/test_headline.py": 20,
    "tests/pipelines/report/test_run.py": 20,
    "tests/pipelines/cli/test_sweep.py": 17,
    "tests/pipelines/cli/test_cli_contract.py": 16,
    "tests/mesher/test_volume.py": 15,
    "tests/pipelines/calculix/test_calculix_stress.py": 15,
    "tests/pipelines/models/stress/test_end_relief_stress.py": 14,
    "tests/pipelines/analyses/test_tca_face.py": 14,
    "tests/pipelines/cli/test_tca.py": 14,
}


def pytest_collection_modifyitems(session, config, items):
    items.sort(key=lambda item: -HEAVY_FILES.get(item.nodeid.split("::")[0], 0))  # stable: files stay in order


@pytest.fixture
def shipped():
    """``shipped.data(name, {"mesh.refine": 0.3})``, ``shipped.table(...)``, ``shipped.write(folder, name, data)``."""
    return types.SimpleNamespace(data=_shipped.shipped_data, table=_shipped.shipped_table, write=_shipped.write_case)
