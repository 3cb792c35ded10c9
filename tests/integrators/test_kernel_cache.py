"""Tests of cradle.integrators._cache: numba's compiled kernels are keyed by all their sources.

numba's own cache invalidates a kernel only when the file defining it
changes; the splitting loop of ``_splitting.py`` (with the onset correction of ``_onset.py``) calls
``_kernels.py``, so an edit of ``_kernels.py`` used to leave it stale (issue 17). The
end-to-end test edits the Hertz force in a scratch copy of the package and
checks that srkn6c follows the edit, then the restore, in fresh processes.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numba
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from cradle.integrators import _cache, _dop853, _kernels as K, _onset, _onset_impulse, _splitting
from cradle.models import lattice as L
from cradle.models.dps import amplitude_from_omega

SRC = Path(_cache.__file__).resolve().parents[2]   # the src/ folder holding cradle

#: The Hertz force of _kernels._bond (mode 0), and the same slightly scaled.
HERTZ_LINE = "return -c * math.sqrt(c), c"
HERTZ_SCALED = "return -1.0001 * c * math.sqrt(c), c"

#: A small travelling wave with contacts, x_n = a cos(Qn), v_n = a OMEGA sin(Qn), integrated to T.
N, Q, OMEGA, T = 16, np.pi / 4, 1.1, 20.0

#: One srkn6c run of the wave to t = T in a fresh process; prints what the test compares.
SCRIPT = r"""
import hashlib, json, sys
import numpy as np
from cradle.integrators import _cache, integrate_lattice
from cradle.integrators import _splitting
from cradle.models.dps import amplitude_from_omega

N, q, omega, T = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
a = amplitude_from_omega(omega, q, 1.5)
n = np.arange(N)
sol = integrate_lattice(a * np.cos(q * n), a * omega * np.sin(q * n), [0.0, T / 2, T], alpha=1.5, method="srkn6c")
state = np.concatenate([sol.x[-1], sol.v[-1]])
stats = _splitting.split_run.stats
print(json.dumps({"sha256": hashlib.sha256(state.tobytes()).hexdigest(), "state": state.tolist(),
                  "drift": float(sol.energy_drift), "onsets": int(sol.n_onset_corrections),
                  "folder": str(_cache.activate()), "hits": sum(stats.cache_hits.values()),
                  "misses": sum(stats.cache_misses.values())}))
"""


def _run(src: Path, cache: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env.update(PYTHONPATH=str(src), CRADLE_KERNEL_CACHE=str(cache))
    proc = subprocess.run([sys.executable, "-c", SCRIPT, str(N), repr(Q), repr(OMEGA), repr(T)], env=env,
                          capture_output=True, text=True, cwd=src)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _reference(scale: float) -> np.ndarray:
    """Final (x, v) of the wave under (nc) with the Hertz force times ``scale``: numpy model, scipy
    DOP853 at rtol = atol = 1e-13 (independent of the numba kernels)."""
    a = amplitude_from_omega(OMEGA, Q, 1.5)
    n = np.arange(N)

    def rhs(t, y):
        f = scale * L.bond_forces(y[:N], 1.5)
        return np.concatenate([y[N:], -y[:N] + f - np.roll(f, 1)])

    y0 = np.concatenate([a * np.cos(Q * n), a * OMEGA * np.sin(Q * n)])
    return solve_ivp(rhs, (0.0, T), y0, method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]


def test_edit_of_kernels_reaches_onset_kernels_and_restore_comes_back(tmp_path):
    """Scale the Hertz force of _kernels.py by 1.0001 in a scratch copy: srkn6c (the splitting loop of
    _splitting.py with the correction of _onset.py, calling _kernels.py) recompiles and solves the edited
    equations; restoring the text loads the first run's machine code again and gives its result bitwise."""
    src = tmp_path / "src"
    shutil.copytree(SRC / "cradle", src / "cradle", ignore=shutil.ignore_patterns("__pycache__"))
    cache = tmp_path / "kernel-cache"
    kernels = src / "cradle" / "integrators" / "_kernels.py"
    original = kernels.read_text()
    assert original.count(HERTZ_LINE) == 1
    ref, ref_scaled = _reference(1.0), _reference(1.0001)
    assert np.abs(ref_scaled - ref).max() > 1e-4       # the edit matters at this resolution

    first = _run(src, cache)
    assert first["misses"] == 1 and first["hits"] == 0           # compiled
    assert first["onsets"] > 0 and first["drift"] < 1e-9
    assert np.abs(np.array(first["state"]) - ref).max() < 1e-8

    kernels.write_text(original.replace(HERTZ_LINE, HERTZ_SCALED))
    edited = _run(src, cache)
    assert edited["misses"] == 1 and edited["hits"] == 0         # recompiled, not the stale code
    assert edited["folder"] != first["folder"]
    # the edited equations, solved consistently: stale onset kernels mixed with the new force
    # leave the state near the unscaled one and drift far above the integrator's error
    assert np.abs(np.array(edited["state"]) - ref_scaled).max() < 1e-8
    assert edited["onsets"] > 0 and edited["drift"] < 1e-9

    kernels.write_text(original)
    restored = _run(src, cache)
    assert restored["hits"] == 1 and restored["misses"] == 0      # loaded from the first run's folder
    assert restored["folder"] == first["folder"]
    assert restored["sha256"] == first["sha256"] and restored["state"] == first["state"]
    assert sorted(p.name for p in cache.iterdir()) == sorted(Path(r["folder"]).name for r in (first, edited))


