"""python -m unexmin.identify BAG --out DIR ... (docs/identification.md)."""

import sys

from unexmin.identify.cli import main

sys.exit(main())
