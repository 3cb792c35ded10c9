"""JKC 2013's variants as scenes: surface mode, boomeron and nanopteron of a kicked chain, measured.

James, Kevrekidis & Cuevas, Physica D 251 (2013) 39 ("Breathers in oscillator chains with Hertzian interactions")
kick one bead of the Hertzian chain with an on-site potential from rest. Their abstract (the only text we have)
claims, for the lattice (ncimperfect) with W = x^2/2 + beta x^4/4 and a precompression delta_0:

* a travelling breather, "well described by the DpS equation", forms from a small kick at the first site;
* soft W (beta < 0): "a part of the energy remains trapped near the boundary and forms a surface mode";
* hard W (beta > 0), large to moderate kicks: a "boomeron", a travelling breather that reverses its direction;
* precompression delta_0 > 0: enhanced dispersion, no travelling breather, or a "nanopteron" with a sizable
  wave train on both sides of the localised excitation.

Here each of the three scenes (``surface``, ``boomeron``, ``nanopteron``, each optional: kicks of config.yaml's
``scenes:``, their exact (ncimperfect) and DpS (dpsimperfect) runs) and the same kick in the harmonic,
uncompressed chain (the reference, run here with the scene's integrators, lattice (nc) and DpS (dfnls)) are
measured alike, in four ``model`` rows: ``exact``, ``dps``, ``reference``, ``reference_dps``. The definitions (the
choices are parameters of the spec, several values each where a choice matters):

* local energy e_n (:func:`local_energy`): m_n v_n^2/2 + m_n omega_n^2 W(x_n) plus half of the potential k_n Phi_n
  of each bond of bead n (the generalised (ham) of (ncimperfect), so sum_n e_n = H); for a DpS run the same
  formula on its ansatz (ansatz) x_n = 2 eps Re(A_n e^{it}), v_n = -2 eps Im(A_n e^{it}) (leading order);
* energy centre X(t) = sum n e_n / sum e_n (bead indices, no wrap: the ring scene stops before its waves meet
  opposite the kick), smoothed by a running mean over ``smoothing`` time units; its reversals
  (:func:`reversals`): extrema from which X retreats by at least ``reversal_threshold`` sites; a reversal within
  ``edge_sites`` of a free end is a bounce (:func:`touches_end`: the excitation's 1 % or 99 % energy extent, on the
  side it moved to, within ``edge_sites`` of that end within ``smoothing`` of the reversal), any other is
  spontaneous. The same for the core position (below);
* near the boundary: the fraction of the energy on the first m beads, m in ``boundary_sites``, and its mean
  over the last ``late_fraction`` of the run;
* core and tails: for a half-width w in ``core_halfwidths``, the core is the window of 2w+1 beads holding the
  most energy (its centre the core position), the left and right tails the energy of the beads below and
  above it, as fractions of the total; the 1 % and 99 % energy quantiles give the extent of the excitation;
* DpS's error E(t) = max_n |x_n^app - x_n| / |v| (plot4-5's measure, scale the kick velocity v).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis, scene_reads
from cradle.data.variables import Var
from cradle.specs.declare import NAME_PATTERN, NULL, declared, param, plain

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.integrators.lattice_solver import LatticeSolution
    from cradle.models.inhomogeneity import Sites
    from cradle.models.lattice_terms import Terms
    from cradle.scenes.spec import Context, Scene, Where
    from cradle.specs.values import Errors

#: the three roles, each a scene of config.yaml
ROLES = ("surface", "boomeron", "nanopteron")
#: the rows of every measured quantity: the scene's two runs and the reference's two
MODELS = ("exact", "dps", "reference", "reference_dps")


@declared("jkcVariants", doc="JKC 2013's variants (surface mode, boomeron, nanopteron) of a kicked chain, lattice "
                             "(ncimperfect) and DpS (dpsimperfect) against the harmonic uncompressed kick -> "
                             "results/jkc-variants/jkc-variants.nc and results/figures/jkc-variants.{pdf,png}.")
class JkcVariants:
    # no scene by default: a config without these scenes stays valid (config.yaml names its three)
    surface: str | None = param(NULL, "Kick scene with a soft quartic on-site potential (beta < 0), free ends; "
                                "null: not measured.", pattern=NAME_PATTERN)
    boomeron: str | None = param(NULL, "Kick scene with a hard quartic on-site potential (beta > 0), free ends; "
                                 "null: not measured.", pattern=NAME_PATTERN)
    nanopteron: str | None = param(NULL, "Kick scene with a precompression delta0 > 0 (a ring); null: not "
                                   "measured.", pattern=NAME_PATTERN)
    smoothing: float = param(20.0, "Window (time units) of the running mean of the energy centre and core "
                             "position before reversals are sought; in (0, 1e3].", exclusiveMinimum=0, maximum=1e3)
    reversal_threshold: float = param(2.0, "A reversal: an extremum of the smoothed position from which it "
                                      "retreats by at least this many sites; in (0, 1e3].", exclusiveMinimum=0,
                                      maximum=1e3)
    edge_sites: int = param(5, "A reversal while the energy extent (1 % or 99 % quantile) on the side of the motion "
                            "is within this many sites of a free end is a bounce, not spontaneous.",
                            minimum=0, maximum=1000)
    boundary_sites: list[int] = param([2, 5], "Definitions of 'near the boundary': the first m beads, one m each.",
                                      minItems=1, maxItems=8,
                                      items={"description": "A number of beads.", "type": "integer", "minimum": 1,
                                             "maximum": 1000})
    late_fraction: float = param(0.25, "Late times: the last late_fraction of each run; in (0, 1].",
                                 exclusiveMinimum=0, maximum=1)
    core_halfwidths: list[int] = param([4, 8], "Half-widths w of the core window (2w+1 beads), one definition "
                                       "each.", minItems=1, maxItems=8,
                                       items={"description": "A half-width in beads.", "type": "integer",
                                              "minimum": 0, "maximum": 1000})

    def scene_of(self, role: str) -> str | None:
        """The scene name playing ``role`` (one of :data:`ROLES`), None if not given."""
        return getattr(self, role)

    @property
    def roles(self) -> list[str]:
        """The roles given a scene, in the order of :data:`ROLES`."""
        return [role for role in ROLES if self.scene_of(role) is not None]

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each named scene that exists is a kick scene with the terms its role needs: a soft, a hard quartic
        on-site potential on a free chain, a precompression on a ring. A name that is no scene is reported with
        every analysis's reads (cradle.pipeline.config.checks)."""
        for role in self.roles:
            name = str(self.scene_of(role))
            sc = context.scenes.get(name)
            if sc is None:
                continue
            why = _role_problem(role, sc)
            if why:
                out.add(where + [role], why, name)


