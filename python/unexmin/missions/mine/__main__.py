"""python -m unexmin.missions.mine ... (docs/mapping.md, "The mission")."""

import sys

from unexmin.missions.mine.cli import main

sys.exit(main())
