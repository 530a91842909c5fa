r"""Lit off-screen views of the three-tooth models, in the spirit of the report's Figs. 1.8–1.9.

Colour range. The von Mises field of a loaded gear model spans three orders of magnitude: the
Hertz peak under the contact (thousands of MPa) sits in a patch a few elements wide, the fillets
carry a few hundred MPa and the rims almost nothing. On the linear range 0…max the whole model is
one dark blue. The views therefore clip the range at a percentile :math:`P` of the nodal values
shown (:func:`clip_range`, default :data:`CLIP_PERCENTILE`), raised to a floor where needed (the
largest fillet stress × 1.1, so fillets never saturate): values above it are drawn in
:data:`ABOVE_COLOR` and the scalar bar is labelled ``clipped at ... (max ... MPa)``, so the contact
zones and the fillets are both readable and nothing is hidden.

Views (:func:`render_teeth`; directions in a :class:`Frame`, the field and its range in a
:class:`Colouring`): left, the meshing parts seen along the gear axis (parallel
projection, the loaded tooth upright); right, the loaded flank's part seen along the contact
normal from the side of the other body (cells in front of the tangent plane left out, they would
hide the flank). Smooth shading with VTK's light kit; sharp edges stay sharp
(``split_sharp_edges``); element edges on request. The loaded pair is marked by an arrow along the
contact normal at the TCA contact point.

:func:`render_deformed`: the same axial view with the displacements scaled by a factor (given in
the caption) over the undeformed outline.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pyvista as pv

from tca.errors import InputError

from pipelines.render.settings import apply_samples, write_png

__all__ = ["CLIP_PERCENTILE", "ABOVE_COLOR", "ColourRange", "clip_range", "Mark", "Frame", "Colouring", "render_teeth",
           "render_deformed", "deformation_scale"]

CLIP_PERCENTILE = 99.5  # [%] of the shown nodal values: the top of the colour range
ABOVE_COLOR = "magenta"  # values above the clipped range
_BAR = dict(title_font_size=18, label_font_size=18, n_labels=6, fmt="%.0f", vertical=True, position_x=0.88,
            position_y=0.12, height=0.72, width=0.05, color="black", background_color="white", fill=True)


@dataclass(frozen=True)
class ColourRange:
    """A colour range [MPa] and whether values above it exist (drawn in ABOVE_COLOR)."""

    lo: float
    hi: float
    max: float  # largest value shown [MPa]
    percentile: float | None  # the clipping percentile, None: not clipped

    @property
    def clipped(self) -> bool:
        return self.percentile is not None and self.max > self.hi

    def label(self, name: str) -> str:
        """Scalar-bar title: the name, and when clipped the top of the range and the largest value [MPa]."""
        if self.clipped:
            return f"{name}\nclipped at {self.hi:.0f}\n(max {self.max:.0f})"
        return name


def clip_range(values, percentile: float | None = CLIP_PERCENTILE, floor: float = 0.0,
               fixed: float | None = None) -> ColourRange:
    """Colour range 0…max(P-th percentile of the finite `values`, `floor`), at most their maximum.

    ``floor`` [MPa] keeps a value readable (the pictures pass 1.1 x the largest fillet von Mises
    stress, so the fillets never saturate whatever share of the nodes sits in unloaded rims);
    ``fixed`` gives the top directly (e.g. one range for two designs).
    """
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    vmax = float(v.max(initial=0.0))
    if fixed is not None:
        return ColourRange(0.0, float(fixed) or 1.0, vmax, percentile if vmax > fixed else None)
    if percentile is None or len(v) == 0:
        return ColourRange(0.0, vmax or 1.0, vmax, None)
    if not 50.0 <= percentile <= 100.0:
        raise InputError("percentile", percentile, "in [50, 100] %")
    hi = min(max(float(np.percentile(v, percentile)), float(floor)), vmax)
    return ColourRange(0.0, hi or vmax or 1.0, vmax, percentile if hi < vmax else None)


@dataclass(frozen=True)
class Mark:
    """An arrow at a contact point along its normal, with a label (the loaded pair)."""

    point: tuple  # [mm]
    normal: tuple  # unit vector
    label: str


@dataclass(frozen=True)
class Frame:
    """Directions of the views of meshing parts: the gear ``axis``, ``up`` (radial at the contact), the contact
    ``normal`` toward the camera of the flank view, and ``cut`` [mm], the point whose transverse plane cuts
    the axial view (None: not cut)."""

    axis: tuple
    up: tuple
    normal: tuple | None = None
    cut: tuple | None = None


@dataclass(frozen=True)
class Colouring:
    """The point field drawn, its colour range, the scalar-bar title, and whether element edges are drawn."""

    cr: ColourRange
    field: str = "von_mises"
    title: str = "von Mises [MPa]"
    show_edges: bool = False


def _unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _surface(grid: pv.UnstructuredGrid) -> pv.PolyData:
    return grid.extract_surface(algorithm="dataset_surface") if grid.n_cells else pv.PolyData()


def _add_field(p: pv.Plotter, grid, colouring: Colouring, bar: bool):
    field, cr, title, show_edges = colouring.field, colouring.cr, colouring.title, colouring.show_edges
    surf = _surface(grid)
    p.add_mesh(surf, scalars=field, cmap="jet", clim=(cr.lo, cr.hi), above_color=ABOVE_COLOR if cr.clipped else None,
               smooth_shading=True, split_sharp_edges=True, specular=0.25, specular_power=20, show_edges=show_edges,
               edge_color="#404040", line_width=0.3, show_scalar_bar=bar,
               scalar_bar_args={**_BAR, "title": cr.label(title), **({"above_label": "above"} if cr.clipped else {})})


def _add_marks(p: pv.Plotter, marks, length: float, offset=None):
    """Arrows along the marks' normals (tip at the point) and labels, shifted by `offset` [mm] from the point."""
    for m in marks:
        n = _unit(m.normal)
        x = np.asarray(m.point, float)
        p.add_mesh(pv.Arrow(start=x + n * 1.05 * length, direction=-n, scale=length, tip_length=0.3, tip_radius=0.1,
                            shaft_radius=0.035), color="black")
        p.add_mesh(pv.Sphere(radius=0.06 * length, center=x), color="black")
        at = x + (n * 1.1 * length if offset is None else np.asarray(offset, float))
        p.add_point_labels(np.array([at]), [m.label], font_size=12, text_color="black", point_size=1,
                           shape_opacity=0.6, always_visible=True, show_points=False)


