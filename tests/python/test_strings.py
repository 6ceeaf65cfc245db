"""Strings and string-like forces in Python: StringConstraint (ends, fixed pulleys and pulleys
carried by bodies), StringPull, CableForce, JointTorque and a force at a world point, against
closed forms derived here."""

import math

import pytest

import chasles
from conftest import assert_rel

G = 9.81
Z = [0, 0, 1]


def box(model, name, m, inertia=(0.01, 0.01, 0.01)):
    return model.add_body(name, chasles.MassProperties(
        m, [0, 0, 0], chasles.RotationalInertia(*inertia)))


def test_atwood_machine_with_a_massive_pulley():
    # The pulley (M, radius r, I = M r^2/2) grips the string: two strings wound on its rim.
    # m1 a = m1 g - T1, m2 a = T2 - m2 g, I a/r = (T1 - T2) r
    #   => a = (m1 - m2) g / (m1 + m2 + I/r^2), T1 = m1 (g - a), T2 = m2 (g + a).
    m1, m2, M, r = 3.0, 1.25, 2.0, 0.15
    I = 0.5 * M * r * r
    model = chasles.Model()
    p = box(model, "pulley", M, (I / 2, I / 2, I))
    b1 = box(model, "m1", m1)
    b2 = box(model, "m2", m2)
    model.add_force_element(chasles.UniformGravity("g", [0, -G, 0]))
    frame = chasles.AttachmentFrame([0, 0, 0])
    model.add_constraint(chasles.Joint("axle", chasles.JointKind.REVOLUTE, chasles.WORLD, frame,
                                       p, frame))
    # Followed up from each mass: round the rim clockwise on the left, counterclockwise on the
    # right (about z).
    model.add_constraint(chasles.StringConstraint(
        "left", chasles.StringEnd(b1, [0, 0, 0]), [],
        chasles.StringEnd(p, [0, 0, 0], r, "clockwise"), Z, 1.0))
    model.add_constraint(chasles.StringConstraint(
        "right", chasles.StringEnd(b2, [0, 0, 0]), [],
        chasles.StringEnd(p, [0, 0, 0], r, "counterclockwise"), Z, 0.6))
    s = chasles.make_rest_state(model)
    s.bodies[1].position = [-r, -1.0, 0]
    s.bodies[2].position = [r, -0.6, 0]
    a = (m1 - m2) * G / (m1 + m2 + I / r**2)
    sol = chasles.solve_instantaneous(model, s)
    assert_rel(sol.bodies[1].acceleration, [0, -a, 0])
    assert_rel(sol.bodies[2].acceleration, [0, a, 0])
    assert sol.reactions[1].kind == "string"
    assert_rel(sol.reactions[1].multipliers[0], m1 * (G - a))
    assert_rel(sol.reactions[2].multipliers[0], m2 * (G + a))


def test_movable_pulley_carried_by_a_body():
    # Ceiling -> down round a pulley on m2 (counterclockwise) -> up over a fixed pulley
    # (clockwise) -> m1. a1 = -2 a2; m1 a1 = T - m1 g, m2 a2 = 2T - m2 g
    #   => a2 = (2 m1 - m2) g / (4 m1 + m2), T = 3 m1 m2 g / (4 m1 + m2).
    m1, m2, r1, r2 = 1.5, 2.0, 0.1, 0.15
    model = chasles.Model()
    b1 = box(model, "m1", m1)
    b2 = box(model, "m2", m2)
    model.add_force_element(chasles.UniformGravity("g", [0, -G, 0]))
    s = chasles.make_rest_state(model)
    s.bodies[0].position = [r2 + 2 * r1, -1.0, 0]
    s.bodies[1].position = [0, -1.5, 0]
    a_end = chasles.StringEnd(chasles.WORLD, [-r2, -0.2, 0])
    pulleys = [chasles.StringPulley([0, 0, 0], r2, "counterclockwise", body=b2),
               chasles.StringPulley([r2 + r1, 0, 0], r1, "clockwise")]
    assert pulleys[0].body == b2 and pulleys[1].body == chasles.WORLD
    b_end = chasles.StringEnd(b1, [0, 0, 0])
    L = chasles.StringConstraint.free_length(model, s, a_end, pulleys, b_end, Z)
    assert_rel(L, 1.3 + math.pi * r2 + 1.5 + math.pi * r1 + 1.0)
    rope = chasles.StringConstraint("rope", a_end, pulleys, b_end, Z, L)
    assert rope.length == L and rope.parent == chasles.WORLD and rope.child == b1
    model.add_constraint(rope)
    a2 = (2 * m1 - m2) * G / (4 * m1 + m2)
    sol = chasles.solve_instantaneous(model, s)
    assert_rel(sol.bodies[1].acceleration, [0, a2, 0], scale=a2)
    assert_rel(sol.bodies[0].acceleration, [0, -2 * a2, 0], scale=a2)
    assert_rel(sol.reactions[0].multipliers[0], 3 * m1 * m2 * G / (4 * m1 + m2))
    r = chasles.simulate(model, s, t_end=0.4, rtol=1e-12)
    assert_rel(r.final_state.bodies[1].position[1], -1.5 + 0.5 * a2 * 0.4**2)


