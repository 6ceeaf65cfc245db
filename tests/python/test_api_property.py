"""A property of the whole module's boundary: seeded random arguments of every type (None,
ints, huge, negative, NaN and infinite floats, strings, lists, dicts, bytes, arrays,
callables, the module's own objects) given to every public function, class and method of
``chasles`` (found by introspection, so that new ones are covered) raise only the documented
exceptions, and never crash, hang or return a NaN (docs/python.md, "Errors";
docs/reliability.md, "The Python module").

The documented exceptions: ``InputError`` (a ValueError; SceneError and LimitError are
InputErrors), ``ValueError``, ``TypeError``, ``IndexError`` (an index out of range) and
``KeyError`` (a lookup by a name that is not there)."""

import faulthandler
import inspect
import math
import random
import re
import time

import numpy as np
import pytest

import chasles
from conftest import SOURCE_DIR, example

# The exceptions docs/python.md promises; anything else (RuntimeError, SystemError,
# OverflowError, AttributeError, ...) out of a call is a defect.
DOCUMENTED = (chasles.InputError, ValueError, TypeError, IndexError, KeyError)
# Calls per callable and seed; the seeds make every failure reproducible.
CALLS = 60
SEEDS = (1, 2, 3, 4, 5, 6)
# A call taking longer than this is a hang as far as the boundary is concerned: every
# argument the module accepts is bounded by its limits (steps, rows, runs) long before.
SLOWEST_CALL_S = 5.0

NAN, INF = math.nan, math.inf
FLOATS = [0.0, -0.0, 1.0, -1.0, 0.25, 3.0, 1e-3, 1e-300, 5e-324, 1e300, -1e300, NAN, INF, -INF]
INTS = [0, 1, 2, 3, -1, 7, -2**31, 2**31, 2**62, 2**63, 2**70, -2**70]
# Strings the module reads as names, expressions, sweeps, modes and paths: never a path that
# could block (/dev/stdin) or write anywhere.
STRINGS = ["", "x", "block", "ball", "k", "t", "1 m", "30 deg", "-1 kg", "nan", "1e999",
           "k=100 N/m:1000 N/m:3", "k=1:2:0", "max(block_x)", "final(block_vx)", "mass",
           "solid", "shell", "body", "world", "counterclockwise", "rotation", "\x00", "\u00e9",
           "a" * 300, "{", "[1, 2", "k: [", example("spring-mass.yaml"),
           SOURCE_DIR + "/no/such/file.yaml", SOURCE_DIR + "/examples"]
CALLABLES = [lambda *a: [0.0, 0.0, 1.0], lambda *a: NAN, lambda *a: INF, lambda *a: "x",
             lambda *a: None, lambda *a: 1.0, lambda *a: [NAN, 0.0, 0.0], lambda *a: [1.0]]


class Pool:
    """Instances of the module's classes to pass and to call methods on, rebuilt for each seed
    (methods may change them)."""

    def __init__(self, csv_path):
        spring = chasles.load_scene(example("spring-mass.yaml"))
        self.objects = {"Scene": [spring, chasles.load_scene(example("pendulum.yaml"))]}
        shape = chasles.sphere(0.1)
        mp = shape.mass_properties(2.0)
        model = chasles.Model()
        ball = model.add_body("ball", mp)
        model.add_force_element(chasles.UniformGravity("gravity", [0.0, 0.0, -9.80665]))
        state = chasles.make_rest_state(model)
        run = chasles.run(spring, until=0.01)
        self.objects.update({
            "Shape": [shape, chasles.box(1.0, 2.0, 3.0)],
            "MassProperties": [mp],
            "RotationalInertia": [mp.rotational_inertia],
            "Model": [model],
            "State": [state],
            "BodyState": [state.bodies[0]],
            "Solution": [chasles.solve(spring)],
            "Run": [run],
            "StudyResult": [run.result],
            "SimulationOptions": [chasles.SimulationOptions(0.01)],
            "SimulationResult": [chasles.simulate(model, state, t_end=0.01)],
            "TimeSteppingOptions": [chasles.TimeSteppingOptions(0.01)],
            "TimeSteppingResult": [chasles.simulate_time_stepping(model, state, t_end=0.01,
                                                                  store_steps=True)],
            "Table": [chasles.read_csv(csv_path)],
            "Sweep": [chasles.sweep(spring, "k=100 N/m:1000 N/m:2")],
            "Certificate": [run.certificate],
            "TimeFunction": [chasles.TimeFunction.quadratic(0.0, 1.0, 0.0)],
            "StringEnd": [chasles.StringEnd(ball, [0.0, 0.0, 0.0])],
            "StringPulley": [chasles.StringPulley([0.0, 0.0, 1.0], 0.1, "counterclockwise")],
            "AttachmentFrame": [chasles.AttachmentFrame([0.0, 0.0, 0.0], np.eye(3))],
            "PitchCircle": [chasles.PitchCircle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.1)],
            "Balance": [chasles.balance(chasles.load_scene(example("unbalanced-disk-rotor.yaml")),
                                        "rotor", planes="-25 cm, 25 cm", radius="15 cm",
                                        speed="3000 rpm", grade=6.3)],
        })

    def of(self, name):
        return self.objects.get(name, [])

    def any(self, rng):
        return rng.choice(rng.choice([v for v in self.objects.values() if v]))


