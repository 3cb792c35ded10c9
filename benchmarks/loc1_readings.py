"""The readings of figure loc1 mapped: which initial data give the paper's picture.

    python benchmarks/loc1_readings.py [--periods 1200] [--out FILE]   (default: its tables in docs/loc1-readings.md)

The paper (section 4.3) leaves the initial data of loc1 open. Pair (right):
"two small amplitude static breathers initially separated by one lattice site,
with amplitude close to 0.01", merging "after a long transient", ~175
breather periods in (nc) and about twice that in DpS. Packet (left): "almost
compactly supported on 12 lattice sites, modulating binary oscillation with
amplitude close to 0.016", splitting "into a static breather and two pairs of
breathers travelling slowly in opposite directions". This script runs every
reading in both models (N = 50, periodic, zero velocities, DpS from tau = 0
in (breatherdps)) and writes the table reading -> outcome:

* pair: site-, bond-centred and mixed copies of the homoclinic profile of
  (dpsstn) (:mod:`cradle.models.pairs`), centre spacings from adjacent cores
  to 10 sites, theta = 0 (in phase on the (-1)^n carrier) and pi
  (antiphase), each copy of peak |x| = 0.01; outcome and merging period by
  :func:`cradle.measurements.interactions.classify`, both merging times (first coalescence, final
  single breather); then the noise seeds of the breather-interactions sweep at the loc1-pair reading;
* packet: Gaussian envelopes of a few widths, sech, super-Gaussian, box and
  cos^2 on ~12 sites, peak 0.016; the number of humps that leave the centre
  and how many stay (:func:`packet_outcome`).
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

# below the thread count (numba reads it when first imported) and the path
from cradle.analyses import pair_runs  # noqa: E402
from cradle.measurements import interactions  # noqa: E402
from cradle.models import initial, pairs  # noqa: E402
from doctable import publish  # noqa: E402

N, ALPHA, AMP = 50, 1.5, 0.01
PACKET_AMP, PACKET_OMEGA = 0.016, 1.1
PROFILE_PAIRS = (("site", "site"), ("bond", "bond"), ("site", "bond"))
THETAS = ((0.0, "0"), (np.pi, "pi"))


def spacings(profiles, largest=10):
    half = 0.5 if profiles[0] != profiles[1] else 0.0
    return [k + half for k in range(1, largest + 1)] if half == 0 else [k + half for k in range(largest)]


def pair_rows(periods: float):
    rows = []
    for prof in PROFILE_PAIRS:
        for sp in spacings(prof):
            for theta, label in THETAS:
                c = pairs.symmetric_centres(N, prof, sp)
                d = pairs.two_breathers(N, ALPHA, profiles=prof, centres=c, amplitudes=(AMP, AMP), theta=theta)
                t_end = periods * 2 * np.pi / d.info["omega_sw"]
                r = pair_runs.run_pair(d, t_end, ALPHA)
                rows.append({"profiles": "-".join(prof), "spacing": sp, "theta": label, "centres": c,
                             "omega_sw": d.info["omega_sw"], **{m: r[m] for m in r}})
                print(rows[-1]["profiles"], sp, label, *(f"{m}: {_cell(r[m])}" for m in r), flush=True)
    return rows


def _cell(res) -> str:
    o = res["outcome"]
    first = "" if not np.isfinite(o.first_coalescence) else f" (first coalescence {o.first_coalescence:.0f})"
    if o.outcome == "merge":
        return f"merge at {o.merge_period:.0f}{first}"
    if o.outcome == "repel":
        return f"repel ({o.separation_velocity:.3f} sites/period)"
    if o.outcome == "none":
        return "one hump from the start"
    return o.outcome + first


def seed_rows():
    """The noise seeds of the breather-interactions sweep (its full form's declared defaults) at the loc1-pair
    reading (site-site 6 apart, in phase): both merging times of each seed, in both models."""
    from cradle.analyses import breather_interactions as bi

    spec = bi.BreatherInteractions()
    rows = []
    for seed in range(spec.n_seeds):
        r = bi.run_case(spec, "site-site", 6.0, 0.0, 1.0, spec.amplitude, seed)
        rows.append({"seed": seed, **r})
        print("seed", seed, {k: v for k, v in r.items() if "merge_period" in k or "first_coalescence" in k}, flush=True)
    return rows, spec


def seed_markdown(rows, spec) -> list[str]:
    def cell(r, m):
        merged = f"{r[f'merge_period_{m}']:.0f}" if np.isfinite(r[f"merge_period_{m}"]) else f"none in {spec.periods:g}"
        return f"{r[f'first_coalescence_{m}']:.0f} | {merged}"

    def spread(key):
        v = np.array([r[key] for r in rows], float)
        ok = v[np.isfinite(v)]
        return (f"{ok.min():.0f}-{ok.max():.0f}, median {np.median(ok):.0f} ({ok.size} of {v.size})" if ok.size
                else f"none of {v.size}")

    lines = ["", "### Pair: the noise seeds of breather-interactions at the loc1-pair reading", "",
             (f"Site-site 6 apart in phase, |x| = {spec.amplitude:g} each, plus the sweep's noise "
              f"(A_n(0) += {spec.noise:g} amplitude / 2 xi_n, seeds (seed_base, s)); {spec.periods:g} periods. "
              "First coalescence: first period of the first single state; final: first period of the final "
              "single breather (`Outcome.first_coalescence`, `Outcome.merge_period`)."), "",
             "| seed | exact first | exact final | DpS first | DpS final |", "|---|---|---|---|---|"]
    lines += [f"| {r['seed']} | {cell(r, 'exact')} | {cell(r, 'dps')} |" for r in rows]
    lines += ["", *(f"* {m}: first coalescence {spread(f'first_coalescence_{m}')}; final single breather "
                    f"{spread(f'merge_period_{m}')}" for m in ("exact", "dps"))]
    return lines


# ------------------------------------------------------------------ packets

def envelope(s, kind, width):
    """Envelopes of peak 1 on ~``width`` sites (s = n - centre)."""
    if kind.startswith("gaussian"):        # gaussian-w6: sigma = width/6, gaussian-w4: width/4, ...
        sigma = width / float(kind.split("-w")[1])
        return np.exp(-0.5 * (s / sigma) ** 2)
    if kind == "sech":                     # 1/cosh with the 0.5 % level at width/2
        return 1.0 / np.cosh(s * np.arccosh(200.0) / (width / 2.0))
    if kind == "super-gaussian":           # exp(-(s/w)^4), 0.5 % at width/2
        w = (width / 2.0) / np.log(200.0) ** 0.25
        return np.exp(-(s / w) ** 4)
    if kind == "box":
        return (np.abs(s) < width / 2.0).astype(float)
    if kind == "cos2":
        return initial.envelope(s, "cos2", width)
    raise ValueError(kind)


PACKETS = ("gaussian-w6", "gaussian-w4", "gaussian-w8", "sech", "super-gaussian", "box", "cos2")


def packet_outcome(t, x, period, window=(20, 250), rel=0.05, hold=10):
    """What the packet became: humps of max_t |x_n| per period (down to ``rel`` of the largest: the
    travelling pulses are small beside the static breather) over the periods ``window`` (after the
    split, before the pulses meet on the far side of the ring): (within 3 sites of the centre, to its
    left, to its right), each the largest count seen in at least ``hold`` periods (pulses leave the
    packet at different times)."""
    _starts, P = interactions.peak_compression(t, x, period)
    N = x.shape[1]
    cent0 = (N - 1) / 2.0
    got = []
    for p in P[window[0]:window[1]]:
        c, _ = interactions.humps(p, rel=rel)
        d = (c - cent0 + N / 2) % N - N / 2
        got.append((int(np.sum(np.abs(d) <= 3)), int(np.sum(d < -3)), int(np.sum(d > 3))))
    got = np.array(got)
    return tuple(int(max([c for c in range(got[:, j].max() + 1) if np.sum(got[:, j] >= c) >= hold]))
                 for j in range(3))


def packet_rows(periods: float, widths=(12,)):
    from cradle.integrators import integrate_dps, integrate_lattice
    from cradle.measurements import compare

    rows = []
    period = 2 * np.pi / PACKET_OMEGA
    t_end = periods * period
    times = np.arange(0.0, t_end + 1e-9, pair_runs.EVERY)
    n = np.arange(N)
    for width in widths:
        for kind in PACKETS:
            x0 = PACKET_AMP * (-1.0) ** n * envelope(n - (N - 1) / 2.0, kind, width)
            d = initial.from_displacements(x0, ALPHA)
            out = {"envelope": kind, "width": width, "sites": int(np.sum(np.abs(x0) >= 0.005 * PACKET_AMP))}
            ex = integrate_lattice(d.x0, d.v0, times, alpha=ALPHA, method="srkn6c")
            ap = integrate_dps(d.A0, times, alpha=ALPHA, method="dop853_numba", rtol=pair_runs.DPS_RTOL)
            xa = compare.approximate_displacement(ap.A, times, 1.0)
            for model, x in (("exact", ex.x), ("dps", xa)):
                out[model] = packet_outcome(times, x, period)
            rows.append(out)
            print(out, flush=True)
    return rows


def markdown(prs, pks, periods, packet_periods, wall, seeds=None) -> str:
    lines = [(f"N = {N}, periodic, zero velocities; pairs run {periods:g} breather periods 2 pi/omega_sw, packets "
              f"{packet_periods:g} periods 2 pi/1.1; DpS from tau = 0 in (breatherdps); measured in {wall:.0f} s."),
             "",
             "### Pair (loc1, right): two copies of peak |x| = 0.01", "",
             ("theta = 0: in phase on the (-1)^n carrier; pi: antiphase. Spacing: distance of the centres "
             "(sites; a bond-centred copy sits on a bond midpoint). Outcome by "
             "`cradle.measurements.interactions.classify`; merging in breather periods."), "",
             "| copies | spacing | theta | omega_sw | exact (nc) | DpS |", "|---|---|---|---|---|---|"]
    for r in prs:
        lines.append(f"| {r['profiles']} | {r['spacing']:g} | {r['theta']} | {r['omega_sw']:.4f} | "
                     f"{_cell(r['exact'])} | {_cell(r['dps'])} |")
    if seeds:
        lines += seed_markdown(*seeds)
    lines += ["", "### Packet (loc1, left): peak 0.016, ~12 sites", "",
              ("Humps of max_t |x_n| per period (omega = 1.1, humps down to 5 % of the largest) over periods "
               "20-250 (after the split, before the pulses meet on the far side of the ring), the largest count "
               "held for >= 10 periods: static (within 3 sites of the centre) + left + right. The paper: a static "
               "breather and two pairs travelling in opposite directions, 1 + 2 + 2."), "",
              "| envelope | sites >= 0.5 % of peak | exact | DpS |",
              "|---|---|---|---|"]
    for r in pks:
        ex, dp = r["exact"], r["dps"]
        lines.append(f"| {r['envelope']} (width {r['width']}) | {r['sites']} | {ex[0]} + {ex[1]} + {ex[2]} | "
                     f"{dp[0]} + {dp[1]} + {dp[2]} |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--periods", type=float, default=1200.0, help="length of the pair runs")
    ap.add_argument("--packet-periods", type=float, default=600.0, help="length of the packet runs")
    ap.add_argument("--out", help="write the tables to this file instead of their place in docs/loc1-readings.md")
    ap.add_argument("--only", choices=("pair", "packet", "both"), default="both")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    prs = pair_rows(args.periods) if args.only in ("pair", "both") else []
    seeds = seed_rows() if args.only in ("pair", "both") else None
    pks = packet_rows(args.packet_periods) if args.only in ("packet", "both") else []
    text = markdown(prs, pks, args.periods, args.packet_periods, time.perf_counter() - t0, seeds)
    if args.out:
        Path(args.out).write_text(text)
    else:   # only between the markers: the page's own text (the paragraphs the claims table links to) stays
        publish("loc1-readings.md", "readings", text)
    print(text)


if __name__ == "__main__":
    main()
