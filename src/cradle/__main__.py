"""``python -m cradle``: the ``cradle`` command line (:mod:`cradle.pipeline.cli`)."""
import sys

from cradle.pipeline.cli import main

sys.exit(main())
