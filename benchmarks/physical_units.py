"""The numbers of docs/physical-units.md: the materials, the scales of (nc) for real cradles, the paper's
amplitudes in metres, a desk toy's swing in (nc)'s units and its Hertz collision time.

    python benchmarks/physical_units.py [--no-docs]   (default: its tables into docs/physical-units.md)

Every number comes from cradle.models.physical (and the tw-weak amplitude from (freq),
cradle.models.dps.amplitude_from_omega, as the scene computes it); nothing here is typed by hand but the
cradles' geometry and the amplitudes' names.
"""
from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from cradle.models import physical as ph  # noqa: E402
from cradle.models.dps import amplitude_from_omega  # noqa: E402
from doctable import publish  # noqa: E402

RADIUS, LENGTH, ANGLE = 0.01, 0.1, 20.0  # 1 cm balls on 10 cm strings, lifted to 20 degrees
CRADLES = {name: ph.real_cradle(name, RADIUS, length=LENGTH) for name in ("steel", "brass", "glass", "ptfe")}


def amplitudes() -> dict[str, float]:
    """The paper's amplitudes (dimensionless): the tw-weak one from (freq) at omega_tw = 1.01, q = pi/5."""
    a_weak = amplitude_from_omega(1.01, math.pi / 5, 1.5)
    return {"a = 0.01": 0.01, f"tw-weak a = {a_weak:.5g} (plot4-5, from (freq) at omega_tw = 1.01)": a_weak,
            "breathers' max abs x ~ 0.01 (loc1, section 4.3)": 0.01}


def materials_table() -> str:
    rows = ["| material | E (GPa) | nu | rho (kg/m^3) | source |", "|---|---|---|---|---|"]
    for m in ph.MATERIALS.values():
        rows.append(f"| {m.name} | {m.E / 1e9:.4g} | {m.nu:.3g} | {m.rho:.4g} | {m.source} |")
    return "\n".join(rows)


def scales_table() -> str:
    rows = [f"Spheres of radius {RADIUS:g} m on pendulum strings of {LENGTH:g} m (omega_0 = sqrt(g_n/L)).", "",
            "| material | m (kg) | k (N/m^1.5) | omega_0 (rad/s) | T (s) | X (m) | X omega_0 (m/s) | "
            "m omega_0^2 X (N) | m omega_0^2 X^2 (J) |", "|---|---|---|---|---|---|---|---|---|"]
    for name, spec in CRADLES.items():
        s = ph.scales(spec)
        rows.append(f"| {name} | {s.m:.4g} | {s.k:.4g} | {s.omega0:.5g} | {s.T:.4g} | {s.X:.4g} | {s.V:.4g} | "
                    f"{s.F:.4g} | {s.E:.4g} |")
    return "\n".join(rows)


def amplitudes_table() -> str:
    names = list(CRADLES)
    rows = ["| amplitude (nc) | " + " | ".join(f"{n} (m)" for n in names) + " |", "|---" * (len(names) + 1) + "|"]
    for label, a in amplitudes().items():
        rows.append(f"| {label} | " + " | ".join(f"{ph.to_si(a, 'displacement', ph.scales(CRADLES[n])):.3g}"
                                                   for n in names) + " |")
    # the stiff on-site oscillator for which a = 0.01 is one micrometre: X = 1e-4 m, omega_0^2 = k sqrt(X) / m
    rows += ["", "The on-site frequency a stiff oscillator would need for a = 0.01 to be 1 micrometre "
                 "(X = 1e-4 m, omega_0 = sqrt(k sqrt(X) / m)):", "",
             "| material | omega_0 (rad/s) | f = omega_0 / 2 pi (Hz) |", "|---|---|---|"]
    for name, spec in CRADLES.items():
        s = ph.scales(spec)
        w = math.sqrt(s.k * math.sqrt(1e-4) / s.m)
        check = ph.scales(ph.real_cradle(name, RADIUS, omega0=w))
        assert math.isclose(check.X, 1e-4, rel_tol=1e-12)
        rows.append(f"| {name} | {w:.4g} | {w / (2 * math.pi):.4g} |")
    return "\n".join(rows)


def desk_table() -> str:
    rows = [f"A ball lifted to {ANGLE:g} degrees on its {LENGTH:g} m string and released: its horizontal "
            "displacement L sin(theta), its speed at the bottom sqrt(2 g L (1 - cos theta)) (the impact speed), "
            "both in (nc)'s units, and the Hertz collision time t_c of an impact at that speed against the "
            "small-angle swing period 2 pi / omega_0.", "",
            "| material | L sin(theta) (nc) | v (m/s) | v (nc) | delta_max (m) | t_c (s) | 2 pi/omega_0 (s) | "
            "t_c omega_0 / 2 pi |", "|---|---|---|---|---|---|---|---|"]
    for name, spec in CRADLES.items():
        s = ph.scales(spec)
        v = ph.release_speed(spec, ANGLE)
        tc = ph.collision_time(spec, v)
        delta = (5 * (s.m / 2) * v**2 / (4 * s.k)) ** 0.4
        period = 2 * math.pi / s.omega0
        rows.append(f"| {name} | {ph.release_amplitude(spec, ANGLE):.4g} | {v:.4g} | "
                    f"{ph.from_si(v, 'velocity', s):.4g} | {delta:.3g} | {tc:.3g} | {period:.4g} | "
                    f"{tc / period:.3g} |")
    return "\n".join(rows)


def nc_contact_fraction(A: float) -> float:
    """t_c / 2 pi in (nc)'s units (m = k = 1, mu = 1/2) for two beads meeting at relative speed v = A, without
    the on-site force: t_c = 2 I (5 v^2 / 8)^(2/5) / v, so t_c ~ A^(-1/5)."""
    return 2 * ph.COLLISION_INTEGRAL * (5 * A**2 / 8) ** 0.4 / A / (2 * math.pi)


def integrators_table() -> str:
    spec = CRADLES["steel"]
    s = ph.scales(spec)
    v = ph.release_speed(spec, ANGLE)
    tc, period = ph.collision_time(spec, v), 2 * math.pi / s.omega0
    A = ph.release_amplitude(spec, ANGLE)
    # the SI estimate and the (nc) one are the same formula in two unit systems: they must agree
    v_nc = ph.from_si(v, "velocity", s)
    assert math.isclose(nc_contact_fraction(v_nc), tc / period, rel_tol=1e-9)
    rows = ["| quantity | value |", "|---|---|",
            f"| steel desk toy ({ANGLE:g} degrees): t_c / swing period | {tc / period:.3g} |",
            f"| fixed steps per swing at dt = t_c / 50 | {50 * period / tc:.3g} |",
            f"| (nc) contact time / 2 pi at the desk toy's speed ({v_nc:.3g}) | {nc_contact_fraction(v_nc):.3g} |",
            f"| (nc) contact time / 2 pi at speed 0.01 (the paper's amplitudes) | {nc_contact_fraction(0.01):.3g} |",
            f"| desk toy's release amplitude in (nc) units | {A:.3g} |"]
    return "\n".join(rows)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--no-docs", action="store_true", help="print the tables only")
    args = p.parse_args(argv)
    tables = {"physical-materials": materials_table(), "physical-scales": scales_table(),
              "physical-amplitudes": amplitudes_table(), "physical-desk": desk_table(),
              "physical-integrators": integrators_table()}
    for name, text in tables.items():
        print(f"{name}:\n{text}\n")
        if not args.no_docs:
            publish("physical-units.md", name, text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
