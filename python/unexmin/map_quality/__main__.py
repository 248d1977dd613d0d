"""python -m unexmin.map_quality MAP.bt --world WORLD --out DIR ... (docs/mapping.md)."""

import sys

from unexmin.map_quality.cli import main

sys.exit(main())
