"""Reading config files (bounded in size, UTF-8, a key given twice refused with its line) and the command line
``python -m cradle.pipeline.config``."""
from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any

import yaml

from cradle.specs.declare import plain
from cradle.specs.values import CONFIG_MAX_BYTES, CONFIG_MAX_DEPTH, CONFIG_MAX_VALUES, ConfigError

from .sections import SECTIONS
from .validate import homoclinic, map_entry, scene, validate


def _line(event: yaml.Event) -> int:
    return event.start_mark.line + 1 if event.start_mark is not None else 0


def _bounded(text: str, name: str) -> None:
    """Refuse ``text`` holding too many values (aliases expanded) or nested too deep, from the parser's events
    (never building the values)."""
    sizes: dict[str | None, int] = {}   # anchor -> number of values it stands for
    open_: list[tuple[str | None, int]] = []   # (anchor, count at its start) of each open mapping or list
    count = 0
    for event in yaml.parse(text, Loader=_Parser):
        if isinstance(event, yaml.AliasEvent):
            count += sizes.get(event.anchor, 1)
        elif isinstance(event, (yaml.ScalarEvent, yaml.CollectionStartEvent)):
            count += 1
            if isinstance(event, yaml.CollectionStartEvent):
                open_.append((event.anchor, count))
                if len(open_) > CONFIG_MAX_DEPTH:
                    raise ConfigError(f"config error: {name}: line {_line(event)}: nested more than "
                                      f"{CONFIG_MAX_DEPTH} deep (mappings and lists)")
            elif event.anchor is not None:
                sizes[event.anchor] = 1
        elif isinstance(event, yaml.CollectionEndEvent):
            anchor, start = open_.pop()
            if anchor is not None:
                sizes[anchor] = count - start + 1
        if count > CONFIG_MAX_VALUES:
            raise ConfigError(f"config error: {name}: line {_line(event)}: more than {CONFIG_MAX_VALUES} "
                              f"values (aliases counted as the values they stand for); a config holds a few "
                              f"thousand")


_Parser = getattr(yaml, "CSafeLoader", yaml.SafeLoader)   # libyaml's parser when PyYAML has it: ~20x faster


class StrictLoader(_Parser):   # type: ignore[valid-type, misc]
    """PyYAML's safe loader, refusing a key given twice in one mapping (merge keys ``<<: *base`` honoured)."""

    def construct_yaml_int(self, node: yaml.ScalarNode) -> Any:
        """An integer as PyYAML reads it; one past Python's limit of digits (a ValueError from deep inside the
        loader) said as the YAML error it is, with its line."""
        try:
            return super().construct_yaml_int(node)
        except ValueError:
            digits = sum(c.isdigit() for c in str(node.value))
            raise yaml.constructor.ConstructorError(
                None, None, f"an integer of {digits} digits: no config number needs more than a few (Python reads "
                            f"at most {sys.get_int_max_str_digits()})", node.start_mark) from None

    def construct_document(self, node: yaml.Node) -> Any:
        self._check_keys(node, set())
        return super().construct_document(node)

    def _check_keys(self, node: yaml.Node, done: set) -> None:
        """Each mapping under ``node`` (each once) refused if one of its own keys is given twice."""
        if id(node) in done:
            return
        done.add(id(node))
        if isinstance(node, yaml.MappingNode):
            seen: dict[object, yaml.Mark] = {}   # key -> where it was first given
            for key_node, value_node in node.value:
                self._check_keys(value_node, done)
                if key_node.tag == "tag:yaml.org,2002:merge" or not isinstance(key_node, yaml.ScalarNode):
                    continue
                key = self.construct_object(key_node)
                try:
                    first = seen.setdefault(key, key_node.start_mark)
                except TypeError:   # an unhashable key: construct_mapping reports it
                    continue
                if first is not key_node.start_mark:
                    at = key_node.start_mark
                    where = f"the same line, column {first.column + 1}" if first.line == at.line else \
                        f"line {first.line + 1}"
                    raise ConfigError(f"config error: {self.name}: line {at.line + 1}: key {key!r} given twice in "
                                      f"one mapping (first on {where}); YAML would silently keep the last")
        elif isinstance(node, yaml.SequenceNode):
            for item in node.value:
                self._check_keys(item, done)


StrictLoader.add_constructor("tag:yaml.org,2002:int", StrictLoader.construct_yaml_int)


def read_yaml(path: str | os.PathLike) -> dict:
    """The mapping of a YAML config file (ConfigError: not UTF-8, too large, too many values or too deep, a key
    given twice)."""
    path = Path(path)
    try:
        with path.open("rb") as f:
            data = f.read(CONFIG_MAX_BYTES + 1)
    except OSError as err:
        raise ConfigError(f"config error: cannot read {str(path)!r}: {err.strerror}") from None
    if len(data) > CONFIG_MAX_BYTES:
        raise ConfigError(f"config error: {path}: larger than {CONFIG_MAX_BYTES} bytes; a config is a few tens of kB")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        line = data[:err.start].count(b"\n") + 1
        raise ConfigError(f"config error: {path}: line {line}: byte {data[err.start]:#04x} is not UTF-8 text "
                          f"({err.reason}); save the file as UTF-8") from None
    try:
        _bounded(text, str(path))
        loader = StrictLoader(text)
        loader.name = str(path)
        try:
            return loader.get_single_data()
        finally:
            loader.dispose()
    except yaml.YAMLError as err:
        raise ConfigError(f"config error: {path}: not valid YAML: {' '.join(str(err).split())}") from None


def load(path: str | Path) -> dict:
    """Read a YAML config file (duplicate keys refused) and :func:`validate` it."""
    return validate(read_yaml(path))


def main(argv: list[str] | None = None) -> int:
    """Validate a config file (exit status 1 and one line per problem if it is bad); with a NAME, print that
    entry's resolved parameters as JSON."""
    import argparse

    parser = argparse.ArgumentParser(prog="python -m cradle.pipeline.config", description=main.__doc__)
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
    if args.write_schema or args.write_reference:
        from . import reference

        print(f"wrote {reference.write_schema() if args.write_schema else reference.write_reference()}")
        return 0
    try:
        cfg = load(args.config)
        for name, resolve in ((args.scene, scene), (args.homoclinic, homoclinic), (args.map, map_entry)):
            if name:
                print(json.dumps(plain(resolve(cfg, name)), indent=1))
        if not (args.scene or args.homoclinic or args.map):
            counts = ", ".join(f"{len(cfg.get(s) or {})} {s}" for s in (*SECTIONS, "figures"))
            print(f"{args.config}: OK ({counts})")
    except ConfigError as err:
        print(err, file=sys.stderr)
        return 1
    return 0


