"""Rendering: every plot and image of the pipelines. Matplotlib plots of TCA results and the one
``savefig`` (:mod:`.plots`), maps of FE fields (:mod:`.maps`), the face-gear train's figures
(:mod:`.face`), the loaded TCA's (:mod:`.ltca`), a stress sweep through the cycle (:mod:`.sweep`);
off-screen pyvista images of FE results (:mod:`.images`, :mod:`.views`); HTML pages (:mod:`.html`); how pictures are
rendered and written (anti-aliasing samples, plot resolution, PNG compression: :mod:`.settings`, from the
environment, defaults the pictures' usual look).

Nothing here changes global state at import. Without a display call :func:`offscreen` once before
rendering (the ``gearfe`` command and the test suite do)::

    from pipelines.render import offscreen
    offscreen()
"""

from __future__ import annotations

import os

__all__ = ["offscreen", "EGL_WINDOW"]

EGL_WINDOW = "vtkEGLRenderWindow"


def offscreen() -> None:
    """Render without a display: VTK's EGL window (unless the environment names another) and pyvista off screen.

    Call it before the first plotter is made: VTK reads ``VTK_DEFAULT_OPENGL_WINDOW`` when it creates
    a render window, not at import. Idempotent.
    """
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", EGL_WINDOW)
    import pyvista as pv

    pv.OFF_SCREEN = True