# ---------------------------------------------------------------- key and location

def test_kernels_of_this_process_are_cached_in_the_keyed_folder():
    folder = _cache.activate()
    assert numba.config.CACHE_DIR == str(folder)
    assert folder.name == _cache.cache_key()[0][:_cache.KEY_DIGITS]
    dispatchers = [f for mod in (K, _onset, _onset_impulse, _dop853, _splitting) for f in vars(mod).values()
                   if isinstance(f, numba.core.registry.CPUDispatcher)]
    assert len(dispatchers) >= 20
    for f in dispatchers:
        assert Path(f._cache.cache_path).parent == folder, f


def test_key_sources_are_the_kernel_modules_and_their_cradle_imports():
    names = [p.relative_to(_cache.KERNEL_DIR).as_posix() for p in _cache.kernel_sources()]
    assert names == ["_cache.py", "_dop853.py", "_dop853_events.py", "_generic.py", "_kernels.py",
                     "_kernels_dps_sites.py", "_onset.py", "_onset_impulse.py", "_splitting.py", "_types.py",
                     "systems/dps.py", "systems/dps_variational.py", "systems/imperfect.py", "systems/lattice.py",
                     "systems/lattice_variational.py",
                     "terms/contact_damping.py",
                     "terms/hertz.py", "terms/inhomogeneity.py", "terms/onsite_damping.py",
                     "terms/onsite_harmonic.py", "terms/onsite_pendulum.py", "terms/onsite_quartic.py",
                     "terms/precompression.py", "terms/slots.py"]
    # every module of the package that uses numba is covered
    uses_numba = {p.relative_to(_cache.KERNEL_DIR).as_posix() if p.is_relative_to(_cache.KERNEL_DIR) else str(p)
                  for p in _cache.PACKAGE_DIR.rglob("*.py")
                  if re.search(r"^\s*(from|import) numba", p.read_text(), re.M)}
    assert uses_numba <= set(names)



def test_key_sources_agree_with_the_ast_import_scan_of_codedeps():
    """The regular-expression scan of _cache finds every cradle module (not package) that the
    ast-based scan of cradle.pipeline.codedeps finds in the kernel modules."""
    from cradle.pipeline import codedeps

    sources = _cache.kernel_sources()
    src = _cache.PACKAGE_DIR.parent
    for path in sources:
        package = ".".join(path.relative_to(src).parts[:-1])
        for name in codedeps._imports(path, package):
            found = codedeps._module_file(src, name)
            if found is not None and found.name != "__init__.py":
                assert found in sources, (path.name, name)

def _copy_key(tmp_path, monkeypatch, edit=None):
    """Key of a scratch copy of the package, after ``edit(package_dir)``."""
    pkg = tmp_path / "cradle"
    if not pkg.exists():
        shutil.copytree(SRC / "cradle", pkg, ignore=shutil.ignore_patterns("__pycache__"))
    if edit:
        edit(pkg)
    monkeypatch.setattr(_cache, "PACKAGE_DIR", pkg)
    monkeypatch.setattr(_cache, "KERNEL_DIR", pkg / "integrators")
    return _cache.cache_key()[0]


def test_key_follows_kernel_sources_only(tmp_path, monkeypatch):
    base = _copy_key(tmp_path, monkeypatch)
    assert base == _cache.cache_key()[0]             # deterministic
    kernels = tmp_path / "cradle" / "integrators" / "_kernels.py"
    original = kernels.read_text()

    def scale(pkg):
        kernels.write_text(original.replace(HERTZ_LINE, HERTZ_SCALED))

    def restore(pkg):
        kernels.write_text(original)

    def edit_solver(pkg):
        path = pkg / "integrators" / "lattice_solver.py"
        path.write_text(path.read_text() + "\n# not a kernel\n")

    assert _copy_key(tmp_path, monkeypatch, scale) != base
    assert _copy_key(tmp_path, monkeypatch, restore) == base
    assert _copy_key(tmp_path, monkeypatch, edit_solver) == base   # no kernel in it: no recompilation


