"""Studies and sweeps without a scene file: a Model built in Python run through the library's
RunStudy (run_study), and a sweep over a Python function of the parameters (sweep_function),
against closed forms."""

import math

import numpy as np
import pytest

import chasles
from conftest import G0, assert_rel

# Dormand-Prince at rtol = atol = 1e-13 follows a quadratic in t to round-off: the projectile's
# positions and the range agree with the closed forms to this relative tolerance.
REL_QUADRATIC = 1e-12


def projectile(v, theta, m=0.5, r=0.02):
    """A ball launched at speed v [m/s] and angle theta [rad] above x from the origin, under
    standard gravity: its Model and initial State."""
    model = chasles.Model()
    b = model.add_body("ball", chasles.sphere(r).mass_properties(m))
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    s = chasles.make_rest_state(model)
    chasles.set_body_velocity(model, b, [v * math.cos(theta), 0, v * math.sin(theta)], [0, 0, 0],
                              s)
    return model, s


def test_run_study_of_a_python_model():
    # x = v cos(theta) t, z = v sin(theta) t - g t^2 / 2 (uniform gravity, no drag); the
    # mechanical energy E = m v^2 / 2 stays, and the ledger's residual is round-off.
    v, theta, m = 12.0, 0.6, 0.5
    model, s = projectile(v, theta, m)
    study = chasles.run_study(model, s, t_end=1.0, output_interval=0.125, rtol=1e-13, atol=1e-13)
    assert isinstance(study, chasles.Study)
    assert study.columns[:4] == ["t", "ball_x", "ball_y", "ball_z"]
    assert study.unit("ball_vz") == "m/s" and study.unit("E") == "J"
    t = study["t"]
    assert_rel(t, np.arange(9) * 0.125)
    assert_rel(study["ball_x"], v * math.cos(theta) * t, rel=REL_QUADRATIC)
    assert_rel(study["ball_z"], v * math.sin(theta) * t - 0.5 * G0 * t**2, rel=REL_QUADRATIC,
               scale=v * math.sin(theta) * t[-1])
    assert_rel(study["ball_vz"], v * math.sin(theta) - G0 * t, rel=REL_QUADRATIC, scale=v)
    energy = 0.5 * m * v**2
    assert_rel(study["E"], np.full(len(t), energy), rel=REL_QUADRATIC)
    assert abs(study.ledger.residual) <= REL_QUADRATIC * energy
    assert study.certificate.passed
    assert study.final_bodies[0].name == "ball"
    # Columns by name, and the bad ones refused before the run.
    only = chasles.run_study(model, s, t_end=0.5, output_interval=0.5, columns=["ball_wz", "T"])
    assert only.columns == ["t", "ball_wz", "T"]
    with pytest.raises(chasles.InputError):
        chasles.run_study(model, s, t_end=1.0, columns=["ball_q"])
    with pytest.raises(chasles.LimitError):
        chasles.run_study(model, s, t_end=1.0, output_interval=0.001, max_rows=10)


def flight_range(v, theta):
    """The range of the projectile over flat ground, from a study that ends when it lands:
    the time of flight 2 v sin(theta) / g is the study's end time."""
    if v <= 0:
        raise chasles.InputError(f"no flight at v = {v} m/s")
    model, s = projectile(v, theta)
    t_flight = 2 * v * math.sin(theta) / G0
    study = chasles.run_study(model, s, t_end=t_flight, output_interval=t_flight,
                              columns=["ball_x", "ball_z"], rtol=1e-13, atol=1e-13)
    return study["ball_x"][-1], study["ball_z"][-1]


def test_sweep_function_of_a_projectiles_range():
    # Range over flat ground R = v^2 sin(2 theta) / g, and the ball back at z = 0.
    table = chasles.sweep_function(flight_range,
                                   {"v": (0.0, 30.0, 4, "m/s"), "theta": (0.2, 1.2, 5, "rad")},
                                   quantities=["range", "z_end"], units=["m", "m"])
    assert table.columns == ["v", "theta", "range", "z_end"]
    assert [table.unit(c) for c in table.columns] == ["m/s", "rad", "m", "m"]
    assert table.parameters == ["v", "theta"]
    assert len(table) == 20
    for k, (v, theta, r, z) in enumerate(table.data):
        # The last parameter varies fastest: point k = 5 i_v + i_theta.
        assert v == 10.0 * (k // 5) and theta == pytest.approx(0.2 + 0.25 * (k % 5), abs=1e-15)
        if v == 0:
            assert math.isnan(r) and math.isnan(z)
            assert table.errors[k] == "no flight at v = 0.0 m/s"
            continue
        assert table.errors[k] == ""
        exact = v**2 * math.sin(2 * theta) / G0
        assert abs(r - exact) <= REL_QUADRATIC * exact
        assert abs(z) <= REL_QUADRATIC * exact
    # Two threads give the same table bit for bit; the Python function holds the GIL.
    two = chasles.sweep_function(flight_range,
                                 {"v": (0.0, 30.0, 4, "m/s"), "theta": (0.2, 1.2, 5, "rad")},
                                 quantities=["range", "z_end"], units=["m", "m"], jobs=2)
    assert np.array_equal(two.data, table.data, equal_nan=True)
    assert two.errors == table.errors


def test_sweep_function_checks_its_grid_and_passes_other_errors_on():
    square = lambda a: a * a  # noqa: E731
    table = chasles.sweep_function(square, {"a": (1, 3, 3)})
    assert table.columns == ["a", "value"]
    assert_rel(table["value"], [1.0, 4.0, 9.0])
    with pytest.raises(chasles.InputError):
        chasles.sweep_function(square, {"a": (0, 1, 1)})  # COUNT < 2
    with pytest.raises(chasles.InputError):
        chasles.sweep_function(square, {"a": (0, 1, 10)}, max_points=5)
    with pytest.raises(TypeError):
        chasles.sweep_function(square, {"a": (0, 1)})

    def broken(a):
        raise ZeroDivisionError("not an input error")

    with pytest.raises(ZeroDivisionError):
        chasles.sweep_function(broken, {"a": (0, 1, 3)}, jobs=2)
