"""The README's API example runs and rates both ways (as scikit-fem tests its documentation examples)."""

import re
from pathlib import Path

README = Path(__file__).resolve().parents[3] / "docs" / "rating.md"


def test_readme_example_runs():
    code = re.search(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.S).group(1)
    scope: dict = {}
    exec(compile(code, str(README), "exec"), scope)
    iso, tca = scope["iso"], scope["tca"]
    assert iso.pinion.factors["K_Hbeta"].source.value == "iso"
    assert tca.pinion.factors["K_Hbeta"].source.value == "gearfe" and tca.pinion.factors["K_Hbeta"].value == 1.23
    assert tca.pinion.s_h < iso.pinion.s_h  # the larger K_Hβ lowers the safety
