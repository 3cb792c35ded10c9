"""The probes of a user trying to break the pipeline, rerun against their expected outcomes.

    python benchmarks/probes.py [--keep] [--reuse FOLDER [--rev REV]] [--only GROUP ...]

In a scratch clone of this repository (the committed state, this Python, its own compiled-kernel cache),
builds ``all`` (the paper and the reduced analyses), then runs each probe the way a user would
(``snakemake``, ``cradle``, ``python -c``) and records the command's last line of output, its exit
status, its wall time and whether the outcome is the one expected. The expectations are written here,
beside each probe, before the probes are run (the issue "Every reader checks what it reads"): a probe
*holds* when its exit status, the words it must say (the key, the file, the reason), the absence of a
traceback, its wall time and its check of the tree afterwards (nothing lost, nothing rerun) all match.

Writes the table ``probes`` of docs/recovery.md.
"""
from __future__ import annotations

import argparse
import hashlib
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doctable import git_commit, publish  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SNAKEMAKE = shutil.which("snakemake", path=str(Path(sys.executable).parent)) or "snakemake"
EXACT = "results/sim/tw-weak/exact.nc"
FIGURE = "results/figures/plot4-5.png"
CLAIMS = "results/paper-checks/paper-checks.nc"
PAIR_METRICS = "results/metrics/loc1-pair.nc"
NOTHING = "Nothing to be done"


@dataclass(frozen=True)
class Expect:
    """What a probe must end in: its exit status (0, or "fail" for any other), the words its output must
    hold (case-insensitive), no traceback, at most ``within_s`` seconds."""

    exit: int | str
    says: tuple[str, ...] = ()
    within_s: float = 120.0
    note: str = ""   # what else is checked afterwards, in words
    api: bool = False   # a Python call: refusing is raising, and Python prints the exception's traceback

    def text(self) -> str:
        parts = ["exit 0" if self.exit == 0 else "raises" if self.api else "refused (exit != 0)"]
        if self.says:
            parts.append("names " + ", ".join(f"`{s}`" for s in self.says))
        if not self.api:
            parts.append("one line, no traceback")
        if self.within_s < 120:
            parts.append(f"< {self.within_s:g} s")
        if self.note:
            parts.append(self.note)
        return "; ".join(parts)


