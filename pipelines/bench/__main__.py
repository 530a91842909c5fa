"""``python -m pipelines.bench``: run every benchmark area (see :mod:`pipelines.bench`)."""

from pipelines.bench import main

raise SystemExit(main())