def _role_problem(role: str, sc: Scene) -> str:
    """Why scene ``sc`` cannot play ``role`` ('' if it can)."""
    if sc.initial.kind != "kick":
        return f"must be a kick scene (initial.kind kick), got {sc.initial.kind}"
    terms = sc.terms
    on = None if terms is None else terms.onsite
    beta = on.beta if on is not None and on.potential == "quartic" else 0.0
    if role == "surface" and not beta < 0:
        return "must have a soft quartic on-site potential (terms.onsite: quartic, beta < 0)"
    if role == "boomeron" and not beta > 0:
        return "must have a hard quartic on-site potential (terms.onsite: quartic, beta > 0)"
    if role == "nanopteron" and (terms is None or not terms.precompression.delta0 > 0):
        return "must have a precompression (terms.precompression.delta0 > 0)"
    return ""


# ----------------------------------------------------------------- measures

def local_energy(x: ArrayLike, v: ArrayLike, alpha: float, terms: Terms, s: Sites, bc: str) -> np.ndarray:
    """e_n: m_n v_n^2/2 + m_n omega_n^2 W(x_n) + (k_{n-1} Phi_{n-1} + k_n Phi_n)/2 of (ncimperfect), whose sum
    over n is the generalised (ham) (:func:`cradle.models.lattice_terms.hamiltonian`); beads on the last axis.
    A missing bond of a free chain (bond N-1) carries nothing."""
    from cradle.models.lattice_terms import pendulum_scales, positions, static_overlaps

    x = np.asarray(x, dtype=float)
    v = np.asarray(v, dtype=float)
    delta = static_overlaps(terms.precompression.delta0, s.stiffness, alpha)
    dp = np.maximum(delta, 0.0)
    u = positions(x, terms, s)
    d = np.roll(u, -1, axis=-1) - u
    phi = (np.maximum(delta - d, 0.0) ** (alpha + 1.0) - dp ** (alpha + 1.0)) / (alpha + 1.0) + dp**alpha * d
    bond = s.stiffness * phi
    if bc == "free":
        bond[..., -1] = 0.0
    onsite = s.mass * s.omega**2 * terms.onsite.W(x, pendulum_scales(terms, s))
    return 0.5 * s.mass * v**2 + onsite + 0.5 * (bond + np.roll(bond, 1, axis=-1))