def random_value(rng, pool, depth=0):
    """A value of a random type; containers hold random values themselves."""
    kind = rng.randrange(12 if depth == 0 else 8)
    if kind == 0:
        return None
    if kind in (1, 2):
        return rng.choice(FLOATS) if kind == 1 else rng.uniform(-10.0, 10.0)
    if kind == 3:
        return rng.choice(INTS)
    if kind == 4:
        return rng.choice(STRINGS)
    if kind == 5:
        return rng.choice([b"", b"\xff\x00", b"1 m", True, False])
    if kind == 6:
        return [rng.choice(FLOATS) for _ in range(rng.choice([0, 1, 2, 3, 3, 3, 4, 9]))]
    if kind == 7:
        return np.array([rng.choice(FLOATS) for _ in range(3)])
    if kind == 8:
        return [random_value(rng, pool, depth + 1) for _ in range(rng.randrange(4))]
    if kind == 9:
        return {rng.choice(STRINGS + ["k", "m"]): random_value(rng, pool, depth + 1)
                for _ in range(rng.randrange(3))}
    if kind == 10:
        return rng.choice(CALLABLES)
    return pool.any(rng)


def typed_value(rng, pool, annotation, name):
    """A hostile value of the type the signature asks for (by annotation or by name), so that
    the call passes the type check and reaches the checks of values."""
    a = annotation or ""
    m = re.search(r"chasles\._chasles\.(\w+)", a)
    if m and pool.of(m.group(1)):
        return rng.choice(pool.of(m.group(1)))
    if name in ("scene",) and pool.of("Scene"):
        return rng.choice(pool.of("Scene"))
    if "ndarray" in a or "List[float]" in a:
        width = 3 if "[3, 1]" in a else (4 if "[4, 1]" in a else rng.choice([2, 3]))
        shape = (3, 3) if "[3, 3]" in a else (width,)
        return np.array([rng.choice(FLOATS) for _ in range(int(np.prod(shape)))]).reshape(shape)
    if "Callable" in a or "function" in a:
        return rng.choice(CALLABLES)
    if a.startswith("float") or name in ("until", "timeout", "min_step", "t_end", "radius"):
        return rng.choice(FLOATS)
    if a.startswith("int") or name.startswith("max_") or name in ("count", "jobs", "index"):
        return rng.choice(INTS)
    if a.startswith("str") or name in ("parameter", "start", "stop", "path", "name"):
        return rng.choice(STRINGS)
    return random_value(rng, pool)


def parameters(fn):
    """(name, annotation, keyword-only) of each parameter: pybind11's first signature line in
    the docstring, else Python's own signature."""
    doc = inspect.getdoc(fn) or ""
    m = re.match(r"^\w+\((.*)\) ->", doc.splitlines()[0] if doc else "")
    if m is None:
        m = re.search(r"^\d\. \w+\((.*)\) ->", doc, re.M)  # an overloaded function's first
    if m is not None:
        out, keyword_only = [], False
        for part in re.split(r", (?![^\[]*\])", m.group(1)):
            if part.strip() == "*":
                keyword_only = True
                continue
            name, _, rest = part.partition(":")
            if name.strip() in ("self", "*args", "**kwargs"):
                continue
            out.append((name.strip(), rest.split("=")[0].strip(), keyword_only))
        return out
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):
        return [("arg0", "", False), ("arg1", "", False)]
    return [(p.name, "", p.kind == p.KEYWORD_ONLY) for p in sig.parameters.values()
            if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD) and p.name != "self"]


def random_call(rng, pool, fn):
    """Arguments for one call: the signature's parameters (sometimes one fewer or more), each
    of its own type most of the time and of any type otherwise."""
    params = parameters(fn)
    args, kwargs = [], {}
    count = len(params) + rng.choice([0, 0, 0, 0, -1, 1])
    for k in range(max(count, 0)):
        if k < len(params):
            name, annotation, keyword_only = params[k]
            value = (typed_value(rng, pool, annotation, name) if rng.random() < 0.75
                     else random_value(rng, pool))
            if keyword_only or (rng.random() < 0.2 and not name.startswith("arg")):
                kwargs[name] = value
                continue
            if kwargs:  # a positional argument after a keyword one is Python's own error
                break
            args.append(value)
        else:
            args.append(random_value(rng, pool))
    return args, kwargs


