"""python -m unexmin.mine_generator --out DIR ... (docs/mine_world.md)."""

import sys

from unexmin.mine_generator.generator import main

sys.exit(main())