def _look(p: pv.Plotter, centre, direction, up, scale: float):
    """Parallel-projection camera on `centre` looking along `direction`, `up` upright, half-height `scale` [mm]."""
    d = _unit(direction)
    up = np.asarray(up, float) - (np.asarray(up, float) @ d) * d
    p.enable_parallel_projection()
    p.camera.focal_point = tuple(centre)
    p.camera.position = tuple(np.asarray(centre) - d * 10.0 * scale)
    p.camera.up = tuple(_unit(up))
    p.reset_camera_clipping_range()
    p.camera.parallel_scale = scale
    p.renderer.camera_set = True  # keep this framing at the first render (no automatic reset)


def _half_height(grid, direction, up, aspect: float) -> float:
    """Half the height [mm] of a parallel view along `direction` (`up` upright) that shows all of a grid
    (viewport width/height `aspect`, 8 % margin)."""
    d = _unit(direction)
    u = _unit(np.asarray(up, float) - (np.asarray(up, float) @ d) * d)
    x = np.asarray(grid.points) - np.asarray(grid.center)
    ext = [np.ptp(x @ u), np.ptp(x @ np.cross(d, u))]
    return 0.54 * max(ext[0], ext[1] / aspect)


def render_teeth(parts: pv.UnstructuredGrid, flank: pv.UnstructuredGrid, path: Path, frame: Frame, colouring: Colouring, *,
                 marks=(), caption: str = "", size=(1300, 600)) -> Path:
    """Two lit views (module docstring): `parts` along the frame's axis, `flank` along -normal (camera on +normal).

    The frame's ``cut`` [mm]: a point (the contact point) whose transverse plane cuts the axial view:
    the half toward the camera is left out, so the contact zone under the surface and the fillets show.
    """
    field = colouring.field
    for g in (parts, flank):
        if g.n_cells and field not in g.point_data:
            raise InputError("field", field, "a point field of the result: " + ", ".join(g.point_data))
    if frame.normal is None:
        raise InputError("frame.normal", None, "the contact normal (the flank view looks along it)")
    axis, up, normal, cut = _unit(frame.axis), np.asarray(frame.up, float), _unit(frame.normal), frame.cut
    aspect = 0.5 * size[0] / size[1]
    p = apply_samples(pv.Plotter(off_screen=True, window_size=list(size), shape=(1, 2), border=False))
    try:
        p.set_background("white")
        p.subplot(0, 0)
        shown = parts
        if cut is not None and parts.n_cells:  # the half behind the transverse plane through the contact
            shown = parts.clip(normal=axis, origin=np.asarray(cut, float), invert=True)
        _add_field(p, shown, colouring, bar=False)
        h = _half_height(parts, axis, up, aspect)
        _add_marks(p, [Mark(m.point, tuple(_unit(np.asarray(m.normal) - (np.asarray(m.normal) @ axis) * axis)), m.label)
                       for m in marks], 0.18 * h)
        p.add_text("seen along the gear axis" + (", cut through the contact point" if cut is not None else ""),
                   position="lower_left", font_size=10, color="black")
        if caption:
            p.add_text(caption, position="upper_left", font_size=10, color="black")
        _look(p, parts.center, -axis, up, h)
        p.subplot(0, 1)
        _add_field(p, flank, colouring, bar=True)
        side = np.cross(normal, axis)
        hf = _half_height(flank, normal, axis, aspect / 1.25) if flank.n_cells else h
        p.add_text("loaded flank, along the contact normal", position="lower_left", font_size=10, color="black")
        for m in marks:  # a dot and a label beside it: an arrow along the line of sight would not show
            x = np.asarray(m.point, float)
            p.add_mesh(pv.Sphere(radius=0.012 * hf, center=x + 0.01 * hf * normal), color="black")
            p.add_point_labels(np.array([x + 0.25 * hf * side + 0.05 * hf * normal]), [m.label], font_size=12,
                               text_color="black", point_size=1, shape_opacity=0.6, always_visible=True, show_points=False)
        _look(p, flank.center if flank.n_cells else parts.center, -normal, axis, hf)
        write_png(p, path)
    finally:
        p.close()
    return Path(path)


