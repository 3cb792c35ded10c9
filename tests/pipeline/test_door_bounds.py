"""Values that passed validation and then failed or hung in the job, each refused at the door in one line naming
the key and the value, with a bound from the model (a tolerance the integrator can honour, a swing within its
string, the scales of a real cradle) or from the budget (the samples and steps the job would take), before
anything is written."""
from __future__ import annotations

import copy
import sys

import pytest
import yaml

from conftest import ROOT
from cradle.pipeline import config as cc
from cradle.specs.values import DRIFT_FLOOR, DT_FACTOR_FLOOR, RTOL_FLOOR, SEED_MAX

RAW = cc.read_yaml(ROOT / "config.yaml")
#: a scene of a real cradle in SI (docs/physical-units.md): 1 cm steel balls on 10 cm strings, a 1 nm packet
SI = {"N": 16, "bc": "free", "cradle": {"material": "steel", "radius": 0.01, "length": 0.1}, "units": "si",
      "initial": {"kind": "packet", "amplitude": 1.0e-9, "width": 6},
      "exact": {"method": "dop853_numba", "rtol": 1e-12}, "t_end": 0.5, "store": {"every": 0.01}}


def _set(raw: dict, path: str, value) -> dict:
    """``raw`` with ``value`` at the dotted ``path`` (mappings made on the way)."""
    keys = path.split(".")
    node = raw
    for k in keys[:-1]:
        if not isinstance(node.get(k), dict):
            node[k] = {}
        node = node[k]
    node[keys[-1]] = value
    return raw


def _refused(tmp_path, raw: dict) -> list[str]:
    """The lines ``python -m cradle.pipeline.config`` refuses ``raw`` with (exit 1, each line one problem), and
    nothing written beside the config."""
    p = tmp_path / "config.yaml"
    p.write_text(yaml.safe_dump(raw, sort_keys=False))
    with pytest.raises(cc.ConfigError) as err:
        cc.load(p)
    assert cc.main([str(p)]) == 1
    assert sorted(f.name for f in tmp_path.iterdir()) == ["config.yaml"]
    return err.value.errors


def _with_scene(**changes) -> dict:
    raw = copy.deepcopy(RAW)
    scene = copy.deepcopy(SI)
    for path, value in changes.items():
        _set(scene, path.replace("__", "."), value)
    raw["scenes"]["si"] = scene
    return raw


def test_the_si_scene_of_the_docs_is_valid():
    raw = _with_scene()
    assert "si" in cc.validate(raw)["scenes"]


@pytest.mark.parametrize("section", ["dissipation", "trapping"])
def test_a_sampling_step_goes_through_the_size_estimate(tmp_path, section):
    raw = copy.deepcopy(RAW)
    raw["beyond"][section] = {"sample_every": 1e-300}
    lines = _refused(tmp_path, raw)
    assert len(lines) == 2   # the reduced and the full form
    for line, form in zip(lines, [".reduced", ""], strict=True):
        assert line.startswith(f"config error: beyond.{section}{form}: ")
        assert "sample_every = 1e-300: 1e+18 samples each: estimated peak memory" in line
        assert "exceeds budget.memory_gb = 8" in line


def test_a_sampling_step_that_fits_the_budget_runs():
    raw = copy.deepcopy(RAW)
    raw["beyond"]["trapping"] = {"sample_every": 0.05}
    cc.validate(raw)


@pytest.mark.parametrize("path", ["beyond.dissipation.rtol", "beyond.trapping.rtol", "beyond.disorder.rtol",
                                  "beyond.desk-toy.rtol", "beyond.dps-validity.dps_rtol",
                                  "beyond.mi-statistics.dps.rtol", "scenes.tw-weak.exact.rtol",
                                  "scenes.tw-weak.dps.rtol", "defaults.dps.rtol"])
def test_every_tolerance_has_a_floor_the_integrator_can_honour(tmp_path, path):
    raw = _set(copy.deepcopy(RAW), path, 1e-300)
    lines = _refused(tmp_path, raw)
    floor = 1e-13 if path == "beyond.disorder.rtol" else RTOL_FLOOR   # disorder's own floor is higher
    assert lines == [f"config error: {path} = 1e-300: must be >= {floor:g} (a floor the integrator can honour, "
                     f"about 1e2 machine epsilons or more: below, a step's error estimate is rounding noise and the "
                     f"steps shrink until they underflow)"]
    cc.validate(_set(copy.deepcopy(RAW), path, floor))


