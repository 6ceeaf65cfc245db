"""Gears, drivers and events built in Python, against closed forms."""

import math

import numpy as np
import pytest

import chasles
from conftest import G0, assert_rel


def disk(model, name, m, r):
    """A uniform disk in the x-y plane (axis z): I_z = m r^2 / 2."""
    return model.add_body(name, chasles.MassProperties(
        m, [0, 0, 0], chasles.RotationalInertia(m * r**2 / 4, m * r**2 / 4, m * r**2 / 2)))


def pin(model, s, b, x):
    """A revolute joint about the world z axis through (x, 0, 0)."""
    w = chasles.attachment_frame_at_world_pose(model, s, chasles.WORLD, [x, 0, 0])
    f = chasles.attachment_frame_at_world_pose(model, s, b, [x, 0, 0])
    model.add_constraint(chasles.Joint(f"pin_{b}", chasles.JointKind.REVOLUTE, chasles.WORLD, w,
                                       b, f))


def test_gear_pair_under_a_torque():
    # Gear A (m_a, r_a) at the origin driven by a torque tau about z meshes externally with
    # gear B (m_b, r_b) at x = r_a + r_b; both on bearings. No slip at the pitch point:
    # r_a w_a = -r_b w_b. Power balance with the mesh force F on the pitch circles:
    #   I_a alpha_a = tau - F r_a,  I_b alpha_b = -F r_b ... with alpha_b = -(r_a / r_b) alpha_a
    #   -> alpha_a = tau / (I_a + I_b (r_a / r_b)^2).
    ma, ra, mb, rb, tau = 2.0, 0.1, 3.0, 0.25, 1.5
    Ia, Ib = ma * ra**2 / 2, mb * rb**2 / 2
    model = chasles.Model()
    a = disk(model, "a", ma, ra)
    b = disk(model, "b", mb, rb)
    s = chasles.make_rest_state(model)
    s.bodies[b].position = [ra + rb, 0, 0]
    pin(model, s, a, 0.0)
    pin(model, s, b, ra + rb)
    mesh = chasles.GearMesh("mesh", chasles.GearKind.EXTERNAL, a,
                            chasles.PitchCircle([0, 0, 0], [0, 0, 1], ra), b,
                            chasles.PitchCircle([0, 0, 0], [0, 0, 1], rb))
    assert mesh.num_rows == 1
    model.add_constraint(mesh)
    model.add_force_element(chasles.AppliedMoment("drive", a, [0, 0, tau]))
    s = chasles.make_rest_state(model)  # sized for the finished model
    s.bodies[b].position = [ra + rb, 0, 0]
    sol = chasles.solve_instantaneous(model, s)
    alpha_a = tau / (Ia + Ib * (ra / rb) ** 2)
    assert_rel(sol.bodies[a].angular_acceleration, [0, 0, alpha_a], scale=alpha_a)
    assert_rel(sol.bodies[b].angular_acceleration, [0, 0, -alpha_a * ra / rb], scale=alpha_a)
    # The mesh force: I_b |alpha_b| = F r_b.
    F = Ib * alpha_a * ra / rb / rb
    (m,) = [r for r in sol.reactions if r.name == "mesh"]
    assert_rel(np.linalg.norm(m.force), F)


def test_rotation_driver_holds_a_constant_acceleration():
    # A disk on a revolute about z, its angle driven as f = f2 t^2 / 2: the driver supplies
    # the moment I_z f2 (no other load), found in its reaction.
    m, r, f2 = 1.5, 0.2, 3.0
    Iz = m * r**2 / 2
    model = chasles.Model()
    d = disk(model, "d", m, r)
    s = chasles.make_rest_state(model)
    pin(model, s, d, 0.0)
    w = chasles.attachment_frame_at_world_pose(model, s, chasles.WORLD, [0, 0, 0])
    f = chasles.attachment_frame_at_world_pose(model, s, d, [0, 0, 0])
    drive = chasles.PrescribedMotion("motor", chasles.DriverKind.ROTATION, chasles.WORLD, w, d,
                                     f, chasles.TimeFunction.quadratic(0.0, 0.0, f2))
    model.add_constraint(drive)
    s = chasles.make_rest_state(model)
    sol = chasles.solve_instantaneous(model, s)
    assert_rel(sol.bodies[d].angular_acceleration, [0, 0, f2], scale=f2)
    (motor,) = [x for x in sol.reactions if x.name == "motor"]
    assert_rel(motor.multipliers, [Iz * f2])
    # The same driver from Python callables: f = sin t, rate cos t, acceleration -sin t; at
    # t = 0.5 the driver's moment is I_z (-sin 0.5).
    model2 = chasles.Model()
    d2 = disk(model2, "d", m, r)
    s2 = chasles.make_rest_state(model2)
    pin(model2, s2, d2, 0.0)
    fn = chasles.TimeFunction(math.sin, math.cos, lambda t: -math.sin(t))
    model2.add_constraint(chasles.PrescribedMotion("motor", chasles.DriverKind.ROTATION,
                                                   chasles.WORLD, w, d2, f, fn))
    s2 = chasles.make_rest_state(model2)
    angle = math.sin(0.5)
    q = [math.cos(angle / 2), 0, 0, math.sin(angle / 2)]
    chasles.set_body_pose(model2, d2, [0, 0, 0], q, s2)
    chasles.set_body_velocity(model2, d2, [0, 0, 0], [0, 0, math.cos(0.5)], s2)
    s2.t = 0.5
    sol2 = chasles.solve_instantaneous(model2, s2)
    assert_rel(sol2.bodies[d2].angular_acceleration, [0, 0, -math.sin(0.5)], scale=1.0)
    (motor2,) = [x for x in sol2.reactions if x.name == "motor"]
    assert_rel(motor2.multipliers, [-Iz * math.sin(0.5)])


def test_event_stops_a_falling_ball_at_the_floor():
    # Dropped from h: z = h - g t^2 / 2 reaches 0 at t = sqrt(2 h / g). A RECORD event at
    # z = h / 2 (t = sqrt(h / g)) is logged and the run goes on to the STOP event.
    h = 2.0
    model = chasles.Model()
    b = model.add_body("ball", chasles.sphere(0.05).mass_properties(1.0))
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    s = chasles.make_rest_state(model)
    s.bodies[b].position = [0, 0, h]
    half = chasles.EventSpec("half", lambda t, st: st.bodies[0].position[2] - h / 2,
                             chasles.EventDirection.FALLING, chasles.EventAction.RECORD)
    floor = chasles.EventSpec("floor", lambda t, st: st.bodies[0].position[2],
                              chasles.EventDirection.FALLING)
    assert floor.action == chasles.EventAction.STOP
    r = chasles.simulate(model, s, t_end=5.0, events=[half, floor])
    assert r.stopped_by_event
    assert [e.name for e in r.events] == ["half", "floor"]
    assert [e.event for e in r.events] == [0, 1]
    assert_rel(r.events[0].t, math.sqrt(h / G0), rel=1e-11)
    assert_rel(r.events[1].t, math.sqrt(2 * h / G0), rel=1e-11)
    assert_rel(r.final_state.t, math.sqrt(2 * h / G0), rel=1e-11)
    # Events need the adaptive integrator.
    with pytest.raises(chasles.InputError, match="Dormand-Prince"):
        chasles.simulate(model, s, t_end=1.0, integrator=chasles.Integrator.RK4,
                         events=[floor])
