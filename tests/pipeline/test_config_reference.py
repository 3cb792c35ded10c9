"""docs/config-reference.md: every key of config.yaml documented, generated from the declarations."""
from pathlib import Path

from cradle.pipeline import config as cc
from cradle.pipeline.config.reference import REFERENCE_FILE, generated_schema, reference

ROOT = Path(__file__).resolve().parents[2]


def test_committed_reference_is_the_generated_one():
    """Regenerate with `python -m cradle.pipeline.config --write-reference` after changing a declaration."""
    assert (ROOT / REFERENCE_FILE).read_text(encoding="utf-8") == reference(generated_schema()) + "\n"


def test_reference_names_every_key_of_config_yaml():
    text = (ROOT / REFERENCE_FILE).read_text(encoding="utf-8")
    raw = cc.read_yaml(ROOT / "config.yaml")

    def keys(node, path):
        if isinstance(node, dict):
            for k, v in node.items():
                named = path in ("map", "homoclinic", "scenes", "figures") or \
                    path.endswith(("work-precision.scenes", "work-precision.reduced.scenes"))
                where = f"{path}.<name>" if named else (f"{path}.{k}" if path else k)
                yield where
                yield from keys(v, where)

    missing = sorted({k for k in keys(raw, "") if f"`{k}`" not in text and not k.endswith("<name>")})
    assert not missing, missing