def test_a_ladder_of_tolerances_has_the_floor_too(tmp_path):
    raw = copy.deepcopy(RAW)
    raw["beyond"]["work-precision"]["methods"]["dop853"] = {"rtol": [1e-5, 1e-300]}
    assert _refused(tmp_path, raw) == [f"config error: beyond.work-precision.methods.dop853.rtol[1] = 1e-300: must "
                                       f"be >= {RTOL_FLOOR:g}"]


def test_the_desk_toy_s_cradle_has_the_scales_of_a_real_one(tmp_path):
    raw = copy.deepcopy(RAW)
    raw["beyond"]["desk-toy"]["cradle"]["radius"] = 1e-300
    assert _refused(tmp_path, raw) == ["config error: beyond.desk-toy.cradle.radius = 1e-300: must be >= 1e-06"]


@pytest.mark.parametrize("term", ["onsite", "contact"])
def test_damping_the_integrator_cannot_resolve_in_the_budget_is_refused(tmp_path, term):
    raw = copy.deepcopy(RAW)
    raw["beyond"]["desk-toy"]["damping"] = {term: 1e300}
    lines = _refused(tmp_path, raw)
    assert lines[0].startswith("config error: beyond.desk-toy.reduced: 3 runs of N <= 5 over 6 swings, damping rate "
                               "1e+300: ~1e+300 steps each: estimated run time ")
    assert lines[0].endswith("exceeds budget.hours = 12 (raise it under budget: in the config if this machine "
                             "allows, or change the entry)")


def test_the_damped_desk_toy_of_a_steel_cradle_is_valid():
    raw = copy.deepcopy(RAW)
    raw["beyond"]["desk-toy"]["damping"] = {"onsite": 1e-5, "contact": 1e-5}
    cc.validate(raw)


def test_a_scene_s_damping_goes_through_its_step_estimate(tmp_path):
    lines = _refused(tmp_path, _with_scene(damping={"onsite": 1e300}))
    assert lines == [lines[0]] and lines[0].startswith("config error: scenes.si: N = 16, t_end = 4.95143")
    assert "(a damping rate 1.00981e+299 to resolve): estimated run time" in lines[0]


def test_an_si_amplitude_beyond_the_string_is_refused(tmp_path):
    lines = _refused(tmp_path, _with_scene(initial__amplitude=1.0))
    assert lines == ["config error: scenes.si.initial.amplitude = 1.0: a displacement of 1 m: must be below the "
                     "string length 0.1 m (a bead swings within its string)"]
    cc.validate(_with_scene(initial__amplitude=0.05))


@pytest.mark.parametrize("key, value, why", [("radius", 1e-9, "must be >= 1e-06"),
                                             ("radius", 1e-300, "must be >= 1e-06"),
                                             ("length", 1e-300, "must be >= 0.001"),
                                             ("g", 1e-300, "must be >= 0.001")])
def test_an_si_cradle_has_finite_scales(tmp_path, key, value, why):
    lines = _refused(tmp_path, _with_scene(**{f"cradle__{key}": value}))
    assert lines == [f"config error: scenes.si.cradle.{key} = {value!r}: {why}"]


def test_an_si_cradle_without_length_or_omega0_is_one_line(tmp_path):
    lines = _refused(tmp_path, _with_scene(cradle__length=None))
    assert lines == ["config error: scenes.si.cradle: give the pendulum length or omega0, one of them (given: "
                     "neither)"]


def test_a_long_chain_is_judged_by_the_budget_s_estimate(tmp_path):
    """N = 1e9 is refused with the memory it would need (no fixed cap); N = 2e7, beyond the old cap of 1e7, runs
    when the budget allows it."""
    raw = copy.deepcopy(RAW)
    raw["scenes"]["fft106"]["N"] = 10**9
    line = _refused(tmp_path, raw)[0]
    assert line.startswith("config error: scenes.fft106: N = 1000000000, t_end = 543.7: 7 stored times, ~1.27e+04 "
                           "steps of srkn6c, streamed block by block: estimated peak memory 257 GB exceeds "
                           "budget.memory_gb = 8")
    raw = copy.deepcopy(RAW)
    raw["scenes"]["fft106"]["N"] = 2 * 10**7
    raw["budget"] = {"memory_gb": 200, "disk_gb": 100, "hours": 1000}
    cc.validate(raw)


