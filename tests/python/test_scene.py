"""Scenes from Python: loading with overrides, solve, run, sweep and errors, against the
chapter's closed forms derived here."""

import math

import numpy as np
import pytest

import chasles
from conftest import G0, assert_rel, example

# Example 8.3: a uniform solid cylinder (m, R) rolls without slipping down a plane at theta.
# With friction f up the slope and normal force N: m a = m g sin(theta) - f, I alpha = f R,
# I = m R^2 / 2, a = alpha R  give  a = (2/3) g sin(theta), f = m g sin(theta) / 3,
# N = m g cos(theta), f / N = tan(theta) / 3. The plane's normal is n = (sin, 0, cos) and
# downhill is d = (cos, 0, -sin); rolling about y: v = R w_y d, so alpha_y = a / R.
M, R = 5.0, 0.1


def cylinder_closed_form(theta):
    a = 2.0 / 3.0 * G0 * math.sin(theta)
    d = np.array([math.cos(theta), 0.0, -math.sin(theta)])
    return a, d


def test_example_8_3_solve():
    scene = chasles.load_scene(example("example-8.3-cylinder-incline.yaml"))
    assert scene.title.startswith("Example 8.3")
    assert_rel(scene.parameters["theta"], math.radians(30))
    s = chasles.solve(scene)
    theta = math.radians(30)
    a, d = cylinder_closed_form(theta)
    body = s.body("cylinder")
    assert_rel(body.acceleration, a * d)
    assert_rel(body.angular_acceleration, [0.0, a / R, 0.0])
    r = s.reaction("contact")
    assert r.is_rolling
    assert_rel(r.normal_force, M * G0 * math.cos(theta))
    assert_rel(np.linalg.norm(r.friction), M * G0 * math.sin(theta) / 3)
    assert_rel(r.friction_needed, math.tan(theta) / 3)
    # The whole reaction: F = m a - m g (Newton's second law on the cylinder).
    assert_rel(r.force, M * a * d - M * np.array([0, 0, -G0]))
    assert_rel(s.mu_s[0], 0.25)
    # At rest: no kinetic energy; the certificate passed.
    assert s.total.T == 0.0
    assert s.certificate.passed
    assert s.warnings == []
    row = s.table()
    assert_rel(row["contact_f_over_N"][0], math.tan(theta) / 3)
    assert row.unit("contact_N") == "N"
    assert row.unit("cylinder_ax") == "m/s^2"


def test_example_8_3_with_override_slips_past_the_limit():
    # tan(theta)/3 = mu_s = 0.25 at theta = atan(0.75) = 36.87 deg: at 40 deg rolling needs
    # more friction than mu_s.
    scene = chasles.load_scene(example("example-8.3-cylinder-incline.yaml"),
                               set={"theta": "40 deg", "m": "2 kg"})
    assert_rel(scene.parameters["m"], 2.0)
    r = chasles.solve(scene).reaction("contact")
    assert_rel(r.friction_needed, math.tan(math.radians(40)) / 3)
    assert r.friction_needed > 0.25
    assert_rel(r.normal_force, 2.0 * G0 * math.cos(math.radians(40)))


def test_example_8_3_run():
    scene = chasles.load_scene(example("example-8.3-cylinder-incline.yaml"))
    run = chasles.run(scene)
    theta = math.radians(30)
    a, d = cylinder_closed_form(theta)
    t = run["t"]
    assert t[0] == 0.0
    assert_rel(t[-1], 0.5)
    assert_rel(run.t_end, 0.5)
    # From rest: x(t) = x0 + a t^2 / 2 along d (a polynomial the integrator follows exactly),
    # v = a t d, w_y = a t / R.
    x0 = R * np.array([math.sin(theta), 0.0, math.cos(theta)])
    for k in ("x", "y", "z"):
        i = "xyz".index(k)
        assert_rel(run["cylinder_" + k], x0[i] + 0.5 * a * t**2 * d[i], scale=R)
        assert_rel(run["cylinder_v" + k], a * t * d[i], scale=a * 0.5)
    assert_rel(run["cylinder_wy"], a * t / R, scale=a * 0.5 / R)
    assert run.unit("cylinder_x") == "m"
    assert run.unit("cylinder_wy") == "rad/s"
    assert run.unit("T") == "J"
    assert run.unit("contact_Fx") == "N"
    # Energy is conserved by rolling: the ledger's residual is integration error only.
    assert abs(run.ledger.residual) <= 1e-9 * run.ledger.energy_scale
    assert run.certificate.passed
    assert [r.name for r in run.final_reactions] == ["contact"]
    assert_rel(run.final_reactions[0].force, M * a * d - M * np.array([0, 0, -G0]))
    assert run.stats.steps > 0
    df = run.to_pandas()
    assert list(df.columns) == run.columns
    assert df.attrs["units"]["cylinder_x"] == "m"
    assert_rel(df["cylinder_x"].to_numpy(), run["cylinder_x"])


