"""Moreau-Jean time stepping from Python (docs/python.md, "Models from Python"; docs/contact.md,
"Time stepping"): simulate_time_stepping on a Model built in Python, with its options as
keywords, every pair of balls able to collide, threads over the islands, the error estimate and
a velocity tolerance, and the certificate read back."""

import math

import numpy as np
import pytest

import chasles
from conftest import G0

STEP = 1e-3  # [s]


def ball_model(radius=0.1, mass=2.0):
    """One ball over the floor z = 0 (restitution 0, frictionless), with gravity."""
    model = chasles.Model()
    b = model.add_body("ball", chasles.sphere(radius).mass_properties(mass))
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    model.add_contact(chasles.ContactSpec("floor", chasles.ContactShape.SPHERE, b, radius=radius))
    return model


def drop(model, height, radius=0.1, **options):
    """The ball let go at rest with its lowest point `height` above the floor, sampled every
    step."""
    s = chasles.make_rest_state(model)
    s.bodies[0].position = [0, 0, radius + height]
    return chasles.simulate_time_stepping(model, s, t_end=0.5, step=STEP, output_interval=STEP,
                                          store_steps=True, **options)


def roundoff(speed):
    """Bound on the round-off left when a velocity of `speed` [m/s] is cancelled by an impulse
    (a few units in the last place of the speed)."""
    return 8 * np.finfo(float).eps * speed


def assert_certified(r, options=None):
    """Every step's contact problem met the solver's tolerance (max |F_i| <= 1e-12 of the
    impulse scale), and the run says so."""
    tolerance = chasles.ContactProblemSettings().tolerance if options is None else \
        options.solver.tolerance
    assert tolerance == 1e-12
    assert r.steps and len(r.steps) == r.summary.steps
    for step in r.steps:
        assert step.converged
        assert step.residual_impulse <= tolerance * step.impulse_scale, step.t
    assert r.summary.max_residual_impulse == max(s.residual_impulse for s in r.steps)
    assert r.tolerance_met and r.warnings == []


@pytest.mark.parametrize("error_estimate", [True, False])
def test_a_dropped_ball_lands_and_rests(error_estimate):
    """Free flight is exact on the step grid (constant force: u_k+1 = u_k - g h and
    q_k+1 = q_k + h (u_k + u_k+1)/2 are the parabola). A point is active when its gap at the
    step's midpoint is within the touching tolerance, so the step that sees the landing ends
    at that midpoint at rest (restitution 0: u_k+1 = 0). With the error estimate each step is
    two half steps, so the scheme's own step is h' = h/2. A drop height H = g k (k + 1) h'^2 / 2
    puts the midpoint of the step from t = k h' on the floor: the ball then rests touching."""
    R, k = 0.1, 319
    h = STEP / 2 if error_estimate else STEP
    H = G0 * k * (k + 1) * h * h / 2
    model = ball_model(R)
    r = drop(model, H, R, error_estimate=error_estimate)
    assert_certified(r)
    assert r.stats.steps == r.summary.steps == 500 and len(r.samples) == 501
    t_land = k * h  # the start of the step that sees the landing
    gap_tolerance = chasles.ContactTolerances().gap
    assert gap_tolerance == 1e-9
    for s in r.samples:
        z, vz = s.bodies[0].position[2], s.bodies[0].velocity[2]
        if s.t <= t_land + 1e-12:
            # The parabola, to round-off.
            assert abs(z - (R + H - G0 * s.t**2 / 2)) <= 1e-13, s.t
            assert abs(vz + G0 * s.t) <= 1e-13, s.t
        else:
            # At rest on the floor: the gap within the touching tolerance, and the velocity
            # within the residual's velocity (|U_n| = |F_n| / rho at a pressing point) plus the
            # round-off of cancelling the impact speed.
            assert abs(z - R) <= gap_tolerance, s.t
            assert abs(vz) <= r.summary.max_residual_velocity + roundoff(G0 * t_land), s.t
    assert r.summary.max_residual_velocity < 2e-12
    assert r.summary.max_penetration <= gap_tolerance
    assert list(r.regime_changes) == [1] and r.summary.regime_changes == 1
    final = r.final_state.bodies[0]
    assert r.final_state.t == 0.5 and abs(final.position[2] - R) <= gap_tolerance
    # The estimate of the velocity error: the impact's timing, known to within the step h
    # (the one full step of the doubling), g h/2 of velocity.
    if error_estimate:
        # plus the round-off of the smooth steps' doubling (velocities up to g k h' m/s).
        assert abs(r.summary.accumulated_velocity_error - G0 * STEP / 2) <= \
            r.summary.steps * roundoff(G0 * t_land)
    else:
        assert r.summary.accumulated_velocity_error == 0.0


