"""Building models in Python: bodies, force elements (constant and Python callables), joints,
rolling, contacts, State, solve_instantaneous and simulate, against closed forms."""

import math

import numpy as np
import pytest

import chasles
from conftest import G0, assert_rel


def ball(model, name="ball", m=2.0, r=0.1):
    return model.add_body(name, chasles.sphere(r).mass_properties(m))


def test_state_helpers():
    model = chasles.Model()
    b = model.add_body("box", chasles.MassProperties(
        1.0, [0.1, 0.0, 0.0], chasles.RotationalInertia(1.0, 1.0, 1.0)))
    s = chasles.make_rest_state(model)
    assert s.t == 0.0 and len(s.bodies) == 1
    # A quarter turn about z: the centre of mass (0.1 m along x in B) lands on y.
    q = [math.cos(math.pi / 4), 0, 0, math.sin(math.pi / 4)]
    chasles.set_body_pose(model, b, [1.0, 2.0, 3.0], q, s)
    assert_rel(s.bodies[0].position, [1.0, 2.1, 3.0])
    assert_rel(chasles.body_origin_position(model, s, b), [1.0, 2.0, 3.0])
    assert_rel(s.bodies[0].quaternion, q)
    # v_cm = v_o + w x r: w = 2 z, r = 0.1 y  ->  (-0.2, 0, 0).
    chasles.set_body_velocity(model, b, [0, 0, 0], [0, 0, 2.0], s)
    assert_rel(s.bodies[0].velocity, [-0.2, 0, 0])
    assert_rel(s.bodies[0].angular_velocity, [0, 0, 2.0])
    assert_rel(s.bodies[0].angular_velocity_body, [0, 0, 2.0])
    s.bodies[0].velocity = [1.0, 0.0, 0.0]  # a view: writes reach the State
    assert_rel(s.bodies[0].velocity, [1.0, 0, 0])
    c = s.copy()
    c.t = 5.0
    assert s.t == 0.0
    s.bodies[0].position = [math.nan, 0, 0]
    with pytest.raises(chasles.InputError):
        chasles.validate_state(model, s)
    assert model.body(b).name == "box" and model.find_body("box") == 0


def test_gravity_and_constant_force():
    # Constant force F on mass m under gravity: a = F/m + g, x(t) = a t^2 / 2 from rest.
    model = chasles.Model()
    b = ball(model)
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    model.add_force_element(chasles.AppliedForce("push", b, [0, 0, 0], [4.0, 0, 0]))
    s = chasles.make_rest_state(model)
    sol = chasles.solve_instantaneous(model, s)
    assert_rel(sol.bodies[0].acceleration, [2.0, 0, -G0])
    r = chasles.simulate(model, s, t_end=1.0, output_interval=0.25)
    t = np.array([x.t for x in r.samples])
    assert_rel(t, [0, 0.25, 0.5, 0.75, 1.0])
    table = r.table(model)
    assert_rel(table["ball_x"], t**2, scale=1.0)
    assert_rel(table["ball_z"], -0.5 * G0 * t**2)
    assert table.unit("ball_vx") == "m/s"
    assert_rel(r.final_state.bodies[0].velocity, [2.0, 0, -G0])
    assert r.stats.steps > 0


def test_python_force_callable_and_moment():
    # F_x = c t (a Python callable reading state.t): x = c t^3 / (6 m), a cubic that
    # Dormand-Prince follows to round-off.
    c, m = 3.0, 2.0
    model = chasles.Model()
    b = ball(model, m=m)
    calls = []

    def force(t, state):
        calls.append(t)
        assert t == state.t
        return [c * t, 0.0, 0.0]

    model.add_force_element(chasles.AppliedForce("ramp", b, [0, 0, 0], force))
    # A constant moment about z on a sphere (I = 2/5 m r^2): alpha = M / I.
    I = 0.4 * m * 0.1**2
    model.add_force_element(chasles.AppliedMoment("twist", b, [0, 0, 0.5]))
    # And a moment from a callable in the body frame: M_z = 0 (returns zeros).
    model.add_force_element(chasles.AppliedMoment("none", b, lambda t, s: np.zeros(3), "body"))
    s = chasles.make_rest_state(model)
    opts = chasles.SimulationOptions(t_end=2.0, output_interval=0.5, rtol=1e-12, atol=1e-14)
    r = chasles.simulate(model, s, opts)
    assert calls
    t = np.array([x.t for x in r.samples])
    x = np.array([x.bodies[0].position[0] for x in r.samples])
    assert_rel(x, c * t**3 / (6 * m))
    wz = np.array([x.bodies[0].angular_velocity[2] for x in r.samples])
    assert_rel(wz, 0.5 / I * t)


