"""``cradle scenes``: the config's scenes, homoclinic and map entries, figures, what each needs and costs."""
from __future__ import annotations

from typing import TYPE_CHECKING

from cradle.pipeline.cli.common import load_config, section_of
from cradle.scenes.spec import Breather, Packet, Pair, Scene, Travelling

if TYPE_CHECKING:
    import argparse


def _scene_line(name: str, spec: Scene) -> str:
    """One line of ``cradle scenes``: the scene's size, its stored times and its initial condition."""
    ini = spec.initial
    what = ini.kind
    if isinstance(ini, Travelling):
        what += f" q={ini.q}" + "".join(f" {k}={v}" for k, v in (("a", ini.a), ("omega_tw", ini.omega_tw))
                                        if v is not None)
        if ini.noise:
            what += f" +{ini.noise.kind} noise"
    elif isinstance(ini, Breather):
        what += f" from homoclinic '{ini.homoclinic}'"
    if isinstance(ini, (Breather, Packet, Pair)) and ini.amplitude is not None:
        what += f" amplitude={ini.amplitude:g}"
    return (f"  {name:<16} N={spec.N:<4} {spec.bc:<8} t_end={spec.t_end:<8g} {len(spec.times):>6} stored times  "
            f"{what}")


def _cost_line(name: str, spec: Scene) -> str:
    """The scene's estimated job cost (cradle.pipeline.budget), under its line of ``cradle scenes``."""
    from cradle.pipeline import budget

    e = budget.spec_estimate(spec, name)
    return (f"  {'':<16} estimated: peak memory {budget.fmt_bytes(e.memory_bytes)}, "
            f"writes {budget.fmt_bytes(e.disk_bytes)}, about {budget.fmt_duration(e.seconds)}")


def cmd_scenes(args: argparse.Namespace) -> int:
    from cradle.pipeline import config as cc

    cfg = load_config(args.config)
    out = [f"{args.config}: {len(cfg.get('scenes') or {})} scenes, {len(cfg.get('homoclinic') or {})} homoclinic, "
           f"{len(cfg.get('map') or {})} map, {len(cfg.get('figures') or {})} figures", "", "scenes:"]
    for name in cfg.get("scenes") or {}:
        spec = cc.scene(cfg, name)
        out.append(_scene_line(name, spec))
        out.append(_cost_line(name, spec))
        if isinstance(spec.initial, Breather):
            out.append(f"  {'':<16} needs homoclinic/{spec.initial.homoclinic}.nc")
        out.append(f"  {'':<16} makes initial/{name}.nc, sim/{name}/exact.nc, sim/{name}/dps.nc, metrics/{name}.nc")
    out += ["", "homoclinic:"]
    for name in cfg.get("homoclinic") or {}:
        h = cc.homoclinic(cfg, name)
        out.append(f"  {name:<16} N={h.N:<4} {h.bc:<8} guess={h.guess:<8} makes homoclinic/{name}.nc")
    out += ["", "map:"]
    for name in cfg.get("map") or {}:
        m = cc.map_entry(cfg, name)
        out.append(f"  {name:<16} iterations={m.iterations} box={m.box}  makes map/{name}.nc")
    out += ["", "figures (label: the entries it reads, the times it shows):"]
    for label, fig in (cfg.get("figures") or {}).items():
        reads = [name if section_of(cfg, name) == "scenes" else f"{name} ({section_of(cfg, name)})"
                 for name in fig["scenes"]]
        times = f"  at t = {', '.join(f'{t:g}' for t in fig['times'])}" if fig.get("times") else ""
        out.append(f"  {label:<12} {', '.join(reads)}{times}")
    print("\n".join(out))
    return 0
