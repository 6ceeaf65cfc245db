"""chasles: rigid-body kinetics from Python.

Load a scene (``load_scene``, ``load_scene_string``), read its mass properties, solve the
instantaneous problem (``solve``), run it (``run``), sweep a parameter (``sweep``) or balance a
rotor (``balance``); or build
a ``Model`` of bodies, force elements, joints and contacts and call ``solve_instantaneous``,
``simulate``, ``simulate_time_stepping`` and ``run_study``; ``sweep_function`` sweeps any Python function of parameters. Everything is SI; vectors and matrices are numpy arrays; quaternions are
``[w, x, y, z]``. Tables (``Table``, ``Run``) carry column names and units and convert to
pandas with ``to_pandas()``. Bad input raises ``InputError`` (a ``ValueError``) or its
subclass ``SceneError`` with ``file``, ``line``, ``column`` and ``key``. See docs/python.md.
"""

import math as _math
import os as _os

import numpy as _np

from ._chasles import *  # noqa: F401,F403  (the compiled bindings)
from ._chasles import (  # noqa: F401
    InputError,
    LimitError,
    SceneError,
    Scene,
    Solution,
    SimulationOptions,
    SimulationResult,
    StudyResult,
    TimeSteppingOptions,
    TimeSteppingResult,
    SweepTable,
    _run_definition,
    _run_json,
    _run_text,
    _mass_text,
    _modes_text,
    _modes_sweep_text,
    _balance,
    _BalanceOptions,
    _run_study,
    _run_sweep,
    _simulate,
    _simulate_time_stepping,
    _solve,
    _solve_text,
    _sweep,
    _simulate_sweep,
    _mass_sweep,
    parse_sweep,
    study_column_units,
)

def _instance(name, value, cls):
    """``value`` itself; TypeError naming the argument unless it is a ``cls``."""
    if not isinstance(value, cls):
        raise TypeError(f"{name} must be a {cls.__name__}, got {type(value).__name__} {value!r}")
    return value


class Table:
    """Named columns of numbers with their SI units.

    ``columns`` (names), ``units`` (one per column, ``""`` for pure numbers), ``data`` (a 2-D
    numpy array, one row per sample). ``table["name"]`` is one column as a 1-D array;
    ``to_pandas()`` gives a DataFrame (pandas must be installed).
    """

    def __init__(self, columns, units, data):
        self.columns = list(columns)
        self.units = list(units)
        self.data = _np.asarray(data, dtype=float).reshape(-1, len(self.columns))
        if len(self.units) != len(self.columns):
            raise ValueError("one unit per column is needed")

    def __getitem__(self, name):
        """The column called ``name`` as a 1-D numpy array (KeyError naming the columns)."""
        try:
            return self.data[:, self.columns.index(name)]
        except ValueError:
            raise KeyError(
                f"no column {name!r}; columns: {', '.join(self.columns)}") from None

    def __contains__(self, name):
        return name in self.columns

    def __len__(self):
        """Number of rows."""
        return self.data.shape[0]

    def unit(self, name):
        """The SI unit of column ``name``."""
        self[name]  # raises KeyError for an unknown name
        return self.units[self.columns.index(name)]

    def to_pandas(self):
        """The table as a pandas DataFrame; the units are in ``df.attrs["units"]``.

        Raises ImportError when pandas is not installed.
        """
        try:
            import pandas
        except ImportError as e:
            raise ImportError(
                "Table.to_pandas() needs pandas (Debian: apt install python3-pandas; "
                "pip: pip install pandas)") from e
        df = pandas.DataFrame(self.data, columns=self.columns)
        df.attrs["units"] = dict(zip(self.columns, self.units))
        return df

    def __repr__(self):
        return f"{type(self).__name__}({len(self)} rows, columns={self.columns!r})"


