r"""How pictures are rendered and written: three settings read from the environment, each defaulting to the
look every picture had before they existed (a user who sets nothing gets the same pixels).

=========================  =================================================================  =========
variable                   meaning                                                            default
=========================  =================================================================  =========
``GEARFE_RENDER_SAMPLES``  multisample anti-aliasing of the VTK images (samples per pixel:     8
                           0, 1, 2, 4 or 8; 0 and 1 are off)
``GEARFE_PLOT_DPI_SCALE``  factor on the resolution (dpi) of the matplotlib plots, in          1
                           [0.25, 4]: the layout (inches, points) is unchanged, the picture
                           has scale x the pixels along each side
``GEARFE_PNG_COMPRESSION`` zlib level of every PNG written, 0-9: lossless, trades file size    6
                           for time (the pixels are the same at every level)
=========================  =================================================================  =========

The defaults are pyvista's (``multi_samples`` = 8 of its global theme, with MSAA) and Pillow's (zlib level 6).
The test suite renders with 0 samples, dpi scale 0.5 and level 1 (tests/conftest.py): its tests check that the
pictures are made, named, not blank and coloured where the load is, not their anti-aliasing, resolution or size
on disk. Rendering in software (Mesa llvmpipe), MSAA with 8 samples costs about a third of a VTK image's time and a
PNG's zlib level 6 twice the time of level 1 (docs/benchmarks.md, "The time of make test").

A value outside its range is an :class:`tca.errors.InputError` naming the variable, found when the ``gearfe``
command starts (:func:`picture_settings` is called before any work) and exit status 2.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

from tca.errors import InputError

__all__ = ["SAMPLES", "DPI_SCALE", "PNG_COMPRESSION", "PictureSettings", "picture_settings", "apply_samples",
           "write_png"]

SAMPLES = "GEARFE_RENDER_SAMPLES"
DPI_SCALE = "GEARFE_PLOT_DPI_SCALE"
PNG_COMPRESSION = "GEARFE_PNG_COMPRESSION"
_SAMPLE_COUNTS = (0, 1, 2, 4, 8)


@dataclass(frozen=True)
class PictureSettings:
    """MSAA samples of the VTK images, the dpi factor of the plots and the PNG zlib level (module docstring)."""

    samples: int = 8
    dpi_scale: float = 1.0
    png_compression: int = 6

    def __post_init__(self):
        if self.samples not in _SAMPLE_COUNTS:
            raise InputError(SAMPLES, self.samples, "one of 0, 1, 2, 4, 8 (samples per pixel)")
        if not (math.isfinite(self.dpi_scale) and 0.25 <= self.dpi_scale <= 4.0):
            raise InputError(DPI_SCALE, self.dpi_scale, "a number in [0.25, 4]")
        if self.png_compression not in range(10):
            raise InputError(PNG_COMPRESSION, self.png_compression, "an integer in [0, 9] (zlib level)")

    def dpi(self, dpi: float) -> int:
        """A plot's resolution [dots per inch] scaled by ``dpi_scale`` (at least 10)."""
        return max(10, round(dpi * self.dpi_scale))


def _number(name: str, kind, valid: str):
    env = os.environ.get(name)
    if env is None:
        return None
    try:
        return kind(env)
    except ValueError:
        raise InputError(name, env, valid) from None


def picture_settings() -> PictureSettings:
    """The settings of the environment (module docstring); a variable not set keeps its default."""
    given = {"samples": _number(SAMPLES, int, "one of 0, 1, 2, 4, 8 (samples per pixel)"),
             "dpi_scale": _number(DPI_SCALE, float, "a number in [0.25, 4]"),
             "png_compression": _number(PNG_COMPRESSION, int, "an integer in [0, 9] (zlib level)")}
    return PictureSettings(**{k: v for k, v in given.items() if v is not None})


def apply_samples(plotter, settings: PictureSettings | None = None):
    """Set a new pyvista plotter's multisampling (before its first render); returns the plotter."""
    s = settings or picture_settings()
    plotter.render_window.SetMultiSamples(s.samples)
    return plotter


def write_png(plotter, path: Path, settings: PictureSettings | None = None) -> Path:
    """The plotter's screenshot written as a PNG at the settings' zlib level (the plotter stays open)."""
    from PIL import Image

    s = settings or picture_settings()
    img = plotter.screenshot(None, return_img=True)
    Image.fromarray(img).save(str(path), format="png", compress_level=s.png_compression)
    return Path(path)
