"""Rendering: matplotlib plots (:mod:`.plots`) and off-screen pyvista images of FE results (:mod:`.images`)."""

__all__: list[str] = []
