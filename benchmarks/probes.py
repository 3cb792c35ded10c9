"""The probes of a new user trying to break the pipeline, rerun: what each ends in, and how fast.

    python benchmarks/probes.py [--keep]

In a scratch clone of this repository (the committed state, this Python), builds plot4-5 (the
scene tw-weak and its figure), then runs each probe the way a user would (``snakemake``,
``cradle``) and records the command's last line of output, its exit status and its wall time.
Writes the table ``probes`` of docs/recovery.md. A probe's outcome is what the pipeline said;
the column "nothing lost" checks that the outputs present before the probe are still readable
afterwards (``cradle verify``) or were rebuilt.
"""
from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doctable import publish  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SNAKEMAKE = shutil.which("snakemake", path=str(Path(sys.executable).parent)) or "snakemake"
EXACT = "results/sim/tw-weak/exact.nc"
FIGURE = "results/figures/plot4-5.png"


class Probe:
    def __init__(self, repo: Path):
        self.repo = repo
        self.env = dict(os.environ, PYTHONPATH=str(repo / "src"), PYTHONWARNINGS="ignore")
        self.rows = []

    def sh(self, args, timeout=900):
        t0 = time.perf_counter()
        p = subprocess.run(args, cwd=self.repo, env=self.env, capture_output=True, text=True, timeout=timeout)
        return p, time.perf_counter() - t0

    def cradle(self, *args):
        return self.sh([sys.executable, "-m", "cradle", *args])

    def snakemake(self, *args):
        return self.sh([SNAKEMAKE, "--cores", "2", *args])

    def config_variant(self, name, edit) -> str:
        cfg = yaml.safe_load((self.repo / "config.yaml").read_text())
        edit(cfg)
        path = self.repo / f"probe-{name}.yaml"
        path.write_text(yaml.safe_dump(cfg, sort_keys=False))
        return path.name

    def record(self, probe, proc_wall, outcome=None, lost="-"):
        proc, wall = proc_wall
        text = outcome or _last_line(proc)
        self.rows.append((probe, f"exit {proc.returncode}", text, f"{wall:.1f} s", lost))
        print(self.rows[-1], flush=True)

    def verified(self) -> str:
        p, _ = self.cradle("verify", "results")
        return "yes (cradle verify: all readable)" if p.returncode == 0 else "NO: " + _last_line(p)


def _last_line(proc) -> str:
    lines = [ln for ln in (proc.stderr + "\n" + proc.stdout).splitlines()
             if ln.strip() and not ln.startswith(("Building DAG", "Using shell", "Provided cores", "Rules claiming",
                                                   "Select jobs", "Assuming", "host:"))]
    # what cradle said (a job's one-line error, a config error), else Snakemake's last word
    said = [ln for ln in lines if any(k in ln for k in ("input error:", "config error:", "cradle: error:", "DAMAGED"))]
    keep = said or [ln for ln in lines if "error" in ln.lower() and not ln.rstrip().endswith(":")]
    line = (keep or lines or ["(no output)"])[-1].strip()
    return line if len(line) <= 260 else line[:257] + "..."


def garbage(path: Path, offset_fraction=0.6, size=4096):
    st = path.stat()
    with open(path, "r+b") as f:
        f.seek(int(st.st_size * offset_fraction))
        f.write(os.urandom(size))
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))   # modification time kept