@pytest.mark.parametrize("theta_deg", [30.0, 75.0])
def test_spool_pulled_by_a_string_on_its_hub(theta_deg):
    # Spool (m, R, k) rolling on the floor, a string leaving the hub's underside (radius r)
    # pulled with P at theta. m a = P cos(theta) + f, m k^2 alpha = r P + R f, alpha = -a/R
    #   => a = P (cos(theta) - r/R) / (m (1 + k^2/R^2)); it rolls towards the pull only below
    #   acos(r/R) = 60 deg.
    m, R, r, k, P = 2.0, 0.1, 0.05, 0.07, 5.0
    th = math.radians(theta_deg)
    model = chasles.Model()
    b = box(model, "spool", m, (m * k * k / 2, m * k * k / 2, m * k * k))
    model.add_force_element(chasles.UniformGravity("g", [0, -G, 0]))
    model.add_constraint(chasles.RollingContact("floor", chasles.RollingShape.CYLINDER, b,
                                                [0, 0, 0], Z, R, [0, 0, 0], [0, 1, 0]))
    d = [math.cos(th), math.sin(th), 0]
    pull = chasles.StringPull("hand", b, [0, 0, 0], Z, r, "counterclockwise", d,
                              lambda t, state: P)
    model.add_force_element(pull)
    s = chasles.make_rest_state(model)
    s.bodies[0].position = [0, R, 0]
    assert_rel(pull.tangent_point(model, s), [r * math.sin(th), R - r * math.cos(th), 0])
    a = P * (math.cos(th) - r / R) / (m * (1 + k * k / R**2))
    sol = chasles.solve_instantaneous(model, s)
    assert_rel(sol.bodies[0].acceleration[0], a)
    assert (a > 0) == (theta_deg < 60)
    assert_rel(sol.bodies[0].angular_acceleration[2], -a / R)
    assert_rel(sol.reactions[0].friction[0], m * a - P * math.cos(th), scale=P)


def test_cable_joint_torque_and_world_point_force():
    # A free box (m, I_zz) without gravity: a cable to a winch far along +x with tension 2 t
    # [N] at t = 1.5 s pulls it at a = 3/m; a torque tau across a revolute joint turns a
    # wheel at alpha = tau / I; a force F x at the world point (0, h, 0) on a free disk
    # centred at the origin gives a = F/m and alpha_z = -h F / I.
    m, Izz, tau, F, h = 2.0, 0.3, 0.9, 4.0, 0.25
    model = chasles.Model()
    crate = box(model, "crate", m, (0.2, 0.2, Izz))
    wheel = box(model, "wheel", m, (0.2, 0.2, Izz))
    disk = box(model, "disk", m, (0.2, 0.2, Izz))
    model.add_force_element(chasles.CableForce("hoist", crate, [0, 0, 0], [100, 0, 0],
                                               lambda t, state: 2.0 * t))
    frame = chasles.AttachmentFrame([0, 0, 0])
    model.add_constraint(chasles.Joint("axle", chasles.JointKind.REVOLUTE, chasles.WORLD, frame,
                                       wheel, frame))
    model.add_force_element(chasles.JointTorque("motor", chasles.WORLD, wheel, Z, tau))
    model.add_force_element(chasles.AppliedForce("push", disk, [0, h, 0], [F, 0, 0],
                                                 point_frame="world"))
    s = chasles.make_rest_state(model)
    s.t = 1.5
    s.bodies[1].position = [0, 0, 0]
    s.bodies[2].position = [0, 0, 0]
    s.bodies[0].position = [-1, 0, 0]
    sol = chasles.solve_instantaneous(model, s)
    assert_rel(sol.bodies[0].acceleration, [3.0 / m, 0, 0])
    assert_rel(sol.bodies[1].angular_acceleration, [0, 0, tau / Izz])
    assert_rel(sol.bodies[2].acceleration, [F / m, 0, 0])
    assert_rel(sol.bodies[2].angular_acceleration, [0, 0, -h * F / Izz])
    # A cable cannot push: a negative tension stops the solve.
    model.add_force_element(chasles.CableForce("bad", crate, [0, 0, 0], [1, 0, 0], -1.0))
    with pytest.raises(chasles.InputError):
        chasles.solve_instantaneous(model, s)
    with pytest.raises(chasles.InputError):
        chasles.StringPulley([0, 0, 0], 0.1, "sideways")
