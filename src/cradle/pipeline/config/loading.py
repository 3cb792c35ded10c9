"""Reading config files (a key given twice refused with its line) and the command line.

``python -m cradle.pipeline.config [config.yaml]`` validates a file; with
``--scene``/``--homoclinic``/``--map NAME`` it prints that entry's resolved
parameters (what its job receives, and what the ``params_sha256`` of its files
hashes); ``--write-schema`` regenerates config.schema.json.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import yaml

from cradle.specs.declare import plain
from cradle.specs.values import ConfigError

from .resolve import homoclinic, map_entry, scene
from .sections import SECTIONS
from .validate import validate


class StrictLoader(yaml.SafeLoader):
    """PyYAML's safe loader, refusing a key given twice in one mapping (PyYAML keeps the last silently)."""

    def construct_mapping(self, node, deep=False):
        if isinstance(node, yaml.MappingNode):
            self.flatten_mapping(node)
            seen: dict[object, int] = {}   # key -> line of its first occurrence
            for key_node, _ in node.value:
                key = self.construct_object(key_node, deep=True)
                try:
                    first = seen.setdefault(key, key_node.start_mark.line + 1)
                except TypeError:   # an unhashable key: construct_mapping reports it
                    continue
                if first != key_node.start_mark.line + 1:
                    raise ConfigError(f"config error: {self.name}: line {key_node.start_mark.line + 1}: key {key!r} "
                                      f"given twice in one mapping (first on line {first}); YAML would silently "
                                      f"keep the last")
        return super().construct_mapping(node, deep=deep)


def read_yaml(path) -> dict:
    """The mapping of a YAML config file, read with :class:`StrictLoader` (ConfigError on any problem)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ConfigError(f"config error: cannot read {str(path)!r}: {err.strerror}") from None
    try:
        loader = StrictLoader(text)
        loader.name = str(path)
        try:
            return loader.get_single_data()
        finally:
            loader.dispose()
    except yaml.YAMLError as err:
        raise ConfigError(f"config error: {path}: not valid YAML: {' '.join(str(err).split())}") from None


def load(path) -> dict:
    """Read a YAML config file (duplicate keys refused) and :func:`validate` it."""
    return validate(read_yaml(path))


def main(argv=None) -> int:
    """``python -m cradle.pipeline.config [config.yaml] [--scene|--homoclinic|--map NAME] [--write-schema]``.

    Validates the config (exit status 1 and one line per problem on stderr if
    it is bad); with a NAME, prints that entry's resolved parameters as JSON.
    """
    import argparse

    parser = argparse.ArgumentParser(prog="python -m cradle.pipeline.config",
                                     description=main.__doc__.splitlines()[0] if main.__doc__ else None)
    parser.add_argument("config", nargs="?", default="config.yaml")
    parser.add_argument("--write-schema", action="store_true",
                        help="regenerate src/cradle/pipeline/config.schema.json from the declarations and exit")
    parser.add_argument("--write-reference", action="store_true",
                        help="regenerate docs/config-reference.md (every key documented) from the declarations "
                             "and exit")
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--scene", metavar="NAME")
    group.add_argument("--homoclinic", metavar="NAME")
    group.add_argument("--map", metavar="NAME")
    args = parser.parse_args(argv)
    if args.write_schema:
        from .reference import write_schema

        print(f"wrote {write_schema()}")
        return 0
    if args.write_reference:
        from .reference import REFERENCE_FILE, generated_schema, reference

        REFERENCE_FILE.write_text(reference(generated_schema()) + "\n", encoding="utf-8")
        print(f"wrote {REFERENCE_FILE}")
        return 0
    try:
        cfg = load(args.config)
        if args.scene:
            print(json.dumps(plain(scene(cfg, args.scene)), indent=1))
        elif args.homoclinic:
            print(json.dumps(plain(homoclinic(cfg, args.homoclinic)), indent=1))
        elif args.map:
            print(json.dumps(plain(map_entry(cfg, args.map)), indent=1))
        else:
            counts = ", ".join(f"{len(cfg.get(s) or {})} {s}" for s in (*SECTIONS, "figures"))
            print(f"{args.config}: OK ({counts})")
    except ConfigError as err:
        print(err, file=sys.stderr)
        return 1
    return 0


