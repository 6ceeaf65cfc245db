"""The module applies the program's limits and validation at its boundary: bad arguments raise
InputError (a ValueError), TypeError or IndexError naming the argument, never an internal
error, a crash or a run without end (docs/reliability.md, "The Python module")."""

import math

import pytest

import chasles
from conftest import example

SPRING = example("spring-mass.yaml")


@pytest.mark.parametrize("kwargs, message", [
    ({"until": float("nan")}, "until must be a finite time in seconds > 0, got nan"),
    ({"until": -1.0}, "until must be a finite time in seconds > 0"),
    ({"until": math.inf}, "until must be a finite time in seconds > 0"),
    ({"max_steps": -5}, "max_steps must be a whole number from 0 to"),
    ({"max_rows": -1}, "max_rows must be a whole number from 0 to"),
    ({"timeout": -1}, "timeout must be a finite time in seconds >= 0, got -1"),
    ({"min_step": 0.0}, "min_step must be a finite time in seconds > 0"),
    ({"min_step": float("nan")}, "min_step must be a finite time in seconds > 0"),
])
def test_run_refuses_what_the_program_refuses(kwargs, message):
    scene = chasles.load_scene(SPRING)
    with pytest.raises(chasles.InputError, match=message):
        chasles.run(scene, **kwargs)


@pytest.mark.parametrize("kwargs", [{"until": "1 s"}, {"max_steps": 2.5}, {"max_rows": True},
                                    {"timeout": [1]}, {"min_step": None, "until": object()}])
def test_run_refuses_arguments_of_the_wrong_type(kwargs):
    with pytest.raises(TypeError, match="must be a"):
        chasles.run(chasles.load_scene(SPRING), **kwargs)


def test_sweeps_apply_the_row_and_run_limits_before_any_work():
    scene = chasles.load_scene(SPRING)
    # 10**8 values would take hours: refused at once, naming the limit and how to raise it.
    with pytest.raises(chasles.InputError, match="count: 100000000 values are more than the "
                                                 "limit of 1000000 rows; raise the limit with "
                                                 "max_rows="):
        chasles.sweep(scene, "k", "100 N/m", "1000 N/m", 10**8)
    with pytest.raises(chasles.InputError, match="count must be a whole number from 1"):
        chasles.sweep(scene, "k", "100 N/m", "1000 N/m", 0)
    with pytest.raises(chasles.InputError, match=r"more points than the limit of 4 runs; raise the limit "
                                                 r"with --max-runs N \(max_runs= from Python\)"):
        chasles.simulate_sweep(scene, "k=100 N/m:1000 N/m:5", "max(block_x)", until=0.01,
                               max_runs=4)
    with pytest.raises(chasles.InputError, match="jobs must be a whole number from 0 to 65536"):
        chasles.mass_sweep(scene, "m=1 kg:2 kg:3", "mass", jobs=-1)
    with pytest.raises(chasles.InputError, match="until must be a finite time"):
        chasles.simulate_sweep(scene, "k=100 N/m:1000 N/m:3", "max(block_x)", until=float("nan"))
    table = chasles.simulate_sweep(scene, "k=100 N/m:1000 N/m:3", "max(block_x)", until=0.01,
                                   max_runs=3)
    assert len(table.data) == 3


def test_read_csv_caps_the_bytes_and_names_the_line_and_column(tmp_path):
    with pytest.raises(chasles.InputError, match="/dev/zero: the table is longer than the limit "
                                                 "of 1000 bytes"):
        chasles.read_csv("/dev/zero", max_bytes=1000)
    with pytest.raises(chasles.InputError, match="cannot read the table"):
        chasles.read_csv(str(tmp_path))
    bad = tmp_path / "nan.csv"
    bad.write_text("t [s],x [m]\n0,1\n0.1,nan\n")
    with pytest.raises(chasles.InputError, match=r"nan.csv:3: column 'x': nan is not a finite"):
        chasles.read_csv(str(bad))
    bad.write_text("t [s],x [m]\n0,one\n")
    with pytest.raises(chasles.InputError, match=r"nan.csv:2: column 'x': 'one' is not a number"):
        chasles.read_csv(str(bad))
    good = tmp_path / "good.csv"
    good.write_text("t [s],x [m]\n0,1\n0.5,2\n")
    assert list(chasles.read_csv(str(good))["x"]) == [1.0, 2.0]


def _ball_model():
    model = chasles.Model()
    model.add_body("ball", chasles.sphere(0.1).mass_properties(2.0))
    return model


