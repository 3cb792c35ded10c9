"""``python -m cradle``: the ``cradle`` command line (:mod:`cradle.cli`)."""
import sys

from .cli import main

sys.exit(main())