def _sha(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest() if path.exists() else "missing"


def _last_line(out: str) -> str:
    lines = [ln for ln in out.splitlines()
             if ln.strip() and not ln.startswith(("Building DAG", "Using shell", "Provided cores", "Rules claiming",
                                                   "Select jobs", "Assuming", "host:", "Using profile"))]
    # what cradle said (a job's one-line error, a config error), else Snakemake's last word
    said = [ln for ln in lines if any(k in ln for k in ("input error:", "config error:", "cradle: error:", "DAMAGED",
                                                         "MISMATCH", "error:", "Error:"))]
    keep = said or lines or ["(no output)"]
    line = re.sub(r"^\d{4}-\d\d-\d\d [\d:,]+ ", "", keep[-1].strip())
    return line if len(line) <= 240 else line[:237] + "..."


class Probes:
    def __init__(self, repo: Path, cache: Path):
        self.repo = repo
        self.env = dict(os.environ, PYTHONPATH=str(repo / "src"), PYTHONWARNINGS="ignore",
                        CRADLE_KERNEL_CACHE=str(cache))
        self.rows: list[tuple[str, ...]] = []
        self.group = ""

    # ---- running things the way a user does
    def sh(self, args, timeout=900):
        t0 = time.perf_counter()
        try:
            p = subprocess.run(args, cwd=self.repo, env=self.env, capture_output=True, text=True, timeout=timeout)
            out, code = p.stderr + "\n" + p.stdout, p.returncode
        except subprocess.TimeoutExpired as err:
            out, code = f"TIMEOUT after {timeout} s ({(err.stderr or b'')[-200:]!r})", -9
        return code, out, time.perf_counter() - t0

    def cradle(self, *args, **kw):
        return self.sh([sys.executable, "-m", "cradle", *args], **kw)

    def python(self, code: str):
        return self.sh([sys.executable, "-c", code])

    def snakemake(self, *args, **kw):
        return self.sh([SNAKEMAKE, "--cores", "2", *args], **kw)

    def dry(self, *args):
        return self.snakemake("-n", *args)

    def config_variant(self, name, edit=None, text=None) -> str:
        path = self.repo / f"probe-{name}.yaml"
        if text is None:
            cfg = yaml.safe_load((self.repo / "config.yaml").read_text())
            edit(cfg)
            text = yaml.safe_dump(cfg, sort_keys=False)
        path.write_text(text)
        return path.name

    def up_to_date(self) -> None:
        """``snakemake all`` (what earlier probes forced or changed is rebuilt), then a row: the dry run
        after it has nothing to do -- the baseline of the probes that follow."""
        code, out, _ = self.snakemake("all")
        if code:
            sys.exit(out[-3000:])
        self.check("baseline: `snakemake -n` after `snakemake all`", Expect(0, (NOTHING,), within_s=30),
                   self.dry("all"))

    # ---- recording against the expectation
    def check(self, probe: str, expect: Expect, run, after=None) -> bool:
        code, out, wall = run
        problems = []
        if (expect.exit == 0) != (code == 0):
            problems.append(f"exit {code}")
        low = out.lower()
        problems += [f"does not say `{w}`" for w in expect.says if w.lower() not in low]
        if "Traceback (most recent call last)" in out and not expect.api:
            problems.append("traceback")
        if wall > expect.within_s:
            problems.append(f"took {wall:.0f} s")
        if after is not None:
            ok, what = after()
            if not ok:
                problems.append(what)
        holds = "yes" if not problems else "NO: " + "; ".join(problems)
        told = _last_line(out)
        self.rows.append((self.group, probe, expect.text(), f"exit {code}", told, f"{wall:.1f} s", holds))
        print(f"[{holds[:3]}] {probe}: {told}", flush=True)
        return not problems

    def unchanged(self, *paths: str):
        """An ``after`` check: the files hold the bytes they held before the probe."""
        before = {p: _sha(self.repo / p) for p in paths}

        def after():
            changed = [p for p in paths if _sha(self.repo / p) != before[p]]
            return (not changed, "changed or lost: " + ", ".join(changed))
        return after


def _keep_mtime(path: Path, write) -> None:
    st = path.stat()
    write()
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))


def _files_of(folder: Path) -> dict:
    """Each file of ``folder``: its bytes and its (access, modification) times."""
    return {p.name: (p.read_bytes(), (p.stat().st_atime_ns, p.stat().st_mtime_ns)) for p in folder.iterdir()}


def _put_files(folder: Path, files: dict) -> None:
    """Write back what :func:`_files_of` read, times included (moving files is no change to Snakemake)."""
    for name, (data, times) in files.items():
        (folder / name).write_bytes(data)
        os.utime(folder / name, ns=times)


def _mount_small(folder: Path, size_kib: int) -> bool:
    folder.mkdir(parents=True, exist_ok=True)
    return subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size_kib}k", "tmpfs", str(folder)],
                          capture_output=True).returncode == 0


def _umount(folder: Path) -> None:
    subprocess.run(["umount", "-l", str(folder)], capture_output=True)


# ------------------------------------------------------------------ the probes, by group

