"""Declaration of ``movies:`` (``cradle animate``, target ``movies``): drawn from stored runs, no scene's
parameters."""
from __future__ import annotations

from cradle.analyses.desk_toy_minute_movie import MinuteMovie
from cradle.analyses.desk_toy_movie import SlowMotion
from cradle.specs.declare import declared, param, schema_doc
from cradle.specs.values import ConfigError, did_you_mean

_NAMES = {"$ref": "#/$defs/name"}


@declared(doc="Movies of scenes' exact and DpS runs side by side (cradle.figures.movie) -> "
              "results/movies/<scene>.mp4 and .gif; target `movies` builds one for every scene listed here.")
class Movies:
    scenes: list[str] = param([], "Scenes (names under scenes:) the target `movies` animates; any scene can be "
                              "asked for by its file results/movies/<scene>.mp4.", maxItems=40, items=_NAMES)
    fps: int = param(25, "Frames per second of the MP4.", minimum=1, maximum=60)
    duration: float = param(20.0, "Length of the MP4 in seconds: fps * duration stored states, evenly spaced over "
                            "the run (every stored state if there are fewer); a long run is subsampled.",
                            exclusiveMinimum=0, maximum=600)
    width: int = param(1280, "Frame width in pixels (even).", minimum=64, maximum=3840, multipleOf=2)
    height: int = param(720, "Frame height in pixels (even).", minimum=64, maximum=2160, multipleOf=2)
    gif_fps: int = param(10, "Frames per second of the small GIF (results/movies/<scene>.gif).", minimum=1,
                         maximum=30)
    gif_duration: float = param(8.0, "Length of the GIF in seconds (over the whole run, as the MP4).",
                                exclusiveMinimum=0, maximum=60)
    gif_width: int = param(480, "Width of the GIF in pixels (its frames are the MP4's, scaled down).", minimum=64,
                           maximum=1280)
    desk_toy: SlowMotion = param(SlowMotion(), schema_doc(SlowMotion))
    desk_toy_minute: MinuteMovie = param(MinuteMovie(), schema_doc(MinuteMovie))

    @staticmethod
    def resolve(cfg: dict) -> dict:
        """``movies``, every name of ``scenes`` an existing scene (checked when the target is built)."""
        spec = dict(cfg.get("movies") or {})
        scenes = cfg.get("scenes") or {}
        for i, name in enumerate(spec.get("scenes") or []):
            if name not in scenes:
                raise ConfigError(f"config error: movies.scenes[{i}] = {name!r}: unknown scene: no `scenes:` entry "
                                  f"of that name{did_you_mean(name, scenes)}")
        return spec