def test_key_follows_a_new_cradle_import_of_a_kernel_module(tmp_path, monkeypatch):
    base = _copy_key(tmp_path, monkeypatch)

    def import_models(pkg):
        path = pkg / "integrators" / "_onset.py"
        path.write_text(path.read_text().replace("import math\n", "import math\nfrom ..models import lattice\n", 1))

    _copy_key(tmp_path, monkeypatch, import_models)
    assert "lattice.py" in [p.name for p in _cache.kernel_sources()]
    models = tmp_path / "cradle" / "models" / "lattice.py"
    with_import = _cache.cache_key()[0]
    models.write_text(models.read_text() + "\n# edited\n")
    assert with_import != base and _cache.cache_key()[0] != with_import


@pytest.mark.parametrize("env, expected", [
    ({"CRADLE_KERNEL_CACHE": "/a/b", "NUMBA_CACHE_DIR": "/n", "XDG_CACHE_HOME": "/x"}, "/a/b"),
    ({"NUMBA_CACHE_DIR": "/n", "XDG_CACHE_HOME": "/x"}, "/n/cradle"),
    ({"XDG_CACHE_HOME": "/x"}, "/x/cradle/numba"),
    ({"CRADLE_KERNEL_CACHE": "", "HOME": "/h"}, "/h/.cache/cradle/numba"),
])
def test_cache_root(monkeypatch, env, expected):
    for var in ("CRADLE_KERNEL_CACHE", "NUMBA_CACHE_DIR", "XDG_CACHE_HOME"):
        monkeypatch.delenv(var, raising=False)
    for var, value in env.items():
        monkeypatch.setenv(var, value)
    assert _cache.cache_root() == Path(expected)


# ---------------------------------------------------------------- cleanup

NOW = 1.8e9


def _folders(root, ages_s, now=NOW):
    """Key folders named 000..0i, each last used ages_s[i] seconds before ``now``."""
    out = []
    for i, age in enumerate(ages_s):
        folder = root / f"{i:016x}"
        (folder / "integrators_x").mkdir(parents=True)
        (folder / "integrators_x" / "f.nbi").write_bytes(b"x")
        os.utime(folder, (now - age, now - age))
        out.append(folder)
    return out


def test_prune_keeps_the_most_recent_the_current_and_the_recently_used(tmp_path):
    hour = 3600.0
    # ages: 0, 1, ..., 9 hours, then one used 10 minutes ago (but listed last)
    folders = _folders(tmp_path, [i * hour for i in range(10)] + [600.0])
    current = folders[9]                       # the oldest, in use again by this process
    other = tmp_path / "not-a-key"
    other.mkdir()
    (tmp_path / ".trash-0000000000000000-dead").mkdir()   # left by an interrupted prune
    removed = _cache.prune(tmp_path, current, keep=3, grace_s=hour, now=NOW)
    # kept: the 3 most recent (ages 0, 10 min, 1 h), the current one, and none else older than 1 h
    assert sorted(removed) == sorted(folders[2:9])
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        [folders[0].name, folders[1].name, folders[10].name, current.name, "not-a-key"])
    assert _cache.prune(tmp_path, current, keep=3, grace_s=hour, now=NOW) == []


def test_prune_grace_protects_folders_beyond_keep(tmp_path):
    folders = _folders(tmp_path, [0.0, 100.0, 200.0, 300.0, 7200.0])
    removed = _cache.prune(tmp_path, folders[0], keep=1, grace_s=3600.0, now=NOW)
    assert removed == [folders[4]]
    assert all(f.exists() for f in folders[:4])


def test_prune_tolerates_a_concurrent_prune(tmp_path, monkeypatch):
    """Another process renames a folder away between our listing and our rename: ours fails
    quietly, the folder is gone once, and nothing else is touched."""
    folders = _folders(tmp_path, [0.0, 7200.0, 9000.0])
    real_rename = os.rename

    def rename(src, dst):
        if Path(src) == folders[1]:            # the other process wins this one
            real_rename(src, tmp_path / ".trash-other")
        return real_rename(src, dst)

    monkeypatch.setattr(_cache.os, "rename", rename)
    removed = _cache.prune(tmp_path, folders[0], keep=1, grace_s=3600.0, now=NOW)
    assert removed == [folders[2]]
    assert sorted(p.name for p in tmp_path.iterdir()) == [".trash-other", folders[0].name]


def test_activate_marks_use_and_prunes(tmp_path, monkeypatch):
    """A fresh activation creates its folder with a note of its key, touches it, and prunes the root."""
    monkeypatch.setenv("CRADLE_KERNEL_CACHE", str(tmp_path))
    old = _folders(tmp_path, [2 * _cache.GRACE_S + i for i in range(_cache.KEEP + 2)], now=time.time())
    folder = _fresh_activation(monkeypatch)
    key, info = _cache.cache_key()
    assert folder == tmp_path / key[:_cache.KEY_DIGITS]
    assert (folder / _cache.INFO_FILE).read_text() == info
    left = sorted(p for p in tmp_path.iterdir())
    # the new folder is the most recent; KEEP - 1 of the old ones remain, the youngest
    assert left == sorted([folder] + old[:_cache.KEEP - 1])


