"""The DpS travelling breathers' verdicts in the limit N -> infinity, ring by ring (travelling-breathers.md).

    python benchmarks/tb_limit.py OUT.nc N [N ...] [--step S] [--halfwidth H] [--speeds C,C,...] [--newton-tol E]
    e.g. ... /tmp/l64.nc 64;  ... /tmp/l96.nc 96 --speeds 0.08,0.1,0.12,0.14 --newton-tol 5e-11

The fine scan of robustness_limit (cradle.analyses.travelling_breathers.fine_scan; the full form's speeds, alpha =
3/2, unit norm, rtol 1e-13; default step and half-width those of the full form) on the rings N given, written to
OUT.nc (the group /robustness_limit of the analysis's file, with the rings given) and summarised per member: the
unstable fraction, the median and the largest growth rate of its neighbourhood on each ring, the exponent k and the
limit verdict of LIMIT_RULE over the rings given (the analysis's full form gives it over limit_N). --speeds scans
the neighbourhoods of those members only (the grid still runs continuously from the slowest to the fastest);
--newton-tol relaxes Newton on large rings (on 96 sites the first TB stops at 2.4e-11 against the default 1e-11).
Several files of single rings are combined by benchmarks/tb_limit.py --merge OUT.nc IN.nc [IN.nc ...]. CPU: about
30 s (N = 24) to several minutes (N = 64) per ring on the shared machine; run under nice.

    python benchmarks/tb_limit.py --rule FULL.nc [RING.nc ...]

reads the tail rule (tail_rule_of of cradle.analyses.travelling_breathers.limit_tail) from a full form's file (its
/robustness, /robustness_limit and /limit_large) with the rings of the RING.nc files (this script's output, on the
grid of /limit_large) added as larger rings, and prints per member with an MI-stable tail the envelope and the
member's own growth rate on each ring, their fits g_inf + b N^-k and both verdicts (the table of
travelling-breathers.md).
"""
from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from cradle.analyses import travelling_breathers as tb  # noqa: E402
from cradle.analyses.protocol import FULL, form_spec  # noqa: E402
from cradle.analyses.travelling_breathers import fine_scan, limit_tail  # noqa: E402
from cradle.specs.declare import from_plain, plain  # noqa: E402


def summary(c: np.ndarray, rings: list[int], group: dict, spec: tb.TravellingBreathers) -> None:
    """One line per member: per ring the unstable fraction, median and largest growth; k and the verdict."""
    print("c     | " + " | ".join(f"N = {n}: frac  median   largest" for n in rings) + " | k      verdict")
    for j, x in enumerate(c):
        cells = [f"{group['unstable_fraction'][j, i]:.2f} {group['typical_growth'][j, i]:.1e} "
                 f"{group['largest_growth'][j, i]:.1e}" for i in range(len(rings))]
        v, k = fine_scan.limit_rule(np.array(rings, float), group["typical_growth"][j], spec.stability_threshold)
        print(f"{x:.3f} | " + " | ".join(cells) + f" | {k:+.2f} {({1: 'U', 0: 'S'}).get(v, '?')}")


