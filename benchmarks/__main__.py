"""``python -m benchmarks``: run every benchmark area (see :mod:`benchmarks`)."""

from benchmarks import main

raise SystemExit(main())