def test_a_store_is_judged_by_the_budget_even_beside_another_problem(tmp_path):
    """every = 1e-9 (6e11 stored times) next to a bad key elsewhere: refused with its estimate, never built."""
    raw = copy.deepcopy(RAW)
    raw["scenes"]["tw-weak"]["store"]["every"] = 1e-9
    raw["scenes"]["tw-strong"]["N"] = "many"
    lines = _refused(tmp_path, raw)
    assert lines == ["config error: scenes.tw-weak: N = 50, t_end = 621.95, store.every = 1e-09: 6.22e+11 stored "
                     "times, ~6.22e+11 steps of srkn6c, streamed block by block: estimated peak memory 29.9 TB exceeds "
                     "budget.memory_gb = 8 (raise it under budget: in the config if this machine allows, or change "
                     "the entry)"]


def test_t_end_is_bounded_by_the_resolution_of_float64(tmp_path):
    raw = copy.deepcopy(RAW)
    raw["scenes"]["fft106"]["t_end"] = 1e12
    assert _refused(tmp_path, raw) == ["config error: scenes.fft106.t_end = 1000000000000.0: must be <= 4194304 "
                                       "(float64 tells stored times 1e-9 apart only below 2^22 = 4194304)"]


def test_an_si_value_out_of_bounds_in_nc_units_is_said_at_the_scene(tmp_path):
    """0.1 m of precompression is fine in SI and 1.07e18 in (nc)'s units, beyond its bound there: one line at the
    scene, in (nc)'s units (the Terms built by the conversion are checked as any)."""
    raw = _with_scene(bc="periodic", damping=None,
                      terms={"precompression": {"delta0": 0.1}})
    raw["scenes"]["si"].pop("damping", None)
    lines = _refused(tmp_path, raw)
    assert lines == ["config error: scenes.si: in (nc)'s units, precompression.delta0 = 1.0721759889938697e+18: "
                     "must be <= 100"]


DT_FACTOR_WHY = (" (the step dt_factor 2 pi / omega_max is then about 1e2 spacings of doubles at the longest t_end "
                 "or more: below, t + dt is rounding noise)")


@pytest.mark.parametrize("path", ["defaults.exact.dt_factor", "scenes.tw-weak.exact.dt_factor",
                                  "beyond.mi-statistics.exact.dt_factor", "beyond.dps-validity.dt_factor",
                                  "beyond.work-precision.reference.dt_factor"])
def test_a_step_factor_has_a_floor_said_at_its_key(tmp_path, path):
    """1e-300 was refused by the budget at every scene that inherits it, naming the scenes and not the key."""
    raw = _set(copy.deepcopy(RAW), path, 1e-300)
    assert _refused(tmp_path, raw) == [f"config error: {path} = 1e-300: must be >= {DT_FACTOR_FLOOR:g}"
                                       f"{DT_FACTOR_WHY}"]
    cc.validate(_set(copy.deepcopy(RAW), path, 0.01))


def test_a_ladder_of_step_factors_has_the_floor_too(tmp_path):
    raw = copy.deepcopy(RAW)
    raw["beyond"]["work-precision"]["methods"]["srkn4"] = {"dt_factor": [0.01, 1e-300]}
    assert _refused(tmp_path, raw) == [f"config error: beyond.work-precision.methods.srkn4.dt_factor[1] = 1e-300: "
                                       f"must be >= {DT_FACTOR_FLOOR:g}"]


@pytest.mark.parametrize("key, what", [("memory_gb", "peak memory"), ("disk_gb", "output"), ("hours", "run time")])
def test_a_budget_below_every_job_is_said_at_its_key(tmp_path, key, what):
    """A limit no job fits is the budget's fault: one line at its key naming the least job, not a line per job."""
    raw = _set(copy.deepcopy(RAW), f"budget.{key}", 1e-300)
    lines = _refused(tmp_path, raw)
    assert len(lines) == 1 and lines[0].startswith(f"config error: budget.{key} = 1e-300: below the estimated {what} "
                                                   f"of every job (the least, "), lines
    assert lines[0].endswith("); raise it to what this machine allows")


def test_a_budget_one_entry_exceeds_is_still_said_at_the_entry(tmp_path):
    """Every config has the analyses' jobs at their defaults: one oversized scene never makes the budget the fault."""
    raw = _set(copy.deepcopy(RAW), "scenes.tw-weak.N", 10**9)
    lines = _refused(tmp_path, raw)
    assert lines and lines[0].startswith("config error: scenes.tw-weak: N = 1000000000, "), lines
    assert not any(line.startswith("config error: budget.") for line in lines)