def test_python_callable_errors_reach_python():
    model = chasles.Model()
    b = ball(model)

    def bad(t, state):
        raise RuntimeError("the force cannot be computed")

    model.add_force_element(chasles.AppliedForce("bad", b, [0, 0, 0], bad))
    with pytest.raises(RuntimeError, match="cannot be computed"):
        chasles.simulate(model, chasles.make_rest_state(model), t_end=1.0)
    model2 = chasles.Model()
    b2 = ball(model2)
    model2.add_force_element(chasles.AppliedForce("short", b2, [0, 0, 0], lambda t, s: [1.0]))
    with pytest.raises(Exception):
        chasles.simulate(model2, chasles.make_rest_state(model2), t_end=1.0)


def test_spring_damper_and_drag():
    # Spring from the world origin to the ball at x = 1.5 (k = 40, L0 = 1): F = -k (x - L0);
    # the damper c and drag c_d add -(c + c_d) v along x at v = 2 m/s.
    k, L0, c, cd, m = 40.0, 1.0, 3.0, 0.5, 2.0
    model = chasles.Model()
    b = ball(model, m=m)
    model.add_force_element(chasles.SpringDamper("spring", b, [0, 0, 0], chasles.WORLD,
                                                 [0, 0, 0], L0, k, c))
    model.add_force_element(chasles.LinearDrag("drag", b, cd, 0.2))
    s = chasles.make_rest_state(model)
    s.bodies[0].position = [1.5, 0, 0]
    s.bodies[0].velocity = [2.0, 0, 0]
    s.bodies[0].angular_velocity_body = [0, 0, 1.0]
    sol = chasles.solve_instantaneous(model, s)
    assert_rel(sol.bodies[0].acceleration, [(-k * 0.5 - (c + cd) * 2.0) / m, 0, 0])
    # Angular drag -c_w w on I = 2/5 m r^2.
    assert_rel(sol.bodies[0].angular_acceleration, [0, 0, -0.2 / (0.4 * m * 0.01)])
    with pytest.raises(chasles.InputError):
        chasles.SpringDamper("bad", b, [0, 0, 0], chasles.WORLD, [0, 0, 0], 1.0, -1.0, 0.0)
    with pytest.raises(chasles.InputError):
        model.add_force_element(chasles.LinearDrag("drag", b, 1.0))  # duplicate name


def test_revolute_pendulum_reaction():
    # A uniform bar (m, L) pinned at one end to the world, horizontal, at rest. About the pin
    # I = m L^2 / 3 and the moment of gravity is m g L / 2: alpha = 3 g / (2 L); the centre
    # of mass falls at a = alpha L / 2 = 3 g / 4, so the pin carries F = m (a - g) = m g / 4 up.
    m, L = 2.0, 1.2
    Iy = m * L**2 / 12
    model = chasles.Model()
    b = model.add_body("bar", chasles.MassProperties(
        m, [L / 2, 0, 0], chasles.RotationalInertia(1e-4, Iy, Iy + 1e-4)))
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    s = chasles.make_rest_state(model)
    chasles.set_body_pose(model, b, [0, 0, 0], [1, 0, 0, 0], s)
    R = chasles.frame_with_z_axis([0, 1, 0])
    world_frame = chasles.attachment_frame_at_world_pose(model, s, chasles.WORLD, [0, 0, 0], R)
    bar_frame = chasles.attachment_frame_at_world_pose(model, s, b, [0, 0, 0], R)
    assert_rel(bar_frame.origin, [0, 0, 0], scale=1.0)
    joint = chasles.Joint("pin", chasles.JointKind.REVOLUTE, chasles.WORLD, world_frame, b,
                          bar_frame)
    assert joint.num_rows == 5 and joint.kind == "revolute"
    model.add_constraint(joint)
    sol = chasles.solve_instantaneous(model, s)
    # Rotation about +y takes +x towards -z: alpha_y = +3g/(2L).
    assert_rel(sol.bodies[0].angular_acceleration, [0, 3 * G0 / (2 * L), 0])
    assert_rel(sol.bodies[0].acceleration, [0, 0, -3 * G0 / 4])
    r = sol.reactions[0]
    assert r.name == "pin"
    assert_rel(r.force, [0, 0, m * G0 / 4])
    assert_rel(r.point, [0, 0, 0], scale=L)
    # The frame class itself.
    f = chasles.AttachmentFrame([1, 2, 3])
    assert_rel(f.rotation, np.eye(3))


