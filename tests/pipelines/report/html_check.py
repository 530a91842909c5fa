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


_LAYOUT_JS = """<script>
window.addEventListener('load', () => {
  const box = e => { const r = e.getBoundingClientRect(); return [r.left, r.top + window.scrollY, r.right, r.bottom + window.scrollY]; };
  const out = {width: document.documentElement.clientWidth,
               tables: [...document.querySelectorAll('table')].filter(t => t.offsetParent !== null && !t.closest('details:not([open])')).map(box),
               images: [...document.querySelectorAll('img')].map(box),
               headings: [...document.querySelectorAll('h1,h2,h3')].map(box)};
  const pre = document.createElement('pre'); pre.id = 'layout-json'; pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
});
</script>"""


def layout(html: Path, tmp: Path, width: int = 1400) -> dict:
    """Bounding boxes [left, top, right, bottom] (px, page coordinates) of the visible tables, images and headings of
    a page laid out by headless Chromium at ``width`` px, and the viewport's width."""
    import json

    exe = need_chromium()
    page = tmp / f"layout_{Path(html).name}"
    page.write_text(Path(html).read_text(encoding="utf-8").replace("</body>", _LAYOUT_JS + "</body>"), encoding="utf-8")
    cmd = [exe, *FLAGS, f"--user-data-dir={tmp / 'chromium-profile'}", "--dump-dom", "--virtual-time-budget=20000",
           f"--window-size={width},1200", page.resolve().as_uri()]
    dom = subprocess.run(cmd, check=True, capture_output=True, timeout=180).stdout.decode("utf-8", "replace")
    m = re.search(r'<pre id="layout-json">(.*?)</pre>', dom, re.S)
    assert m, "the layout script did not run"
    import html as _html

    return json.loads(_html.unescape(m.group(1)))


def overlaps(boxes: list) -> list[tuple[int, int]]:
    """Pairs of boxes that overlap (by more than a pixel each way)."""
    out = []
    for i, a in enumerate(boxes):
        for j in range(i + 1, len(boxes)):
            b = boxes[j]
            if min(a[2], b[2]) - max(a[0], b[0]) > 1 and min(a[3], b[3]) - max(a[1], b[1]) > 1:
                out.append((i, j))
    return out
