"""Declaration of ``beyond.mi_statistics``: the modulational-instability threshold over noise seeds.

The fftseuil experiment (travelling wave (ansatzapprox)-(freq) perturbed as in
(perturb)) repeated over a grid of q, ring sizes N and seeds, in both models;
shared settings at the top, the sweep per variant (reduced, full).
"""
from __future__ import annotations

import dataclasses

from cradle.scenes.context import Context, Where
from cradle.scenes.spec import DPS_METHODS, SPLITTINGS
from cradle.specs.declare import NULL, declared, param
from cradle.specs.values import INTEGER_TOL, ConfigError, Errors


@declared(doc="Lattice integrator (null keys: defaults.exact).")
class MIStatisticsExact:
    method: str = param("srkn6c", "A splitting of cradle.integrators (srkn6c is the fastest at the default "
                        "accuracy).", enum=list(SPLITTINGS))
    dt_factor: float | None = param(NULL, "Step as a fraction of the shortest linear period; null = the method's "
                                    "default.", exclusiveMinimum=0, maximum=0.5)


@declared(doc="DpS integrator.")
class MIStatisticsDps:
    method: str = param("dop853_numba", "dop853_numba: DOP853 compiled (fastest for these N).", enum=list(DPS_METHODS))
    rtol: float = param(1e-10, "Relative tolerance (atol = rtol max |A_n(0)|), as defaults.dps.rtol.",
                        exclusiveMinimum=0, maximum=0.001)


@declared(doc="Grid of carrier wavenumbers q / pi: count values from start to stop.")
class QGrid:
    start: float = param(0.47, "Smallest q / pi.", exclusiveMinimum=0, maximum=1.0)
    stop: float = param(0.59, "Largest q / pi.", exclusiveMinimum=0, maximum=1.0)
    count: int = param(7, "Number of q values.", minimum=2, maximum=1000)


@declared(doc="One sweep: ring sizes, q grid, seeds and batching.")
class MIVariant:
    N: list[int] = param([200], "Ring sizes N (even; q N / (2 pi) must be an integer for every q of the grid).",
                         minItems=1, maxItems=6, items={"type": "integer", "minimum": 8, "maximum": 4096,
                                                        "description": "A ring size."})
    q_over_pi: QGrid = param(QGrid(), "Grid of carrier wavenumbers q / pi: count values from start to stop.")
    n_seeds: int = param(4, "Noise realisations per (q, N, model).", minimum=1, maximum=1000)
    chunks: int = param(1, "Batches (Snakemake jobs) per (N, model); q values dealt round-robin.", minimum=1,
                        maximum=100)

    def check(self, where: Where, out: Errors) -> None:
        """start < stop, no more batches than q values, and every q of the grid on every ring's
        wavenumber grid (N even for Gamma*, q N / (2 pi) an integer)."""
        g = self.q_over_pi
        if not g.start < g.stop:
            out.add(where + ["q_over_pi"], "need start < stop", dataclasses.asdict(g))
            return
        count = int(g.count)
        vals = [g.start + i * (g.stop - g.start) / (count - 1) for i in range(count)]
        if self.chunks > count:
            out.add(where + ["chunks"], f"more batches than q values (count = {count})", self.chunks)
        for j, N in enumerate(self.N):
            if N % 2:
                out.add(where + ["N", j], "must be even (Gamma* of the spatial DFT)", N)
                continue
            for x in vals:
                m = x * N / 2.0
                if abs(m - round(m)) > INTEGER_TOL:
                    out.add(where + ["q_over_pi"], f"q = {x:.10g} pi gives q N/(2 pi) = {m:.10g} for N = {N}: with "
                                                   f"periodic ends it must be an integer (choose start, stop, count "
                                                   f"so that the step is a multiple of 2/N)", dataclasses.asdict(g))
                    break


VARIANTS = ("reduced", "full")


