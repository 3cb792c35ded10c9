"""@checked (cradle.specs.checked): public functions refuse bad numbers in one line, through the shared
declarations; no per-function parameter check is left under src/cradle (an ast scan)."""
import ast
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from cradle.specs import schema
from cradle.specs.checked import checked, checker
from cradle.specs.declare import SHARED, declared, param
from cradle.specs.schema import generate
from cradle.specs.values import ConfigError

SRC = Path(__file__).resolve().parents[2] / "src" / "cradle"

#: shared types @checked can check (numbers, integers, strings of an enum); the others are config-only: angles
#: and names, whose patterns the config words itself
CHECKABLE = [k for k, d in SHARED.items() if d.get("type") in ("number", "integer", "string") and "pattern" not in d]


def refusal(shared, value, arg=None) -> str:
    """The message of checking ``value`` as ``shared`` (the argument named ``arg``, default the type)."""
    with pytest.raises(ConfigError) as err:
        checker(shared)(arg or shared, value)
    assert isinstance(err.value, ValueError) and len(err.value.errors) == 1 and "\n" not in str(err.value)
    return str(err.value)


# ----------------------------------------------------------------------------- one line per bad value

DT_FACTOR_WHY = (" (the step dt_factor 2 pi / omega_max is then about 1e2 spacings of doubles at the longest t_end "
                 "or more: below, t + dt is rounding noise)")
RTOL_WHY = (" (a floor the integrator can honour, about 1e2 machine epsilons or more: below, a step's error "
            "estimate is rounding noise and the steps shrink until they underflow)")


@pytest.mark.parametrize("shared, value, line", [
    ("alpha", 1.0, "alpha = 1.0: must be > 1 (Hertz exponent of (vhertz))"),
    ("alpha", 1, "alpha = 1: must be > 1 (Hertz exponent of (vhertz))"),
    ("alpha", 0.0, "alpha = 0.0: must be > 1 (Hertz exponent of (vhertz))"),
    ("alpha", -1.5, "alpha = -1.5: must be > 1 (Hertz exponent of (vhertz))"),
    ("alpha", np.float64(0.5), "alpha = 0.5: must be > 1 (Hertz exponent of (vhertz))"),
    ("alpha", math.nan, "alpha = nan: must be a finite number"),
    ("alpha", math.inf, "alpha = inf: must be a finite number"),
    ("alpha", -math.inf, "alpha = -inf: must be a finite number"),
    ("alpha", np.float32("nan"), "alpha = nan: must be a finite number"),
    ("alpha", 10**400, "alpha = " + repr(10**400)[:77] + "...: must be a finite number"),
    ("alpha", "1.5", "alpha = '1.5': must be a number"),
    ("alpha", True, "alpha = True: must be a number"),
    ("alpha", None, "alpha = None: must be a number"),
    ("alpha", np.array(1.5), "alpha = array(1.5): must be a number"),
    ("alpha", 1.5j, "alpha = 1.5j: must be a number"),
    ("N", 1, "N = 1: must be >= 2"),
    ("N", 0, "N = 0: must be >= 2"),
    ("N", -3, "N = -3: must be >= 2"),
    ("N", np.int64(1), "N = 1: must be >= 2"),
    ("N", 1.0, "N = 1.0: must be >= 2"),
    ("N", 20.5, "N = 20.5: must be an integer"),
    ("N", math.nan, "N = nan: must be a finite number"),
    ("N", math.inf, "N = inf: must be a finite number"),
    ("N", "20", "N = '20': must be an integer"),
    ("N", False, "N = False: must be an integer"),
    ("N", None, "N = None: must be an integer"),
    ("bc", "fixed", "bc = 'fixed': must be one of periodic, free"),
    ("bc", "Periodic", "bc = 'Periodic': must be one of periodic, free"),
    ("bc", "", "bc = '': must be one of periodic, free"),
    ("bc", 0, "bc = 0: must be a string"),
    ("bc", None, "bc = None: must be a string"),
    ("bc", True, "bc = True: must be a string"),
    ("rtol", 0.0, f"rtol = 0.0: must be >= 1e-14{RTOL_WHY}"),
    ("rtol", -1e-10, f"rtol = -1e-10: must be >= 1e-14{RTOL_WHY}"),
    ("rtol", 1e-300, f"rtol = 1e-300: must be >= 1e-14{RTOL_WHY}"),
    ("rtol", 0.1, "rtol = 0.1: must be <= 0.01"),
    ("rtol", 1e300, "rtol = 1e+300: must be <= 0.01"),
    ("rtol", math.nan, "rtol = nan: must be a finite number"),
    ("rtol", "1e-10", "rtol = '1e-10': must be a number"),
    ("rtol", True, "rtol = True: must be a number"),
    ("maxEnergyDrift", 0, "maxEnergyDrift = 0: must be >= 1e-14"),
    ("atol", -1.0, "atol = -1.0: must be >= 1e-150 (the error norm squares state / atol, which overflows float64 "
                   "below it)"),
    ("atol", math.inf, "atol = inf: must be a finite number"),
    ("dt", 0.0, "dt = 0.0: must be > 0"),
    ("dt", -0.1, "dt = -0.1: must be > 0"),
    ("dt", math.nan, "dt = nan: must be a finite number"),
    ("dt", "0.1", "dt = '0.1': must be a number"),
    ("dt_factor", 0, f"dt_factor = 0: must be >= 1e-08{DT_FACTOR_WHY}"),
    ("dt_factor", 1e-300, f"dt_factor = 1e-300: must be >= 1e-08{DT_FACTOR_WHY}"),
    ("latticeMethod", "euler", "latticeMethod = 'euler': must be one of srkn6c, srkn4c, srkn6, srkn4, strang, "
                               "dop853_numba, dop853, rk45, lsoda, radau"),
    ("dpsMethod", "srkn6", "dpsMethod = 'srkn6': must be one of dop853_numba, dop853, rk45"),
    ("potential", "fpu", "potential = 'fpu': must be one of hertz, smooth"),
    ("potential", 1.5, "potential = 1.5: must be a string"),
])
def test_a_bad_value_is_one_line_naming_the_argument_the_value_and_why(shared, value, line):
    assert refusal(shared, value) == line