def test_spinning_ball_problem_8_26():
    # Problems 8.26/8.27: a ball spinning at w0 about y, at rest, set on the floor. Its
    # contact point slides backward (v_C = w0 y x (-R z) = -R w0 x), so kinetic friction
    # mu_k m g pushes it forward: a = mu_k g, alpha_y = -5 mu_k g / (2 R) (I = 2/5 m R^2).
    # Sliding ends when v = R w: mu_k g t = R (w0 - 5 mu_k g t / (2R)), t* = 2 R w0 / (7 mu_k g),
    # with v* = (2/7) R w0 and w* = (2/7) w0; then it rolls at constant speed.
    scene = chasles.load_scene(example("problem-8.26-spinning-ball.yaml"))
    R = 9 / 8 * 0.0254
    w0 = 100 * 2 * math.pi / 60
    t_star = 0.025
    mu_k = 2 * R * w0 / (7 * G0 * t_star)
    assert_rel(scene.parameters["mu_k"], mu_k)
    s = chasles.solve(scene)
    c = s.contact("floor")
    assert c.regime == "slides"
    assert c.mode == chasles.ContactMode.SLIDING
    m = 0.17
    assert_rel(c.normal_force, m * G0)
    assert_rel(c.friction, [mu_k * m * G0, 0, 0])
    assert_rel(s.body("ball").acceleration, [mu_k * G0, 0, 0])
    assert_rel(s.body("ball").angular_acceleration, [0, -5 * mu_k * G0 / (2 * R), 0])

    run = chasles.run(scene)
    # The contact timeline: sliding from the start, sticking (rolling) from t*.
    events = [(e.from_mode, e.to_mode) for e in run.contact_events]
    assert events[0][1] == "sliding"
    stick = [e for e in run.contact_events if e.to_mode == "sticking"]
    assert len(stick) == 1
    assert_rel(stick[0].t, 2 * R * w0 / (7 * mu_k * G0))
    assert_rel(stick[0].t, t_star)
    ball = run.final_bodies[0]
    assert_rel(ball.velocity, [2 / 7 * R * w0, 0, 0])
    assert_rel(ball.angular_velocity, [0, 2 / 7 * w0, 0])
    # Energy lost to friction: T0 - T_end = (1/2)(2/5 m R^2) w0^2 - (7/10) m v*^2.
    I = 0.4 * m * R**2
    lost = 0.5 * I * w0**2 - 0.7 * m * (2 / 7 * R * w0) ** 2
    assert_rel(-run.ledger.friction_work, lost)
    assert run.final_contacts[0].mode == "sticking"
    assert run.unit("floor_N") == "N" and run.unit("floor_slip") == "m/s"


def test_sweep_example_8_3():
    scene = chasles.load_scene(example("example-8.3-cylinder-incline.yaml"))
    table = chasles.sweep(scene, "theta", "10 deg", "50 deg", 5)
    assert table.parameter == "theta"
    assert table.columns[0] == "theta"
    thetas = np.radians([10, 20, 30, 40, 50])
    assert_rel(table["theta"], thetas)
    # Rolling assumed at every angle: f/N = tan(theta)/3, N = m g cos(theta),
    # |a| = (2/3) g sin(theta).
    assert_rel(table["contact_f_over_N"], np.tan(thetas) / 3)
    assert_rel(table["contact_N"], M * G0 * np.cos(thetas))
    a = 2 / 3 * G0 * np.sin(thetas)
    assert_rel(table["cylinder_ax"], a * np.cos(thetas))
    assert_rel(table["cylinder_az"], -a * np.sin(thetas))
    assert table.unit("contact_N") == "N"
    assert table.unit("contact_f_over_N") == ""
    assert table.warnings == []
    same = chasles.sweep(scene, "theta=10 deg:50 deg:5")
    assert np.array_equal(same.data, table.data)
    # Bare numbers are plain numbers (an angle in radians).
    numeric = chasles.sweep(scene, "theta", 0.1, 0.2, 2)
    assert_rel(numeric["theta"], [0.1, 0.2])