def energy_centre(e: NDArray[np.float64]) -> np.ndarray:
    """X(t) = sum_n n e_n / sum_n e_n (bead indices 0..N-1; beads on the last axis)."""
    e = np.asarray(e, dtype=float)
    n = np.arange(e.shape[-1])
    return (e * n).sum(-1) / e.sum(-1)


def running_mean(t: NDArray[np.float64], y: NDArray[np.float64], window: float) -> np.ndarray:
    """The centred running mean of y over ``window`` time units on the uniform grid t (fewer points near the
    ends: the mean of those the window covers)."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    dt = float(t[1] - t[0]) if t.size > 1 else 1.0
    half = max(int(round(0.5 * window / dt)), 0)
    kernel = np.ones(2 * half + 1)
    return np.convolve(y, kernel, mode="same") / np.convolve(np.ones_like(y), kernel, mode="same")


def reversals(y: NDArray[np.float64], threshold: float) -> np.ndarray:
    """Indices of the reversals of the series y: extrema (a maximum when y went up, a minimum when it went down)
    from which y then retreats by at least ``threshold``; the first direction is the first move of
    ``threshold``. Wiggles smaller than ``threshold`` are not reversals."""
    y = np.asarray(y, dtype=float)
    out: list[int] = []
    imax = imin = 0
    direction, ext = 0, 0
    for i in range(1, y.size):
        if direction == 0:
            imax = i if y[i] > y[imax] else imax
            imin = i if y[i] < y[imin] else imin
            if y[imax] - y[imin] >= threshold:
                direction = 1 if imax > imin else -1
                ext = imax if direction == 1 else imin
        elif direction == 1:
            if y[i] > y[ext]:
                ext = i
            elif y[ext] - y[i] >= threshold:
                out.append(ext)
                direction, ext = -1, i
        else:
            if y[i] < y[ext]:
                ext = i
            elif y[i] - y[ext] >= threshold:
                out.append(ext)
                direction, ext = 1, i
    return np.asarray(out, dtype=int)


def touches_end(t: NDArray[np.float64], low: NDArray[np.float64], high: NDArray[np.float64], y: NDArray[np.float64],
                j: int, N: int, edge_sites: int, window: float) -> bool:
    """Whether the reversal of y at index j is a bounce: within ``window`` time units of it, the energy extent on
    the side y was moving to (``high``, the 99 % quantile, at a maximum; ``low``, the 1 % quantile, at a minimum)
    comes within ``edge_sites`` of that end of the free chain. Conservative: with energy left at the kicked end,
    every minimum near it counts as a bounce."""
    near = np.abs(np.asarray(t, dtype=float) - t[j]) <= window
    is_max = (j == 0 or y[j] >= y[j - 1]) and (j == len(y) - 1 or y[j] >= y[j + 1])
    if is_max:
        return bool(np.max(high[near]) >= N - 1 - edge_sites)
    return bool(np.min(low[near]) <= edge_sites)


def core_and_tails(e: NDArray[np.float64], w: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """For a half-width w: (position, core, left, right) per row of e (beads on the last axis, no wrap): the
    window of 2w+1 beads with the most energy (clipped at the chain's ends), its centre, its energy and the
    energy below and above it, each as a fraction of the row's total."""
    e = np.asarray(e, dtype=float)
    N = e.shape[-1]
    c = np.concatenate([np.zeros(e.shape[:-1] + (1,)), np.cumsum(e, axis=-1)], axis=-1)
    lo = np.clip(np.arange(N) - w, 0, N)
    hi = np.clip(np.arange(N) + w + 1, 0, N)
    window = c[..., hi] - c[..., lo]
    k = np.argmax(window, axis=-1)
    total = c[..., -1]
    rows = np.arange(e.shape[0])
    core = window[rows, k] / total
    left = c[rows, lo[k]] / total
    right = (total - c[rows, hi[k]]) / total
    return k.astype(float), core, left, right


def quantile_sites(e: NDArray[np.float64], q: float) -> np.ndarray:
    """The first bead at which the cumulative energy reaches the fraction q of the total, per row."""
    e = np.asarray(e, dtype=float)
    c = np.cumsum(e, axis=-1) / e.sum(-1, keepdims=True)
    return np.argmax(c >= q, axis=-1).astype(float)


#: zero padding of the spectrum of :func:`dominant_frequency`: its grid is PAD times finer than 2 pi / span
PAD = 16


def dominant_frequency(t: NDArray[np.float64], x: NDArray[np.float64]) -> float:
    """The angular frequency of the largest peak of |FFT| of x(t) (Hann window, zero-padded PAD times) on the
    uniform grid t; the peak of a sine of a span T is located to well within its width ~ 4 pi / T."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    n = PAD * x.size
    spec = np.abs(np.fft.rfft((x - x.mean()) * np.hanning(x.size), n=n))
    freq = 2.0 * np.pi * np.fft.rfftfreq(n, d=float(t[1] - t[0]))
    return float(freq[int(np.argmax(spec[1:])) + 1])


# ----------------------------------------------------------------- the runs

def _terms_and_sites(exact_ds: xr.Dataset, init_ds: xr.Dataset) -> tuple[Terms, Sites]:
    """The terms and sites of a scene's exact run, from its stored attributes and site values."""
    from cradle.models.inhomogeneity import Sites
    from cradle.models.lattice_terms import Terms
    from cradle.models.onsite import OnSite
    from cradle.models.precompression import Precompression

    a = exact_ds.attrs
    terms = Terms(precompression=Precompression(delta0=float(a.get("precompression_delta0", 0.0))),
                  onsite=OnSite(potential=str(a.get("onsite_potential", "harmonic")),
                                beta=float(a.get("onsite_beta", 0.0)), scale=float(a.get("onsite_scale", 0.0))))
    N = int(a["N"])
    if "omega_n" in init_ds:
        s = Sites(mass=init_ds["mass_n"].values, omega=init_ds["omega_n"].values,
                  stiffness=init_ds["stiffness_n"].values)
    else:
        s = Sites(mass=np.ones(N), omega=np.ones(N), stiffness=np.ones(N))
    return terms, s


def _dps_state(A: NDArray[np.complex128], t: NDArray[np.float64], eps: float) -> tuple[np.ndarray, np.ndarray]:
    """The ansatz (ansatz) at leading order: x = 2 eps Re(A e^{it}), v = -2 eps Im(A e^{it})."""
    z = 2.0 * eps * np.asarray(A) * np.exp(1j * np.asarray(t, dtype=float))[:, None]
    return z.real, -z.imag


def reference_runs(init_ds: xr.Dataset, exact_ds: xr.Dataset,
                   dps_ds: xr.Dataset) -> tuple[LatticeSolution, np.ndarray, np.ndarray]:
    """The same kick in the harmonic, uncompressed chain (nc) and in DpS (dfnls), with the scene's integrators
    (lattice: its method and rtol; DpS: its method and rtol) at the scene's stored times: (x, v, x_dps, v_dps)."""
    from cradle.integrators import integrate_dps, integrate_lattice

    a = exact_ds.attrs
    alpha, bc = float(a["alpha"]), str(a["bc"])
    t = exact_ds["t"].values
    eps = float(a["eps"])
    sol = integrate_lattice(init_ds["x0"].values, init_ds["v0"].values, t, alpha=alpha, bc=bc,
                            method=str(a["integrator"]), rtol=float(a["rtol"]))
    A0 = init_ds["A0_re"].values + 1j * init_ds["A0_im"].values
    dsol = integrate_dps(A0, eps ** (alpha - 1.0) * t, alpha=alpha, bc=bc, method=str(dps_ds.attrs["integrator"]),
                         rtol=float(dps_ds.attrs["rtol"]))
    xd, vd = _dps_state(dsol.A, t, eps)
    return sol, xd, vd


def measure(spec: JkcVariants, t: NDArray[np.float64], energies: dict, N: int, bc: str, kick_site: int, xs: dict,
            scale: float) -> tuple:
    """Every measure of one scene (see the module docstring) from its four local-energy maps ``energies``
    (model -> (T, N)) and displacements ``xs`` (model -> (T, N)): (data, coords) of its group."""
    T = t.size
    M = len(MODELS)
    late = t >= t[-1] - spec.late_fraction * (t[-1] - t[0])
    w0 = spec.core_halfwidths[0]
    bsites = list(spec.boundary_sites)
    hws = list(spec.core_halfwidths)
    X, Xs, Cs = np.zeros((M, T)), np.zeros((M, T)), np.zeros((M, T))
    frac = np.zeros((M, len(bsites), T))
    pos, core, left, right = (np.zeros((M, len(hws), T)) for _ in range(4))
    q01, q99 = np.zeros((M, T)), np.zeros((M, T))
    edge_om = np.zeros(M)
    rev: dict[str, list[np.ndarray]] = {"centre": [], "core": []}
    for i, model in enumerate(MODELS):
        e = energies[model]
        E = e.sum(-1)
        X[i] = energy_centre(e)
        Xs[i] = running_mean(t, X[i], spec.smoothing)
        for j, m in enumerate(bsites):
            frac[i, j] = e[:, : min(m, N)].sum(-1) / E
        for j, w in enumerate(hws):
            pos[i, j], core[i, j], left[i, j], right[i, j] = core_and_tails(e, w)
        Cs[i] = running_mean(t, pos[i, hws.index(w0)], spec.smoothing)
        q01[i], q99[i] = quantile_sites(e, 0.01), quantile_sites(e, 0.99)
        edge_om[i] = dominant_frequency(t[late], xs[model][late, kick_site])
        for key, y in (("centre", Xs[i]), ("core", Cs[i])):
            rev[key].append(reversals(y, spec.reversal_threshold))
    R = max([1] + [r.size for k in rev for r in rev[k]])
    data: dict = {"energy_map": np.stack([energies[m] for m in MODELS]), "X": X, "X_smooth": Xs, "core_smooth": Cs,
                  "boundary_fraction": frac, "boundary_fraction_late": frac[:, :, late].mean(-1),
                  "core_position": pos, "core_fraction": core, "left_tail": left, "right_tail": right,
                  "core_fraction_final": core[:, :, -1], "left_tail_final": left[:, :, -1],
                  "right_tail_final": right[:, :, -1], "extent_low": q01, "extent_high": q99,
                  "kick_site_frequency": edge_om}
    for key, y in (("centre", Xs), ("core", Cs)):
        times, where, spont = (np.full((M, R), np.nan) for _ in range(3))
        counts, counts_sp = np.zeros(M, dtype=np.int64), np.zeros(M, dtype=np.int64)
        for i, idx in enumerate(rev[key]):
            p = y[i, idx]
            free_end = np.array([bc == "free" and touches_end(t, q01[i], q99[i], y[i], j, N, spec.edge_sites,
                                                              spec.smoothing) for j in idx], dtype=bool)
            times[i, : idx.size], where[i, : idx.size] = t[idx], p
            spont[i, : idx.size] = ~free_end
            counts[i], counts_sp[i] = idx.size, int((~free_end).sum())
        data.update({f"reversal_time_{key}": times, f"reversal_site_{key}": where,
                     f"reversal_spontaneous_{key}": spont, f"reversals_{key}": counts,
                     f"reversals_spontaneous_{key}": counts_sp})
    # DpS's error E(t) against the lattice, for the scene and for the reference
    data["dps_error"] = np.stack([np.max(np.abs(xs["dps"] - xs["exact"]), axis=-1) / scale,
                                  np.max(np.abs(xs["reference_dps"] - xs["reference"]), axis=-1) / scale])
    coords = {"model": list(MODELS), "t": t, "n": np.arange(N), "boundary": np.asarray(bsites),
              "halfwidth": np.asarray(hws), "reversal": np.arange(R), "pair": ["scene", "reference"]}
    return data, coords


def compute(spec: JkcVariants, inputs: dict, log: Log | None = None) -> xr.DataTree:
    """The `jkc-variants` analysis: one group per role (see the module docstring and :data:`VARIABLES`)."""
    import time

    from cradle.data.io import make_tree
    from cradle.models.inhomogeneity import Sites
    from cradle.models.lattice_terms import Terms

    say = log or (lambda *a: None)
    t_start = time.perf_counter()
    groups: dict = {"/": ({}, {})}
    attrs: dict = {}
    for role in spec.roles:
        name = str(spec.scene_of(role))
        init_ds, exact_ds, dps_ds = (inputs[f"{name}/{part}"] for part in ("initial", "exact", "dps"))
        a = exact_ds.attrs
        alpha, bc, N = float(a["alpha"]), str(a["bc"]), int(a["N"])
        t = exact_ds["t"].values
        eps, v = float(a["eps"]), float(a["velocity"])
        terms, s = _terms_and_sites(exact_ds, init_ds)
        ref_terms, ref_s = Terms(), Sites(mass=np.ones(N), omega=np.ones(N), stiffness=np.ones(N))
        sol, xrd, vrd = reference_runs(init_ds, exact_ds, dps_ds)
        xd, vd = _dps_state(dps_ds["A_re"].values + 1j * dps_ds["A_im"].values, t, eps)
        xs = {"exact": exact_ds["x"].values, "dps": xd, "reference": sol.x, "reference_dps": xrd}
        energies = {"exact": local_energy(exact_ds["x"].values, exact_ds["v"].values, alpha, terms, s, bc),
                    "dps": local_energy(xd, vd, alpha, terms, s, bc),
                    "reference": local_energy(sol.x, sol.v, alpha, ref_terms, ref_s, bc),
                    "reference_dps": local_energy(xrd, vrd, alpha, ref_terms, ref_s, bc)}
        data, coords = measure(spec, t, energies, N, bc, int(a["kick_site"]), xs, abs(v))
        data["energy_drift"] = np.array([float(a["energy_drift"]), float(sol.energy_drift)])
        groups[f"/{role}"] = (data, coords)
        attrs.update({f"{role}_scene": name, f"{role}_N": N, f"{role}_bc": bc, f"{role}_velocity": v,
                      f"{role}_beta": terms.onsite.beta if terms.onsite.potential == "quartic" else 0.0,
                      f"{role}_delta0": terms.precompression.delta0, f"{role}_t_end": float(t[-1])})
        say(f"{role} ({name}): spontaneous reversals of X (exact, dps, ref, ref dps) "
            f"{data['reversals_spontaneous_centre'].tolist()}, late fraction on the first "
            f"{spec.boundary_sites[0]} beads {np.round(data['boundary_fraction_late'][:, 0], 3).tolist()}, "
            f"DpS E_max {np.round(data['dps_error'].max(-1), 3).tolist()}")
    attrs["wall_time_s"] = time.perf_counter() - t_start
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="JKC 2013 variants: surface mode, boomeron, nanopteron of a kicked chain")