def wrong_file(pr: Probes) -> None:
    pr.group = "a wrong file"
    exact = pr.repo / EXACT
    saved = exact.read_bytes()
    _keep_mtime(exact, lambda: shutil.copyfile(pr.repo / "results/sim/tw-moderate/exact.nc", exact))
    pr.check("tw-moderate's exact.nc copied over tw-weak's (mtime kept): `cradle verify`",
             Expect("fail", ("tw-weak", "tw-moderate")), pr.cradle("verify", "results"))
    pr.check("... `cradle describe` it", Expect(0, ("tw-moderate", "expected")), pr.cradle("describe", EXACT))
    pr.check("... `snakemake -n` (Snakemake compares times, not contents)", Expect(0, (NOTHING,)), pr.dry(FIGURE))
    pr.check("... plot4-5 forced to read it", Expect("fail", ("tw-moderate",), note="figure kept"),
             pr.snakemake("--forcerun", FIGURE, "--", FIGURE), pr.unchanged(FIGURE))
    pr.check("... the claims table forced to read it", Expect("fail", ("tw-moderate",), note="claims table kept"),
             pr.snakemake("--forcerun", CLAIMS, "--", CLAIMS), pr.unchanged(CLAIMS))
    pr.check("... `cradle.open_scene('tw-weak')`", Expect("fail", ("WrongOutput", "tw-moderate"), api=True),
             pr.python("import cradle; cradle.open_scene('tw-weak')"))
    exact.write_bytes(saved)

    # a parameter changed in config.yaml after the build, not rebuilt
    cfg = pr.config_variant("changed", lambda c: c["scenes"]["tw-weak"]["initial"].update(omega_tw=1.02))
    pr.check("config changed (tw-weak omega_tw 1.02), not rebuilt: `cradle verify --config`",
             Expect("fail", ("tw-weak", "snakemake")), pr.cradle("verify", "results", "--config", cfg))
    pr.check("... `cradle.open_scene('tw-weak', config=...)`", Expect("fail", ("WrongOutput", "omega_tw"), api=True),
             pr.python(f"import cradle; cradle.open_scene('tw-weak', config='{cfg}')"))
    pr.check("... `cradle.open_scene('tw-weak', config=..., check=False)`", Expect(0, ("tw-weak",), api=True),
             pr.python(f"import cradle; ds = cradle.open_scene('tw-weak', config='{cfg}', check=False); "
                       "print(ds.attrs['title'])"))


def edited_values(pr: Probes) -> None:
    pr.group = "an edited value"
    metrics = pr.repo / PAIR_METRICS
    saved = metrics.read_bytes()

    def edit():
        import netCDF4
        with netCDF4.Dataset(metrics, "r+") as nc:
            var = nc.variables["merging_time_exact"]
            var.assignValue(10 * var.getValue())
    _keep_mtime(metrics, edit)
    pr.check("loc1-pair's 0-d `merging_time_exact` x 10 with netCDF4: `cradle verify`",
             Expect("fail", ("merging_time_exact", "loc1-pair")), pr.cradle("verify", "results"))
    pr.check("... loc1 forced to read it", Expect("fail", ("merging_time_exact",), note="figure kept"),
             pr.snakemake("--forcerun", "results/figures/loc1.png", "--", "results/figures/loc1.png"),
             pr.unchanged("results/figures/loc1.png"))
    metrics.write_bytes(saved)

    wp = next((pr.repo / "results/work-precision").glob("*.nc"))
    saved = wp.read_bytes()

    def edit_string():
        import netCDF4
        with netCDF4.Dataset(wp, "r+") as nc:
            for group in [nc, *nc.groups.values()]:
                for var in group.variables.values():
                    if var.dtype is str and var.size:
                        values = var[:]
                        values.flat[0] = "edited"
                        var[:] = values
                        return
    _keep_mtime(wp, edit_string)
    pr.check(f"a string value of {wp.relative_to(pr.repo)} edited: `cradle verify`",
             Expect("fail", (wp.name,)), pr.cradle("verify", "results"))
    wp.write_bytes(saved)
    pr.check("a fresh build: `cradle verify results`", Expect(0, ("verified",), note="no note line"),
             pr.cradle("verify", "results"),
             lambda: (("note" not in pr.cradle("verify", "results")[1].lower()), "a note line"))


