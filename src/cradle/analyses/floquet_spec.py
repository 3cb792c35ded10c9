"""The spec of the `floquet` analysis (``beyond: floquet:``): Bloch-Floquet stability of the exact travelling
waves of (nc), its reduced form and its finer numerics (:mod:`cradle.analyses.floquet` computes from it).

Angles stay as given (numbers or 'pi/5'-style text, what :func:`cradle.specs.declare.plain` gives back and a
file stores); :func:`cradle.specs.values.parse_angle` reads them where they are used.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from cradle.specs.declare import declared, param, schema_doc
from cradle.specs.values import angle_or_none, show

if TYPE_CHECKING:
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

_ANGLES = {"$ref": "#/$defs/angle"}


_OMEGA = {"type": "number", "exclusiveMinimum": 1, "maximum": 2, "description": "One omega_tw."}


@declared(doc="Finer numerics for the convergence checks (threshold, growth at q_profiles), on the main wave grid "
              "(wave_grid_log2); a key left out takes the default of its form.")
class FloquetConvergence:
    hill_modes: int = param(32, "Hill modes of the check.", minimum=4, maximum=256)
    grid_log2: int = param(20, "log2 of the K grid of the check.", minimum=8, maximum=22)
    wave_modes: int = param(256, "Sine modes of the wave of the check.", minimum=8, maximum=2048)


@dataclass(frozen=True)
class Numerics:
    """One resolution of Hill's method and of the wave solver: Hill modes |m| <= hill_modes of W, K sampled
    on 2^grid_log2 points, wave_modes sine modes of the exact wave on 2^wave_grid_log2 points."""

    hill_modes: int
    grid_log2: int
    wave_modes: int
    wave_grid_log2: int


@declared(doc="Spectral (Bloch-Floquet) stability of the exact travelling waves of (nc) in the co-moving frame "
              "(Hill's method), against the DpS threshold q_c = pi/2 -> results/floquet/floquet.nc and "
              "results/figures/floquet.{pdf,png}.")
class Floquet:
    alpha: float = param(1.5, "Hertz exponent alpha of V0 (> 1).", ref="alpha", maximum=10)
    omega_tw: float = param(1.1, "omega_tw of (freq): at each q the amplitude a is (freq) inverted (as the paper's "
                            "travelling-wave scenes); > 1.", exclusiveMinimum=1, maximum=2)
    q_min: float | str = param("0.4pi", "Smallest q of the sweep, in (0, pi).", ref="angle")
    q_max: float | str = param("0.7pi", "Largest q of the sweep, in (q_min, pi).", ref="angle")
    n_q: int = param(61, "Number of q of the sweep.", minimum=3, maximum=1001,
                     reduced=9)
    n_p: int = param(121, "Number of Bloch wavenumbers p in [0, pi] (maxima are refined between them).", minimum=9,
                     maximum=2001,
                     reduced=31)
    hill_modes: int = param(16, "Hill's method: Fourier modes |m| <= hill_modes of the Bloch profile W.", minimum=4,
                            maximum=256,
                            reduced=12)
    grid_log2: int = param(18, "The Fourier coefficients of K = V0''(u(xi+q) - u(xi)) come from 2^grid_log2 samples; "
                           "2^grid_log2 >= 8 (2 hill_modes + 1).", minimum=8, maximum=22,
                           reduced=16)
    wave_modes: int = param(128, "Sine modes of the exact wave (theorem1.solve).", minimum=8, maximum=1024,
                            reduced=64)
    wave_grid_log2: int = param(15, "Grid 2^wave_grid_log2 of the wave solver; >= 8 x wave_modes (also those of "
                                "`convergence`).", minimum=8, maximum=20,
                                reduced=13)
    convergence: FloquetConvergence = param(FloquetConvergence(), schema_doc(FloquetConvergence),
                                            reduced=FloquetConvergence(hill_modes=16, grid_log2=17, wave_modes=96))
    q_profiles: list[float | str] = param(["pi/2", "51pi/100", "52pi/100", "55pi/100", "3pi/5"], "Wavenumbers q where "
                                          "the growth rate against p is stored (numbers or 'pi/2'-style strings, in "
                                          "(0, pi)).", minItems=1, maxItems=10, items=_ANGLES,
                                          reduced=["pi/2"])
    threshold_omega_tw: list[float] = param([1.1, 1.03, 1.01, 1.003], "omega_tw values (each > 1) at which the "
                                            "lattice threshold is searched; must contain omega_tw.", minItems=1,
                                            maxItems=8, items=_OMEGA,
                                            reduced=[1.1, 1.03])
    threshold_q_min: float | str = param("0.4pi", "Lower end of the threshold scan (must be stable), in (0, pi).",
                                         ref="angle")
    threshold_q_max: float | str = param("0.55pi", "Upper end of the threshold scan, in (threshold_q_min, pi).",
                                         ref="angle")
    threshold_n_scan: int = param(16, "Scan points before the bisection of the threshold.", minimum=2, maximum=200,
                                  reduced=6)
    small_omega_tw: float = param(1.001, "Small amplitude (as omega_tw) where the lattice growth rates are checked "
                                  "against DpS; > 1.", exclusiveMinimum=1, maximum=2)
    small_q: list[float | str] = param(["3pi/5", "4pi/5"], "Wavenumbers (DpS-unstable, in (0, pi)) of the "
                                       "small-amplitude check.", minItems=1, maxItems=8, items=_ANGLES,
                                       reduced=["3pi/5"])
    ring_N: int = param(20, "Ring size of the brute-force monodromy check (2N x 2N variational equations).",
                        minimum=3, maximum=200)
    ring_k: int = param(5, "q = 2 pi ring_k / ring_N of the brute-force check; 0 < ring_k < ring_N.", minimum=1,
                        maximum=199)
    direct_N: int = param(20, "Ring size of the direct nonlinear run seeded with the top Floquet mode.", minimum=3,
                          maximum=200)
    direct_k: int = param(5, "q = 2 pi direct_k / direct_N of the direct run (must be unstable).", minimum=1,
                          maximum=199)
    direct_growth_factor: float = param(1000.0, "The direct run lasts until the mode grows by this factor (> 1).",
                                        exclusiveMinimum=1, maximum=100000000.0,
                                        reduced=100.0)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Angles in (0, pi) with q_min < q_max and threshold_q_min < threshold_q_max, omega_tw among
        threshold_omega_tw, grids fine enough for the Hill and sine modes, 0 < k < N for the ring checks."""
        given = {"q_min": self.q_min, "q_max": self.q_max, "threshold_q_min": self.threshold_q_min,
                 "threshold_q_max": self.threshold_q_max}
        q = {key: angle_or_none(value) for key, value in given.items()}
        for key, x in q.items():
            if x is not None and not 0.0 < x < math.pi:
                out.add(where + [key], "must be in (0, pi)", given[key])
        for lo, hi in (("q_min", "q_max"), ("threshold_q_min", "threshold_q_max")):
            x_lo, x_hi = q[lo], q[hi]
            if x_lo is not None and x_hi is not None and 0 < x_lo < math.pi and not x_hi > x_lo:
                out.add(where + [hi], f"must exceed {lo} = {show(given[lo])}", given[hi])
        for key, angles in (("q_profiles", self.q_profiles), ("small_q", self.small_q)):
            for i, e in enumerate(angles):
                x = angle_or_none(e)
                if x is not None and not 0.0 < x < math.pi:
                    out.add(where + [key, i], "must be in (0, pi)", e)
        if float(self.omega_tw) not in [float(x) for x in self.threshold_omega_tw]:
            out.add(where + ["threshold_omega_tw"], f"must contain omega_tw = {show(self.omega_tw)}",
                    self.threshold_omega_tw)
        conv = self.convergence
        for at, g, h in ((where, self.grid_log2, self.hill_modes), (where + ["convergence"], conv.grid_log2,
                                                                     conv.hill_modes)):
            if 2 ** g < 8 * (2 * h + 1):
                out.add(at + ["grid_log2"], f"2^grid_log2 must be >= 8 (2 hill_modes + 1) = {8 * (2 * h + 1)}", g)
        if 2 ** self.wave_grid_log2 < 8 * max(self.wave_modes, conv.wave_modes):
            out.add(where + ["wave_grid_log2"], "2^wave_grid_log2 must be >= 8 x wave_modes (also those of "
                                                "`convergence`)", self.wave_grid_log2)
        for key_n, key_k, n, k in (("ring_N", "ring_k", self.ring_N, self.ring_k),
                                   ("direct_N", "direct_k", self.direct_N, self.direct_k)):
            if not 0 < k < n:
                out.add(where + [key_k], f"need 0 < {key_k} < {key_n} = {n} (q = 2 pi k / N)", k)

    @property
    def numerics(self) -> Numerics:
        """The main numerics of every Hill problem and wave."""
        return Numerics(self.hill_modes, self.grid_log2, self.wave_modes, self.wave_grid_log2)

    @property
    def fine(self) -> Numerics:
        """The finer numerics of the convergence checks: those of ``convergence`` on the main wave grid."""
        conv = self.convergence
        return Numerics(conv.hill_modes, conv.grid_log2, conv.wave_modes, self.wave_grid_log2)
