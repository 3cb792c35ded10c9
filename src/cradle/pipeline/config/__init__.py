"""The config of the pipeline (config.yaml), declared once and typed.

- :mod:`cradle.scenes.spec`, :mod:`.sections`, :mod:`.movies`: each section and entry as a
  declared frozen dataclass (:mod:`cradle.specs.declare`), the checks across keys as its ``check`` method;
- :mod:`.validate`: the one validation pass (:mod:`cradle.specs.parse`) and the checks (:mod:`.checks`);
  :mod:`.loading`: reading files (a YAML key given twice refused) and the command line; :mod:`.resolve`: the
  typed spec of one entry or analysis;
- :mod:`.reference`: the JSON Schema and the markdown reference generated from the declarations, for
  editors and readers (``python -m cradle.pipeline.config --write-schema``, ``--write-reference``).
"""
from cradle.scenes.times import store_times
from cradle.specs.values import ANGLE_PATTERN, TIME_TOL, ConfigError, parse_angle

from .loading import StrictLoader, load, main, read_yaml
from .resolve import analysis_reads, analysis_spec, homoclinic, map_entry, scene
from .sections import KNOWN_FIGURES, SECTIONS
from .validate import assume_validated, typed, validate

__all__ = [
    "ConfigError", "KNOWN_FIGURES", "SECTIONS", "ANGLE_PATTERN", "TIME_TOL", "parse_angle", "validate", "store_times",
    "scene", "homoclinic", "map_entry", "analysis_reads", "analysis_spec", "load", "read_yaml", "StrictLoader", "main",
    "typed", "assume_validated",
]
