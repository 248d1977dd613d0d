"""python -m unexmin.explore ... (docs/explore.md)."""

import sys

from unexmin.explore.cli import main

sys.exit(main())