class Run(Table):
    """The result of a scene's run (``run``): the output table plus the rest of StudyResult.

    Attributes besides the table: ``events``, ``jumps``, ``contact_events`` (the contact
    timeline), ``impacts``, ``final_contacts``, ``final_bodies``, ``final_reactions``,
    ``ledger``, ``certificate``, ``notes``, ``warnings``, ``t_end``, ``stopped_by_event``,
    ``integrator``, ``stats``, ``run_path`` (the path the run took: ``path``, its name as the
    JSON's ``run_path.path``, and ``reason``), ``event_driven`` (``integrator: events``: collisions, impacts,
    regime changes, pressing groups and the closed-form energy balance; None otherwise),
    ``segments`` (``integrator: auto``: each engine's stretch of the run and why it took over;
    empty otherwise), ``engine_by_default`` (True when auto ran because the scene named no
    integrator: format version 3's default for a scene with contacts);
    ``result`` is the StudyResult itself. ``to_csv()`` and
    ``to_json()`` give the two files ``chasles simulate`` writes; ``text()`` the report it
    prints.
    """

    def __init__(self, scene, result):
        _instance("scene", scene, Scene)
        _instance("result", result, StudyResult)
        super().__init__(result.columns, study_column_units(scene, result.columns), result.data)
        self.result = result
        self._scene = scene
        for name in ("events", "jumps", "contact_events", "impacts", "final_contacts",
                     "final_bodies", "final_reactions", "ledger", "certificate", "notes",
                     "warnings", "t_end", "stopped_by_event", "integrator", "stats",
                     "run_path", "event_driven", "segments", "engine_by_default"):
            setattr(self, name, getattr(result, name))

    def to_csv(self, full_precision=False):
        """The CSV time series, as ``chasles simulate`` writes it (text); ``full_precision``:
        every value with %.17g, as ``--full-precision`` writes it."""
        return self.result.to_csv(full_precision)

    def to_json(self, csv_path=""):
        """The JSON summary, as ``chasles simulate`` writes it (text); ``csv_path`` is
        recorded under ``"csv"``."""
        return _run_json(self._scene, self.result, csv_path)

    def text(self, units=None, out=None):
        """The report ``chasles simulate SCENE`` prints (text), in ``units`` ("SI", "US", or a
        list such as "mm,g"; None: the scene's own, as ``--units``); its last line names the
        CSV and JSON files the program writes in the folder ``out`` (None: the current folder,
        as ``--out``)."""
        return _run_text(self._scene, self.result, _text_option("units", units),
                         _text_option("out", out))

    def event(self, name):
        """The first event called ``name`` (KeyError when none fired)."""
        for e in self.events:
            if e.name == name:
                return e
        raise KeyError(f"no event {name!r}; events: {[e.name for e in self.events]}")


class Sweep(Table):
    """A sweep's table (``sweep``): the parameter's SI value first, then the solve's columns.

    ``parameter`` names the swept parameter; ``warnings`` lists the failed checks.
    ``to_csv()`` and ``to_json()`` give the table as ``chasles solve --sweep`` prints it.
    """

    def __init__(self, table):
        _instance("table", table, SweepTable)
        super().__init__(table.columns, table.units, table.data)
        self._table = table
        self.parameter = table.parameter
        self.parameters = list(table.parameters) or [table.parameter]
        self.warnings = list(table.warnings)
        self.failed = table.failed
        #: Per row why its run failed ("" when it ran; its values are then NaN).
        self.errors = list(table.errors) or [""] * len(table.data)

    def to_csv(self, full_precision=False):
        """The table as ``chasles solve --sweep`` prints it (text); ``full_precision``: every
        value with %.17g, as ``--full-precision`` prints it."""
        return self._table.to_csv(full_precision)

    def to_json(self):
        """The table as ``chasles solve --sweep ... --format json`` prints it (text)."""
        return self._table.to_json()


def _quantity(value):
    """A sweep bound as scene text: strings as they are, numbers in full precision."""
    return value if isinstance(value, str) else repr(float(value))


def solve(scene):
    """The instantaneous problem of ``scene`` at its initial state (``chasles solve``).

    Returns a Solution: ``bodies`` (accelerations), ``reactions``, ``contacts``,
    ``motion`` / ``total`` (energy, momenta, dH/dt; per body ω, v, named points' velocity
    and acceleration), ``certificate``, ``warnings``; ``table()``
    gives the sweep-table row as a one-row Table; ``text()`` the report ``chasles solve``
    prints.
    """
    solution = _solve(scene)
    solution._scene = scene
    return solution