def test_scene_from_string_and_errors():
    text = """chasles: 1
parameters: {h: 2 m}
bodies:
  - name: ball
    parts: [{shape: sphere, radius: 0.1 m, mass: 1 kg}]
    initial: {position: [0, 0, h]}
gravity: standard
simulation: {until: 0.5 s, tolerance: 1e-12, output_interval: 0.1 s}
"""
    scene = chasles.load_scene_string(text, set={"h": "3 m"}, name="drop.yaml")
    assert scene.file == "drop.yaml"
    run = chasles.run(scene)
    # Free fall from rest: z = h - g t^2 / 2.
    assert_rel(run["ball_z"], 3.0 - 0.5 * G0 * run["t"] ** 2)
    assert_rel(run["t"], np.arange(6) * 0.1, scale=0.5)
    # A bad value: SceneError with file, line, column and key.
    with pytest.raises(chasles.SceneError) as e:
        chasles.load_scene_string(text.replace("radius: 0.1 m", "radius: -0.1 m"), name="bad.yaml")
    err = e.value
    assert isinstance(err, chasles.InputError) and isinstance(err, ValueError)
    assert err.file == "bad.yaml"
    assert err.line == 5
    assert err.column > 0
    assert "radius" in err.key
    assert str(err).startswith(f"bad.yaml:5:{err.column}:")
    # An override of an unknown parameter.
    with pytest.raises(chasles.SceneError) as e:
        chasles.load_scene_string(text, set={"hh": "1 m"})
    assert "hh" in str(e.value)
    # A sweep of an unknown parameter names the sweep.
    with pytest.raises(chasles.SceneError) as e:
        chasles.sweep(scene, "height", "1 m", "2 m", 3)
    assert e.value.key == "sweep" and "height" in str(e.value)
    with pytest.raises(chasles.SceneError):
        chasles.sweep(scene, "h=1 m:2 m")
    with pytest.raises(chasles.InputError):
        chasles.load_scene("/nonexistent/scene.yaml")
    # A limit on the run's work is bad input at the scene's `simulation` entry.
    with pytest.raises(chasles.SceneError) as e:
        chasles.run(scene, max_steps=1)
    assert e.value.key == "simulation" and "limit of 1 integration steps" in str(e.value)
    # A bare number is a plain number: a position needs its unit.
    with pytest.raises(chasles.SceneError) as e:
        chasles.load_scene_string(text, set={"h": 3})
    assert "length" in str(e.value)
    with pytest.raises(KeyError):
        run["no_such_column"]
    with pytest.raises(chasles.InputError):
        chasles.study_column_units(scene, ["no_such_column"])


def test_events_in_a_run():
    text = """chasles: 1
bodies:
  - name: ball
    parts: [{shape: sphere, radius: 0.1 m, mass: 1 kg}]
    initial: {position: [0, 0, 2 m]}
gravity: standard
events:
  - {name: half, when: ball_z, crosses: 1 m, direction: falling, action: stop}
simulation: {until: 5 s, tolerance: 1e-12}
"""
    run = chasles.run(chasles.load_scene_string(text))
    # z = 2 - g t^2 / 2 reaches 1 m at t = sqrt(2 / g).
    assert run.stopped_by_event
    e = run.event("half")
    assert_rel(e.t, math.sqrt(2 / G0))
    assert_rel(e.snapshot.bodies[0].velocity, [0, 0, -G0 * math.sqrt(2 / G0)])
    assert_rel(run.t_end, math.sqrt(2 / G0))