def test_an_eps_max_below_every_eps_min_is_said_at_eps_max(tmp_path):
    raw = _set(copy.deepcopy(RAW), "beyond.dps-validity.eps_max", 1e-300)
    lines = _refused(tmp_path, raw)
    assert lines[0] == ("config error: beyond.dps-validity.eps_max = 1e-300: must be above every eps_min (eps_min = "
                        "[1e-05, 1e-05, 0.0001, 0.01])"), lines
    raw = _set(copy.deepcopy(RAW), "beyond.dps-validity.eps_min", [1e-5, 0.5, 1e-4, 1e-2])
    assert _refused(tmp_path, raw) == ["config error: beyond.dps-validity.eps_min[1] = 0.5: must be below eps_max = "
                                       "0.1"]


@pytest.mark.parametrize("path", ["scenes.tw-weak-noise.initial.noise.seed", "beyond.dps-validity.seed",
                                  "beyond.breather-interactions.seed_base", "beyond.mi-statistics.seed0"])
def test_a_seed_fits_the_int64_attribute_that_records_it(tmp_path, path):
    """A seed of 1e300 was accepted and the job failed writing it as a netCDF attribute (the config fuzz's run for
    real found it)."""
    raw = _set(copy.deepcopy(RAW), path, 1e300)
    assert _refused(tmp_path, raw) == [f"config error: {path} = 1e+300: must be <= {SEED_MAX}"]


def test_a_scene_s_dps_run_goes_through_its_pace(tmp_path):
    """A packet of 5 mm in a cradle of 1 cm balls is 5e16 in (nc)'s units, where DpS turns (2 a)^(1/2) ~ 3e8 times
    faster than at a = 1/2 (DpS's scaling): the job passed validation and then stepped DpS for hours (an ETA of
    11 h). Its estimate now counts DpS's steps; under a budget of one hour it is refused in one line."""
    from cradle.pipeline import budget

    raw = _with_scene(initial__amplitude=0.005, exact={"method": "srkn6c"}, t_end=1.0, store={"every": 0.1})
    raw["budget"] = {"hours": 1.0}
    lines = _refused(tmp_path, raw)
    assert lines == [lines[0]] and lines[0].startswith("config error: scenes.si: N = 16, t_end = 9.90285")
    assert "steps of DpS (dop853_numba; its pace grows as amplitude^(alpha-1))" in lines[0]
    assert lines[0].endswith("exceeds budget.hours = 1 (raise it under budget: in the config if this machine allows, "
                             "or change the entry)")
    # the paper's scenes: DpS's steps are a few thousand at most, never what sets a job's time
    for name, scene in cc.typed(RAW).scenes.items():
        assert budget.DPS_STEPS_PER_PERIOD * budget.dps_periods(scene) < 1e4, name


@pytest.mark.parametrize("path", ["defaults.max_energy_drift", "scenes.tw-weak.max_energy_drift"])
def test_an_energy_drift_bound_has_a_floor_a_run_can_meet(tmp_path, path):
    """1e-300 was accepted and every run then failed its energy check (the config fuzz's run for real found it)."""
    raw = _set(copy.deepcopy(RAW), path, 1e-300)
    assert _refused(tmp_path, raw) == [f"config error: {path} = 1e-300: must be >= {DRIFT_FLOOR:g} (H is computed in "
                                       f"double precision: a relative drift below about 1e2 machine epsilons is its "
                                       f"rounding alone, so a smaller bound fails every run)"]
    cc.validate(_set(copy.deepcopy(RAW), path, DRIFT_FLOOR))


@pytest.mark.parametrize("mu, line", [
    (1e-300, "must be >= 4e-150 at alpha = 1.5: the solution's amplitude (mu/nu)^(1/(alpha-1)) with nu > 4 "
             "underflows double precision beyond"),
    (1e300, "must be <= 4e+150 at alpha = 1.5: the solution's amplitude (mu/nu)^(1/(alpha-1)) with nu > 4 "
            "overflows double precision beyond"),
])
def test_a_homoclinic_mu_whose_solution_is_no_double_is_refused(tmp_path, mu, line):
    """mu = 1e-300 was accepted and the job failed: max|a_n| = 10^-601 (the config fuzz's run for real found it)."""
    raw = _set(copy.deepcopy(RAW), "homoclinic.site.mu", mu)
    assert _refused(tmp_path, raw) == [f"config error: homoclinic.site.mu = {mu:g}: {line}"]
    cc.validate(_set(copy.deepcopy(RAW), "homoclinic.site.mu", 1e-100))


