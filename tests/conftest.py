"""Test-session setup: images are rendered off screen (EGL, no display), as the ``gearfe`` command does."""

from pipelines.render import offscreen

offscreen()
