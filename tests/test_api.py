"""The public API a researcher finds with ``dir(cradle)`` and ``help(cradle)``: every name resolves, is documented
and listed with a one-line summary; ``import cradle`` stays light; the README's Python example runs."""
from __future__ import annotations

import pydoc
import re
import subprocess
import sys
from pathlib import Path

import numpy as np

import cradle

ROOT = Path(__file__).resolve().parents[1]
PUBLIC = [name for name in cradle.__all__ if name != "__version__"]


def test_import_is_light_and_dir_lists_the_api():
    code = ("import sys, cradle; names = dir(cradle); help_text = cradle.__doc__; "
            "print(sorted(m for m in ('numpy', 'xarray', 'numba', 'scipy', 'matplotlib') if m in sys.modules)); "
            "print(' '.join(names))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.splitlines()
    assert out[0] == "[]", f"import cradle loaded {out[0]}"
    assert set(cradle.__all__) <= set(out[1].split())


def test_every_public_name_resolves_and_has_a_docstring():
    for name in PUBLIC:
        obj = getattr(cradle, name)
        doc = getattr(obj, "__doc__", None) or ""
        # a dataclass without a docstring gets its signature as __doc__
        assert doc.strip() and not doc.startswith(f"{getattr(obj, '__name__', name)}("), f"{name}: no docstring"


def test_help_lists_every_public_name_with_a_one_line_summary():
    text = pydoc.render_doc(cradle, renderer=pydoc.plaintext)
    rows = dict(re.findall(r"^ {4,}(\w+) {2,}(\S[^\n]*)$", text, flags=re.M))
    for name in PUBLIC:
        assert name in rows and len(rows[name].split()) >= 3, f"help(cradle) gives no one-line summary of {name}"
    # the table of the docstring is the API, in the order of __all__
    table = re.findall(r"^ {4}(\w+) {2,}\S", cradle.__doc__, flags=re.M)
    assert table == PUBLIC


def _readme_example() -> str:
    text = (ROOT / "README.md").read_text()
    section = text.split("## Python: your own initial data, both models", 1)[1].split("\n## ", 1)[0]
    return re.search(r"```python\n(.*?)```", section, flags=re.S).group(1)


def test_readme_example_runs_and_gives_one_dataset_of_both_models():
    ns: dict = {}
    exec(compile(_readme_example(), "README.md", "exec"), ns)
    ds, lattice, dps, data = ns["ds"], ns["lattice"], ns["dps"], ns["data"]
    assert list(ds["model"].values) == ["exact", "dps"] and ds["x"].dims == ("model", "t", "n")
    np.testing.assert_array_equal(ds["x"].sel(model="exact").values, lattice.x)
    x_app = cradle.approximate_displacement(dps.A, ns["t"], data.eps)
    np.testing.assert_array_equal(ds["x"].sel(model="dps").values, x_app)
    np.testing.assert_array_equal(ds["E"].values, cradle.relative_error(lattice.x, x_app, data.info["a"]))
    assert ds["spectrum"].dims == ("model", "t", "k") and ds["k"].size == lattice.x.shape[1]