def test_a_noise_larger_than_its_wave_is_refused(tmp_path):
    """A relative noise of 1e300 was accepted and the job's initial velocities overflowed to nan (the config fuzz's
    run for real found it)."""
    raw = _set(copy.deepcopy(RAW), "scenes.tw-weak-noise.initial.noise.amplitude", 1e300)
    assert _refused(tmp_path, raw) == ["config error: scenes.tw-weak-noise.initial.noise.amplitude = 1e+300: must be "
                                       "<= 1"]


def test_a_splitting_s_steps_at_a_large_amplitude_are_estimated_from_its_step():
    """The same 5 mm packet with srkn6c: the splitting's default step dt = 0.01 2 pi / omega_max(c) shrinks as
    c^(-1/4) at a compression c; the estimate took the steps of a small wave (231 for the run below, which takes
    millions). Now within 25 % of the run's own count (the run's assumed compression is 2 c0 + A0, the estimate's
    2 a)."""
    import numpy as np

    from cradle.integrators import integrate_lattice
    from cradle.pipeline import budget
    from cradle.scenes import stages

    raw = _with_scene(initial__amplitude=0.005, exact={"method": "srkn6c"}, t_end=0.01, store={"every": 0.005})
    scene = cc.typed(raw).scenes["si"]
    estimated = budget.spec_estimate(scene, "si").steps
    ini = stages.initial_data(scene)
    run = integrate_lattice(ini["x0"].values, ini["v0"].values, np.asarray(scene.times), alpha=scene.alpha,
                            bc=scene.bc)
    assert 0.75 < estimated / run.n_steps < 1.25, (estimated, run.n_steps)


def test_a_stiffness_beyond_float64_is_refused_by_its_estimate(tmp_path):
    """alpha = 10 and a = 1e40: (2a)^(alpha-1) overflows a double. The estimate raised OverflowError, the budget
    skipped the scene and it was accepted; now its steps are infinite and the budget refuses it in one line."""
    raw = copy.deepcopy(RAW)
    scene = raw["scenes"]["tw-weak"]
    scene["alpha"] = 10.0
    scene["initial"].pop("omega_tw", None)
    scene["initial"]["a"] = 1e40
    lines = _refused(tmp_path, raw)
    assert lines == [lines[0]] and lines[0].startswith("config error: scenes.tw-weak: N = 50")
    assert "estimated run time inf years exceeds budget.hours = 12" in lines[0]


@pytest.mark.parametrize("failing, key", [("spec_estimate", "scenes.tw-weak"),
                                          ("dissipation_estimate", "beyond.dissipation")])
def test_a_job_whose_estimate_fails_is_refused_not_run_unbudgeted(tmp_path, monkeypatch, failing, key):
    """An estimate that raises (a value no estimate foresaw) was skipped as 'a bad value the checks name', and a job
    the checks passed ran without a budget; now it is refused in one line naming its key and the error."""
    from cradle.pipeline import budget

    real = getattr(budget, failing)

    def overflows(*args, **kwargs):
        if failing == "spec_estimate" and args[1:2] != ("tw-weak",) or failing != "spec_estimate" and args[1] != "full":
            return real(*args, **kwargs)
        raise OverflowError("math range error")

    monkeypatch.setattr(budget, failing, overflows)
    # the config is RAW, validated before without the failure: not from the cache
    monkeypatch.setattr(sys.modules["cradle.pipeline.config.validate"], "_TYPED", {})
    assert _refused(tmp_path, copy.deepcopy(RAW)) == [
        f"config error: {key}: its cost cannot be estimated (OverflowError: math range error): refused rather than "
        f"run without a budget; change the entry's values"]


def test_a_failing_estimate_gives_way_to_the_check_that_names_the_value(tmp_path, monkeypatch):
    """Beside another problem (often the cause of the failure), only that problem is said."""
    from cradle.pipeline import budget

    monkeypatch.setattr(budget, "spec_estimate", lambda spec, name="?": 1 / 0)
    monkeypatch.setattr(sys.modules["cradle.pipeline.config.validate"], "_TYPED", {})
    raw = copy.deepcopy(RAW)
    raw["scenes"]["tw-weak"]["max_energy_drift"] = 1e-300
    lines = _refused(tmp_path, raw)
    assert lines == [lines[0]], lines
    assert lines[0].startswith("config error: scenes.tw-weak.max_energy_drift = 1e-300: ")