def test_example_8_3_angular_momentum_rate_and_surface_area():
    # The cylinder starts at rest: dH/dt about its centre of mass is I alpha with
    # I = m R^2 / 2 about its axis y and alpha = a / R (the omega x I omega term is 0), and
    # the velocity of every point is 0.
    s = chasles.solve(chasles.load_scene(example("example-8.3-cylinder-incline.yaml")))
    a, _ = cylinder_closed_form(math.radians(30))
    m = s.motion[0]
    assert_rel(m.Hdot_cm, [0.0, M * R * R / 2 * a / R, 0.0])
    assert np.all(np.asarray(m.velocity) == 0.0)
    assert np.all(np.asarray(m.angular_velocity) == 0.0)
    assert_rel(s.table()["cylinder_dHy"][0], M * R * a / 2)
    # A solid cylinder's surface: two ends pi R^2 and the side 2 pi R h.
    assert_rel(chasles.cylinder(R, 0.3).surface_area(), 2 * math.pi * R * R + 2 * math.pi * R * 0.3)


def _complete_elliptic_k(k):
    """K(k) = pi / (2 AGM(1, sqrt(1 - k^2))), the arithmetic-geometric mean to round-off."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    while abs(a - b) > 1e-16 * a:
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def test_simulate_sweep_pendulum_quarter_period():
    # examples/pendulum.yaml: a ball (r = 5 cm, k^2 = (2/5) r^2) on an arm of length L released
    # at theta0: I_O theta'' = -m g L sin(theta), I_O = m (k^2 + L^2) (eq. 8.39), so the bottom
    # is reached after T/4 = sqrt((k^2 + L^2) / (g L)) K(sin(theta0 / 2)).
    scene = chasles.load_scene(example("pendulum.yaml"))
    t = chasles.simulate_sweep(scene, ["L=0.5 m:1.5 m:3", "theta0=20 deg:60 deg:3"],
                               ["event(bottom)", "t_end"], jobs=2)
    assert t.parameters == ["L", "theta0"]
    assert t.columns == ["L", "theta0", "event(bottom)", "t_end"]
    assert t.units[:3] == ["m", "rad", "s"]
    assert len(t.data) == 9 and t.errors == [""] * 9
    k2 = 0.4 * 0.05**2
    for L, theta0, tq, t_end in t.data:
        want = math.sqrt((k2 + L * L) / (G0 * L)) * _complete_elliptic_k(math.sin(theta0 / 2))
        assert_rel(tq, want, 1e-9)
        assert tq == t_end
    # The same table with one thread, and the CSV the command prints.
    assert np.array_equal(chasles.simulate_sweep(scene, ["L=0.5 m:1.5 m:3", "theta0=20 deg:60 deg:3"],
                                                 ["event(bottom)", "t_end"], jobs=1).data, t.data)
    assert t.to_csv().splitlines()[0] == "L [m],theta0 [rad],event(bottom) [s],t_end [s],error"


def test_mass_sweep_failed_point_and_closed_form():
    # Example 8.1's cylinder: mass = rho_al pi R^2 h1 + rho_pb pi R^2 (h - h1) grows as R^2;
    # a negative radius fails that point with its reason.
    scene = chasles.load_scene(example("example-8.1-cylinder.yaml"))
    t = chasles.mass_sweep(scene, "R=-1 cm:4 cm:3", ["cylinder.mass"])
    assert "radius must be positive" in t.errors[0]
    assert math.isnan(t.data[0][1])
    (_, m1), (_, m2) = t.data[1][:2], t.data[2][:2]
    assert t.errors[1:] == ["", ""]
    assert_rel(m2 / m1, (0.04 / 0.015) ** 2, 1e-12)


def test_pool_balls_event_driven():
    # examples/pool-head-on-events.yaml (closed forms in its comments): rolling at v the cue
    # ball meets the object ball at t1 = (d - 2R)/v; then v_A = v (1 - e)/2, v_B = v (1 + e)/2,
    # and each slides until rolling with (m + I/R^2) v_roll = m v + I w / R (I = 2/5 m R^2):
    # A at (5 v_A + 2 v)/7, B at 5/7 v_B.
    run = chasles.run(chasles.load_scene(example("pool-head-on-events.yaml")))
    v, d, R, e = 2.0, 0.5, 0.028575, 0.93
    assert run.integrator == "events"
    assert run.event_driven["collisions"] == 1
    assert abs(run.event_driven["energy"]["residual"]) < 1e-15
    assert [i.point for i in run.impacts] == ["cue | object"]
    assert_rel(run.impacts[0].t, (d - 2 * R) / v)
    cue, obj = run.final_bodies
    assert_rel(cue.velocity, [(5 * v * (1 - e) / 2 + 2 * v) / 7, 0, 0])
    assert_rel(obj.velocity, [5 / 7 * v * (1 + e) / 2, 0, 0])
    assert run.certificate.passed
    # A scene with contacts that names no integrator runs auto (format version 3), and says so.
    spinning = chasles.run(chasles.load_scene(example("problem-8.26-spinning-ball.yaml")))
    assert spinning.event_driven is None
    assert spinning.integrator == "auto" and spinning.engine_by_default


def test_auto_engine_segments():
    # examples/contact-cube-tumbles-auto.yaml (closed forms in its comments): event-driven, time
    # stepped where the rocking chatters, event-driven again at rest; kicked at t_k = 1.2 s by
    # J = 0.6 N*s through its centre, the cube slides until t_k + v0/(mu g), v0 = J/m.
    run = chasles.run(chasles.load_scene(example("contact-cube-tumbles-auto.yaml")))
    assert run.integrator == "auto"
    assert not run.engine_by_default  # the scene names it
    engines = [g.engine for g in run.segments]
    assert engines[0] == "adaptive" and engines[-1] == "adaptive" and "stepping" in engines
    assert [g.reason for g in run.segments][:2] == ["start", "regime changes"]
    stepping = next(g for g in run.segments if g.engine == "stepping")
    assert stepping.changes == 8 and stepping.stepping["steps"] > 0
    assert run.segments[-1].reason == "quiet" and run.segments[-1].t_end == 1.6
    stop = next(e for e in run.contact_events if e.reason == "slip stopped")
    assert abs(stop.t - (1.2 + 0.6 / (0.3 * G0))) < 1e-10
    assert run.certificate.passed
    # Auto by default (a scene with contacts that names no integrator): one event-driven stretch.
    spinning = chasles.run(chasles.load_scene(example("problem-8.26-spinning-ball.yaml")))
    assert [(g.engine, g.reason) for g in spinning.segments] == [("adaptive", "start")]
    assert chasles.run(chasles.load_scene(example("pendulum.yaml"))).segments == []


def test_struck_double_pendulum_pin_impulses():
    # examples/double-pendulum-struck.yaml (closed forms in its comments): hanging rods
    # (m1 = 2 kg, L1 = 1 m; m2 = 1 kg, L2 = 0.8 m) struck along x by J = 3 N*s at s = 0.6 m
    # below the elbow. With M11 = (m1/3 + m2) L1^2, M12 = m2 L1 L2/2, M22 = m2 L2^2/3 the
    # angular velocity jumps are M^-1 (J L1, J s); impulse-momentum of each rod gives the pins'
    # impulses R_E = m2 (L1 w1 + L2 w2/2) - J and R_O = m1 (L1/2) w1 + R_E along x.
    m1, L1, m2, L2, s, J = 2.0, 1.0, 1.0, 0.8, 0.6, 3.0
    M12 = m2 * L1 * L2 / 2
    M = np.array([[(m1 / 3 + m2) * L1**2, M12], [M12, m2 * L2**2 / 3]])
    w1, w2 = np.linalg.solve(M, [J * L1, J * s])
    R_E = m2 * (L1 * w1 + L2 * w2 / 2) - J
    R_O = m1 * L1 / 2 * w1 + R_E
    run = chasles.run(chasles.load_scene(example("double-pendulum-struck.yaml")))
    (jump,) = run.jumps
    pins = {r.name: r for r in jump.reactions}
    assert_rel(pins["O"].force, [R_O, 0, 0], 1e-12, J)
    assert_rel(pins["elbow"].force, [R_E, 0, 0], 1e-12, J)
    # The elbow's parent is the upper rod, hanging: its x axis is W's -y, its y axis W's x.
    assert_rel(pins["elbow"].force_parent, [0, R_E, 0], 1e-12, J)
    upper, lower = jump.bodies
    assert_rel(upper.angular_velocity_change, [0, 0, w1], 1e-12, w2)
    assert_rel(lower.velocity_change, [L1 * w1 + L2 / 2 * w2, 0, 0], 1e-12, J / m2)
    assert [i.source for i in lower.impulses][:2] == ["applied", "elbow"]
    assert jump.impacts == []
    assert run.certificate.passed