def bounded(pr: Probes) -> None:
    pr.group = "validation is bounded"

    def beyond(name, *path, value):
        def edit(cfg):
            node = cfg.setdefault("beyond", {}).setdefault(name, {})
            for key in path[:-1]:
                node = node.setdefault(key, {})
            node[path[-1]] = value
        return edit

    cases = [
        ("`beyond.theorem1.grid_log2: 1e300`", beyond("theorem1", "grid_log2", value=1e300), "grid_log2"),
        ("`beyond.floquet.grid_log2: 1e300`", beyond("floquet", "grid_log2", value=1e300), "grid_log2"),
        ("`beyond.floquet.reduced.convergence.grid_log2: 1e300`",
         beyond("floquet", "reduced", "convergence", "grid_log2", value=1e300), "grid_log2"),
        ("`beyond.mi-statistics.q_over_pi.count: 1e300`",
         beyond("mi-statistics", "q_over_pi", "count", value=1e300), "count"),
        ("`defaults.max_energy_drift: 1e300` (would turn the energy check off)",
         lambda c: c.setdefault("defaults", {}).update(max_energy_drift=1e300), "max_energy_drift"),
        ("`beyond.work-precision.scenes.tw-weak.t_end: 1e300`",
         lambda c: c["beyond"]["work-precision"]["scenes"]["tw-weak"].update(t_end=1e300), "t_end"),
        ("`homoclinic.site.N: 1e300`", lambda c: c["homoclinic"]["site"].update(N=1e300), "site"),
        ("a scalar for `store.snapshots`",
         lambda c: c["scenes"]["tw-weak"]["store"].update(snapshots=333.7), "snapshots"),
        ("`beyond.mi-diagram.alpha: [1e300]`", beyond("mi-diagram", "alpha", value=[1e300]), "alpha"),
        ("`beyond.theorem1.scenes: [garbage]`", beyond("theorem1", "scenes", value=["garbage"]), "garbage"),
    ]
    for i, (label, edit, key) in enumerate(cases):
        cfg = pr.config_variant(f"bound{i}", edit)
        pr.check(f"{label} (`snakemake -n --configfile`)", Expect("fail", (key,), within_s=30),
                 pr.dry("all", "--configfile", cfg))


def command_line(pr: Probes) -> None:
    pr.group = "the command line"
    for label, args, key in [
            ("`cradle extend exact.nc --t-end 1e7`", ("--t-end", "1e7"), "t_end"),
            ("`cradle extend exact.nc --t-end 1e300`", ("--t-end", "1e300"), "t_end"),
            ("`cradle extend exact.nc --every 1e-9 --t-end 700`", ("--every", "1e-9", "--t-end", "700"), "every"),
    ]:
        pr.check(label, Expect("fail", (key,), within_s=20, note="nothing written"), pr.cradle("extend", EXACT, *args),
                 lambda: (not list((pr.repo / "results/sim/tw-weak").glob("exact-t*")), "a file was written"))
    slow = pr.config_variant("hours", lambda c: c.update(budget={"hours": 0.05}))
    pr.check("`cradle extend exact.nc --t-end 9e5` with `budget.hours: 0.05`",
             Expect("fail", ("estimated", "budget"), within_s=20, note="nothing written"),
             pr.cradle("extend", EXACT, "--t-end", "9e5", "--config", slow),
             lambda: (not list((pr.repo / "results/sim/tw-weak").glob("exact-t*")), "a file was written"))
    pr.check("`cradle animate tw-weak --width 100000`", Expect("fail", ("width",), within_s=20),
             pr.cradle("animate", "tw-weak", "--width", "100000", "--out", "probe.mp4"))
    pr.check("`cradle animate tw-weak --gif --gif-fps 0`", Expect("fail", ("gif-fps",), within_s=20),
             pr.cradle("animate", "tw-weak", "--gif", "--gif-fps", "0", "--out", "probe.mp4"))


