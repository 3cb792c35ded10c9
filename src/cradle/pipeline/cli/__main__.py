"""``python -m cradle.pipeline.cli``: the same as ``python -m cradle``."""
import sys

from cradle.pipeline.cli import main

sys.exit(main())
