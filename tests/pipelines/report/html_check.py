"""Headless Chromium rendering of a self-contained report page for the tests (skipped without chromium)."""

import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync")


def need_chromium() -> str:
    if not Path(CHROMIUM).is_file():
        pytest.skip("headless Chromium is not installed: apt-get install chromium")
    return CHROMIUM


def screenshot(html: Path, png: Path, tmp: Path, size=(1400, 2400)) -> Path:
    """A screenshot of `html` rendered by headless Chromium (a fresh profile in `tmp`)."""
    exe = need_chromium()
    cmd = [exe, *FLAGS, f"--user-data-dir={tmp / 'chromium-profile'}", f"--screenshot={png}",
           f"--window-size={size[0]},{size[1]}", Path(html).resolve().as_uri()]
    subprocess.run(cmd, check=True, capture_output=True, timeout=120)
    assert png.is_file(), "chromium wrote no screenshot"
    return png


def self_contained(text: str) -> list[str]:
    """Resources the page would load from elsewhere (src/href not data: URIs or anchors); [] when self-contained."""
    refs = re.findall(r'(?:src|href)="([^"]*)"', text)
    return [r for r in refs if not (r.startswith("data:") or r.startswith("#"))]


def embedded_images(text: str) -> int:
    return len(re.findall(r'src="data:image/png;base64,', text))


def coloured_share(png: Path) -> float:
    """Fraction of the screenshot's pixels that are saturated colour (the stress maps), not grey/white text."""
    import matplotlib.image as mpimg

    img = mpimg.imread(str(png))[..., :3]
    return float((np.ptp(img, axis=-1) > 0.3).mean())
