"""``python -m cradle.pipeline.config``: validate a config file, print a resolved entry, or rewrite the schema."""
import sys

from .loading import main

sys.exit(main())
