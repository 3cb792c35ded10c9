"""The config of the pipeline (config.yaml), declared once and typed.

- :mod:`.spec`: the declaration helpers (:func:`.spec.param`) and the JSON Schema generator;
- :mod:`.scenes`, :mod:`.sections`, :mod:`.beyond`: each
  section and each kind of initial condition as a frozen dataclass, with the checks the schema
  cannot express as its ``check`` method and, for the analyses, its ``resolve`` method;
- :mod:`.validate`: coercion of strings, one-line messages, defaults; :mod:`.loading`: reading
  files (a YAML key given twice refused) and the command line; :mod:`.resolve`: the resolved
  parameters of one entry (:func:`scene`, :func:`homoclinic`, :func:`map_entry`: typed instances) or
  analysis, and :func:`typed`, the config as frozen instances.

``python -m cradle.pipeline.config --write-schema`` regenerates ``config.schema.json``.
"""
from cradle.specs.values import ANGLE_PATTERN, TIME_TOL, ConfigError, parse_angle, store_times

from .loading import StrictLoader, load, main, read_yaml
from .resolve import (
    analysis_reads,
    analysis_spec,
    homoclinic,
    map_entry,
    resolved_homoclinic,
    resolved_map,
    resolved_scene,
    scene,
    typed,
)
from .sections import KNOWN_FIGURES, SECTIONS
from .validate import SCHEMA_FILE, assume_validated, generated_schema, schema, schema_path, validate, write_schema

__all__ = [
    "ConfigError", "KNOWN_FIGURES", "SECTIONS", "SCHEMA_FILE", "ANGLE_PATTERN", "TIME_TOL", "schema",
    "generated_schema", "schema_path", "write_schema", "parse_angle", "validate", "store_times", "scene", "homoclinic",
    "map_entry", "resolved_scene", "resolved_homoclinic", "resolved_map", "analysis_reads", "analysis_spec", "load",
    "read_yaml", "StrictLoader", "main", "typed", "assume_validated",
]
