"""The one error a scene's stages raise when they computed something they must not hand on."""
from __future__ import annotations

import xarray


class StageFailure(RuntimeError):
    """A stage computed something it must not hand on; ``partial`` keeps it for diagnosis."""

    def __init__(self, message: str, partial: xarray.Dataset | None = None):
        super().__init__(message)
        self.partial = partial