def test_the_speed_before_impact_is_first_order_in_the_step():
    """From H = 0.5 m, off the grid. The landing half step (h' = h/2, with the estimate) starts
    at t_j with t_j - h'/2 < t* <= t_j + h'/2 (its midpoint touches, the previous one's did
    not; the touching tolerance moves t* by 1e-9 m / v, below 1e-9 s). The fastest sample is at
    the start of its step, t_s = t_j or t_j - h', so |v_s - g t*| <= g (3 h'/2 + 1e-9 s), with
    g t* = sqrt(2 g H): first order in h, at most 3 g h / 4. The ball ends at the landing
    step's midpoint, below the floor by less than h' |v_j| <= h' (|v_s| + g h')."""
    R, H = 0.1, 0.5
    model = ball_model(R)
    r = drop(model, H, R)
    assert_certified(r)
    speeds = [-s.bodies[0].velocity[2] for s in r.samples]
    i = int(np.argmax(speeds))
    v_s, exact = speeds[i], math.sqrt(2 * G0 * H)
    h = STEP / 2
    assert abs(v_s - exact) <= G0 * (1.5 * h + 1e-9)
    assert abs(v_s - exact) > 0  # off the grid the step is seen: the bound is not vacuous
    assert abs(v_s - G0 * r.samples[i].t) <= 1e-13  # free flight exact up to there
    z_end = r.final_state.bodies[0].position[2]
    penetration = R - z_end
    assert 0 < penetration < h * (v_s + G0 * h)
    assert abs(r.summary.max_penetration - penetration) <= 1e-15
    v_rest = r.summary.max_residual_velocity + roundoff(v_s)
    for s in r.samples[i + 1:]:
        # At rest: the velocity within the residual's, so the drift within that times 0.5 s.
        assert abs(s.bodies[0].velocity[2]) <= v_rest
        assert abs(s.bodies[0].position[2] - z_end) <= 0.5 * v_rest


def test_velocity_tolerance_is_reported_not_enforced():
    """The run's accumulated estimate after the impact is g h/2 (the impact's timing): a
    velocity tolerance below it is missed (tolerance_met False, a warning), one above it met;
    the run goes on to t_end either way."""
    model = ball_model()
    bound = G0 * STEP / 2
    for tolerance, met in ((0.5 * bound, False), (2 * bound, True)):
        r = drop(model, 0.5, velocity_tolerance=tolerance)
        assert r.tolerance_met is met
        assert r.final_state.t == 0.5
        assert all(s.converged for s in r.steps)
        assert any(not s.within_tolerance for s in r.steps) is not met
        assert (len(r.warnings) > 0) is not met


R_BALL, M_BALL = 0.028575, 0.17  # a pool ball [m], [kg]


