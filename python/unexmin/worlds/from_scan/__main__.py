"""python -m unexmin.worlds.from_scan SCAN --out DIR ... (docs/world_from_scan.md)."""

import sys

from unexmin.worlds.from_scan.build import main

sys.exit(main())
