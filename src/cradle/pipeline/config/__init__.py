"""The config of the pipeline (config.yaml): its sections declared (:mod:`.sections`, :mod:`.movies`,
:mod:`cradle.scenes.spec`), read (:mod:`.loading`), validated and resolved (:mod:`.validate`, :mod:`.checks`)."""
from cradle.scenes.times import store_times
from cradle.specs.values import ANGLE_PATTERN, TIME_TOL, ConfigError, parse_angle

from .loading import StrictLoader, load, main, read_yaml
from .sections import KNOWN_FIGURES, SECTIONS
from .validate import analysis_reads, analysis_spec, assume_validated, homoclinic, map_entry, scene, typed, validate

__all__ = [
    "ConfigError", "KNOWN_FIGURES", "SECTIONS", "ANGLE_PATTERN", "TIME_TOL", "parse_angle", "validate", "store_times",
    "scene", "homoclinic", "map_entry", "analysis_reads", "analysis_spec", "load", "read_yaml", "StrictLoader", "main",
    "typed", "assume_validated",
]