def test_rolling_sphere_on_incline():
    # A solid sphere rolling down a plane at theta: I = 2/5 m r^2 gives a = (5/7) g sin(theta).
    m, r, theta = 1.5, 0.2, math.radians(25)
    n = np.array([math.sin(theta), 0, math.cos(theta)])
    d = np.array([math.cos(theta), 0, -math.sin(theta)])
    model = chasles.Model()
    b = ball(model, m=m, r=r)
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    model.add_constraint(chasles.RollingContact("roll", chasles.RollingShape.SPHERE, b,
                                                [0, 0, 0], [0, 0, 1], r, [0, 0, 0], n))
    s = chasles.make_rest_state(model)
    s.bodies[0].position = r * n
    sol = chasles.solve_instantaneous(model, s)
    assert_rel(sol.bodies[0].acceleration, 5 / 7 * G0 * math.sin(theta) * d)
    rr = sol.reactions[0]
    assert rr.is_rolling
    assert_rel(rr.normal_force, m * G0 * math.cos(theta))
    # f = m g sin - m a = (2/7) m g sin.
    assert_rel(rr.friction_needed, 2 / 7 * math.tan(theta))


def test_contact_sphere_lands():
    # A sphere dropped from height h (centre at h + r) lands at t = sqrt(2 h / g); with
    # restitution 0 it stays (sticking).
    m, r, h = 1.0, 0.05, 0.8
    model = chasles.Model()
    b = ball(model, m=m, r=r)
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    spec = chasles.ContactSpec("floor", chasles.ContactShape.SPHERE, b, radius=r, mu_s=0.5,
                               mu_k=0.4, plane_normal=[0, 0, 1])
    assert spec.radius == r and spec.plane_normal[2] == 1.0
    model.add_contact(spec)
    assert model.num_contacts == 1 and model.num_contact_points == 1
    assert model.contact_point_name(0) == "floor"
    s = chasles.make_rest_state(model)
    s.bodies[0].position = [0, 0, h + r]
    res = chasles.simulate(model, s, t_end=1.0, output_interval=0.1, rtol=1e-12, atol=1e-14)
    touch = [e for e in res.contact_events if e.reason == "touch-down"]
    assert touch, [e.reason for e in res.contact_events]
    assert_rel(touch[0].t, math.sqrt(2 * h / G0))
    assert len(res.impacts) == 1
    # Plastic impact: the energy lost is the kinetic energy at touch-down, m g h.
    assert_rel(res.impacts[0].energy_lost, m * G0 * h)
    assert_rel(res.final_state.bodies[0].position[2], r)
    with pytest.raises(chasles.InputError):
        model.add_contact(chasles.ContactSpec("bad", chasles.ContactShape.SPHERE, b, radius=-1.0))



