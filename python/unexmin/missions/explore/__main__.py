"""python -m unexmin.missions.explore ... (docs/explore.md)."""

import sys

from unexmin.missions.explore.cli import main

sys.exit(main())
