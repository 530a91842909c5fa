"""Fixtures of the hostile-input tests."""

import pytest


@pytest.fixture(scope="module", autouse=True)
def _imported():
    """Import every subcommand (and what it imports) once, so the time limit measures the checks."""
    from pipelines.cli import build_parser
    import pipelines.models.stress.run  # noqa: F401
    import pipelines.report.run  # noqa: F401

    build_parser()