def pyramid_model(count=1, spacing=0.0):
    """`count` pyramids of four balls, `spacing` apart along x: three touching in a triangle
    on the floor, one nested on them; mu = 0.5 on the floor (a contact set) and between the
    balls (no pair listed: collide_all_pairs with pair_law). The scene of
    tests/e2e/stepping_integrator_test.cpp's BallCollisionsHoldAPyramidAtRest."""
    R = R_BALL
    d = 2 * R / math.sqrt(3)  # centre of the triangle to a ball's centre
    base = [[d, 0, R], [-d / 2, R, R], [-d / 2, -R, R], [0, 0, R + math.sqrt(4 * R * R - d * d)]]
    model = chasles.Model()
    for p in range(count):
        for name in ("b1", "b2", "b3", "top"):
            model.add_body(f"{name}_{p}", chasles.sphere(R).mass_properties(M_BALL))
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    model.add_contact_set(chasles.ContactSpec("floor", chasles.ContactShape.SPHERE, 0, radius=R,
                                              mu_s=0.5, mu_k=0.5), bodies="all")
    s = chasles.make_rest_state(model)
    start = []
    for p in range(count):
        for b in range(4):
            start.append(np.array(base[b]) + [p * spacing, 0, 0])
            s.bodies[4 * p + b].position = start[-1]
    return model, s, start


def pyramid_options(threads=1):
    return chasles.TimeSteppingOptions(
        t_end=0.2, step=STEP, collide_all_pairs=True,
        pair_law=chasles.SphereCollisionLaw(mu_s=0.5, mu_k=0.5), threads=threads,
        store_steps=True)


def test_ball_collisions_hold_a_pyramid_at_rest():
    """Every pair of balls may collide and none is listed: the broadphase finds the six
    touching pairs, which with the three floor points make one island of 9 points, and the
    exact cone (no regularisation, no creep) holds the pyramid: every centre stays put to
    round-off over 0.2 s, as in the C++ test over 1 s."""
    model, s, start = pyramid_model()
    options = pyramid_options()
    r = chasles.simulate_time_stepping(model, s, options)
    assert_certified(r, options)
    assert r.summary.largest_island == 9  # 3 floor points and the 6 pairs
    assert all(step.islands == 1 and step.active_points == 9 for step in r.steps)
    assert r.summary.steps == 200 and r.final_state.t == pytest.approx(0.2, abs=1e-15)
    for b, p in enumerate(start):
        assert np.linalg.norm(r.final_state.bodies[b].position - p) < 1e-12, b
    # Each of the 9 points changes once, in the first step: from separated (the initial
    # state's mode) to sticking; the top ball's floor point never touches.
    assert r.summary.regime_changes == 9 and list(r.regime_changes) == [1, 1, 1, 0]
    assert r.steps[0].regime_changes == 9 and r.last_regime_change == STEP
    # The samples (initial and final only) as a table: t, then per body 13 columns.
    table = r.table(model)
    assert table.data.shape == (2, 1 + 13 * 4)
    assert table.columns[1:4] == ["b1_0_x", "b1_0_y", "b1_0_z"]


def state_arrays(state):
    return np.concatenate([np.concatenate([b.position, b.quaternion, b.velocity,
                                           b.angular_velocity_body]) for b in state.bodies])


@pytest.mark.parametrize("count", [1, 2])
def test_threads_give_the_same_result_bit_for_bit(count):
    """One pyramid (one island: the second thread has nothing to do), and two pyramids 10 R
    apart (two islands each step, one per thread): two threads or one give the same final
    state and certificate to the bit."""
    model, s, start = pyramid_model(count, 10 * R_BALL)
    runs = [chasles.simulate_time_stepping(model, s, pyramid_options(threads))
            for threads in (1, 2)]
    for r in runs:
        assert_certified(r)
        assert all(step.islands == count and step.active_points == 9 * count
                   and step.largest_island == 9 for step in r.steps)
        # The most points in one island: one pyramid's, however many there are.
        assert r.summary.largest_island == 9
    one, two = runs
    assert np.array_equal(state_arrays(one.final_state), state_arrays(two.final_state))
    for name in ("max_residual_impulse", "max_residual_velocity", "max_momentum_residual",
                 "numerical_energy_error", "newton_iterations", "sweeps",
                 "accumulated_velocity_error", "final_energy"):
        assert getattr(one.summary, name) == getattr(two.summary, name), name
    for b, p in enumerate(start):
        assert np.linalg.norm(one.final_state.bodies[b].position - p) < 1e-12, b