def _text_option(name, value):
    """A text option as the program's of that name takes it: a string, None for its default."""
    if value is None:
        return ""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, got {type(value).__name__} {value!r}")
    return value


def _solution_text(self, units=None):
    """The report ``chasles solve SCENE`` prints (text), in ``units`` ("SI", "US", or a list
    such as "ft,slug"; None: the scene's own, as ``--units``)."""
    return _solve_text(self._scene, self, _text_option("units", units))


def mass_text(scene, units=None):
    """The report ``chasles mass SCENE`` prints (text), in ``units`` ("SI", "US", or a list
    such as "mm,g"; None: the scene's own, as ``--units``)."""
    _instance("scene", scene, Scene)
    return _mass_text(scene, _text_option("units", units))


def modes_text(scene, sweep=None):
    """The report ``chasles modes SCENE`` prints (text); with ``sweep`` ("NAME=START:STOP:N",
    as ``--sweep``), the report of the modes over that parameter's grid."""
    _instance("scene", scene, Scene)
    if sweep is None:
        return _modes_text(scene)
    return _modes_sweep_text(scene, _text_option("sweep", sweep))


def _option_quantity(name, value, unit):
    """A quantity option as the program takes it: a string as written there (an expression with
    its units, as in the scene: "15 cm", "3000 rpm"), or a number in the SI ``unit``."""
    if isinstance(value, str):
        return value
    v = _number(name, value)
    if not _math.isfinite(v):
        raise InputError(f"{name} must be a finite number, got {value!r}")
    return f"{v!r} {unit}"


def _option_point(name, value, unit):
    """A point or direction option: a string as in the scene ("[0, 0, 5 cm]"), or 3 numbers
    (SI ``unit``; "" for a direction)."""
    if isinstance(value, str):
        return value
    if not isinstance(value, (list, tuple, _np.ndarray)) or len(value) != 3:
        raise TypeError(f"{name} must be a string or 3 numbers, got {type(value).__name__} "
                        f"{value!r}")
    entries = [_option_quantity(name, v, unit).strip() for v in value]
    return "[" + ", ".join(entries) + "]"


def balance(scene, body, planes, radius, axis=None, through=None, speed=None, grade=None,
            whirl=None):
    """A rotor's balance (``chasles balance``, docs/modes.md "Rotors"): the static and couple
    unbalance of the body ``body`` of ``scene`` about a spin axis, the two correction masses,
    the bearing forces at a speed, the ISO 21940-11 permissible residual unbalance and, when a
    bearing element holds the rotor, its whirl rows. Returns a Balance; its ``text()`` and
    ``json()`` are what the program prints.

    The options are the program's: ``planes`` (``--planes``) the two planes' positions along
    the axis from ``through``, "A, B" or a pair (each a string or metres); ``radius``
    (``--radius``) the correction radius; ``axis`` (``--axis``, default [0, 0, 1]) and
    ``through`` (``--through``, default [0, 0, 0] m) a string as in the scene or 3 numbers;
    ``speed`` (``--speed``) a string ("3000 rpm") or rad/s; ``grade`` (``--grade``) G in
    mm/s, which needs ``speed``; ``whirl`` (``--whirl``) "A:B:N" or (A, B, N), N spins from A
    to B (strings or rad/s). A string is read as in the scene (its parameters and units). Bad
    options raise SceneError naming the option, a value of another type TypeError.
    """
    _instance("scene", scene, Scene)
    options = _BalanceOptions()
    options.source, options.option_prefix = "chasles.balance", ""
    options.body = _instance("body", body, str)
    if isinstance(planes, str):
        options.planes = planes
    elif isinstance(planes, (list, tuple, _np.ndarray)) and len(planes) == 2:
        options.planes = ", ".join(_option_quantity("planes", p, "m") for p in planes)
    else:
        raise TypeError(f"planes must be a string 'A, B' or 2 positions, got "
                        f"{type(planes).__name__} {planes!r}")
    options.radius = _option_quantity("radius", radius, "m")
    if axis is not None:
        options.axis = _option_point("axis", axis, "")
    if through is not None:
        options.through = _option_point("through", through, "m")
    if speed is not None:
        options.speed = _option_quantity("speed", speed, "rad/s")
    if grade is not None:
        options.grade = _number("grade", grade)
    if isinstance(whirl, str):
        options.whirl = whirl
    elif isinstance(whirl, (list, tuple)) and len(whirl) == 3:
        count = _whole("whirl's N", whirl[2], 2, 1000)
        options.whirl = ":".join([_option_quantity("whirl", whirl[0], "rad/s"),
                                  _option_quantity("whirl", whirl[1], "rad/s"), str(count)])
    elif whirl is not None:
        raise TypeError(f"whirl must be a string 'A:B:N' or (A, B, N), got "
                        f"{type(whirl).__name__} {whirl!r}")
    return _balance(scene, options)


