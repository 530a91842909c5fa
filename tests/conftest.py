"""Test-session setup: images are rendered off screen (EGL, no display), as the ``gearfe`` command does;
the fixture ``shipped`` gives a shipped case with overrides (:mod:`tests.support.shipped`)."""

import types

import pytest

from pipelines.render import offscreen

from tests.support import shipped as _shipped

offscreen()


@pytest.fixture
def shipped():
    """``shipped.data(name, {"mesh.refine": 0.3})``, ``shipped.table(...)``, ``shipped.write(folder, name, data)``."""
    return types.SimpleNamespace(data=_shipped.shipped_data, table=_shipped.shipped_table, write=_shipped.write_case)