def test_options_and_their_keywords():
    o = chasles.TimeSteppingOptions(t_end=1.0)
    assert (o.step, o.output_interval, o.threads, o.collide_all_pairs) == (1e-3, 0.0, 1, False)
    assert o.error_estimate and o.store_samples and not o.store_steps
    assert math.isinf(o.velocity_tolerance) and math.isinf(o.quiet_span)
    assert math.isnan(o.quiet_from) and o.ball_radii == []
    assert (o.tolerances.gap, o.tolerances.stick_speed, o.solver.tolerance) == (1e-9, 1e-6, 1e-12)
    o.tolerances.gap = 1e-8  # the nested settings are views into the options
    o.pair_law.mu_s = 0.3
    assert o.tolerances.gap == 1e-8 and o.pair_law.mu_s == 0.3
    law = chasles.SphereCollisionLaw(restitution=0.9, mu_s=0.2, mu_k=0.1)
    assert (law.restitution, law.mu_s, law.mu_k) == (0.9, 0.2, 0.1)
    # Without store_samples the samples are dropped; the final state is kept.
    model = ball_model()
    s = chasles.make_rest_state(model)
    s.bodies[0].position = [0, 0, 0.1]
    r = chasles.simulate_time_stepping(model, s, t_end=0.01, store_samples=False)
    assert r.samples == [] and r.final_state.t == 0.01 and r.steps == []
    assert len(r.sample_energy_error) == 2


def test_bad_input_raises_input_error():
    model = ball_model()
    s = chasles.make_rest_state(model)
    s.bodies[0].position = [0, 0, 0.1]

    def refused(message, **kwargs):
        with pytest.raises(chasles.InputError) as e:
            chasles.simulate_time_stepping(model, s, **kwargs)
        assert message in str(e.value), str(e.value)

    refused("step = -0.001 s must be positive and finite", t_end=1.0, step=-1e-3)
    refused("step = 0 s must be positive", t_end=1.0, step=0.0)
    refused("threads is 0; it must be >= 1", t_end=1.0, threads=0)
    refused("output_interval = -0.1 s must be >= 0", t_end=1.0, output_interval=-0.1)
    refused("ball_radii has 2 entries for 1 bodies", t_end=1.0, collide_all_pairs=True,
            ball_radii=[0.1, 0.1])
    refused("more than the limit of 1000000 rows", t_end=1e3, output_interval=1e-4)
    later = s.copy()
    later.t = 0.5
    with pytest.raises(chasles.InputError) as e:
        chasles.simulate_time_stepping(model, later, t_end=0.2)
    assert "t_end = 0.2 s must be finite and after the initial time 0.5 s" in str(e.value)
    # A joint is not taken by time stepping: the error names it.
    jointed = ball_model()
    jointed.add_constraint(chasles.Joint("pin", chasles.JointKind.REVOLUTE, chasles.WORLD,
                                         chasles.AttachmentFrame([0, 0, 1], np.eye(3)), 0,
                                         chasles.AttachmentFrame([0, 0, 0], np.eye(3))))
    with pytest.raises(chasles.InputError) as e:
        chasles.simulate_time_stepping(jointed, chasles.make_rest_state(jointed), t_end=1.0)
    assert "pin" in str(e.value)
    with pytest.raises(TypeError):
        chasles.simulate_time_stepping(model, s, chasles.TimeSteppingOptions(t_end=1.0),
                                       step=1e-3)
    with pytest.raises(TypeError):
        chasles.simulate_time_stepping(model, s, chasles.SimulationOptions(t_end=1.0))
    # The module is still sound: a valid run goes through.
    assert chasles.simulate_time_stepping(model, s, t_end=0.01).final_state.t == 0.01