def deformation_scale(displacement, size: float, fraction: float = 0.015) -> float:
    """Display factor making the largest displacement `fraction` of `size` [mm] (1 when nothing moves)."""
    u = float(np.linalg.norm(np.asarray(displacement, float), axis=1).max(initial=0.0))
    return fraction * size / u if u > 0 else 1.0


def render_deformed(parts: pv.UnstructuredGrid, path: Path, frame: Frame, colouring: Colouring, *, factor: float,
                    caption: str = "", size=(1000, 800)) -> Path:
    """The parts cut through the frame's ``cut`` [mm] and seen along its axis, displaced by ``displacement`` x
    `factor`, over the undeformed outline of the cut (grey)."""
    if "displacement" not in parts.point_data:
        raise InputError("field", "displacement", "a point field 'displacement' of the grid")
    if frame.cut is None:
        raise InputError("frame.cut", None, "a point [mm] whose transverse plane cuts the parts")
    field, cr, title = colouring.field, colouring.cr, colouring.title
    axis, up = _unit(frame.axis), frame.up
    cut = np.asarray(frame.cut, float)
    half = parts.clip(normal=axis, origin=cut, invert=True)
    warped = _surface(half).warp_by_vector("displacement", factor=factor)
    outline = parts.slice(normal=axis, origin=cut + 1e-3 * axis).extract_feature_edges(
        boundary_edges=True, feature_edges=False, non_manifold_edges=False, manifold_edges=False)
    p = apply_samples(pv.Plotter(off_screen=True, window_size=list(size)))
    try:
        p.set_background("white")
        p.add_mesh(warped, scalars=field, cmap="jet", clim=(cr.lo, cr.hi), above_color=ABOVE_COLOR if cr.clipped else None,
                   smooth_shading=True, split_sharp_edges=True, specular=0.25, show_edges=colouring.show_edges,
                   scalar_bar_args={**_BAR, "title": cr.label(title)})
        if outline.n_points:
            p.add_mesh(outline, color="#303030", line_width=1.5)
        p.add_text(caption or f"displacements x {factor:.3g}", position="upper_left", font_size=10, color="black")
        h = _half_height(parts, axis, up, 0.8 * size[0] / size[1])
        _look(p, np.asarray(parts.center) - 0.08 * h * np.cross(axis, _unit(up)), -axis, up, h)
        write_png(p, path)
    finally:
        p.close()
    return Path(path)
