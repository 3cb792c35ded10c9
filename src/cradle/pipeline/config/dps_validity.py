"""Declaration of ``beyond.dps_validity``: the DpS approximation error against eps and T (cradle.analyses.dps_validity)."""
from __future__ import annotations

from cradle.specs.declare import declared, param
from cradle.specs.values import form_section, number, show

_FAMILIES = ("tw-pi5", "tw-4pi5", "breather-bond", "mi-4pi5-noise")
_ALPHAS = {"$ref": "#/$defs/alpha", "maximum": 10}
_EPS = {"description": "Smallest eps of one alpha.", "type": "number", "exclusiveMinimum": 0, "maximum": 1}
_T = {"description": "A slow time T = eps^(alpha-1) t (> 0).", "type": "number", "exclusiveMinimum": 0,
      "maximum": 1000}
_FAMILY = {"description": "A family of well-prepared data.", "type": "string", "enum": list(_FAMILIES)}


@declared(doc="The reduced form `snakemake all` builds (results/validity/dps-validity.nc, "
              "results/figures/dps-validity.*): these keys replace those of the full form, `snakemake "
              "dps_validity_full` (results/validity/full/).")
class DpsValidityReduced:
    alpha: list[float] = param([1.5], "Hertz exponents alpha.", minItems=1, maxItems=6, items=_ALPHAS)
    eps_min: list[float] = param([1e-3], "Smallest eps, one per alpha.", minItems=1, maxItems=6, items=_EPS)
    n_eps: int = param(3, "Number of eps, log-spaced from eps_min to eps_max.", minimum=3, maximum=41)
    T: list[float] = param([1.0, 2.0], "Slow times T.", minItems=1, maxItems=12, items=_T)


@declared(doc="How long and how well DpS describes the lattice: sup_{t <= T eps^(1-alpha)} |x - x_app| with x_app "
              "from (ansatz), for well-prepared data (travelling waves q = pi/5, 4 pi/5, a bond-centred breather, "
              "a modulationally unstable wave with small noise) over eps and T, and the fitted power of eps "
              "against the consistency order eps^alpha -> results/validity/dps-validity.nc and "
              "results/figures/dps-validity.{pdf,png}.")
class DpsValidity:
    alpha: list[float] = param([1.1, 1.5, 2.0, 3.0], "Hertz exponents alpha of V0 (each > 1).", minItems=1,
                               maxItems=6, items=_ALPHAS)
    eps_min: list[float] = param([1e-5, 1e-5, 1e-4, 1e-2], "Smallest eps of (ansatz), one per alpha (< eps_max): "
                                 "the lattice runs last T eps^(1-alpha) (alpha = 3: T eps^-2, unreachable at "
                                 "eps = 1e-5), so the range shrinks as alpha grows.", minItems=1, maxItems=6,
                                 items=_EPS)
    eps_max: float = param(0.1, "Largest eps (half the largest initial displacement).", exclusiveMinimum=0,
                           maximum=1.0)
    n_eps: int = param(9, "Number of eps, log-spaced from eps_min to eps_max.", minimum=3, maximum=41)
    T: list[float] = param([0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0], "Slow times T = tau: the sup "
                           "over t is taken up to t = T eps^(1-alpha) (one run to the largest T gives them all).",
                           minItems=1, maxItems=12, items=_T)
    families: list[str] = param(list(_FAMILIES), "Families of well-prepared data (cradle.analyses.dps_validity."
                                "FAMILIES).", minItems=1, maxItems=4, items=_FAMILY)
    N_wave: int = param(10, "Ring size of the travelling waves (q N / 2 pi an integer for q = pi/5, 4 pi/5).",
                        minimum=10, maximum=1000, multipleOf=10)
    N_breather: int = param(32, "Ring size of the bond-centred breather.", minimum=8, maximum=1000)
    N_noise: int = param(50, "Ring size of the noisy unstable wave (q N / 2 pi an integer for q = 4 pi/5).",
                         minimum=10, maximum=1000, multipleOf=5)
    noise_amplitude: float = param(0.01, "Amplitude of the uniform noise rho of (perturb) of mi-4pi5-noise.",
                                   exclusiveMinimum=0, maximum=0.5)
    seed: int = param(20261122, "Seed of the noise (numpy default_rng); alpha number k uses seed + round(100 "
                      "alpha).", minimum=0)
    sample_every: float = param(0.2, "Lattice-time spacing of the samples of the sup over t.", exclusiveMinimum=0,
                                maximum=1.0)
    dt_factor: float = param(0.01, "srkn6c step as a fraction of the shortest linearised period (the run at the "
                             "smallest eps is repeated with dt / 2).", exclusiveMinimum=0, maximum=0.05)
    dps_rtol: float = param(1e-11, "Relative tolerance of the DpS runs (dop853_numba).", exclusiveMinimum=0,
                            maximum=1e-6)
    chunk: int = param(20000, "Samples per integration chunk (bounds the memory of the long runs).", minimum=100,
                       maximum=1000000)
    reduced: DpsValidityReduced = param(DpsValidityReduced(), DpsValidityReduced.__schema_doc__)

    @staticmethod
    def check(b: dict, path: list, out) -> None:
        """Both forms: one eps_min per alpha, each below eps_max; the families distinct."""
        DpsValidity._check(b, path, out)
        reduced = b.get("reduced")
        if isinstance(reduced, dict):
            DpsValidity._check(form_section(b, "reduced"), path + ["reduced"], out, own=set(reduced))

    @staticmethod
    def _check(b: dict, path: list, out, own=None) -> None:
        al, em, hi = b.get("alpha"), b.get("eps_min"), b.get("eps_max")
        def mine(key):  # the reduced form reports only the keys it replaces
            return own is None or key in own

        if isinstance(al, list) and isinstance(em, list) and len(al) != len(em) and \
                (mine("eps_min") or mine("alpha")):
            out.add(path + ["eps_min"], f"needs one value per alpha ({len(al)}: {show(al)})", em)
        if isinstance(em, list) and number(hi) and mine("eps_min"):
            for i, e in enumerate(em):
                if number(e) and not float(e) < float(hi):
                    out.add(path + ["eps_min", i], f"must be below eps_max = {show(hi)}", e)
        fam = b.get("families")
        if isinstance(fam, list) and len(set(map(str, fam))) != len(fam) and mine("families"):
            out.add(path + ["families"], "lists a family twice", fam)

    @staticmethod
    def resolve(cfg: dict, form: str = "full") -> dict:
        """``beyond.dps_validity`` of one form (``full``, or ``reduced``: the reduced keys in place)."""
        b = form_section(cfg["beyond"]["dps_validity"], form)
        b["T"] = sorted(float(t) for t in b["T"])
        return b
