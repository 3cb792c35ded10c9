"""``cradle scale``: the SI value of one unit of (nc)'s variables for a cradle of given spheres and strings
(:mod:`cradle.models.physical`), and what a dimensionless amplitude or a pendulum's release means."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

from cradle.pipeline.cli.common import CliError

if TYPE_CHECKING:
    import argparse


def scale_lines(args: argparse.Namespace) -> list[str]:
    """The lines ``cradle scale`` prints for its parsed arguments; a bad value is a one-line ConfigError."""
    from cradle.models import physical as ph

    spec = ph.real_cradle(args.material, args.radius, length=args.length, omega0=args.omega0)
    mat, s = ph.MATERIALS[spec.material], ph.scales(spec)
    period = 2.0 * math.pi * s.T
    oscillator = (f"pendulum L = {spec.length:g} m, g = {spec.g:g} m/s^2" if spec.length is not None
                  else f"stiff oscillator omega_0 = {spec.omega0:g} rad/s")
    out = [f"{mat.name} spheres (E = {mat.E / 1e9:.4g} GPa, nu = {mat.nu:.3g}, rho = {mat.rho:.4g} kg/m^3), "
           f"R = {spec.radius:g} m, {oscillator}",
           f"  sphere mass m = 4/3 pi R^3 rho       {s.m:.4e} kg",
           f"  Hertz constant k = 4/3 E* sqrt(R*)   {s.k:.4e} N/m^1.5  (E* = {s.E_star:.4e} Pa, R* = {s.R_star:.4g} m)",
           f"  omega_0                              {s.omega0:.6g} rad/s  (small-angle period {period:.6g} s)",
           "one unit of (nc) in SI:",
           f"  time       T = 1/omega_0               {s.T:.4e} s",
           f"  length     X = (m omega_0^2 / k)^2     {s.X:.4e} m",
           f"  velocity   X omega_0                   {s.V:.4e} m/s",
           f"  force      m omega_0^2 X               {s.F:.4e} N",
           f"  energy     m omega_0^2 X^2             {s.E:.4e} J"]
    if args.amplitude is not None:
        out.append(f"amplitude {args.amplitude:g} (nc) = {ph.to_si(args.amplitude, 'displacement', s):.4e} m")
    if args.angle is not None:
        a = ph.release_amplitude(spec, args.angle)
        v = ph.release_speed(spec, args.angle)
        tc = ph.collision_time(spec, v)
        out += [f"released at {args.angle:g} deg: horizontal displacement L sin(theta) = "
                f"{a * s.X:.4g} m "
                f"= {a:.4e} in (nc) units",
                f"  speed at the bottom {v:.4g} m/s = {ph.from_si(v, 'velocity', s):.4e} in (nc) units",
                f"  Hertz collision time at that speed t_c = {tc:.4e} s = {tc / period:.3e} of the swing period"]
    return out


def cmd_scale(args: argparse.Namespace) -> int:
    from cradle.specs.values import ConfigError

    try:
        lines = scale_lines(args)
    except ConfigError as err:
        # every problem on the one line, "; " between them
        raise CliError("; ".join(" ".join(line.removeprefix("config error: ").split()) for line in err.errors)) \
            from None
    print("\n".join(lines))
    return 0