def _fresh_activation(monkeypatch):
    """activate() as in a new process; numba's setting of this process restored afterwards."""
    saved = str(_cache.activate())
    monkeypatch.setattr(_cache, "_active", {})
    try:
        return _cache.activate()
    finally:
        numba.config.CACHE_DIR = saved


def test_activate_removes_old_in_tree_cache_files_on_a_new_key(tmp_path, monkeypatch):
    kernel_dir = tmp_path / "integrators"
    (kernel_dir / "__pycache__").mkdir(parents=True)
    for name in ("_onset.split_run_onset-316.py311.nbi", "_onset.split_run_onset-316.py311.1.nbc", "keep.pyc"):
        (kernel_dir / "__pycache__" / name).write_bytes(b"x")
    monkeypatch.setattr(_cache, "KERNEL_DIR", kernel_dir)
    monkeypatch.setattr(_cache, "kernel_sources", lambda: [])   # key of the real sources not needed
    monkeypatch.setenv("CRADLE_KERNEL_CACHE", str(tmp_path / "cache"))
    folder = _fresh_activation(monkeypatch)
    assert folder.parent == tmp_path / "cache"
    assert [p.name for p in (kernel_dir / "__pycache__").iterdir()] == ["keep.pyc"]


def test_activate_falls_back_to_a_temporary_folder(tmp_path, monkeypatch):
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    monkeypatch.setenv("CRADLE_KERNEL_CACHE", str(blocker / "cache"))   # cannot be created
    monkeypatch.setattr(_cache.tempfile, "tempdir", str(tmp_path / "tmp"))
    (tmp_path / "tmp").mkdir()
    with pytest.warns(RuntimeWarning, match="not writable"):
        folder = _fresh_activation(monkeypatch)
    assert folder.parent.parent == tmp_path / "tmp" and folder.parent.name.startswith("cradle-numba-")
    assert (folder / _cache.INFO_FILE).is_file()


#: A cached kernel of its own, in a fresh process with the cache folder under test; prints f(20) and
#: numba's cache hits and misses
DAMAGE_SCRIPT = r"""
import json, sys
from cradle.integrators import _cache
_cache.activate()
sys.path.insert(0, sys.argv[1])
import tinykernel
value = tinykernel.f(20)
stats = tinykernel.f.stats
print(json.dumps({"value": value, "hits": sum(stats.cache_hits.values()),
                  "misses": sum(stats.cache_misses.values())}))
"""


@pytest.mark.parametrize("damage", ["truncated", "garbage"])
@pytest.mark.parametrize("kind", ["nbi", "nbc"])
def test_a_damaged_cache_file_is_quarantined_and_the_kernel_rebuilt(tmp_path, damage, kind):
    """A truncated or overwritten index (.nbi) or data (.nbc) file: the kernel still runs, compiled
    again; the file is moved aside as NAME.damaged, with one line in the log; the next process loads the
    rebuilt entry from the cache."""
    (tmp_path / "mod").mkdir()
    (tmp_path / "mod" / "tinykernel.py").write_text(
        "from numba import njit\n\n\n@njit(cache=True)\ndef f(n):\n    s = 0\n    for i in range(n):\n"
        "        s += i * i\n    return s\n")
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env.update(CRADLE_KERNEL_CACHE=str(tmp_path / "cache"), PYTHONPATH=str(SRC))

    def run():
        proc = subprocess.run([sys.executable, "-c", DAMAGE_SCRIPT, str(tmp_path / "mod")], env=env,
                              capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0, proc.stderr[-2000:]
        return json.loads(proc.stdout.splitlines()[-1]), proc.stderr

    first, _ = run()
    assert first == {"value": 2470, "hits": 0, "misses": 1}
    (path,) = (tmp_path / "cache").rglob(f"tinykernel.f-*.{kind}")
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2] if damage == "truncated" else b"\x89garbage" * 8)
    again, err = run()
    assert again == {"value": 2470, "hits": 0, "misses": 1}
    lines = [line for line in err.splitlines() if "compiled-kernel cache" in line]
    assert len(lines) == 1 and str(path) in lines[0] and "damaged" in lines[0] and "Traceback" not in err
    assert Path(f"{path}.damaged").exists() and path.exists()   # moved aside, and written again
    later, err = run()
    assert later == {"value": 2470, "hits": 1, "misses": 0} and "compiled-kernel cache" not in err