def run(repo: Path) -> list:
    pr = Probe(repo)
    p, wall = pr.snakemake(FIGURE)
    if p.returncode:
        sys.exit(p.stderr[-3000:])
    print(f"built {FIGURE} in {wall:.0f} s", flush=True)

    def fft106(**patch):
        return lambda cfg: cfg["scenes"]["fft106"].update(patch)

    # ---- configs too big, checked before any work (snakemake -n: the DAG is not even built)
    for label, edit in [
            ("`N: 1e9` (fft106)", fft106(N=1e9)),
            ("fft106 stored every 0.001 (7.9 GB)", lambda c: c["scenes"]["fft106"]["store"].update(every=0.001)),
            ("fft106 every 0.01 to t = 99000 (~140 GB)", fft106(t_end=99000.0, store={"every": 0.01})),
            ("`t_end: 1e12`, snapshots only", fft106(t_end=1e12, store={"snapshots": [1.0]})),
            ("`alpha: nan`", lambda c: c.setdefault("defaults", {}).update(alpha=float("nan"))),
    ]:
        cfg = pr.config_variant(str(len(pr.rows)), edit)
        pr.record(f"{label} (`snakemake -n --configfile`)", pr.snakemake("-n", "all", "--configfile", cfg))
    # config.yaml leaves `defaults:` to the declarations: the probe writes it, with `alpha` twice
    (repo / "probe-dup.yaml").write_text((repo / "config.yaml").read_text()
                                         + "\ndefaults:\n  alpha: 1.5\n  alpha: 2.0\n")
    pr.record("duplicate YAML key (`alpha` twice)", pr.snakemake("-n", "all", "--configfile", "probe-dup.yaml"))
    (repo / "probe-empty.yaml").write_text("")
    pr.record("empty config (`--configfile empty.yaml`)",
              pr.cradle("scenes", "--config", "probe-empty.yaml"))

    # ---- damaged outputs
    saved = (repo / EXACT).read_bytes()
    fig = (repo / FIGURE).read_bytes()
    garbage(repo / EXACT)
    pr.record("4 kB of garbage in exact.nc, mtime kept: `cradle describe`", pr.cradle("describe", EXACT))
    pr.record("... `cradle verify`", pr.cradle("verify", "results"))
    pr.record("... `snakemake -n` (compares times, not contents)", pr.snakemake("-n", FIGURE))
    p = pr.snakemake(FIGURE, "--forcerun", FIGURE)
    kept = (repo / FIGURE).read_bytes() == fig
    pr.record("... the figure job forced to read it", p, lost=f"figure {'kept' if kept else 'LOST'}")
    p = pr.snakemake("--force", EXACT)
    pr.record("... `snakemake --force exact.nc` (docs/recovery.md)", p, lost=pr.verified())
    (repo / EXACT).write_bytes(saved[: len(saved) // 2])
    p = pr.snakemake(FIGURE, "--forcerun", FIGURE)
    kept = (repo / FIGURE).read_bytes() == fig
    pr.record("truncated exact.nc, figure job", p, lost=f"figure {'kept' if kept else 'LOST'}")
    (repo / EXACT).unlink()
    p = pr.snakemake(FIGURE)
    pr.record("... file deleted, `snakemake FIGURE`", p, lost=pr.verified())
    (repo / "notnetcdf.nc").write_text("hello\n")
    pr.record("a non-netCDF file: `cradle describe`", pr.cradle("describe", "notnetcdf.nc"))

    # ---- the command line never desynchronises results
    before = (repo / EXACT).read_bytes()
    p = pr.cradle("extend", EXACT, "--t-end", "700")
    unchanged = (repo / EXACT).read_bytes() == before
    pr.record("`cradle extend results/sim/tw-weak/exact.nc --t-end 700`", p,
              lost=f"workflow's exact.nc {'unchanged' if unchanged else 'CHANGED'}")
    pr.record("... `--in-place`", pr.cradle("extend", EXACT, "--t-end", "700", "--in-place"))
    pr.record("... `--t-end inf`", pr.cradle("extend", EXACT, "--t-end", "inf"))
    p = pr.cradle("run", "tw-weak")
    pr.record("`cradle run tw-weak`", p,
              lost=f"writes cradle-runs/: {(repo / 'cradle-runs/sim/tw-weak/exact.nc').exists()}")

    # ---- a changed parameter: the dry run lists jobs, not arrays
    cfg = pr.config_variant("changed", lambda c: c["scenes"]["tw-weak"].update(t_end=700.0))
    p, wall = pr.snakemake("-n", FIGURE, "--configfile", cfg)
    pr.record("changed `t_end` of tw-weak (700): `snakemake -n`", (p, wall),
              outcome=f"{len(p.stdout) + len(p.stderr)} bytes of output; {_last_line(p)}")
    return pr.rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--keep", action="store_true", help="keep the scratch clone")
    args = ap.parse_args(argv)
    tmp = Path(tempfile.mkdtemp(prefix="cradle-probes-"))
    repo = tmp / "repo"
    subprocess.run(["git", "clone", "-q", str(ROOT), str(repo)], check=True)
    try:
        rows = run(repo)
    finally:
        if not args.keep:
            shutil.rmtree(tmp, ignore_errors=True)
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout
    text = (f"Rerun by `python benchmarks/probes.py` ({time.strftime('%Y-%m-%d')}, commit {head.strip()}):\n\n"
            "| probe | exit | what the user is told (last line) | wall | nothing lost |\n|---|---|---|---|---|\n"
            + "\n".join("| " + " | ".join(c.replace("|", "\\|") for c in row) + " |" for row in rows))
    publish("recovery.md", "probes", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
