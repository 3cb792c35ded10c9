"""The config of the pipeline (config.yaml), declared once and typed.

- :mod:`.spec`: the declaration helpers (:func:`.spec.param`) and the JSON Schema generator;
- :mod:`.scenes`, :mod:`.sections`, :mod:`.beyond`, :mod:`.floquet`, :mod:`.breathers`,
  :mod:`.dps_validity`: each
  section and each kind of initial condition as a frozen dataclass, with the checks the schema
  cannot express as its ``check`` method and, for the analyses, its ``resolve`` method;
- :mod:`.validate`: coercion of strings, one-line messages, defaults; :mod:`.loading`: reading
  files (a YAML key given twice refused) and the command line; :mod:`.resolve`: the resolved
  parameters of one entry or analysis, and :func:`typed`, the config as frozen instances.

``python -m cradle.pipeline.config --write-schema`` regenerates ``config.schema.json``.
"""
from .resolve import (resolved_breathers, resolved_dps_validity, resolved_floquet,
                      resolved_homoclinic, resolved_map, resolved_mi_diagram,
                      analysis_reads, analysis_spec, resolved_scene, resolved_theorem1,
                      resolved_work_precision, typed)
from .sections import KNOWN_FIGURES, SECTIONS
from cradle.specs.values import ANGLE_PATTERN
from .loading import StrictLoader, load, main, read_yaml
from .validate import SCHEMA_FILE, _VALIDATED, _validated, generated_schema, schema, schema_path, validate, write_schema
from cradle.specs.values import TIME_TOL, ConfigError, parse_angle, store_times

__all__ = [
    "ConfigError", "KNOWN_FIGURES", "SECTIONS", "SCHEMA_FILE", "ANGLE_PATTERN", "TIME_TOL", "schema",
    "generated_schema", "schema_path", "write_schema", "parse_angle", "validate", "store_times", "resolved_scene",
    "resolved_homoclinic", "resolved_map", "resolved_work_precision", "resolved_theorem1", "resolved_mi_diagram",
    "analysis_reads", "analysis_spec", "resolved_floquet", "resolved_breathers",
    "resolved_dps_validity", "load", "read_yaml", "StrictLoader", "main", "typed",
]
