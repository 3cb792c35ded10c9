"""The spec a stored file of a scene was computed from, rebuilt from the file itself."""
from __future__ import annotations

import json
from typing import TYPE_CHECKING

from cradle.scenes.spec import Scene
from cradle.specs.declare import from_plain
from cradle.specs.values import ConfigError

if TYPE_CHECKING:
    import xarray as xr


def scene_of(ds: xr.Dataset) -> Scene:
    """The resolved :class:`Scene` that produced ``ds`` (a scene's initial, exact, dps or metrics Dataset),
    from its ``parameters`` attribute, validated as it is rebuilt."""
    name = ds.attrs.get("scene", "?")
    text = ds.attrs.get("parameters")
    if text is None:
        raise ConfigError(f"config error: scene {name!r}: its file stores no parameters (written by an older "
                          f"cradle): rebuild it")
    return from_plain(Scene, json.loads(text), where=f"scenes.{name}")
