"""Design-review pictures (issue 17) on small synthetic data: colour ranges, lit views, maps, HTML, off-screen setup."""

import os
import subprocess
import sys

import numpy as np
import pytest

from pipelines.render.html import image, page, table
from pipelines.render.images import image_is_blank, to_pyvista
from pipelines.render.maps import (Curve, DepthMark, TriField, plot_flank_pressure, plot_root_stress, plot_section,
                                   quads_to_triangles)
from pipelines.render.views import Colouring, Frame, Mark, clip_range, deformation_scale, render_deformed, render_teeth
from tests.pipelines.render.test_images import box_mesh


def test_importing_the_renderers_changes_no_global_state():
    """Issue 16: off-screen setup is the caller's (CLI entry, tests/conftest.py), not an import side effect."""
    code = ("import os, pyvista as pv; import pipelines.render.images, pipelines.render.views; "
            "assert 'VTK_DEFAULT_OPENGL_WINDOW' not in os.environ, 'env set at import'; assert not pv.OFF_SCREEN; "
            "from pipelines.render import offscreen; offscreen(); "
            "assert os.environ['VTK_DEFAULT_OPENGL_WINDOW'] == 'vtkEGLRenderWindow' and pv.OFF_SCREEN")
    env = {k: v for k, v in os.environ.items() if k != "VTK_DEFAULT_OPENGL_WINDOW"}
    subprocess.run([sys.executable, "-c", code], check=True, env=env, timeout=120)


def test_clip_range_is_the_percentile_with_a_floor():
    v = np.arange(1001, dtype=float)  # 0..1000: the P99.5 is 995 (linear interpolation)
    cr = clip_range(v)
    assert (cr.lo, cr.hi, cr.max) == (0.0, pytest.approx(995.0), 1000.0) and cr.clipped
    assert "clipped at 995" in cr.label("von Mises [MPa]") and "max 1000" in cr.label("von Mises [MPa]")
    assert clip_range(v, floor=998.0).hi == 998.0  # a floor above the percentile wins
    assert clip_range(v, floor=5000.0).hi == 1000.0 and not clip_range(v, floor=5000.0).clipped  # never above the max
    assert clip_range(v, fixed=500.0).hi == 500.0
    assert not clip_range(v, percentile=None).clipped


def test_deformation_scale():
    u = np.array([[0.0, 0.003, 0.004], [0.0, 0.0, 0.0]])  # largest |u| = 5 um
    assert deformation_scale(u, 10.0, 0.02) == pytest.approx(0.2 / 0.005)
    assert deformation_scale(np.zeros((3, 3)), 10.0) == 1.0


def test_lit_views_render_and_free_their_plotters(tmp_path):
    m = box_mesh(4)
    x = m.points
    vm = 2000.0 * np.exp(-np.sum((x - [10, 5, 5]) ** 2, axis=1) / 4.0)  # a hot spot on the face x = 10
    grid = to_pyvista(m, {"von_mises": vm, "displacement": 1e-3 * (x - 5.0)})
    cr = clip_range(vm, 90.0)
    a = render_teeth(grid, grid, tmp_path / "teeth.png", Frame([0, 0, 1], [0, 1, 0], [1, 0, 0], (5, 5, 5)),
                     Colouring(cr, show_edges=True), marks=[Mark((10, 5, 5), (1, 0, 0), "loaded pair")], size=(600, 300))
    b = render_deformed(grid, tmp_path / "def.png", Frame([0, 0, 1], [0, 1, 0], cut=(5, 5, 5)), Colouring(cr), factor=100.0,
                        size=(400, 300))
    for p in (a, b):
        assert not image_is_blank(p)
    from pyvista.plotting.plotter import _ALL_PLOTTERS

    assert len(_ALL_PLOTTERS) == 0


def test_maps_render(tmp_path):
    # a Hertz pressure p0 sqrt(1 - (z/a)^2 - (s/b)^2) on a flat flank patch
    z, r = np.meshgrid(np.linspace(-5, 5, 21), np.linspace(30, 34, 17), indexing="ij")
    zr = np.stack([z.ravel(), r.ravel()], -1)
    idx = np.arange(zr.shape[0]).reshape(z.shape)
    quads = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], -1).reshape(-1, 4)
    p = 2000.0 * np.sqrt(np.clip(1 - (zr[:, 0] / 3) ** 2 - ((zr[:, 1] - 32) / 0.6) ** 2, 0, None))
    t = np.linspace(0, 2 * np.pi, 50)
    ell = Curve(3 * np.cos(t), 32 + 0.6 * np.sin(t), "Hertz ellipse", "-", "m")
    a = plot_flank_pressure(TriField(zr, quads_to_triangles(quads), p), tmp_path / "flank.png", curves=[ell], point=(0, 32),
                            area=(-5, 5, 30.5, 33.5), zoom=2.0)
    b = plot_section(TriField(zr, quads_to_triangles(quads), p), tmp_path / "sec.png", vmax=1000.0, point=(0, 32),
                     depth=DepthMark(0.2, (0, -1)), zoom=1.0)
    c = plot_root_stress([("tooth", [Curve(np.linspace(-5, 5, 11), np.linspace(0, 100, 11), "fillet")])], tmp_path / "r.png")
    for f in (a, b, c):
        assert not image_is_blank(f)


def test_html_is_escaped_and_embeds_images(tmp_path):
    import matplotlib.image as mpimg

    mpimg.imsave(tmp_path / "a.png", np.random.default_rng(0).random((8, 8, 3)))
    doc = page("<T>", table([{"k": "<b>", "v": 1.23456789}]), image(tmp_path / "a.png", "cap & more"))
    assert "&lt;T&gt;" in doc and "&lt;b&gt;" in doc and "1.235" in doc and "cap &amp; more" in doc
    assert doc.count("data:image/png;base64,") == 1
    assert "missing image" in image(tmp_path / "none.png")