def _solution_table(self):
    """This solution as a one-row Table (the columns of a sweep, without the parameter)."""
    names, units, values = self._row()
    return Table(names, units, [values])


def _find(items, name, attr, what):
    for x in items:
        if getattr(x, attr) == name:
            return x
    raise KeyError(f"no {what} {name!r}; {what}s: {[getattr(x, attr) for x in items]}")


Solution.table = _solution_table
Solution.text = _solution_text
Solution.body = lambda self, name: _find(self.bodies, name, "name", "body")
Solution.body.__doc__ = "The accelerations of the body called ``name``."
Solution.reaction = lambda self, name: _find(self.reactions, name, "name", "reaction")
Solution.reaction.__doc__ = "The reaction of the constraint called ``name``."
Solution.contact = lambda self, point: _find(self.contacts, point, "point", "contact point")
Solution.contact.__doc__ = "The contact point called ``point``."


def _number(name, value):
    """``value`` as a float; TypeError naming the argument for anything but a real number."""
    if isinstance(value, bool) or not isinstance(value, (int, float, _np.integer, _np.floating)):
        raise TypeError(f"{name} must be a number, got {type(value).__name__} {value!r}")
    return float(value)


def _seconds(name, value, positive=True):
    """A time in seconds as the program's options take it: finite and > 0 (``positive``) or
    >= 0; None (the scene's) is NaN for the bindings."""
    if value is None:
        return _math.nan
    v = _number(name, value)
    if not _math.isfinite(v) or v < 0 or (positive and v == 0):
        raise InputError(f"{name} must be a finite time in seconds {'>' if positive else '>='} 0, "
                         f"got {value!r}")
    return v


def _whole(name, value, low, high):
    """A whole number from ``low`` to ``high``, as the program's count options take it."""
    if isinstance(value, bool) or not isinstance(value, (int, _np.integer)):
        raise TypeError(f"{name} must be a whole number, got {type(value).__name__} {value!r}")
    if not low <= value <= high:
        raise InputError(f"{name} must be a whole number from {low} to {high}, got {value}")
    return int(value)


_MAX_COUNT = 2**63 - 1   # the range of the program's counts (std::int64_t)
_MAX_JOBS = 65536        # --jobs


def run(scene, until=None, max_steps=0, max_rows=0, timeout=None, min_step=None):
    """Runs the scene's study (``chasles simulate``) and returns a Run.

    ``until`` [s] overrides the scene's end time; ``max_steps``, ``max_rows`` (0: the
    scene's), ``timeout`` [s] (0: none) and ``min_step`` [s] (None: the scene's) limit the work
    (LimitError when reached). Each is checked as the program's option of that name: a time
    that is not finite and positive, or a count that is negative, raises InputError; a value
    of another type TypeError.
    """
    result = _run_study(scene, _seconds("until", until),
                        _whole("max_steps", max_steps, 0, _MAX_COUNT),
                        _whole("max_rows", max_rows, 0, _MAX_COUNT),
                        _seconds("timeout", timeout, positive=False),
                        _seconds("min_step", min_step))
    return Run(scene, result)