def test_contact_islands():
    # Two balls dropped side by side onto the floor from h1 and h2 (centres at h + r): each its
    # own island, landing at t = sqrt(2 h / g) whatever the other does, on 1 or 2 threads.
    r, h1, h2 = 0.05, 0.8, 0.45
    model = chasles.Model()
    for i in range(2):
        b = ball(model, name=f"ball{i}", r=r)
        model.add_contact(chasles.ContactSpec(f"floor{i}", chasles.ContactShape.SPHERE, b,
                                              radius=r, mu_s=0.5, mu_k=0.4))
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    s = chasles.make_rest_state(model)
    s.bodies[0].position = [0, 0, h1 + r]
    s.bodies[1].position = [1, 0, h2 + r]
    results = []
    for threads in (1, 2):
        o = chasles.SimulationOptions(1.0, 0.1, rtol=1e-12, atol=1e-14)
        o.threads = threads
        res = chasles.simulate(model, s, o)
        assert res.islands.split and res.islands.count == 2, res.islands.reason
        assert [list(x) for x in res.islands.bodies] == [[0], [1]]
        touch = {e.point: e.t for e in res.contact_events if e.reason == "touch-down"}
        assert_rel(touch[0], math.sqrt(2 * h1 / G0))
        assert_rel(touch[1], math.sqrt(2 * h2 / G0))
        results.append(np.array([list(b.position) for b in res.final_state.bodies]))
    assert np.array_equal(results[0], results[1])  # bitwise
    o.islands = False
    res = chasles.simulate(model, s, o)
    assert not res.islands.split and res.islands.reason == "islands turned off"

def test_bad_model_input():
    model = chasles.Model()
    with pytest.raises(chasles.InputError) as e:
        model.add_body("neg", chasles.MassProperties(-1.0, [0, 0, 0],
                                                     chasles.RotationalInertia(1, 1, 1)))
    assert e.value.file is None and e.value.line is None
    with pytest.raises(chasles.InputError):
        model.add_force_element(chasles.LinearDrag("drag", 3, 1.0))  # no body 3
    with pytest.raises(chasles.InputError):
        chasles.AppliedForce("f", 0, [0, 0, 0], [1, 0, 0], "sideways")
    with pytest.raises(chasles.InputError):
        chasles.simulate(model, chasles.make_rest_state(model), t_end=-1.0)



def test_indices_out_of_range_raise_index_error():
    # A one-body model: body(1), body(10) and body(-1) name no body (a negative index is not
    # counted from the end), and neither does a contact point of a model without contacts.
    model = chasles.Model()
    ball(model)
    assert model.body(0).name == "ball"
    for bad in (1, 10, -1):
        with pytest.raises(IndexError, match=f"body index {bad} is out of range: the model has "
                                             "num_bodies = 1"):
            model.body(bad)
    with pytest.raises(IndexError, match="point index 0 is out of range"):
        model.contact_point_name(0)
    with pytest.raises(TypeError):
        model.body("ball")

def test_central_gravity_and_fixed_step_integrators():
    # Inverse-square gravity mu m / r^2 towards the centre: a = -mu / r^2 along r.
    mu = 3.986e14
    model = chasles.Model()
    ball(model)
    model.add_force_element(chasles.CentralGravity("earth", mu, [0, 0, 0]))
    s = chasles.make_rest_state(model)
    s.bodies[0].position = [7.0e6, 0, 0]
    assert_rel(chasles.solve_instantaneous(model, s).bodies[0].acceleration, [-mu / 7.0e6**2, 0, 0])
    # RK4, the energy-momentum integrator and the splitting on a free fall (exact for a
    # quadratic; the splitting's translation is the closed form itself).
    model2 = chasles.Model()
    ball(model2)
    model2.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    for kind in (chasles.Integrator.RK4, chasles.Integrator.ENERGY_MOMENTUM,
                 chasles.Integrator.SPLITTING):
        r = chasles.simulate(model2, chasles.make_rest_state(model2), t_end=0.5,
                             output_interval=0.1, integrator=kind, fixed_step=0.01)
        table = r.table(model2)
        assert_rel(table["ball_z"], -0.5 * G0 * table["t"] ** 2)
    # The splitting steps free bodies under uniform gravity only: central gravity is refused.
    with pytest.raises(chasles.InputError, match="not uniform gravity"):
        chasles.simulate(model, s, t_end=0.5, integrator=chasles.Integrator.SPLITTING,
                         fixed_step=0.01)
