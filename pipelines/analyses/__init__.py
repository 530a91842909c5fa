"""The TCA analyses behind ``gearfe tca``, one module per case kind, each with ``run(case, out) -> summary``."""

__all__: list[str] = []