@pytest.mark.parametrize("returned", [None, "up", [1.0, 2.0], {"x": 1}])
def test_a_force_callable_of_the_wrong_shape_raises_type_error_naming_it(returned):
    model = _ball_model()

    def push(t, state):
        return returned

    model.add_force_element(chasles.AppliedForce("push", 0, [0, 0, 0], push))
    with pytest.raises(TypeError, match=r"the callable .*push must return 3 numbers \[x, y, z\], "
                                        r"got "):
        chasles.solve_instantaneous(model, chasles.make_rest_state(model))


def test_an_event_function_returning_nan_is_refused_naming_the_event():
    model = _ball_model()
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -9.80665]))
    event = chasles.EventSpec("floor", lambda t, s: float("nan"))
    with pytest.raises(chasles.InputError, match=r"event 'floor': g\(t, state\) returned nan"):
        chasles.simulate(model, chasles.make_rest_state(model), t_end=1.0, events=[event])


def test_simulate_refuses_more_samples_than_max_rows_before_the_run():
    # 1e-12 s over 1 s would be 1e12 samples (some 5.8 GB once): refused at once.
    model = _ball_model()
    with pytest.raises(chasles.InputError, match=r"output_interval: 1e-12 s over 1.0 s gives more "
                                                 r"than the limit of 1000000 rows"):
        chasles.simulate(model, chasles.make_rest_state(model), t_end=1.0, output_interval=1e-12)
    r = chasles.simulate(model, chasles.make_rest_state(model), t_end=1.0, output_interval=0.25)
    assert len(r.table(model)["t"]) == 5


def test_a_smallest_step_longer_than_the_run_is_refused_as_the_program_refuses_it():
    # min_step=1e300 bounds nothing: once taken silently when no step was rejected.
    with pytest.raises(chasles.InputError, match=r"simulation: the smallest step 1e\+300 s is "
                                                 r"longer than the run's span of 2 s"):
        chasles.run(chasles.load_scene(SPRING), min_step=1e300)


def test_a_body_index_out_of_range_is_an_index_error_not_a_read_past_the_state():
    # These read and wrote the state's body array at the index unchecked (a heap overrun).
    model = _ball_model()
    state = chasles.make_rest_state(model)
    for body in (1, -1, 2**31 - 1):
        with pytest.raises(IndexError, match="body index .* is out of range: the model has "
                                             "num_bodies = 1"):
            chasles.body_origin_position(model, state, body)
        with pytest.raises(IndexError):
            chasles.set_body_pose(model, body, [0, 0, 0], [1, 0, 0, 0], state)
        with pytest.raises(IndexError):
            chasles.set_body_velocity(model, body, [0, 0, 0], [0, 0, 0], state)
        if body != chasles.WORLD:
            with pytest.raises(IndexError):
                chasles.attachment_frame_at_world_pose(model, state, body, [0, 0, 0])
    other = chasles.make_rest_state(chasles.Model())
    with pytest.raises(chasles.InputError, match="the state has 0 bodies and the model 1"):
        chasles.body_origin_position(model, other, 0)
    with pytest.raises(chasles.InputError, match="origin must be finite numbers"):
        chasles.set_body_pose(model, 0, [math.nan, 0, 0], [1, 0, 0, 0], state)


def test_computing_methods_refuse_non_finite_arguments_and_results():
    mp = chasles.sphere(0.1).mass_properties(2.0)
    with pytest.raises(chasles.InputError, match="point must be finite numbers"):
        mp.inertia_about([math.nan, 0, 0])
    # m d^2 = 2 kg * 1e400 m^2 passes the largest double.
    with pytest.raises(chasles.InputError, match="the inertia about the point is not a finite"):
        mp.inertia_about([1e200, 0, 0])
    with pytest.raises(chasles.InputError, match="position must be finite numbers"):
        chasles.MassProperties.point_mass(1.0, [0, math.inf, 0])
    with pytest.raises(chasles.InputError, match="radii of gyration .* mass of 0.0 kg"):
        chasles.MassProperties.point_mass(0.0, [1, 0, 0]).radii_of_gyration


def test_paths_are_paths_and_file_system_errors_are_input_errors():
    # read_csv(True) opened file descriptor 1 and closed the process's standard output.
    for path in (True, 0, 2.5):
        with pytest.raises(TypeError, match="path must be a str or a path"):
            chasles.read_csv(path)
    # std::filesystem's error on an empty path came out as RuntimeError.
    with pytest.raises(chasles.InputError):
        chasles.load_mesh_scene("", unit="m")
    with pytest.raises(TypeError, match="scene must be a Scene"):
        chasles.mass_properties("examples/spring-mass.yaml")
