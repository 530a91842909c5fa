"""``python -m pipelines.cli``: the ``gearfe`` command line."""

import sys

from pipelines.cli import main

sys.exit(main())
