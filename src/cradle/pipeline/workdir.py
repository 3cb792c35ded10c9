"""A fresh folder that runs a checkout's workflow: for builds beside the checkout (the tests' and benchmarks'
builds from scratch, a researcher's variant of the config in a folder of its own)."""
from __future__ import annotations

import shutil
from pathlib import Path


def copy_workflow(root: str | Path, dest: str | Path, *, config: str | None = None, profiles: bool = True) -> Path:
    """Make ``dest`` (it must not exist) a workflow folder of the checkout ``root``: its ``Snakefile`` and
    ``workflow/`` copied, ``profiles/`` too unless ``profiles=False``, ``config.yaml`` copied (or written
    from the text ``config``), and ``src`` linked to the checkout's (the code stamps of the jobs are read
    from the workflow's ``src``). Returns ``dest``."""
    root, dest = Path(root), Path(dest)
    dest.mkdir(parents=True)
    shutil.copy(root / "Snakefile", dest)
    shutil.copytree(root / "workflow", dest / "workflow")
    if profiles:
        shutil.copytree(root / "profiles", dest / "profiles")
    if config is None:
        shutil.copy(root / "config.yaml", dest)
    else:
        (dest / "config.yaml").write_text(config)
    (dest / "src").symlink_to((root / "src").resolve())
    return dest
