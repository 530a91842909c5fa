"""The resource estimate before meshing against the mesh that is built (issue 26, bad-input contract).

Every shipped stress case at its defaults and the aligned and misaligned (Δγ = 3′) helical pair of
``stress_helical_pair.toml`` at refine 0.25, 0.5 and 1 go through the estimate and the mesher, without a
solve: the estimate is within −10 %/+20 % of the mesh (it is the mesher's own plan, so it is exact), or the
model is refused before meshing when it exceeds the memory limit (the aligned helical pair at refine 1 is
1.64M DOF, 34 GB: refused under ``GEARFE_MAX_MEMORY_GB=10``). About 3 min on the 2-core machine (a loaded
estimate and a mesh per case): ``make bench``.
"""

import pytest

from benchmarks.sizing import estimate_sweep

pytestmark = pytest.mark.bench


def test_every_estimate_is_within_its_band_or_refused():
    rows = estimate_sweep()
    assert len(rows) >= 14
    for r in rows:
        if "refused" in r:
            assert "GB" in r["refused"]
            continue
        assert 0.9 <= r["ratio"] <= 1.2, r