def damage(pr: Probes) -> None:
    pr.group = "damage and failure"
    cache = Path(pr.env["CRADLE_KERNEL_CACHE"])
    damaged = 0
    for f in cache.rglob("*.nbc"):
        data = f.read_bytes()
        f.write_bytes(data[: len(data) // 2])
        damaged += 1
    pr.check(f"{damaged} compiled kernels of the cache truncated: tw-weak forced",
             Expect(0, note="rebuilt, tw-weak verifies"),
             pr.snakemake("--forcerun", EXACT, "--", EXACT),
             lambda: (pr.cradle("verify", "results/sim/tw-weak")[0] == 0, "tw-weak does not verify"))

    small = Path(tempfile.mkdtemp(prefix="cradle-full-"))
    if _mount_small(small, 256):
        try:
            pr.check("a full disk: `cradle run tw-weak --out` a 256 KiB file system",
                     Expect("fail", ("space", str(small))), pr.cradle("run", "tw-weak", "--out", str(small)))
        finally:
            _umount(small)
    else:
        pr.rows.append((pr.group, "a full disk", "-", "-", "not probed: cannot mount a tmpfs here", "-", "-"))

    # a forced scene job that fails (its folder full): the previous four files stay, and nothing reruns for them
    pr.up_to_date()
    folder = pr.repo / "results/sim/tw-strong"
    four = [EXACT.replace("tw-weak", "tw-strong"), "results/sim/tw-strong/dps.nc", "results/initial/tw-strong.nc",
            "results/metrics/tw-strong.nc"]
    before = {p: _sha(pr.repo / p) for p in four}
    keep = _files_of(folder)
    need = sum(len(data) for data, _ in keep.values())
    if _mount_small(folder, need // 1024 + 64):
        _put_files(folder, keep)   # the same bytes and times on the small file system
        try:
            pr.check("tw-strong forced with its folder full: `snakemake --forcerun simulate`",
                     Expect("fail", ("space",), note="the four files kept"),
                     pr.snakemake("--forcerun", "simulate", "--", four[0]),
                     lambda: (all(_sha(pr.repo / p) == before[p] for p in four),
                              "lost or changed: " + ", ".join(p for p in four if _sha(pr.repo / p) != before[p])))
        finally:
            saved = _files_of(folder)
            _umount(folder)
            _put_files(folder, saved)
        pr.check("... then `snakemake -n paper`", Expect(0, (NOTHING,), note="the four files present"),
                 pr.dry("paper"), lambda: (all((pr.repo / p).exists() for p in four), "files missing"))


def killed(pr: Probes) -> None:
    pr.group = "killed runs"
    target = "results/floquet/floquet.nc"
    before = _sha(pr.repo / target)
    proc = subprocess.Popen([SNAKEMAKE, "--cores", "1", "--forcerun", target, "--", target], cwd=pr.repo,
                            env=pr.env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    job = None
    for _ in range(120):   # until the job's own Python runs
        time.sleep(0.5)
        out = subprocess.run(["pgrep", "-f", "-P", str(proc.pid), "python"], capture_output=True, text=True).stdout
        if out.split():
            job = int(out.split()[0])
            time.sleep(3)
            break
    t0 = time.perf_counter()
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    gone = None
    while job and time.perf_counter() - t0 < 30:
        if not Path(f"/proc/{job}").exists():
            gone = time.perf_counter() - t0
            break
        time.sleep(0.2)
    stale = [str(p.relative_to(pr.repo)) for p in (pr.repo / "results").rglob(".*.tmp")]
    fate = "not found" if job is None else f"stopped after {gone:.1f} s" if gone is not None else "STILL RUNNING"
    pr.rows.append((pr.group, "`kill -9` of Snakemake while the floquet job runs",
                    "the job stops within 5 s; no temporary file left; floquet.nc unchanged", "-",
                    f"job {fate}; temporaries left: {stale or 'none'}", f"{time.perf_counter() - t0:.1f} s",
                    "yes" if job and gone is not None and gone < 5 and not stale and _sha(pr.repo / target) == before
                    else "NO"))
    print(pr.rows[-1], flush=True)
    if job and gone is None:
        os.kill(job, signal.SIGKILL)
    pr.sh([SNAKEMAKE, "--unlock"])
    # a temporary file of a writer that is gone (a dead pid in its name, as the atomic writer names them)
    host = re.sub(r"[^A-Za-z0-9-]", "-", socket.gethostname().split(".")[0])
    stale_file = pr.repo / f"results/sim/tw-weak/.exact.nc.pid-999999999@{host}.probe.tmp"
    stale_file.write_bytes(b"\0" * 1024)
    pr.check("a stale `.exact.nc.*.tmp` of a dead writer: `cradle verify`",
             Expect(0, (".tmp",), note="named as a note"),
             pr.cradle("verify", "results"))
    pr.check("... then a run with work (plot4-5 forced)", Expect(0, note="the temporary file removed"),
             pr.snakemake("--forcerun", FIGURE, "--", FIGURE), lambda: (not stale_file.exists(), "still there"))
    stale_file.unlink(missing_ok=True)


def reruns(pr: Probes) -> None:
    pr.group = "nothing reruns for nothing"
    pr.up_to_date()
    cfg = yaml.safe_load((pr.repo / "config.yaml").read_text())
    variants = [
        ("`defaults.exact` written with its declared values", lambda c: c.setdefault("defaults", {}).update(
            exact={"method": "srkn6c", "rtol": 1e-10})),
        ("... in the other key order", lambda c: c.setdefault("defaults", {}).update(
            exact={"rtol": 1e-10, "method": "srkn6c"})),
        ("tw-weak's keys in reverse order",
         lambda c: c["scenes"].update({"tw-weak": dict(reversed(list(c["scenes"]["tw-weak"].items())))})),
        ("tw-weak's `q: 1pi/5` for `pi/5`", lambda c: c["scenes"]["tw-weak"]["initial"].update(q="1pi/5")),
        ("tw-weak's `q: 1*pi/5` for `pi/5`", lambda c: c["scenes"]["tw-weak"]["initial"].update(q="1*pi/5")),
        ("tw-weak's block moved to the end of `scenes:`",
         lambda c: c["scenes"].update({"tw-weak": c["scenes"].pop("tw-weak")})),
    ]
    assert cfg["scenes"]["tw-weak"]["initial"]["q"] == "pi/5"
    for i, (label, edit) in enumerate(variants):
        name = pr.config_variant(f"order{i}", edit)
        pr.check(f"{label}: `snakemake -n`", Expect(0, (NOTHING,), within_s=30), pr.dry("all", "--configfile", name))
    source = pr.repo / "src/cradle/models/dps.py"
    text = source.read_text()
    source.write_text(text + "\n# a comment added by the probe\n")
    pr.check("a comment added to models/dps.py: `snakemake -n`", Expect(0, (NOTHING,), within_s=30), pr.dry("all"))
    head, _, rest = text.partition('"""')
    source.write_text(head + '"""A probe\'s word. ' + rest)
    pr.check("... its docstring edited: `snakemake -n`", Expect(0, (NOTHING,), within_s=30), pr.dry("all"))
    source.write_text(text + "\n_PROBE = 1\n")
    code, out, wall = pr.dry("all")
    m = re.search(r"^total\s+(\d+)", out, re.M)
    pr.check("... a line of code added to models/dps.py: `snakemake -n`",
             Expect(0, ("total",), within_s=30, note="its importers planned"), (code, out, wall),
             lambda: (bool(m and int(m.group(1)) > 0), "nothing planned"))
    if m:
        pr.rows[-1] = pr.rows[-1][:4] + (f"{m.group(1)} jobs planned",) + pr.rows[-1][5:]
    source.write_text(text)


def held_before(pr: Probes) -> None:
    """The probes of the issue "Nothing stale, nothing corrupt, nothing too big": still as they were."""
    pr.group = "held before"

    def fft106(**patch):
        return lambda cfg: cfg["scenes"]["fft106"].update(patch)

    for label, edit, key in [
            ("`N: 1e9` (fft106)", fft106(N=1e9), "scenes.fft106: N = 1000000000"),   # the budget's line
            ("fft106 every 0.01 to t = 99000 (~140 GB)", fft106(t_end=99000.0, store={"every": 0.01}), "disk_gb"),
            ("`t_end: 1e12`, snapshots only", fft106(t_end=1e12, store={"snapshots": [1.0]}), "scenes.fft106.t_end"),
            ("`alpha: nan`", lambda c: c.setdefault("defaults", {}).update(alpha=float("nan")), "alpha"),
    ]:
        cfg = pr.config_variant(f"big{len(pr.rows)}", edit)
        pr.check(f"{label} (`snakemake -n --configfile`)", Expect("fail", (key,), within_s=30),
                 pr.dry("all", "--configfile", cfg))
    twice = "\ndefaults:\n  alpha: 1.5\n  alpha: 2.0\n"
    dup = pr.config_variant("dup", text=(pr.repo / "config.yaml").read_text() + twice)
    pr.check("duplicate YAML key (`alpha` twice)", Expect("fail", ("alpha", "twice")),
             pr.dry("all", "--configfile", dup))
    exact = pr.repo / EXACT
    saved = exact.read_bytes()

    def garbage():
        with open(exact, "r+b") as f:
            f.seek(int(len(saved) * 0.6))
            f.write(os.urandom(4096))
    _keep_mtime(exact, garbage)
    pr.check("4 kB of garbage in exact.nc, mtime kept: `cradle verify`",
             Expect("fail", ("damaged", "snakemake --force")),
             pr.cradle("verify", "results"))
    pr.check("... the figure job forced to read it", Expect("fail", ("damaged",), note="figure kept"),
             pr.snakemake("--forcerun", FIGURE, "--", FIGURE), pr.unchanged(FIGURE))
    pr.check("... `snakemake --force exact.nc` (docs/recovery.md)", Expect(0, note="then everything verifies"),
             pr.snakemake("--force", EXACT), lambda: (pr.cradle("verify", "results")[0] == 0, "verify fails"))
    pr.check("`cradle extend exact.nc --t-end 700`", Expect(0, ("700",), note="the workflow's exact.nc unchanged"),
             pr.cradle("extend", EXACT, "--t-end", "700"), pr.unchanged(EXACT))
    for p in (pr.repo / "results/sim/tw-weak").glob("exact-t*"):
        p.unlink()
    pr.check("... `--in-place`", Expect("fail", ("refusing",)),
             pr.cradle("extend", EXACT, "--t-end", "700", "--in-place"))


GROUPS = {"wrong": wrong_file, "values": edited_values, "bounded": bounded, "cli": command_line,
          "damage": damage, "killed": killed, "reruns": reruns, "before": held_before}


def run(repo: Path, cache: Path, only) -> list:
    pr = Probes(repo, cache)
    code, out, wall = pr.snakemake("all")
    if code:
        sys.exit(out[-3000:])
    print(f"built `all` in {wall:.0f} s", flush=True)
    for name, group in GROUPS.items():
        if only and name not in only:
            continue
        group(pr)
    return pr.rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--keep", action="store_true", help="keep the scratch clone")
    ap.add_argument("--reuse", type=Path, help="a scratch folder kept by --keep: reset to this commit, reused")
    ap.add_argument("--rev", default="HEAD", help="with --reuse: the commit of this checkout to reset it to (the one "
                                                 "its results were built at: nothing rebuilt)")
    ap.add_argument("--only", nargs="*", choices=list(GROUPS), help="run only these groups (the table is not written)")
    args = ap.parse_args(argv)
    tmp = args.reuse or Path(tempfile.mkdtemp(prefix="cradle-probes-"))
    repo, cache = tmp / "repo", tmp / "kernels"
    if args.reuse:   # this commit, its outputs rebuilt where it changed them; the probes' files gone
        rev = git_commit(args.rev, short=False)
        subprocess.run(["git", "fetch", "-q", str(ROOT), rev], cwd=repo, check=True)
        subprocess.run(["git", "reset", "-q", "--hard", "FETCH_HEAD"], cwd=repo, check=True)
        subprocess.run(["git", "clean", "-q", "-f", "-x", "-e", "results", "-e", ".snakemake"], cwd=repo, check=True)
    else:
        subprocess.run(["git", "clone", "-q", str(ROOT), str(repo)], check=True)
    try:
        rows = run(repo, cache, args.only)
        # the commit the scratch clone ran (this checkout may have moved on meanwhile), read before it is removed
        head = git_commit(repo=repo)
    finally:
        if not (args.keep or args.reuse):
            shutil.rmtree(tmp, ignore_errors=True)
        else:
            print(f"kept {tmp}")
    held = sum(r[-1] == "yes" for r in rows)
    print(f"{held} of {len(rows)} probes hold")
    if args.only:
        return 0 if held == len(rows) else 1
    text = (f"Rerun by `python benchmarks/probes.py` ({time.strftime('%Y-%m-%d')}, commit {head}): "
            f"**{held} of {len(rows)} hold**.\n\n"
            "| group | probe | expected | exit | what the user is told (last line) | wall | holds |\n"
            "|---|---|---|---|---|---|---|\n"
            + "\n".join("| " + " | ".join(c.replace("|", "\\|").replace("\n", " ") for c in row) + " |"
                        for row in rows))
    publish("recovery.md", "probes", text)
    return 0 if held == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
