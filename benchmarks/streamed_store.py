"""Peak memory of a scene's job against the size of its store: in memory, and block by block.

    python benchmarks/streamed_store.py [--every 0.01 0.004 0.002] [--scene fft106]

For each storage step, a copy of config.yaml whose scene stores every ``every`` (on top of its
snapshots) runs ``cradle run SCENE`` in a fresh process (scratch folder, deleted after); the
table gives the stored times, the bytes written, the job's estimate (peak memory, time, and
whether it streams: cradle.pipeline.budget.streams), and the measured peak RSS (os.wait4) and
wall time. Writes the table ``streamed-store`` of docs/extremes.md.
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

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doctable import publish  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def run(scene: str, every: float, tmp: Path) -> dict:
    from cradle.pipeline import budget, config as cc
    from cradle.pipeline.config.loading import read_yaml

    cfg = read_yaml(ROOT / "config.yaml")
    cfg["scenes"][scene]["store"] = {**(cfg["scenes"][scene].get("store") or {}), "every": every}
    cfg_path = tmp / "config.yaml"
    import yaml

    cfg_path.write_text(yaml.safe_dump(cfg, sort_keys=False))
    e = budget.spec_estimate(cc.scene(cc.load(cfg_path), scene), scene)
    env = dict(os.environ, PYTHONPATH=f"{ROOT / 'src'}{os.pathsep}{os.environ.get('PYTHONPATH', '')}")
    t0 = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "cradle", "run", scene, "--config", str(cfg_path), "--out",
                             str(tmp / "out")], cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    out = proc.stdout.read().decode()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    if status:
        sys.exit(out[-3000:])
    written = sum(f.stat().st_size for f in (tmp / "out").rglob("*.nc"))
    return {"every": every, "T": e.cause.split(": ")[-1].split(" stored")[0], "written": written,
            "estimate": e.memory_bytes, "est_s": e.seconds, "streamed": e.streamed, "rss": usage.ru_maxrss * 1024,
            "wall": wall}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="fft106")
    ap.add_argument("--every", type=float, nargs="+", default=[0.01, 0.004, 0.002])
    args = ap.parse_args(argv)
    from cradle.pipeline.budget import fmt_bytes, fmt_duration

    rows = []
    for every in args.every:
        tmp = Path(tempfile.mkdtemp(prefix="cradle-stream-"))
        try:
            r = run(args.scene, every, tmp)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        print(r, flush=True)
        rows.append(f"| {every:g} | {r['T']} | {fmt_bytes(r['written'])} "
                    f"| {'block by block' if r['streamed'] else 'in memory'} "
                    f"| {fmt_bytes(r['estimate'])} | {fmt_bytes(r['rss'])} | {fmt_duration(r['est_s'])} "
                    f"| {fmt_duration(r['wall'])} |")
    text = (f"`cradle run {args.scene}` with `store.every` set as below "
            f"({time.strftime('%Y-%m-%d')}, this machine):\n\n"
            "| store.every | stored times | written | job | estimated peak | measured peak RSS | estimated time "
            "| measured wall |\n|---|---|---|---|---|---|---|---|\n" + "\n".join(rows))
    publish("extremes.md", "streamed-store", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