def test_a_breather_measured_where_its_homoclinic_profile_is_0_is_refused(tmp_path):
    """The bond profile of N = 50 underflows to 0 beyond ~15 sites from its core: an amplitude at bead 0 gave
    ValueError in the initial-data job (mu = (amplitude / a_0)^(alpha-1) with a_0 = 0)."""
    from cradle.models import homoclinic_continuation

    raw = copy.deepcopy(RAW)
    raw["scenes"]["breather-small"]["initial"]["site"] = 0
    bond = raw["homoclinic"]["bond"]
    assert homoclinic_continuation.solve_kind(bond["N"], bond["guess"], 1.5, bond["bc"]).a[0] == 0   # the job's
    assert _refused(tmp_path, raw) == [
        "config error: scenes.breather-small.initial.site = 0: the profile of homoclinic.bond is 0 there (its tails "
        "underflow double precision a few sites from its core): the amplitude must be given at a bead where a_n != 0"]


def test_a_breather_measured_on_its_core_stays_valid():
    raw = copy.deepcopy(RAW)
    raw["scenes"]["breather-small"]["initial"]["site"] = 24   # two beads from the bond (25, 26): a_24 != 0
    assert cc.validate(raw)["scenes"]["breather-small"]["initial"]["site"] == 24


@pytest.mark.parametrize("N, centre", [(10, 9), (2, None)])
def test_a_bond_guess_on_the_free_end_of_a_chain_is_refused(tmp_path, N, centre):
    """A bond-centred guess seeds the bond (c, c+1); on the last bead of a chain with free ends that bond is
    not there and the seed wrapped to bead 0 (the job solved from a_{N-1} = 0.1, a_0 = -0.1); N = 2's default
    centre N // 2 is that bead too."""
    from cradle.models.homoclinic import initial_guess

    assert initial_guess(N, "bond", centre=centre)[0] != 0   # the wrap the door now refuses
    raw = copy.deepcopy(RAW)
    raw["homoclinic"]["free-bond"]["N"] = N
    if centre is None:
        del raw["homoclinic"]["free-bond"]["centre"]
    else:
        raw["homoclinic"]["free-bond"]["centre"] = centre
    raw["scenes"]["fini"]["N"] = N
    raw["scenes"]["fini"]["initial"]["site"] = 0
    lines = _refused(tmp_path, raw)
    assert lines[0] == (f"config error: homoclinic.free-bond.centre = {N - 1}: a bond-centred guess seeds the bond "
                        f"({N - 1}, {N}), which a chain of N = {N} with free ends does not have: the centre must be "
                        f"<= N-2 = {N - 2}"), lines


def test_a_homoclinic_whose_solve_fails_from_its_guess_is_refused(tmp_path):
    """The bond guess on beads 0 and 1 of the 10-bead free chain does not converge (found by config_fuzz --real:
    the homoclinic job failed); a chain this short is solved at the door as its job solves it."""
    raw = copy.deepcopy(RAW)
    raw["homoclinic"]["free-bond"]["centre"] = 0
    lines = _refused(tmp_path, raw)
    assert lines == [lines[0]] and lines[0].startswith(
        "config error: homoclinic.free-bond: its job's solve fails from this guess (bond homoclinic: continuation in "
        "alpha from 1.5 to alpha=1.5 failed on N=10"), lines
    assert lines[0].endswith("; change the guess, its centre or N")


@pytest.mark.parametrize("width", [1e-300, 0.9])
def test_a_packet_too_narrow_to_reach_a_bead_is_refused(tmp_path, width):
    """loc1-packet's cos^2 envelope centred on a bond is 0 at every bead below width 1: the packet was x = 0 and its
    job failed at the comparison (found by config_fuzz --real, width = 1e-300)."""
    raw = copy.deepcopy(RAW)
    raw["scenes"]["loc1-packet"]["initial"]["width"] = width
    assert _refused(tmp_path, raw) == [
        f"config error: scenes.loc1-packet.initial.width = {width!r}: too narrow: the envelope is 0 at every bead "
        f"(the packet would be x = 0; a Gaussian's sigma is width/6)"]
    raw["scenes"]["loc1-packet"]["initial"]["width"] = 1.1
    assert cc.validate(raw)["scenes"]["loc1-packet"]["initial"]["width"] == 1.1