@pytest.mark.parametrize("shared", CHECKABLE)
def test_every_shared_type_refuses_every_shape_of_bad_value(shared):
    """Every checkable shared type: the wrong type, a bool, None, nan and inf are refused, and a number
    beyond each bound (negative, zero, 1e300) is refused with that bound's words."""
    decl = SHARED[shared]
    words = {"number": "a number", "integer": "an integer", "string": "a string"}[decl["type"]]
    wrong = "x" if decl["type"] != "string" else 1.5
    for bad in (wrong, True, False, None, [1]):
        assert refusal(shared, bad, "arg") == f"arg = {bad!r}: must be {words}"
    if decl["type"] == "string":
        assert refusal(shared, "not-an-option", "arg").startswith("arg = 'not-an-option': must be one of ")
        return
    for bad in (math.nan, math.inf, -math.inf):
        assert refusal(shared, bad, "arg") == f"arg = {bad!r}: must be a finite number"
    for bad in (-1e300, -1, 0, 0.0, 1e-300, 1e300):
        lo = decl.get("minimum", decl.get("exclusiveMinimum"))
        hi, hi_ex = decl.get("maximum"), decl.get("exclusiveMaximum")
        too_low = bad < lo if "minimum" in decl else bad <= lo if lo is not None else False
        too_high = hi is not None and bad > hi or hi_ex is not None and bad >= hi_ex
        if decl["type"] == "integer" and not float(bad).is_integer():
            assert refusal(shared, bad, "arg") == f"arg = {bad!r}: must be an integer"
        elif too_low or too_high:
            assert refusal(shared, bad, "arg").startswith(f"arg = {bad!r}: must be {'>' if too_low else '<'}")
        else:
            assert checker(shared)("arg", bad) == bad


def test_every_lattice_and_dps_choice_is_declared_once():
    """The enums of the shared types are the integrators' and the lattice's own choices."""
    from cradle.integrators import DPS_METHODS, METHODS
    from cradle.integrators.lattice_solver import POTENTIALS
    from cradle.models.lattice import BOUNDARY_CONDITIONS

    assert sorted(SHARED["latticeMethod"]["enum"]) == sorted(METHODS)
    assert sorted(SHARED["dpsMethod"]["enum"]) == sorted(DPS_METHODS)
    assert sorted(SHARED["potential"]["enum"]) == sorted(POTENTIALS)
    assert SHARED["bc"]["enum"] == list(BOUNDARY_CONDITIONS)


# ----------------------------------------------------------------------------- the decorator