def sweep(scene, parameter, start=None, stop=None, count=None, max_rows=1_000_000):
    """Solves ``scene`` over ``count`` values of ``parameter`` from ``start`` to ``stop``.

    Like ``chasles solve --sweep``: ``sweep(scene, "theta", "10 deg", "50 deg", 5)`` or
    ``sweep(scene, "theta=10 deg:50 deg:5")``. Bounds are expressions with units as in the
    scene file (a bare number is a plain number, e.g. an angle in radians). The scene is read again for each
    value with its own overrides plus this one. Returns a Sweep table. A ``count`` above
    ``max_rows`` (``--max-rows``) raises InputError before any value is solved.
    """
    if start is None and stop is None and count is None:
        parameter, start, stop, count = parse_sweep(parameter)
    if start is None or stop is None or count is None:
        raise TypeError("sweep needs start, stop and count (or one 'NAME=START:STOP:COUNT')")
    count = _whole("count", count, 1, _MAX_COUNT)
    if count > _whole("max_rows", max_rows, 1, _MAX_COUNT):
        raise InputError(f"count: {count} values are more than the limit of {max_rows} rows; "
                         "raise the limit with max_rows=")
    return Sweep(_sweep(scene, parameter, _quantity(start), _quantity(stop), count))


def simulate_sweep(scene, sweeps, quantities, until=None, jobs=0, max_runs=100_000):
    """Runs ``scene`` at every point of a grid and tabulates quantities (``chasles simulate
    --sweep``, docs/sweeps.md).

    ``sweeps``: one ``'NAME=START:STOP:COUNT'`` or a list of them (a grid, the last varying
    fastest); ``quantities``: one or a list of ``final(COL)``, ``max(COL)``, ``min(COL)``,
    ``event(NAME)``, ``event(NAME, k)``, ``event(A) - event(B)``, ``t_end``. ``until`` [s]
    overrides the end time; ``jobs`` threads (0: every core; the table is the same for any).
    Returns a Sweep: the parameters, then the quantities; a failed point has NaN values and
    its reason in ``errors``. A grid of more than ``max_runs`` points (``--max-runs``) raises
    InputError before any run.
    """
    sweeps = [sweeps] if isinstance(sweeps, str) else list(sweeps)
    quantities = [quantities] if isinstance(quantities, str) else list(quantities)
    return Sweep(_simulate_sweep(scene, sweeps, quantities, _seconds("until", until),
                                 _whole("jobs", jobs, 0, _MAX_JOBS),
                                 _whole("max_runs", max_runs, 1, _MAX_COUNT)))


def mass_sweep(scene, sweeps, quantities, jobs=0, max_runs=100_000):
    """The mass properties of ``scene`` over a grid (``chasles mass --sweep``): quantities
    named as in the mass JSON report (``mass``, ``Izz``, ``center_of_mass_z``, ``I1``, ``k1``,
    ...; ``BODY.NAME`` for a scene of several bodies). Returns a Sweep as ``simulate_sweep``.
    """
    sweeps = [sweeps] if isinstance(sweeps, str) else list(sweeps)
    quantities = [quantities] if isinstance(quantities, str) else list(quantities)
    return Sweep(_mass_sweep(scene, sweeps, quantities, _whole("jobs", jobs, 0, _MAX_JOBS),
                             _whole("max_runs", max_runs, 1, _MAX_COUNT)))


