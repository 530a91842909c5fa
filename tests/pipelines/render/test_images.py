"""Off-screen rendering: real images (not blank), labelled scalar bar, plotters freed."""

import numpy as np

from fem.mesh.hexmesh import HexMesh
from pipelines.render.images import Scalars, Zone, image_is_blank, render_contact_zone, render_overview, to_pyvista


def box_mesh(n=6):
    x = np.linspace(0, 10, n + 1)
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    pts = np.stack([X.ravel(), Y.ravel(), Z.ravel()], -1)
    idx = np.arange(len(pts)).reshape(n + 1, n + 1, n + 1)
    c = idx[:-1, :-1, :-1].ravel()
    dx, dy, dz = idx[1, 0, 0], idx[0, 1, 0], idx[0, 0, 1]
    cells = np.stack([c, c + dx, c + dx + dy, c + dy, c + dz, c + dx + dz, c + dx + dy + dz, c + dy + dz], -1)
    return HexMesh(pts, cells, np.zeros(len(cells), int))


def test_renders_stress_images_that_are_not_blank(tmp_path):
    m = box_mesh()
    vm = np.linalg.norm(m.points - [10, 10, 10], axis=1) * 30.0  # a smooth synthetic "stress" [MPa]
    grid = to_pyvista(m, {"von_mises": vm})
    a = render_contact_zone(grid, tmp_path / "zone.png", Zone([10, 10, 10], [1, 1, 1], 4.0), Scalars("von_mises"),
                            caption="test")
    b = render_overview(grid, "von_mises", tmp_path / "all.png")
    for p in (a, b):
        assert p.stat().st_size > 20_000
        assert not image_is_blank(p)
    from pyvista.plotting.plotter import _ALL_PLOTTERS

    assert len(_ALL_PLOTTERS) == 0  # every plotter was closed


def test_blank_image_is_detected(tmp_path):
    import matplotlib.image as mpimg

    mpimg.imsave(tmp_path / "white.png", np.ones((50, 50, 3)))
    assert image_is_blank(tmp_path / "white.png")