def test_checked_arguments_arrive_as_declared():
    @checked(method="dpsMethod", seed=None)
    def f(N, alpha, /, bc="periodic", *, method="dop853_numba", rtol=None, seed=None, dt=0.1):
        return N, alpha, bc, method, rtol, seed, dt

    assert f.checked_arguments == {"N": "N", "alpha": "alpha", "bc": "bc", "method": "dpsMethod", "rtol": "rtol",
                                   "dt": "dt"}
    out = f(np.int64(20), np.float64(1.5))
    assert out == (20, 1.5, "periodic", "dop853_numba", None, None, 0.1)
    assert type(out[0]) is int and type(out[1]) is float
    out = f(20.0, 3, "free", rtol=np.float32(0.0078125), seed="anything", dt=1)
    assert out == (20, 3.0, "free", "dop853_numba", 0.0078125, "anything", 1.0)
    assert [type(v) for v in out] == [int, float, str, str, float, str, float]
    assert f(20, 1.5, rtol=None)[4] is None   # None where the default is None: not given
    with pytest.raises(ConfigError, match=r"^dt = None: must be a number$"):
        f(20, 1.5, dt=None)                   # but None is not a number where a number is the default
    with pytest.raises(ConfigError, match=r"^method = 'rk4': must be one of dop853_numba, dop853, rk45$"):
        f(20, 1.5, method="rk4")
    with pytest.raises(ConfigError, match=r"^bc = 'ring': must be one of periodic, free$"):
        f(20, 1.5, "ring")


def test_mistakes_in_a_decoration_are_refused_when_decorating():
    with pytest.raises(TypeError, match="no argument beta"):
        checked(beta="alpha")(lambda alpha: alpha)
    with pytest.raises(TypeError, match="'hertzExponent' is not a shared type"):
        checked(a="hertzExponent")(lambda a: a)
    with pytest.raises(TypeError, match="no argument of a shared type"):
        checked(lambda x, y: x)
    with pytest.raises(TypeError, match=r"the default alpha = 1.0: must be > 1"):
        checked(lambda alpha=1.0: alpha)
    with pytest.raises(TypeError, match=r"write the default alpha = 2 as 2.0"):
        checked(lambda alpha=2: alpha)
    with pytest.raises(TypeError, match="cannot check the shared type 'angle'"):
        checked(lambda angle: angle)
    with pytest.raises(TypeError, match=r"cannot check the shared type 'name' \(maxLength, pattern\)"):
        checked(lambda name, alpha: alpha)
    assert checked(name=None)(lambda name, alpha: (name, alpha))("x y", 2) == ("x y", 2.0)
    with pytest.raises(TypeError, match=r"\*alpha"):
        checked(lambda *alpha: alpha)


def test_a_public_function_refuses_before_any_work(monkeypatch):
    """The decorator runs before the body: the arrays are not even looked at."""
    from cradle.integrators import integrate_dps, integrate_lattice, lattice_solver
    from cradle.models import initial

    def no_work(*args, **kwargs):
        raise AssertionError("the body ran")

    monkeypatch.setattr(lattice_solver, "check_state", no_work)
    monkeypatch.setattr(initial, "lattice_state", no_work)
    monkeypatch.setattr(initial.dps, "omega_tw", no_work)
    x = np.zeros(4)
    with pytest.raises(ConfigError) as err:
        integrate_lattice(x, x, [0.0, 1.0], alpha=1.0)
    assert str(err.value) == "alpha = 1.0: must be > 1 (Hertz exponent of (vhertz))"
    with pytest.raises(ConfigError, match=r"^dt = -0.1: must be > 0$"):
        integrate_lattice(x, x, [0.0, 1.0], alpha=1.5, dt=-0.1)
    with pytest.raises(ConfigError, match=r"^N = 1: must be >= 2$"):
        initial.travelling_wave(1, np.pi, 1.5, a=0.1)
    with pytest.raises(ConfigError, match=r"^bc = 'fixed': must be one of periodic, free$"):
        initial.travelling_wave(20, np.pi, 1.5, a=0.1, bc="fixed")
    with pytest.raises(ConfigError, match=r"^rtol = 1.0: must be <= 0.01$"):
        integrate_dps(np.array([1.0, 2.0 + 1j]), [0.0, 1.0], alpha=1.5, rtol=1.0)


