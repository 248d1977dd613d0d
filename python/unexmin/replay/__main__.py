"""python -m unexmin.replay BAG --out DIR ... (docs/replay.md)."""

import sys

from unexmin.replay.cli import main

sys.exit(main())