# Results whose NaNs are documented: a sweep's failed points (their row's error says why),
# and "not given" fields of records (e.g. a part's density when its mass was given).
NAN_ALLOWED_TYPES = ("Table", "Sweep", "SweepTable", "DataFrame", "ScenePart")
# Attributes documented as NaN or infinite where they do not apply: a reaction's mu_s unless
# it rolls with one, SimulationOptions.max_step when the step is not limited, and
# TimeSteppingOptions' velocity_tolerance and quiet_span (inf: none) and quiet_from (NaN: the
# initial time) (their docstrings).
NAN_ALLOWED_ATTRIBUTES = ("mu_s", "max_step", "velocity_tolerance", "quiet_span", "quiet_from")


def finite_arguments(value):
    """Whether every number in the arguments is finite: a record (a class's instance) may hold
    what it was given, to be refused where it is used (Model.add_*, simulate), but a record
    made of finite numbers must be finite."""
    if isinstance(value, (float, complex)):
        return bool(np.isfinite(value))
    if isinstance(value, np.ndarray):
        return value.dtype.kind not in "fc" or bool(np.all(np.isfinite(value)))
    if isinstance(value, (list, tuple)):
        # numpy reads None and "nan" in a list of numbers as NaN.
        return all(finite_arguments(v) and not isinstance(v, (str, type(None))) for v in value)
    if isinstance(value, dict):
        return all(finite_arguments(v) for v in value.values())
    return True


def non_finite(value, depth=0):
    """Where a result holds a NaN or an infinity ("" when nowhere): numbers, arrays, lists,
    dicts, and the numeric attributes of the module's own records, two levels deep."""
    if isinstance(value, (bool, int, str, bytes)) or value is None:
        return ""
    if isinstance(value, (float, complex)):
        return "" if np.isfinite(value) else repr(value)
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "fc" and not np.all(np.isfinite(value)):
            return "an array with non-finite entries"
        return ""
    if depth >= 2 or type(value).__name__ in NAN_ALLOWED_TYPES:
        return ""
    if isinstance(value, (list, tuple)):
        items = list(enumerate(value[:20]))
    elif isinstance(value, dict):
        items = list(value.items())[:40]
    elif type(value).__module__.startswith("chasles"):
        items = []
        for attr in dir(value):
            if attr.startswith("_"):
                continue
            try:
                v = getattr(value, attr)
            except DOCUMENTED:
                continue
            if not callable(v) and attr not in NAN_ALLOWED_ATTRIBUTES:
                items.append((attr, v))
    else:
        return ""
    for key, v in items:
        where = non_finite(v, depth + 1)
        if where:
            return f"{key}: {where}"
    return ""


def public_callables(pool):
    """(label, callable, owner type or None): every public function and class of the module,
    and every public method of every class with an instance in the pool."""
    out = []
    for name in sorted(dir(chasles)):
        if name.startswith("_"):
            continue
        obj = getattr(chasles, name)
        if inspect.isclass(obj) and issubclass(obj, BaseException):
            continue
        if callable(obj):
            out.append((name, obj))
        if inspect.isclass(obj):
            for instance in pool.of(name):
                for attr in sorted(dir(instance)):
                    method = getattr(instance, attr, None)
                    if not attr.startswith("_") and callable(method) and not inspect.isclass(method):
                        out.append((f"{name}.{attr}", method))
    return out


@pytest.fixture(scope="module")
def csv_path(tmp_path_factory):
    path = tmp_path_factory.mktemp("api") / "run.csv"
    path.write_text("t [s],x [m]\n0,1\n0.5,2\n")
    return str(path)


@pytest.mark.parametrize("seed", SEEDS)
def test_random_arguments_raise_only_documented_errors(seed, csv_path):
    rng = random.Random(seed)
    pool = Pool(csv_path)
    callables = public_callables(pool)
    assert len(callables) > 100  # the introspection found the module
    # A hang anywhere ends the process with every thread's traceback (the call is in it).
    faulthandler.dump_traceback_later(60, exit=True)
    start, calls, failures = time.monotonic(), 0, {}
    try:
        for label, fn in callables:
            for _ in range(CALLS):
                args, kwargs = random_call(rng, pool, fn)
                call = f"seed {seed}: {label}(*{args!r}, **{kwargs!r})"
                t0 = time.monotonic()
                try:
                    result = fn(*args, **kwargs)
                    record = inspect.isclass(fn)
                    where = "" if record and not finite_arguments([args, kwargs]) else non_finite(result)
                    if where:
                        failures.setdefault(label, f"{call} returned a non-finite value ({where})")
                except DOCUMENTED:
                    pass
                except Exception as e:  # noqa: BLE001 (anything else is the defect sought)
                    failures.setdefault(label, f"{call} raised {type(e).__name__}: {e}")
                if time.monotonic() - t0 > SLOWEST_CALL_S:
                    failures.setdefault(label, f"{call} took {time.monotonic() - t0:.1f} s")
                calls += 1
    finally:
        faulthandler.cancel_dump_traceback_later()
    # One failure per callable, all of them at once.
    assert not failures, "\n".join(failures.values())
    print(f"seed {seed}: {calls} calls of {len(callables)} callables in "
          f"{time.monotonic() - start:.1f} s")