@pytest.mark.parametrize("where, name, arguments", [
    ("cradle.integrators", "integrate_lattice", {"alpha", "atol", "bc", "dt", "dt_factor", "method", "potential",
                                                 "rtol"}),
    ("cradle.integrators", "integrate_dps", {"alpha", "atol", "bc", "method", "rtol"}),
    ("cradle.integrators.dps_solver", "iter_dps", {"alpha", "atol", "bc", "rtol"}),
    ("cradle.models.initial", "travelling_wave", {"N", "a", "alpha", "bc", "q"}),
    ("cradle.models.initial", "breather", {"alpha", "amplitude", "bc"}),
    ("cradle.models.initial", "from_displacements", {"alpha", "bc"}),
    ("cradle.models.initial", "packet", {"N", "alpha", "amplitude", "bc", "width"}),
    ("cradle.models.initial", "pair", {"N", "alpha", "amplitude", "bc", "separation"}),
    ("cradle.models.pairs", "two_breathers", {"N", "alpha", "bc"}),
    ("cradle.models.dps", "c_alpha", {"alpha"}),
    ("cradle.models.dps", "c_alpha_wallis", {"alpha"}),
    ("cradle.models.dps", "tau0", {"alpha"}),
    ("cradle.models.dps", "amplitude_from_omega", {"alpha", "q"}),
    ("cradle.models.homoclinic", "solve", {"alpha", "bc"}),
    ("cradle.models.homoclinic_continuation", "solve_scaled", {"alpha", "bc"}),
    ("cradle.models.homoclinic_continuation", "continued", {"N", "alpha", "bc", "separation"}),
    ("cradle.models.homoclinic_continuation", "solve_sized", {"alpha"}),
    ("cradle.models.homoclinic_continuation", "solve_kind", {"N", "alpha", "amplitude", "bc", "separation"}),
    ("cradle.models.homoclinic_tails", "log_tail_log", {"alpha"}),
    ("cradle.models.stationary", "orbits", {"alpha", "n_iter"}),
    ("cradle.models.stationary", "explicit_periodic_orbits", {"alpha"}),
    ("cradle.models.stationary", "stationary_residual", {"alpha", "bc"}),
    ("cradle.models.waves", "solve", {"alpha", "q"}),
    ("cradle.integrators.lattice_breathers", "newton", {"alpha", "bc", "rtol"}),
])
def test_the_public_entry_points_are_checked(where, name, arguments):
    import importlib

    func = getattr(importlib.import_module(where), name)
    assert set(func.checked_arguments) == arguments
    valid = {"N": 20, "q": 0.6, "amplitude": 0.1, "width": 5.0, "separation": 3, "n_iter": 3}
    with pytest.raises(ConfigError, match=r"^alpha = 0.5: must be > 1 \(Hertz exponent of \(vhertz\)\)$"):
        func(**{p: {"alpha": 0.5, **valid}.get(p) for p in _required(func)})


def _required(func):
    import inspect

    return [p.name for p in inspect.signature(func).parameters.values()
            if p.default is p.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]


def test_a_checked_call_passes_its_arguments_through():
    """@checked reads integrate_lattice's arguments (as the scene job passes them) and calls the function with them
    unchanged; what it costs per call is benchmarks/checked_call_cost.py's (docs/performance.md)."""
    def plain(x0, v0, t_out, *, alpha, bc="periodic", method="srkn6c", dt=None, dt_factor=None, rtol=None,
              atol=None, potential="hertz"):
        return x0, v0, t_out, alpha, bc, method, dt, dt_factor, rtol, atol, potential

    wrapped = checked(method="latticeMethod")(plain)
    args, kwargs = ([0.0], [1.0], [2.0]), {"alpha": 1.5, "bc": "periodic", "method": "srkn6c", "dt": 0.01}
    assert wrapped(*args, **kwargs) == plain(*args, **kwargs)
    assert wrapped.__wrapped__ is plain


def test_specs_imports_nothing_of_cradle_and_no_numpy():
    code = ("import sys, cradle; before = set(sys.modules); import cradle.specs.checked, cradle.specs.declare, "
            "cradle.specs.values; new = set(sys.modules) - before; "
            "print(sorted(m for m in new if m.startswith('cradle') and not m.startswith('cradle.specs')), "
            "'numpy' in sys.modules)")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(SRC.parent), os.environ.get("PYTHONPATH", "")])}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env).stdout
    assert out.split() == ["[]", "False"]


def test_a_schema_lists_only_the_shared_types_its_keys_use(monkeypatch):
    """Types only functions' arguments use (dt, latticeMethod, ...) stay out of config.schema.json."""
    monkeypatch.setattr(schema, "UNIONS", {})   # the registered unions refer to more shared types

    @declared(doc="A test spec.")
    class One:
        alpha: float = param(1.5, "Hertz exponent.", ref="alpha")
        q: float = param(0.0, "Wavenumber.", ref="angle")

    defs = generate(One, title="one")["$defs"]
    assert [k for k in defs if k in SHARED] == ["alpha", "angleString", "angle"]


# ----------------------------------------------------------------------------- no hand-written checks left

#: the removed per-parameter checks: they must not come back
REMOVED = {"check_alpha", "check_bc", "check_positive", "check_choice"}
#: a function named check_<shared type> is a per-parameter check whatever its body
CHECK_NAMES = REMOVED | {f"check_{k}".lower() for k in SHARED}


