"""A scene whose amplitude is above where DpS was measured to approximate the lattice (the dps-validity analysis,
cradle.measurements.dps_range) is run, and its job says so in one warning line naming the amplitude, the
threshold and where it comes from; a paper scene inside the range says nothing."""
from __future__ import annotations

import math

import yaml

from cradle.data.io import open_dataset
from cradle.measurements import dps_range
from cradle.pipeline import cli

#: the SI example scene of docs/physical-units.md, as written there
PACKET_STEEL = {"N": 16, "bc": "free", "cradle": {"material": "steel", "radius": 0.01, "length": 0.1}, "units": "si",
                "initial": {"kind": "packet", "amplitude": 1.0e-9, "width": 6},
                "damping": {"onsite": 0.05, "contact": 1.0e-6}, "exact": {"method": "dop853_numba", "rtol": 1.0e-12},
                "t_end": 0.5, "store": {"every": 0.01}}
#: tw-weak of config.yaml (plot4-5), run to t = 5 instead of 621.95
TW_WEAK = {"N": 50, "bc": "periodic", "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01, "phi": 0.0},
           "t_end": 5.0, "store": {"every": 0.5}}


def test_threshold_is_twice_the_largest_eps_dps_validity_measures():
    from cradle.analyses.dps_validity import DpsValidity

    assert dps_range.measured_amplitude() == 2 * DpsValidity().eps_max == 0.2
    # (ansatz) x = eps (A e^{it} + c.c.), v = eps (i A e^{it} + c.c.): sqrt(x^2 + v^2) = 2 eps |A| at every phase
    eps, A, phase = 0.05, 0.7, 0.3
    x = [0.0, 2 * eps * A * math.cos(phase)]
    v = [0.0, -2 * eps * A * math.sin(phase)]
    assert math.isclose(dps_range.amplitude_of(x, v), 2 * eps * A, rel_tol=1e-15)


def _warnings(err: str) -> list[str]:
    return [line for line in err.splitlines() if "warning:" in line]


def test_run_warns_outside_dps_range_and_not_inside(tmp_path, capsys):
    (tmp_path / "config.yaml").write_text(yaml.safe_dump(
        {"defaults": {"alpha": 1.5}, "scenes": {"packet-steel": PACKET_STEEL, "tw-weak": TW_WEAK}, "figures": {}},
        sort_keys=False))
    out = tmp_path / "cradle-runs"
    assert cli.main(["run", "packet-steel", "--out", str(out), "--config", str(tmp_path / "config.yaml")]) == 0
    lines = _warnings(capsys.readouterr().err)
    assert len(lines) == 1, lines
    x0 = open_dataset(out / "initial" / "packet-steel.nc")
    a = dps_range.amplitude_of(x0["x0"].values, x0["v0"].values)
    assert a > 0.2
    assert f"packet-steel: amplitude a = {a:.3g}" in lines[0] and "above 0.2" in lines[0]
    assert "dps-validity" in lines[0] and "eps <= 0.1" in lines[0]
    # the run's own comparison agrees: DpS is lost (relative error E above 1/2, the level dps-validity calls lost)
    assert open_dataset(out / "metrics" / "packet-steel.nc").attrs["E_max"] > 0.5
    assert cli.main(["run", "tw-weak", "--out", str(out), "--config", str(tmp_path / "config.yaml")]) == 0
    assert _warnings(capsys.readouterr().err) == []
    x0 = open_dataset(out / "initial" / "tw-weak.nc")
    assert dps_range.amplitude_of(x0["x0"].values, x0["v0"].values) < 0.2
