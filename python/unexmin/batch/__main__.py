"""python -m unexmin.batch SPEC.yaml --out DIR ... (docs/batch.md)."""

import sys

from unexmin.batch.run import main

sys.exit(main())
