"""Load cases, the `gearfe` command line, images, reports, sweeps and benchmarks."""

__all__: list[str] = []