def rule(full: str, extra: list[str]) -> None:
    """The tail rule's envelope and member fits over the full form's rings and the extra rings' (module docstring)."""
    import xarray as xr

    def read(group: str, path: str = full) -> xr.Dataset:
        return xr.open_dataset(path, group=group)

    c = xr.open_dataset(full).c.values
    theta = read("family").theta.values
    rob = read("robustness")
    limit = read("robustness_limit")
    large = read("limit_large")
    parts = [read("robustness_limit", p) for p in extra]
    for p in parts:
        if not np.array_equal(np.round(p.c_fine.values, 9), np.round(large.c_large.values, 9)):
            raise SystemExit(f"{p.encoding.get('source')}: its grid is not /limit_large's")
    rings_large = [*large.large_ring.values.tolist(), *[int(n) for p in parts for n in p.limit_ring.values]]
    arrays = {k: np.vstack([large[v].values, *[p[v].values for p in parts]])
              for k, v in (("growth", "growth_rate"), ("theta", "theta"), ("tail", "tail"), ("tail_mi", "tail_mi_rate"),
                           ("quartet_defect", "quartet_defect"), ("unstable", "unstable"))}
    spec = dataclasses.replace(form_spec(from_plain(tb.TravellingBreathers, {}), FULL),
                               limit_N=limit.limit_ring.values.tolist(), limit_large_N=rings_large)
    robd = {"theta_ring": rob.theta.values, "theta_tol": rob.theta.values[:1], "tail_mi_ring": rob.tail_mi_rate.values}
    groups, attrs = limit_tail.tail_rule_of(spec, c, theta, robd, ({"growth_rate": limit.growth_rate.values,
                                                             "theta": limit.theta.values},
                                                            {"c_fine": limit.c_fine.values}),
                                    large.c_large.values, arrays)
    g, coords = groups["/limit_tail"]
    letter = {fine_scan.LIMIT_STABLE: "S", fine_scan.LIMIT_UNSTABLE: "U", fine_scan.LIMIT_UNDECIDED: "?"}
    print("rings " + " ".join(str(n) for n in coords["fit_ring"]))
    for j, x in enumerate(c):
        if g["tail_mi_unstable"][j]:
            continue
        for name, row, pre in (("envelope", g["envelope"][j], "fit_"),
                               ("member", g["member_growth"][j], "member_fit_")):
            v = g["verdict" if name == "envelope" else "member_verdict"][j]
            print(f"{x:.3f} {name:8s} " + " ".join(f"{y:.1e}" for y in row)
                  + f" | g_inf {g[pre + 'g_inf'][j]:.2e} +- {g[pre + 'g_inf_error'][j]:.1e}, k {g[pre + 'k'][j]:.2f}"
                  + f"{' (degenerate)' if g[pre + 'degenerate'][j] == 1 else ''} -> {letter[int(v)]}")


def main(argv: list[str]) -> None:
    import xarray as xr

    if argv[0] == "--rule":
        rule(argv[1], argv[2:])
        return
    if argv[0] == "--merge":
        parts = [xr.open_dataset(p, group="robustness_limit") for p in argv[2:]]
        xr.concat(parts, dim="limit_ring", data_vars="minimal", coords="minimal", compat="override",
                  join="outer").to_netcdf(argv[1], group="robustness_limit")
        return
    out, rest = argv[0], argv[1:]
    opts: dict = {"limit_step": None, "limit_halfwidth": None, "speeds": None, "newton_tol": None}
    rings = []
    while rest:
        a = rest.pop(0)
        if a in ("--step", "--halfwidth"):
            opts["limit_" + a[2:]] = float(rest.pop(0))
        elif a == "--speeds":
            opts["speeds"] = [float(x) for x in rest.pop(0).split(",")]
        elif a == "--newton-tol":
            opts["newton_tol"] = float(rest.pop(0))
        else:
            rings.append(int(a))
    base = plain(form_spec(from_plain(tb.TravellingBreathers, {}), FULL))
    base["limit_N"] = rings if len(rings) >= 2 else [rings[0], rings[0] + 1]
    speeds = opts.pop("speeds")
    base.update({k: v for k, v in opts.items() if v is not None})
    spec = from_plain(tb.TravellingBreathers, base)
    if len(rings) == 1:
        spec = dataclasses.replace(spec, limit_N=rings)
    if speeds is not None:
        # the scan reads only the speeds (two are allowed here, where the spec asks three for its family)
        spec = dataclasses.replace(spec, speeds=speeds)
    c = np.asarray(spec.speeds, float)
    groups, attrs = fine_scan.robustness_limit(spec, c, print)
    data, coords = groups["/robustness_limit"]
    ds = xr.Dataset({k: ((("limit_ring", "c_fine") if np.ndim(v) == 2 and np.shape(v)[0] == len(rings)
                           and np.shape(v)[1] == coords["c_fine"].size else
                           ("c", "limit_ring") if np.ndim(v) == 2 else
                           ("limit_ring",) if np.size(v) == len(rings) and k in ("windows", "window_width",
                                                                                  "ring_largest_growth",
                                                                                  "ring_unstable_fraction")
                           else ("c",)), np.asarray(v)) for k, v in data.items()},
                    coords={"limit_ring": coords["limit_ring"], "c_fine": coords["c_fine"], "c": c},
                    attrs={k: v for k, v in attrs.items() if isinstance(v, (int, float, str))})
    ds.to_netcdf(out, group="robustness_limit")
    summary(c, rings, data, spec)
    print(f"CPU {attrs['limit_cpu_s']:.0f} s")


if __name__ == "__main__":
    main(sys.argv[1:])
