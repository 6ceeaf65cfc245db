"""Sets of bodies in contacts from Python (docs/python.md, "Models from Python";
docs/scene-format.md, "Sets of bodies"): Model.add_contact_set stands for the contacts added one
by one (same names, order and run, to the bit), scenes written with sets load from text, and
bad sets raise InputError naming the argument and item, leaving the model as it was."""

import numpy as np
import pytest

import chasles
from conftest import G0, assert_rel

R, M = 0.05, 0.2


def balls(n):
    """n balls on the floor (the plane z = 0), with gravity."""
    model = chasles.Model()
    for i in range(n):
        model.add_body(f"ball{i + 1}", chasles.sphere(R).mass_properties(M))
    model.add_force_element(chasles.UniformGravity("gravity", [0, 0, -G0]))
    return model


def start(model):
    """The balls in a row along x, centres 3 R apart; the first rolling at 2 m/s."""
    s = chasles.make_rest_state(model)
    for i in range(model.num_bodies):
        s.bodies[i].position = [3 * R * i, 0, R]
    chasles.set_body_velocity(model, 0, [2.0, 0, 0], [0, 2.0 / R, 0], s)  # rolling
    return s


def floor_spec(name="floor"):
    return chasles.ContactSpec(name, chasles.ContactShape.SPHERE, 0, radius=R, mu_s=0.3,
                               mu_k=0.2)


def pair_spec(name="knock"):
    return chasles.ContactSpec(name, chasles.ContactShape.SPHERE_SPHERE, 0, radius=R,
                               other_radius=R, restitution=0.8)


def test_a_set_is_its_contacts_added_one_by_one():
    n = 4
    with_sets = balls(n)
    assert with_sets.add_contact_set(floor_spec(), bodies="all") == [0, 1, 2, 3]
    assert with_sets.add_contact_set(pair_spec(), between="ball?") == [4, 5, 6, 7, 8, 9]
    one_by_one = balls(n)
    for i in range(n):
        s = floor_spec(f"floor_ball{i + 1}")
        s.body = i
        one_by_one.add_contact(s)
    for a in range(n):
        for b in range(a + 1, n):
            s = pair_spec(f"knock_ball{a + 1}_ball{b + 1}")
            s.body, s.other_body = a, b
            one_by_one.add_contact(s)
    names = [with_sets.contact_point_name(i) for i in range(with_sets.num_contact_points)]
    assert names == [one_by_one.contact_point_name(i)
                     for i in range(one_by_one.num_contact_points)]
    assert names[4:7] == ["knock_ball1_ball2", "knock_ball1_ball3", "knock_ball1_ball4"]
    runs = [chasles.simulate(m, start(m), t_end=0.3, output_interval=0.01)
            for m in (with_sets, one_by_one)]
    # Not vacuous: the rolling ball hits the second, which hits the third.
    hit = [with_sets.contact_point_name(i.point) for i in runs[0].impacts]
    assert set(hit) >= {"knock_ball1_ball2", "knock_ball2_ball3"}
    first = runs[0].impacts[0]
    assert hit[0] == "knock_ball1_ball2"
    # Rolling without rolling resistance it keeps 2 m/s over the gap of R: t1 = R / v.
    assert_rel(first.t, R / 2.0)
    a, b = (r.table(m).data for r, m in zip(runs, (with_sets, one_by_one)))
    assert a.shape == b.shape and np.array_equal(a, b)


def test_with_pairs_across_two_sets():
    model = balls(3)
    assert model.add_contact_set(pair_spec("hit"), bodies="ball1",
                                 with_bodies=["ball3", "ball2"]) == [0, 1]
    assert [model.contact_point_name(i) for i in range(2)] == ["hit_ball1_ball2",
                                                               "hit_ball1_ball3"]


def test_bad_sets_leave_the_model_as_it_was():
    model = balls(3)
    model.add_contact_set(pair_spec(), between="all")
    with pytest.raises(chasles.InputError, match=r"bodies\[1\]: the pattern 'cue\*' matches no "
                                                 r"body"):
        model.add_contact_set(floor_spec(), bodies=["ball1", "cue*"])
    with pytest.raises(chasles.InputError, match="with_bodies: contact 'hit_ball1_ball3' would "
                                                 "touch what contact 'knock_ball1_ball3' touches"):
        model.add_contact_set(pair_spec("hit"), bodies="ball1", with_bodies="ball3")
    with pytest.raises(chasles.InputError, match="is in both 'body' and 'with'"):
        model.add_contact_set(pair_spec("hit"), bodies="all", with_bodies="ball3")
    with pytest.raises(chasles.InputError, match="either bodies= .* or between="):
        model.add_contact_set(floor_spec())
    with pytest.raises(chasles.InputError, match="SPHERE_SPHERE"):
        model.add_contact_set(floor_spec(), between="all")
    with pytest.raises(TypeError, match="bodies must be 'all'"):
        model.add_contact_set(floor_spec(), bodies=3)
    with pytest.raises(TypeError, match="every item must be a str"):
        model.add_contact_set(floor_spec(), bodies=["ball1", 2])
    assert model.num_contacts == 3


def test_scene_text_with_sets():
    text = """chasles: 3
parameters: {R: 0.05 m}
bodies:
  - {name: ball1, parts: [{shape: sphere, radius: R, mass: 0.2 kg}],
     initial: {position: [0, 0, R], velocity: [2 m/s, 0, 0], angular_velocity: [0, 40 rad/s, 0]}}
  - {name: ball2, parts: [{shape: sphere, radius: R, mass: 0.2 kg}], initial: {position: [3*R, 0, R]}}
gravity: standard
contacts:
  - {name: floor, body: 'ball*', shape: sphere, radius: R, mu_s: 0.3, mu_k: 0.2,
     plane: {normal: [0, 0, 1]}}
  - {name: knock, between: all, shape: sphere, radius: R, restitution: 0.8}
simulation: {until: 0.1 s, integrator: events}
"""
    run = chasles.run(chasles.load_scene_string(text, name="sets.yaml"))
    assert [c.point for c in run.final_contacts] == ["floor_ball1", "floor_ball2",
                                                    "knock_ball1_ball2"]
    assert run.impacts[0].point == "knock_ball1_ball2"
    assert_rel(run.impacts[0].t, 0.05 / 2.0)  # the gap R at 2 m/s
    bad = text.replace("body: 'ball*'", "body: 'cue*'")
    with pytest.raises(chasles.SceneError) as e:
        chasles.load_scene_string(bad, name="sets.yaml")
    assert (e.value.line, e.value.column, e.value.key) == (9, 25, "contacts[0].body")
    assert "the pattern 'cue*' matches no body" in str(e.value)
