"""``cradle scenes``: the config's scenes, homoclinic and map entries, figures, what each needs and costs."""
from __future__ import annotations

from cradle.pipeline.cli.common import load_config, section_of


def _scene_line(name, spec) -> str:
    from cradle.pipeline import config as cc

    ini = spec["initial"]
    kind = ini["kind"]
    what = kind
    if kind == "travelling":
        what += f" q={ini.get('q')}" + "".join(f" {k}={ini[k]}" for k in ("a", "omega_tw") if ini.get(k) is not None)
        if ini.get("noise"):
            what += f" +{ini['noise'].get('kind')} noise"
    elif kind == "breather":
        what += f" from homoclinic '{ini['homoclinic']}'"
    if kind in ("breather", "packet", "pair") and ini.get("amplitude") is not None:
        what += f" amplitude={ini['amplitude']:g}"
    times = cc.store_times(spec["store"], spec["t_end"])
    return f"  {name:<16} N={spec['N']:<4} {spec['bc']:<8} t_end={spec['t_end']:<8g} {len(times):>6} stored times  {what}"


def _cost_line(cfg, name) -> str:
    """The scene's estimated job cost (cradle.pipeline.budget), under its line of ``cradle scenes``."""
    from cradle.pipeline import budget

    e = budget.scene_estimate(cfg, name)
    return (f"  {'':<16} estimated: peak memory {budget.fmt_bytes(e.memory_bytes)}, "
            f"writes {budget.fmt_bytes(e.disk_bytes)}, about {budget.fmt_duration(e.seconds)}")


def cmd_scenes(args) -> int:
    cfg = load_config(args.config)
    out = [f"{args.config}: {len(cfg.get('scenes') or {})} scenes, {len(cfg.get('homoclinic') or {})} homoclinic, "
           f"{len(cfg.get('map') or {})} map, {len(cfg.get('figures') or {})} figures", "", "scenes:"]
    for name, spec in (cfg.get("scenes") or {}).items():
        out.append(_scene_line(name, spec))
        out.append(_cost_line(cfg, name))
        if spec["initial"]["kind"] == "breather":
            out.append(f"  {'':<16} needs homoclinic/{spec['initial']['homoclinic']}.nc")
        out.append(f"  {'':<16} makes initial/{name}.nc, sim/{name}/exact.nc, sim/{name}/dps.nc, metrics/{name}.nc")
    out += ["", "homoclinic:"]
    for name, spec in (cfg.get("homoclinic") or {}).items():
        out.append(f"  {name:<16} N={spec['N']:<4} {spec['bc']:<8} guess={spec['guess']:<8} makes homoclinic/{name}.nc")
    out += ["", "map:"]
    for name, spec in (cfg.get("map") or {}).items():
        out.append(f"  {name:<16} iterations={spec['iterations']} box={spec['box']}  makes map/{name}.nc")
    out += ["", "figures (label: the entries it reads, the times it shows):"]
    for label, fig in (cfg.get("figures") or {}).items():
        reads = [name if section_of(cfg, name) == "scenes" else f"{name} ({section_of(cfg, name)})"
                 for name in fig["scenes"]]
        times = f"  at t = {', '.join(f'{t:g}' for t in fig['times'])}" if fig.get("times") else ""
        out.append(f"  {label:<12} {', '.join(reads)}{times}")
    print("\n".join(out))
    return 0