def sweep_function(function, parameters, quantities="value", units=None, jobs=1,
                   max_points=100_000):
    """Sweeps a Python function over a grid of parameter values, without a scene file
    (docs/sweeps.md; the grid, the threads and the table are those of ``simulate_sweep``).

    ``parameters``: a dict NAME -> (START, STOP, COUNT) of SI numbers, or NAME -> (START, STOP,
    COUNT, UNIT) to name the column's unit; every combination is a point, the last parameter
    varying fastest, its values START + (STOP - START) i / (COUNT - 1). ``function`` is called
    with the parameters as keywords and returns a number, or a sequence with one number per
    name in ``quantities`` (a name or a list; ``units`` the same length, or None). A
    chasles.InputError it raises fails that point alone (NaN values, the reason in
    ``errors``); any other exception stops the sweep. ``jobs`` threads call it (the GIL is held
    while it runs; the table is the same for any number). Returns a Sweep.
    """
    if not isinstance(parameters, dict) or not parameters:
        raise TypeError("parameters must be a non-empty dict NAME -> (START, STOP, COUNT)")
    names, param_units, start, stop, counts = [], [], [], [], []
    for name, spec in parameters.items():
        spec = tuple(spec)
        if len(spec) not in (3, 4):
            raise TypeError(f"parameter {name!r}: give (START, STOP, COUNT) or (START, STOP, "
                            f"COUNT, UNIT), got {spec!r}")
        names.append(str(name))
        start.append(_number(f"{name} START", spec[0]))
        stop.append(_number(f"{name} STOP", spec[1]))
        counts.append(_whole(f"{name} COUNT", spec[2], 2, _MAX_COUNT))
        param_units.append(str(spec[3]) if len(spec) == 4 else "")
    single = isinstance(quantities, str)
    quantities = [quantities] if single else list(quantities)
    units = [""] * len(quantities) if units is None else \
        ([units] if isinstance(units, str) else list(units))
    if len(units) != len(quantities):
        raise TypeError(f"{len(units)} units for {len(quantities)} quantities")

    def point(*values):
        out = function(**dict(zip(names, values)))
        return [out] if single or _np.ndim(out) == 0 else list(out)

    return Sweep(_run_sweep(names, param_units, start, stop, counts, quantities, units, point,
                            _whole("jobs", jobs, 0, _MAX_JOBS),
                            _whole("max_points", max_points, 1, _MAX_COUNT), InputError))


# Columns a study of a Model can record (``run_study``): per body BODY_Q, and the ledger's.
_BODY_COLUMNS = {
    "x": "m", "y": "m", "z": "m", "qw": "", "qx": "", "qy": "", "qz": "",
    "vx": "m/s", "vy": "m/s", "vz": "m/s", "speed": "m/s",
    "wx": "rad/s", "wy": "rad/s", "wz": "rad/s", "wbx": "rad/s", "wby": "rad/s",
    "wbz": "rad/s", "ax": "m/s^2", "ay": "m/s^2", "az": "m/s^2", "alx": "rad/s^2",
    "aly": "rad/s^2", "alz": "rad/s^2",
}
_LEDGER_COLUMNS = {"t": "s", "T_trans": "J", "T_rot": "J", "T": "J", "V": "J", "E": "J",
                   "W_nc": "J", "dissipated": "J", "residual": "J"}


def _study_column(model, name):
    """(name, body index or -1, quantity) of a column ``run_study`` records, and its unit."""
    if name in _LEDGER_COLUMNS:
        return (name, -1, name), _LEDGER_COLUMNS[name]
    for b in range(model.num_bodies):
        body = model.body(b).name
        q = name[len(body) + 1:]
        if name.startswith(body + "_") and q in _BODY_COLUMNS:
            return (name, b, q), _BODY_COLUMNS[q]
    bodies = [model.body(b).name for b in range(model.num_bodies)]
    raise InputError(f"column {name!r}: neither BODY_Q (bodies: {', '.join(bodies)}; Q one of "
                     f"{', '.join(_BODY_COLUMNS)}) nor one of {', '.join(_LEDGER_COLUMNS)}")


class Study(Table):
    """The result of ``run_study``: the output table (``t`` and the columns asked for) plus
    the StudyResult's ``events``, ``ledger`` (energy, work and momentum across the run),
    ``certificate``, ``final_bodies``, ``final_reactions``, ``final_contacts``, ``notes``,
    ``warnings``, ``t_end``, ``integrator`` and ``stats``; ``result`` is the StudyResult.
    """

    def __init__(self, result, units):
        _instance("result", result, StudyResult)
        super().__init__(result.columns, units, result.data)
        self.result = result
        for name in ("events", "ledger", "certificate", "final_bodies", "final_reactions",
                     "final_contacts", "notes", "warnings", "t_end", "integrator", "stats"):
            setattr(self, name, getattr(result, name))


