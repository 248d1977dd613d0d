"""python -m unexmin.worlds.generator --out DIR ... (docs/mine_world.md)."""

import sys

from unexmin.worlds.generator.generator import main

sys.exit(main())