@declared(doc="Threshold of the modulational instability over noise seeds, ring sizes N and both models "
              "(cradle.analyses.mi_statistics): the fftseuil experiment repeated; shared settings here, the q grid, "
              "N, seeds and batching per variant.")
class MIStatistics:
    alpha: float | None = param(NULL, "Hertz exponent alpha; null = defaults.alpha.", exclusiveMinimum=1, maximum=10)
    omega_tw: float = param(1.1, "Frequency omega_tw of the travelling wave (freq); a follows from q (the fftseuil "
                            "scenes: 1.1).", exclusiveMinimum=1.0, maximum=3.0)
    noise_kind: str = param("gaussian", "Distribution of rho_n^(1), rho_n^(2) of (perturb) (the fftseuil scenes: "
                            "gaussian).", enum=["gaussian", "uniform"])
    noise_amplitude: float = param(0.05, "Standard deviation (gaussian) or half-width (uniform) of the noise of "
                                   "(perturb) (the fftseuil scenes: 0.05).", exclusiveMinimum=0, maximum=1.0)
    t_end: float = param(913.7, "Final time t of every run (the fftseuil scenes: 913.7).", exclusiveMinimum=0,
                         maximum=100000.0)
    sample_every: float = param(1.0, "The spectrum is measured every sample_every time units (the fields are not "
                                "stored).", exclusiveMinimum=0, maximum=100.0)
    fraction: float = param(0.5, "A run is unstable when its sideband-to-carrier ratio reaches this fraction by "
                            "t_end. Below the DpS threshold the noise alone brings the ratio to ~0.2 by t = 913.7, "
                            "hence 0.5.",
                            exclusiveMinimum=0, maximum=10.0)
    exclude_bins: int = param(0, "Bins left out on each side of +-q and of the lattice harmonics +-2(q-pi), "
                              "+-(3q-2pi) in the sideband ratio (0: only those bins).", minimum=0, maximum=10)
    seed0: int = param(20111000, "Seeds are seed0, seed0+1, ..., seed0+n_seeds-1, the same at every q and N.",
                       minimum=0, maximum=4611686018427387904)
    exact: MIStatisticsExact = param(MIStatisticsExact(), "Lattice integrator (null keys: defaults.exact).")
    dps: MIStatisticsDps = param(MIStatisticsDps(), "DpS integrator.")
    reduced: MIVariant = param(MIVariant(), "The small sweep built by `snakemake all` (minutes): "
                               "results/mi/mi-statistics.nc, results/figures/mi-statistics.{pdf,png}.")
    full: MIVariant = param(MIVariant(N=[200, 400], q_over_pi=QGrid(start=0.45, stop=0.65, count=21), n_seeds=32,
                                      chunks=3),
                            "The full sweep (`snakemake -j2 mi_statistics_full`): results/mi/full/mi-statistics.nc "
                            "and results/mi/full/mi-statistics.{pdf,png}.")

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each sweep (reduced, full) on the wavenumber grids of its rings."""
        self.reduced.check(where + ["reduced"], out)
        self.full.check(where + ["full"], out)

    @staticmethod
    def resolve(cfg: dict, variant: str) -> dict:
        """``beyond.mi_statistics.<variant>`` with the shared keys merged in, alpha and the integrators
        inherited from ``defaults`` where not given."""
        ms = cfg["beyond"]["mi_statistics"]
        if variant not in VARIANTS:
            raise ConfigError(f"config error: beyond.mi_statistics: unknown variant {variant!r} (reduced or full)")
        common = {k: v for k, v in ms.items() if k not in VARIANTS}
        spec = {**common, **ms[variant], "variant": variant}
        d = cfg["defaults"]
        spec["alpha"] = float(spec.get("alpha") or d["alpha"])
        spec["exact"] = {"method": d["exact"]["method"], "dt_factor": d["exact"]["dt_factor"],
                         **(spec.get("exact") or {})}
        spec["dps"] = {"method": d["dps"]["method"], "rtol": d["dps"]["rtol"], **(spec.get("dps") or {})}
        return spec