def run_study(model, initial, options=None, columns=None, max_steps=10_000_000,
              max_rows=1_000_000, timeout=0.0, **kwargs):
    """Runs a study of ``model`` from the State ``initial`` (the library's RunStudy, as
    ``chasles simulate`` runs a scene's, without a scene file) and returns a Study.

    Pass a SimulationOptions, or its fields as keywords (``t_end``, ``output_interval``,
    ``integrator``, ``rtol``, ``atol``, ``fixed_step``); the study carries the energy ledger
    and the certificate of its own checks across the run. ``columns``: names BODY_Q (``x``,
    ``vz``, ``wz``, ``qw``, ``ax``, ...) and ledger names (``T``, ``V``, ``E``, ``W_nc``,
    ``residual``, ...); None: every body's position and velocity, then T, V and E. The initial
    state must satisfy the constraints (the run projects round-off only). ``max_steps``,
    ``max_rows`` and ``timeout`` [s] (0: none) limit the work (LimitError when reached).
    """
    if options is None:
        options = SimulationOptions(**kwargs)
    elif kwargs:
        raise TypeError("give either options or keywords, not both")
    _instance("model", model, Model)
    _instance("options", options, SimulationOptions)
    if columns is None:
        columns = [f"{model.body(b).name}_{q}" for b in range(model.num_bodies)
                   for q in ("x", "y", "z", "vx", "vy", "vz")] + ["T", "V", "E"]
    specs, units = [(("t", -1, "t"))], ["s"]
    for name in columns:
        spec, unit = _study_column(model, name)
        specs.append(spec)
        units.append(unit)
    result = _run_definition(model, initial, options, specs,
                             _whole("max_steps", max_steps, 1, _MAX_COUNT),
                             _whole("max_rows", max_rows, 1, _MAX_COUNT),
                             _seconds("timeout", timeout, positive=False))
    return Study(result, units)


def _check_rows(span, interval, max_rows):
    """Refuses, before a run, an output interval that would give more than ``max_rows``
    samples over ``span`` [s] (as the CLI's ``--max-rows``)."""
    max_rows = _whole("max_rows", max_rows, 1, _MAX_COUNT)
    if interval > 0 and _math.isfinite(span) and span / interval > max_rows:
        raise InputError(f"output_interval: {interval} s over {span} s gives more than the limit "
                         f"of {max_rows} rows; raise the limit with max_rows= or sample less "
                         "often")


def simulate(model, initial, options=None, max_rows=1_000_000, **kwargs):
    """Runs ``model`` from the State ``initial`` and returns a SimulationResult.

    Pass a SimulationOptions, or its fields as keywords (``t_end``, ``output_interval``,
    ``integrator``, ``rtol``, ``atol``, ``fixed_step``, and ``events``: a list of EventSpec).
    ``result.table(model)`` gives the samples as a Table (t, then per body x, y, z, qw..qz,
    vx..vz, wbx..wbz). Python force, driver and event callables are called with the GIL
    held; the integration itself releases it. An output interval that would give more than
    ``max_rows`` samples (as ``--max-rows``) raises InputError before the run.
    """
    if options is None:
        events = kwargs.pop("events", None)
        options = SimulationOptions(**kwargs)
        if events is not None:
            options.events = list(events)
    elif kwargs:
        raise TypeError("give either options or keywords, not both")
    _instance("options", options, SimulationOptions)
    _check_rows(options.t_end, options.output_interval, max_rows)
    return _simulate(model, initial, options)


def _simulation_table(self, model):
    """The samples as a Table: t, then per body position, quaternion, velocity, w in B."""
    names, units, data = self._table(model)
    return Table(names, units, data)


SimulationResult.table = _simulation_table
TimeSteppingResult.table = _simulation_table


