"""Picture settings from the environment (pipelines/render/settings.py): defaults are today's look, bad values are
refused by name before any work, and each setting does what it says (samples, dpi, lossless PNG level)."""

import matplotlib.image as mpimg
import numpy as np
import pytest
import pyvista as pv

from pipelines.cli import main
from pipelines.render.plots import plt, savefig
from pipelines.render.settings import (DPI_SCALE, PNG_COMPRESSION, SAMPLES, PictureSettings, apply_samples,
                                       picture_settings, write_png)
from tca.errors import InputError

from tests.support.shipped import shipped_data, write_case


@pytest.fixture
def unset(monkeypatch):
    """No setting in the environment (the suite's own are removed for the test)."""
    for name in (SAMPLES, DPI_SCALE, PNG_COMPRESSION):
        monkeypatch.delenv(name, raising=False)
    return monkeypatch


def test_defaults_are_pyvista_and_pillow_defaults(unset):
    s = picture_settings()
    assert s == PictureSettings(8, 1.0, 6)
    assert s.samples == pv.themes.DocumentTheme().multi_samples == 8  # pyvista's own default, with MSAA
    assert s.dpi(130) == 130


def test_environment_values_are_read(unset):
    unset.setenv(SAMPLES, "0")
    unset.setenv(DPI_SCALE, "0.5")
    unset.setenv(PNG_COMPRESSION, "1")
    s = picture_settings()
    assert (s.samples, s.dpi_scale, s.png_compression) == (0, 0.5, 1)
    assert s.dpi(130) == 65 and s.dpi(100) == 50


@pytest.mark.parametrize("name, value", [(SAMPLES, "3"), (SAMPLES, "-1"), (SAMPLES, "abc"), (SAMPLES, "8.0"),
                                         (DPI_SCALE, "0.1"), (DPI_SCALE, "nan"), (DPI_SCALE, "5"), (DPI_SCALE, "x"),
                                         (PNG_COMPRESSION, "10"), (PNG_COMPRESSION, "-1"), (PNG_COMPRESSION, "1.5")])
def test_bad_values_name_the_variable(unset, name, value):
    unset.setenv(name, value)
    with pytest.raises(InputError) as e:
        picture_settings()
    assert e.value.field == name


def test_cli_refuses_a_bad_setting_before_any_work(unset, tmp_path, capsys):
    case = write_case(tmp_path, "pair", shipped_data("part1_sun_planet"))
    unset.setenv(SAMPLES, "3")
    out = tmp_path / "out"
    assert main(["tca", str(case), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and SAMPLES in err[0] and "0, 1, 2, 4, 8" in err[0]
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == [case.name]


def test_samples_reach_the_render_window(unset):
    for n in (0, 8):
        unset.setenv(SAMPLES, str(n))
        p = apply_samples(pv.Plotter(off_screen=True, window_size=[64, 48]))
        try:
            assert p.render_window.GetMultiSamples() == n
        finally:
            p.close()


def test_png_level_is_lossless_and_samples_only_soften_edges(unset, tmp_path):
    """Same pixels at zlib level 1 and 6; without MSAA the same picture but for the edges of the sphere."""
    shots = {}
    for n, level in ((8, 6), (8, 1), (0, 1)):
        unset.setenv(SAMPLES, str(n))
        unset.setenv(PNG_COMPRESSION, str(level))
        p = apply_samples(pv.Plotter(off_screen=True, window_size=[200, 150]))
        try:
            p.set_background("white")
            p.add_mesh(pv.Sphere(), color="red")
            shots[n, level] = write_png(p, tmp_path / f"s{n}_{level}.png")
        finally:
            p.close()
    a, b, c = (mpimg.imread(str(shots[k])) for k in ((8, 6), (8, 1), (0, 1)))
    assert a.shape == b.shape == c.shape == (150, 200, 3)
    assert np.array_equal(a, b)
    assert shots[8, 1].stat().st_size > shots[8, 6].stat().st_size  # level 1: larger file, same pixels
    differ = np.any(np.abs(a - c) > 0.02, axis=-1)
    assert 0 < differ.mean() < 0.05  # only edge pixels change


def test_plot_dpi_scale_scales_the_pixels_not_the_layout(unset, tmp_path):
    sizes = {}
    for scale in ("1", "0.5"):
        unset.setenv(DPI_SCALE, scale)
        fig, ax = plt.subplots(figsize=(4, 3))
        ax.plot([0, 1], [0, 1])
        sizes[scale] = mpimg.imread(str(savefig(fig, tmp_path / f"p{scale}.png", dpi=100, tight=False))).shape[:2]
    assert sizes == {"1": (300, 400), "0.5": (150, 200)}
