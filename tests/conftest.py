"""Test-session setup: images are rendered off screen (EGL, no display), as the ``gearfe`` command does, and
cheaper than a user's (below); the fixture ``shipped`` gives a shipped case with overrides
(:mod:`tests.support.shipped`)."""

import os
import shutil
import tempfile
import types
from pathlib import Path

import pytest

from pipelines.render import offscreen
from pipelines.render.settings import DPI_SCALE, PNG_COMPRESSION, SAMPLES
from tca.pair.analysis import pair_tca_memo

from tests.support import shipped as _shipped

# Pictures in the suite (pipelines/render/settings.py): no multisampling of the VTK images, matplotlib plots at half
# the dpi, PNGs at zlib level 1 (lossless). The tests check that pictures are made, named, not blank and coloured
# where the load is; tests/pipelines/render/test_settings.py checks the settings themselves at the users' defaults.
# Set before any test (subprocesses of `gearfe` inherit them); a value already in the environment is kept.
for _name, _value in ((SAMPLES, "0"), (DPI_SCALE, "0.5"), (PNG_COMPRESSION, "1")):
    os.environ.setdefault(_name, _value)
offscreen()

# A pair's TCA is computed once per session, not once per process: the pair TCA's memo (tca.pair.memo) shares its
# results through a folder made by the controlling process (inherited by the xdist workers through the environment,
# and by the processes they fork: gearfe compare's second design) and removed at its end. The same inputs give the same
# result wherever it is computed; what a test checks of a TCA is unchanged. Part 1's regulation (18 pair TCAs of
# 1-2 s per design) is the same in test_regulation.py, test_stress.py, test_compare.py and the CLI tests.
# GEARFE_TEST_TCA_STORE= (empty) turns the sharing off: each process computes its own, as before.
TCA_STORE = "GEARFE_TEST_TCA_STORE"
_made_store = TCA_STORE not in os.environ and "PYTEST_XDIST_WORKER" not in os.environ
if _made_store:
    os.environ[TCA_STORE] = tempfile.mkdtemp(prefix="gearfe-tests-tca-")
if os.environ.get(TCA_STORE):
    pair_tca_memo().share(Path(os.environ[TCA_STORE]))


def pytest_unconfigure(config):
    if _made_store:
        shutil.rmtree(os.environ.pop(TCA_STORE), ignore_errors=True)


# `make test` runs two workers, one test file each (-n 2 --dist loadfile --no-loadscope-reorder), in the order
# collected: the heaviest files go first so that the run does not end with one worker alone on a long file.
# Seconds per file from `pytest --durations=0` (quiet 2-core machine, 2026-11-26 at e8c962f); a file not listed
# keeps its place after these.
HEAVY_FILES = {
    "tests/pipelines/report/test_compare.py": 50,
    "tests/pipelines/models/stress/test_stress.py": 43,
    "tests/pipelines/models/ltca/test_ltca.py": 26,
    "tests/tca/planetary/test_regulation.py": 23,
    "tests/pipelines/report/test_report_layout.py": 22,
    "tests/pipelines/report/test_run.py": 22,
    "tests/pipelines/cli/test_cli_contract.py": 20,
    "tests/mesher/test_volume.py": 17,
    "tests/pipelines/cli/test_sweep.py": 17,
    "tests/tca/face/test_train.py": 14,
    "tests/pipelines/cli/test_tca.py": 14,
    "tests/pipelines/analyses/test_tca_face.py": 13,
    "tests/pipelines/models/stress/test_headline.py": 13,
    "tests/pipelines/analyses/test_tca_planetary.py": 13,
    "tests/pipelines/models/stress/test_stress_neighbours.py": 13,
    "tests/tca/geometry/test_end_relief.py": 12,
    "tests/pipelines/sweep/test_sweep_stress.py": 12,
    "tests/tca/isostatic/test_analysis.py": 12,
    "tests/test_examples.py": 11,
    "tests/pipelines/analyses/test_tca_isostatic.py": 10,
}


def pytest_collection_modifyitems(session, config, items):
    items.sort(key=lambda item: -HEAVY_FILES.get(item.nodeid.split("::")[0], 0))  # stable: files stay in order


@pytest.fixture
def shipped():
    """``shipped.data(name, {"mesh.refine": 0.3})``, ``shipped.table(...)``, ``shipped.write(folder, name, data)``."""
    return types.SimpleNamespace(data=_shipped.shipped_data, table=_shipped.shipped_table, write=_shipped.write_case)