def simulate_time_stepping(model, initial, options=None, max_rows=1_000_000, **kwargs):
    """Runs ``model`` from the State ``initial`` by Moreau-Jean time stepping (the library's
    SimulateTimeStepping; docs/contact.md, "Time stepping") and returns a TimeSteppingResult.

    Pass a TimeSteppingOptions, or its fields as keywords: ``t_end`` [s], ``step`` [s],
    ``output_interval`` [s], ``collide_all_pairs`` and ``pair_law`` (a SphereCollisionLaw:
    every pair of balls may collide), ``ball_radii`` [m], ``error_estimate``,
    ``velocity_tolerance`` [m/s], ``threads`` (over each step's islands; the result is the
    same for any number), ``store_steps``, ``store_samples``, ``quiet_span`` [s],
    ``quiet_from`` [s], ``tolerances`` (ContactTolerances) and ``solver``
    (ContactProblemSettings). The result has ``samples``, ``final_state``, ``summary`` (the
    run's certificate), ``tolerance_met``, ``warnings``, ``regime_changes`` (per contact
    point), ``stats``, ``quiet``, ``steps`` (with ``store_steps``) and ``table(model)``. The
    run releases the GIL. A model time stepping cannot take (a constraint), an invalid state
    or options raise InputError; so does an output interval that would give more than
    ``max_rows`` samples, before the run.
    """
    if options is None:
        options = TimeSteppingOptions(**kwargs)
    elif kwargs:
        raise TypeError("give either options or keywords, not both")
    _instance("model", model, Model)
    _instance("initial", initial, State)
    _instance("options", options, TimeSteppingOptions)
    _check_rows(options.t_end - initial.t, options.output_interval, max_rows)
    return _simulate_time_stepping(model, initial, options)


def mass_properties(scene):
    """Mass properties of every body of ``scene`` (``chasles mass``): name -> MassProperties."""
    return _instance("scene", scene, Scene).mass_properties()


def _csv_header_name(field):
    """A CSV header field's name and unit: "car_ax [m/s^2]" -> ("car_ax", "m/s^2"); a field
    without a trailing " [unit]" is a bare name (a pure number)."""
    if field.endswith("]") and " [" in field:
        i = field.rindex(" [")
        if i > 0:
            return field[:i], field[i + 2:-1]
    return field, ""


def read_csv(path, max_bytes=256 << 20):
    """A CSV file the program wrote (``chasles simulate``'s time series, ``chasles solve
    --sweep``'s table) as a ``Table``: each header field is the column's name, then, when it
    has one, one space and its SI unit in brackets (``t [s]``). Read as ``chasles plot`` reads
    it: at most ``max_bytes`` (``--max-input-bytes``; a device such as /dev/zero is refused, not
    read until memory runs out), UTF-8, every cell a finite number. InputError names the file,
    the line and the column otherwise."""
    import csv
    import io

    max_bytes = _whole("max_bytes", max_bytes, 1, _MAX_COUNT)
    # A path, never a number: open(1) would read (and then close) the process's standard output.
    if not isinstance(path, (str, bytes, _os.PathLike)):
        raise TypeError(f"path must be a str or a path, got {type(path).__name__} {path!r}")
    try:
        with open(path, "rb") as f:
            # In pieces: f.read(n) sets n bytes aside first, so a huge limit would ask for
            # that much memory however short the file is.
            pieces, size = [], 0
            while size <= max_bytes:
                piece = f.read(min(max_bytes + 1 - size, 1 << 20))
                if not piece:
                    break
                pieces.append(piece)
                size += len(piece)
            data = b"".join(pieces)
    except OSError as e:
        raise InputError(f"{path}: cannot read the table: {e.strerror}") from None
    if len(data) > max_bytes:
        raise InputError(f"{path}: the table is longer than the limit of {max_bytes} bytes; raise "
                         "it with max_bytes= if it is meant to be read")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise InputError(f"{path}: the byte at offset {e.start} is not UTF-8") from None
    rows = list(csv.reader(io.StringIO(text, newline="")))
    if not rows:
        raise InputError(f"{path}: empty CSV")
    names, units = zip(*(_csv_header_name(h) for h in rows[0])) if rows[0] else ((), ())
    data = []
    for line, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        values = []
        for name, cell in zip(names, row):
            try:
                v = float(cell)
            except ValueError:
                raise InputError(f"{path}:{line}: column '{name}': '{cell[:40]}' is not a "
                                 "number") from None
            if not _math.isfinite(v):
                raise InputError(f"{path}:{line}: column '{name}': {cell} is not a finite number")
            values.append(v)
        if len(row) != len(names):
            raise InputError(f"{path}:{line}: {len(row)} fields where the header has "
                             f"{len(names)}")
        data.append(values)
    return Table(names, units, data)


__all__ = sorted(name for name in dir() if not name.startswith("_"))