def _sources():
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC).as_posix()
        if not rel.startswith("specs/"):
            yield rel, ast.parse(path.read_text(encoding="utf-8"))


def uses_of_removed_checks(tree) -> list[tuple[str, str, int]]:
    """(what, name, line) of every definition, import, call or attribute of a removed check's name."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name.lower() in CHECK_NAMES:
            out.append(("def", node.name, node.lineno))
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            out += [("import", a.name, node.lineno) for a in node.names if a.name.split(".")[-1] in REMOVED]
        elif isinstance(node, ast.Name) and node.id in REMOVED:
            out.append(("use", node.id, node.lineno))
        elif isinstance(node, ast.Attribute) and node.attr in REMOVED:
            out.append(("use", node.attr, node.lineno))
    return out


def _constant(node) -> bool:
    """A literal, a tuple/list/set of literals, -literal, or a module constant (UPPER_CASE name)."""
    if isinstance(node, ast.Constant):
        return True
    if isinstance(node, ast.UnaryOp):
        return _constant(node.operand)
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return all(_constant(e) for e in node.elts)
    return isinstance(node, ast.Name) and node.id.isupper() and len(node.id) > 1


def _alone(test, params) -> set[str]:
    """Parameters that ``test`` compares with constants alone, so that the comparison by itself decides it
    (a Compare, ``not`` one, or one operand of an ``or``; a None test is a default, not a check)."""
    if isinstance(test, ast.UnaryOp) and isinstance(test.op, ast.Not):
        return _alone(test.operand, params)
    if isinstance(test, ast.BoolOp) and isinstance(test.op, ast.Or):
        return set().union(*(_alone(v, params) for v in test.values))
    if isinstance(test, ast.Compare) and not any(isinstance(op, (ast.Is, ast.IsNot)) for op in test.ops):
        sides = [test.left, *test.comparators]
        names = [s.id for s in sides if isinstance(s, ast.Name) and s.id in params]
        if len(names) == 1 and all(_constant(s) for s in sides if not (isinstance(s, ast.Name) and s.id in params)):
            return set(names)
    return set()


def hand_checks(tree) -> list[tuple[str, str, int]]:
    """(function, parameter, line) of every ``if <parameter of a shared type> <op> <constant>: raise``."""
    out = []
    for fn in ast.walk(tree):
        if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        a = fn.args
        params = {p.arg for p in a.posonlyargs + a.args + a.kwonlyargs} & set(SHARED)
        for node in ast.walk(fn) if params else ():
            if isinstance(node, ast.If) and any(isinstance(s, ast.Raise) for s in node.body):
                out += [(fn.name, p, node.lineno) for p in sorted(_alone(node.test, params))]
    return out


def test_the_scan_finds_hand_checks_and_only_them():
    found = hand_checks(ast.parse('''
def a(x, alpha, N):
    if alpha <= 1.0:
        raise ValueError("alpha")
    if not np.isfinite(alpha) or alpha <= 1:
        raise ValueError("alpha")
    if N < 2:
        raise ValueError("N")
def b(bc, rtol=None, dt=None, dt_factor=None, N=2, m=0):
    if bc not in BOUNDARY_CONDITIONS:
        raise ValueError(bc)
    if not 0 < rtol <= 1e-2:
        raise ValueError(rtol)
    if dt is not None and dt_factor is not None:
        raise ValueError("both")
    if bc == "free" and not 0 <= m < N:
        raise ValueError("reflection")
    if rtol is None:
        rtol = 1e-10
    if N < 2:
        N = 2
'''))
    assert found == [("a", "alpha", 3), ("a", "alpha", 5), ("a", "N", 7), ("b", "bc", 10), ("b", "rtol", 12)]
    assert [u[:2] for u in sorted(uses_of_removed_checks(ast.parse(
        "from cradle.models.lattice import check_alpha\nx = lattice.check_bc(bc)\ndef check_N(N): pass\n"
        "def check_state(arr, name): pass\n")), key=lambda u: u[2])] == [("import", "check_alpha"), ("use", "check_bc"),
                                                                  ("def", "check_N")]


def test_no_per_function_parameter_check_remains():
    """Outside cradle.specs, no function defines, imports or calls a per-parameter check (check_alpha,
    check_bc, check_positive, check_choice, check_<shared type>) or raises on a parameter of a shared
    type compared with a constant: @checked does it, from the declarations."""
    uses, checks = {}, {}
    for rel, tree in _sources():
        if found := uses_of_removed_checks(tree):
            uses[rel] = found
        if found := hand_checks(tree):
            checks[rel] = found
    assert uses == {}
    assert checks == {}
