"""The shared parameter types: each bound of alpha, N, bc, rtol, ... written once, for config keys and arguments."""
from __future__ import annotations

from typing import Any

from .values import (
    ANGLE_PATTERN,
    ATOL_FLOOR,
    DRIFT_FLOOR,
    DT_FACTOR_FLOOR,
    MAX_COUNT,
    NAME_MAX_LENGTH,
    NAME_PATTERN,
    RTOL_FLOOR,
)

# Shared scalar types ($defs), each bound written here only.

SHARED: dict[str, dict[str, Any]] = {
    "name": {"description": f"An entry name: letters, digits, '-' and '_', at most {NAME_MAX_LENGTH} characters (it "
                            f"becomes part of file names).", "type": "string", "pattern": NAME_PATTERN,
             "maxLength": NAME_MAX_LENGTH},
    # at most 10: the paper's exponents are 3/2 to 3; beyond, a^(alpha-1) of (freq) under- or overflows
    "alpha": {"description": "Hertz exponent alpha of (vhertz); in (1, 10].", "type": "number", "exclusiveMinimum": 1,
              "maximum": 10},
    # the budget's estimate bounds N; the maximum here is only the largest integer every double holds
    "N": {"description": "Number of sites (beads) n = 0..N-1; >= 2, within the budget's estimate of its jobs.",
          "type": "integer", "minimum": 2, "maximum": MAX_COUNT},
    "bc": {"description": "Boundary conditions: periodic (x_N = x_0, a ring) or free (the end beads have one "
                          "neighbour).", "type": "string", "enum": ["periodic", "free"]},
    "rtol": {"description": f"Relative tolerance of an adaptive integrator, in [{RTOL_FLOOR:g}, 1e-2].",
             "type": "number", "minimum": RTOL_FLOOR, "maximum": 0.01},
    # at most 1e-2: a run whose energy moved by more than 1 % of H(0) is no solution of (nc)
    "maxEnergyDrift": {"description": "Largest accepted relative energy drift max_t |H(t)-H(0)|/H(0) of an exact "
                                      f"run; in [{DRIFT_FLOOR:g}, 1e-2] (a larger bound would turn the check off, a "
                                      "smaller one is below the rounding of H).",
                       "type": "number", "minimum": DRIFT_FLOOR, "maximum": 0.01},
    "angleString": {"description": "A multiple of pi such as 'pi', 'pi/5', '4pi/5', '-52pi/100', '4*pi/5', or a "
                                   "number written as a string.", "type": "string", "pattern": ANGLE_PATTERN},
    "angle": {"description": "An angle: a number (radians) or a multiple of pi as a string ('pi/5', '4pi/5', "
                             "'-52pi/100', '4*pi/5').", "anyOf": [{"type": "number"}, {"$ref": "#/$defs/angleString"}]},
    # arguments of public functions (cradle.specs.checked) only: not in config.schema.json
    "atol": {"description": f"Absolute tolerance of an adaptive integrator; >= {ATOL_FLOOR:g}.", "type": "number",
             "minimum": ATOL_FLOOR},
    "dt": {"description": "Time step of a fixed-step splitting; > 0.", "type": "number", "exclusiveMinimum": 0},
    "dt_factor": {"description": "Splitting step as a fraction of the shortest linearised period 2 pi / omega_max; "
                                 f">= {DT_FACTOR_FLOOR:g}.", "type": "number", "minimum": DT_FACTOR_FLOOR},
    "latticeMethod": {"description": "Integrator of the lattice (nc): a splitting (srkn6c, srkn4c with the "
                                     "contact-onset correction; srkn6, srkn4, strang) or an adaptive method "
                                     "(dop853_numba; scipy's dop853, rk45, lsoda, radau).", "type": "string",
                      "enum": ["srkn6c", "srkn4c", "srkn6", "srkn4", "strang", "dop853_numba", "dop853", "rk45",
                               "lsoda", "radau"]},
    "dpsMethod": {"description": "Integrator of the DpS equation (dfnls): dop853_numba, or scipy's dop853, rk45.",
                  "type": "string", "enum": ["dop853_numba", "dop853", "rk45"]},
    "potential": {"description": "Interaction potential: hertz, V0 of (vhertz), or smooth, |d|^(alpha+1)/(alpha+1) "
                                 "of (meca) with kappa = 1.", "type": "string", "enum": ["hertz", "smooth"]},
    # the arguments of the initial-data builders and the comparison of the models (each read as its config key
    # reads it where one exists)
    "amplitude": {"description": "An amplitude (a displacement in (nc)'s units); > 0.", "type": "number",
                  "exclusiveMinimum": 0},
    "width": {"description": "Number of sites an envelope covers; > 0.", "type": "number", "exclusiveMinimum": 0},
    "velocity": {"description": "A bead's velocity in (nc)'s units.", "type": "number"},
    "separation": {"description": "Distance in sites between two centres; integer >= 1.", "type": "integer",
                   "minimum": 1},
    "eps": {"description": "Amplitude parameter eps of the ansatz (ansatzapprox); > 0.", "type": "number",
            "exclusiveMinimum": 0},
    "q": {"description": "Wavenumber q (radians per site).", "type": "number"},
    "speed": {"description": "A relative speed of two spheres (m/s); > 0 and below the speed of light, "
                             "299792458 m/s (exact in the SI).", "type": "number", "exclusiveMinimum": 0,
              "exclusiveMaximum": 299792458.0},
    "iterations": {"description": "Iterations of the map G; integer >= 0.", "type": "integer", "minimum": 0,
                   "maximum": MAX_COUNT},
}