def reads(spec: JkcVariants) -> dict:
    """The initial data, exact and DpS runs of the three scenes."""
    return scene_reads([str(spec.scene_of(role)) for role in spec.roles])


_MT = ("model", "t")
_MBT = ("model", "boundary", "t")
_MWT = ("model", "halfwidth", "t")
_MW = ("model", "halfwidth")
_MR = ("model", "reversal")


def _group_variables() -> dict:
    out = {
        "model": Var(("model",), "exact (ncimperfect), dps (dpsimperfect), reference: the same kick in the harmonic "
                     "uncompressed lattice (nc), reference_dps: in (dfnls)"),
        "t": Var(("t",), "dimensionless time t of (nc)"),
        "n": Var(("n",), "bead index"),
        "boundary": Var(("boundary",), "number m of first beads counted as 'near the boundary'"),
        "halfwidth": Var(("halfwidth",), "half-width w of the core window (2w+1 beads)"),
        "reversal": Var(("reversal",), "index of a reversal"),
        "pair": Var(("pair",), "scene: DpS against the scene's lattice run; reference: against the reference's"),
        "energy_map": Var(("model", "t", "n"), "local energy e_n (half of each bond to each bead)"),
        "X": Var(_MT, "energy centre X = sum n e_n / sum e_n (bead index)", "1"),
        "X_smooth": Var(_MT, "X, running mean over `smoothing` time units (bead index)", "1"),
        "core_smooth": Var(_MT, "core position (first half-width), running mean over `smoothing` (bead index)", "1"),
        "boundary_fraction": Var(_MBT, "fraction of the energy on the first m beads"),
        "boundary_fraction_late": Var(("model", "boundary"), "boundary_fraction, mean over the last "
                                      "late_fraction of the run"),
        "core_position": Var(_MWT, "centre of the 2w+1-bead window holding the most energy (bead index)", "1"),
        "core_fraction": Var(_MWT, "fraction of the energy in the core window"),
        "left_tail": Var(_MWT, "fraction of the energy below the core window (smaller n)"),
        "right_tail": Var(_MWT, "fraction of the energy above the core window (larger n)"),
        "core_fraction_final": Var(_MW, "core_fraction at t_end"),
        "left_tail_final": Var(_MW, "left_tail at t_end"),
        "right_tail_final": Var(_MW, "right_tail at t_end"),
        "extent_low": Var(_MT, "bead at which the cumulative energy reaches 1 % (bead index)", "1"),
        "extent_high": Var(_MT, "bead at which the cumulative energy reaches 99 % (bead index)", "1"),
        "kick_site_frequency": Var(("model",), "dominant angular frequency of x at the kicked bead, late times",
                                   "rad"),
        "dps_error": Var(("pair", "t"), "E(t) = max_n |x_app - x| / |v|, v the kick velocity"),
        "energy_drift": Var(("pair",), "max |H(t) - H(0)| / H(0) of the lattice run"),
    }
    for key, what in (("centre", "the smoothed energy centre"), ("core", "the smoothed core position")):
        out.update({
            f"reversal_time_{key}": Var(_MR, f"times of the reversals of {what} (NaN: none)"),
            f"reversal_site_{key}": Var(_MR, f"position of {what} at its reversals (bead index)", "1"),
            f"reversal_spontaneous_{key}": Var(_MR, f"1 if a reversal of {what} is spontaneous, 0 if a bounce "
                                                    "(the energy extent reaches a free end), NaN: none"),
            f"reversals_{key}": Var(("model",), f"number of reversals of {what}"),
            f"reversals_spontaneous_{key}": Var(("model",), f"number of spontaneous reversals of {what}"),
        })
    return out


#: the stored variables, per netCDF group: one group per role, the same variables in each
VARIABLES = {"/": {}, **{f"/{role}": _group_variables() for role in ROLES}}

ANALYSIS = Analysis(
    name="jkc-variants", spec=JkcVariants, compute=compute, reads=reads, variables=VARIABLES,
    title="JKC 2013's variants: surface mode, boomeron and nanopteron, lattice and DpS against the harmonic kick")
