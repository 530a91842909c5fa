"""Off-screen images of FE results with pyvista: stress on the contacting teeth and the whole model.

Importing this module changes no global state. Without a display, call :func:`offscreen` once
before rendering (the ``gearfe`` command and the test suite do): it selects VTK's EGL render
window (Mesa, software; no attempt at an X server and no warning) and pyvista's off-screen mode.
Every plotter here is created off screen and closed after its screenshot, so sweeps can render
many images.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pyvista as pv

from fem.mesh.hexmesh import HexMesh
from tca.errors import InputError

from pipelines.render import offscreen
from pipelines.render.settings import apply_samples, write_png

__all__ = ["offscreen", "to_pyvista", "Zone", "Scalars", "render_contact_zone", "render_overview", "image_is_blank"]

SCALAR_BAR = dict(title_font_size=24, label_font_size=22, n_labels=6, fmt="%.0f", vertical=True,
                  position_x=0.84, position_y=0.12, height=0.72, width=0.05, background_color="white", fill=True)


def to_pyvista(mesh: HexMesh, point_data: dict | None = None, cell_data: dict | None = None) -> pv.UnstructuredGrid:
    """A pyvista grid of a hexahedral mesh with named point and cell fields."""
    grid = pv.UnstructuredGrid({pv.CellType.HEXAHEDRON: mesh.cells}, mesh.points)
    grid.cell_data["body"] = mesh.cell_body
    for k, v in (point_data or {}).items():
        v = np.asarray(v)
        if len(v) != mesh.n_points:
            raise InputError(f"point_data.{k}", v.shape, f"length {mesh.n_points}")
        grid.point_data[k] = v
    for k, v in (cell_data or {}).items():
        grid.cell_data[k] = np.asarray(v)
    return grid


@dataclass(frozen=True)
class Zone:
    """A contact zone seen by the camera: on ``focus`` [mm], looking along -``normal``; the cells within
    about 3 ``radius`` [mm] of the focus are drawn."""

    focus: tuple
    normal: tuple
    radius: float


@dataclass(frozen=True)
class Scalars:
    """The point field drawn, its scalar-bar title and colour range ``clim`` (None: the field's range)."""

    field: str
    title: str = "von Mises stress [MPa]"
    clim: tuple | None = None


def _plotter(size):
    p = apply_samples(pv.Plotter(off_screen=True, window_size=list(size)))
    p.set_background("white")
    return p


def render_contact_zone(grid: pv.UnstructuredGrid, path: Path, zone: Zone, scalars: Scalars, *, size=(1600, 1100),
                        caption: str = "", show_edges: bool = True) -> Path:
    """Stress on the teeth around a contact point: camera on the zone's focus [mm], looking along -normal.

    Only cells within ~3 radius of the focus are drawn (the contacting teeth), coloured by the
    point field of ``scalars``, with a labelled scalar bar; its ``clim`` fixes the colour range (to compare
    images); ``show_edges`` draws the element edges (off for fine meshes, where they hide the colours).
    Returns the PNG path.
    """
    field, title, clim, radius = scalars.field, scalars.title, scalars.clim, zone.radius
    if field not in grid.point_data:
        raise InputError("field", field, "a point field of the result: " + ", ".join(grid.point_data))
    focus = np.asarray(zone.focus, float)
    normal = np.asarray(zone.normal, float)
    normal = normal / np.linalg.norm(normal)
    centers = grid.cell_centers().points
    near = np.flatnonzero(np.linalg.norm(centers - focus, axis=1) < 3 * radius)
    sub = grid.extract_cells(near) if len(near) else grid
    p = _plotter(size)
    try:
        p.add_mesh(sub, scalars=field, cmap="jet", clim=clim, show_edges=show_edges, edge_color="#595959", line_width=0.3,
                   scalar_bar_args={**SCALAR_BAR, "title": title})
        if caption:
            p.add_text(caption, position="upper_left", font_size=11, color="black")
        up = np.cross(normal, [0.0, 0.0, 1.0])
        if np.linalg.norm(up) < 1e-6:
            up = np.array([0.0, 1.0, 0.0])
        p.camera.focal_point = focus
        p.camera.position = focus + normal * radius * 4.0
        p.camera.up = np.cross(up, normal)
        p.camera.view_angle = 2 * np.degrees(np.arctan(1.15 * radius / (4.0 * radius)))
        write_png(p, path)
    finally:
        p.close()
    return Path(path)


def render_overview(grid: pv.UnstructuredGrid, field: str, path: Path, *, title: str = "von Mises stress [MPa]",
                    clim=None, size=(1600, 1100), caption: str = "", cut=None) -> Path:
    """The whole model coloured by `field`, isometric view, lit; values above ``clim`` in magenta.

    ``cut = (point, normal)`` [mm]: the half of the model on the normal's side of that plane is left
    out (the loads are inside: a cut through a contact point shows it and the fillets).
    """
    if field not in grid.point_data:
        raise InputError("field", field, "a point field of the result: " + ", ".join(grid.point_data))
    if cut is not None:
        point, normal = (np.asarray(x, float) for x in cut)
        grid = grid.clip(normal=normal, origin=point, invert=True)
    p = _plotter(size)
    try:
        above = clim is not None and float(np.nanmax(grid.point_data[field], initial=0.0)) > clim[1]
        p.add_mesh(grid.extract_surface(algorithm="dataset_surface"), scalars=field, cmap="jet", clim=clim, show_edges=False,
                   smooth_shading=True, split_sharp_edges=True, specular=0.25, above_color="magenta" if above else None,
                   scalar_bar_args={**SCALAR_BAR, "title": title, **({"above_label": "above"} if above else {})})
        if caption:
            p.add_text(caption, position="upper_left", font_size=11, color="black")
        if cut is not None:  # from the cut's side
            p.view_vector(tuple(normal + 0.6 * np.cross(normal, [1.0, 0.0, 0.0]) + 0.3 * np.cross(normal, [0.0, 1.0, 0.0])))
        else:
            p.view_isometric()
        p.reset_camera()
        write_png(p, path)
    finally:
        p.close()
    return Path(path)


def image_is_blank(path: Path, min_colored: float = 0.02) -> bool:
    """True when a screenshot is (almost) uniform: less than `min_colored` of pixels off the background."""
    import matplotlib.image as mpimg

    img = mpimg.imread(str(path))[..., :3]
    bg = img[0, 0]
    off = np.any(np.abs(img - bg) > 0.05, axis=-1)
    return bool(off.mean() < min_colored)
