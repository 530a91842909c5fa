"""Reports of load cases: one case end to end with its images and ``report.md`` (:mod:`.run`)."""

__all__: list[str] = []
