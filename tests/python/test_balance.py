"""chasles.balance (``chasles balance``, docs/modes.md "Rotors"): its text() and json() are
what the program prints for the same scene and options, with and without whirl rows, and its
numbers for a point mass on a shaft are the closed forms of the two-plane correction."""

import json
import math
import os
import subprocess

import numpy as np
import pytest

from conftest import assert_rel, example

CLI = os.environ.get("CHASLES_CLI")
needs_cli = pytest.mark.skipif(not CLI, reason="CHASLES_CLI (the chasles program) not given")

DISK = "unbalanced-disk-rotor.yaml"
BEARINGS = "rotor-on-bearings.yaml"
# (scene, --set overrides, the program's options, the same as chasles.balance's keywords): the
# shipped examples as the e2e tests, the golden case and docs/modes.md run them.
CASES = [
    (DISK, {}, ["--planes", "-25 cm, 25 cm", "--radius", "15 cm", "--speed", "3000 rpm",
                "--grade", "6.3"],
     dict(planes="-25 cm, 25 cm", radius="15 cm", speed="3000 rpm", grade=6.3)),
    (DISK, {}, ["--planes", "-25 cm, 25 cm", "--radius", "15 cm"],
     dict(planes="-25 cm, 25 cm", radius="15 cm")),
    (DISK, {}, ["--axis", "[0, 0, 1]", "--through", "[0, 0, 5 cm]", "--planes", "-30 cm, 20 cm",
                "--radius", "10 cm", "--speed", "1500 rpm"],
     dict(axis="[0, 0, 1]", through="[0, 0, 5 cm]", planes="-30 cm, 20 cm", radius="10 cm",
          speed="1500 rpm")),
    # Whirl rows: over --whirl, over 0 to twice --speed, and without a speed over 0 to twice
    # the highest whirl frequency at rest; undamped as the e2e test's critical speeds.
    (BEARINGS, {}, ["--planes", "-28 cm, 10 cm", "--radius", "10 cm", "--whirl",
                    "0 rpm:6000 rpm:4"],
     dict(planes="-28 cm, 10 cm", radius="10 cm", whirl="0 rpm:6000 rpm:4")),
    (BEARINGS, {"damping": "0 N*s/m"}, ["--planes", "-28 cm, 10 cm", "--radius", "10 cm",
                                        "--whirl", "0 rad/s:400 rad/s:21"],
     dict(planes="-28 cm, 10 cm", radius="10 cm", whirl="0 rad/s:400 rad/s:21")),
    (BEARINGS, {}, ["--planes", "-28 cm, 10 cm", "--radius", "10 cm", "--speed", "3000 rpm"],
     dict(planes="-28 cm, 10 cm", radius="10 cm", speed="3000 rpm")),
    (BEARINGS, {}, ["--planes", "-28 cm, 10 cm", "--radius", "10 cm"],
     dict(planes="-28 cm, 10 cm", radius="10 cm")),
]


def cli(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, check=True).stdout


def set_options(overrides):
    return [a for k, v in overrides.items() for a in ("--set", f"{k}={v}")]


@needs_cli
@pytest.mark.parametrize("name,overrides,options,keywords", CASES)
def test_text_and_json_are_what_balance_prints(chasles, name, overrides, options, keywords):
    scene = example(name)
    args = ["balance", scene, *set_options(overrides), "--body", "rotor", *options]
    b = chasles.balance(chasles.load_scene(scene, set=overrides or None), "rotor", **keywords)
    assert b.text() == cli(*args)
    printed = cli(*args, "--format", "json")
    assert b.json() == printed
    assert (b.whirl is None) == (json.loads(printed)["whirl"] is None)


def test_whirl_rows_are_the_json_s(chasles):
    b = chasles.balance(chasles.load_scene(example(BEARINGS)), "rotor", planes="-28 cm, 10 cm",
                        radius="10 cm", whirl=(0.0, 400.0, 5))
    j = json.loads(b.json())["whirl"]
    assert list(b.whirl["speeds"]) == j["speeds"] == [0.0, 100.0, 200.0, 300.0, 400.0]
    for point, want in zip(b.whirl["points"], j["points"]):
        assert point["speed"] == want["speed"]
        assert list(point["frequency_hz"]) == [m["frequency_hz"] for m in want["modes"]]
        assert point["directions"] == [m["direction"] for m in want["modes"]]
        assert [[e.real, e.imag] for e in point["eigenvalues"]] == \
            [m["eigenvalue"] for m in want["modes"]]
    assert [(s, d) for s, d in b.whirl["critical_speeds"]] == \
        [(c["speed"], c["directions"]) for c in j["critical_speeds"]]


# A shaft (a solid cylinder on the axis: no unbalance of its own) of mass M_s carrying a point
# mass m at radius r, angle phi about z and height z0 (its inertia about itself is zero, so it
# adds no product of inertia about its own place). About O = 0 on the axis z:
#   U = m r e_phi (static unbalance m r),  D = m z0 r e_phi,  C = D - z_cm U, z_cm = m z0 / M;
#   u_A = (z_B U - D)/(z_A - z_B) = -m r (z_B - z0)/(z_B - z_A) e_phi,
#   u_B = (D - z_A U)/(z_A - z_B) = -m r (z0 - z_A)/(z_B - z_A) e_phi:
# the lever rule, both masses opposite the point mass (angle phi - pi), |u_A| + |u_B| = m r;
# at spin w the bearing forces are w^2 |u|, and ISO 21940-11 allows U_per = M G / w.
M_S, L_S, M, R, PHI, Z0 = 4.0, 0.6, 0.03, 0.05, math.radians(30.0), 0.1
Z_A, Z_B, R_C, W, G = -0.25, 0.2, 0.08, 300.0, 2.5

POINT_MASS_ROTOR = f"""chasles: 3
title: "Point mass on a shaft"
bodies:
  - name: rotor
    parts:
      - {{name: shaft, shape: cylinder, radius: 2 cm, length: {L_S} m, mass: {M_S} kg}}
      - {{name: weight, shape: point, mass: {M} kg,
         position: [{R * math.cos(PHI)!r} m, {R * math.sin(PHI)!r} m, {Z0} m]}}
"""


def test_point_mass_on_a_shaft_is_the_closed_form(chasles):
    scene = chasles.load_scene_string(POINT_MASS_ROTOR, name="point-mass-rotor.yaml")
    # Numbers are SI: the planes in m, the radius in m, the speed in rad/s.
    b = chasles.balance(scene, "rotor", planes=(Z_A, Z_B), radius=R_C, speed=W, grade=G)
    total = M_S + M
    e_phi = np.array([math.cos(PHI), math.sin(PHI), 0.0])
    assert_rel(b.mass, total, rel=1e-14)
    assert_rel(b.static_unbalance, M * R, rel=1e-12)
    assert_rel(b.static_unbalance_vector, M * R * e_phi, rel=1e-12)
    z_cm = M * Z0 / total
    # C and D come out of the inertia tensor, M_s L^2 / 12 against m r z0: 1e-11.
    assert_rel(b.couple_unbalance, M * R * (Z0 - z_cm), rel=1e-11)
    u_a = M * R * (Z_B - Z0) / (Z_B - Z_A)
    u_b = M * R * (Z0 - Z_A) / (Z_B - Z_A)
    a, c = b.corrections
    assert (a["plane"], b.corrections[1]["plane"]) == ("A", "B")
    assert (a["position"], c["position"], a["radius"]) == (Z_A, Z_B, R_C)
    assert_rel(a["mass"], u_a / R_C, rel=1e-11)
    assert_rel(c["mass"], u_b / R_C, rel=1e-11)
    assert_rel((a["mass"] + c["mass"]) * R_C, M * R, rel=1e-12)
    for k in (a, c):
        assert_rel(k["angle"], PHI - math.pi, rel=1e-11)
    assert_rel(a["point"], [-R_C * e_phi[0], -R_C * e_phi[1], Z_A], rel=1e-12)
    # Round-off of the sums U + u_A + u_B and D + z_A u_A + z_B u_B: a few ulps.
    assert b.residual_static < 1e-14 * M * R
    assert b.residual_couple < 1e-14 * M * R
    assert b.speed == W
    assert_rel(np.linalg.norm(b.bearing_forces_before, axis=1), [W * W * u_a, W * W * u_b],
               rel=1e-11)
    assert np.max(np.abs(b.bearing_forces_after)) < 1e-12 * W * W * u_a
    assert b.grade == G
    assert_rel(b.permissible, total * G * 1e-3 / W, rel=1e-12)
    per_plane = np.array(b.permissible_per_plane)
    assert_rel(per_plane, b.permissible * np.array([Z_B - z_cm, z_cm - Z_A]) / (Z_B - Z_A),
               rel=1e-12)
    assert b.permissible_met is False  # m r = 1.5e-3 kg·m against U_per = 3.4e-5 kg·m
    assert b.whirl is None
    # The same options written as the program takes them give the same numbers.
    written = chasles.balance(scene, "rotor", planes="-25 cm, 20 cm", radius="8 cm",
                              speed="300 rad/s", grade=2.5)
    for k in range(2):
        assert_rel(written.corrections[k]["mass"], b.corrections[k]["mass"], rel=1e-12)
    assert_rel(written.permissible, b.permissible, rel=1e-12)


def test_without_a_speed_the_speed_s_numbers_are_none(chasles):
    b = chasles.balance(chasles.load_scene(example(DISK)), "rotor", planes="-25 cm, 25 cm",
                        radius="15 cm")
    assert b.speed is None and b.bearing_forces_before is None and b.grade is None
    assert b.permissible is None and b.permissible_per_plane is None
    assert b.permissible_met is None


def test_bad_options_name_the_argument(chasles):
    scene = chasles.load_scene(example(DISK))
    for kwargs, key, text in [
        (dict(planes="10 cm", radius="5 cm"), "planes", "is not two positions"),
        (dict(planes="10 cm, 10 cm", radius="5 cm"), "", "they must differ"),
        (dict(planes="-1 cm, 1 cm", radius="5 kg"), "radius", "is not a length"),
        (dict(planes="-1 cm, 1 cm", radius="5 cm", grade=6.3), "grade", "give speed"),
        (dict(planes="-1 cm, 1 cm", radius="5 cm", speed="3 m"), "speed",
         "is not an angular speed"),
        (dict(planes="-1 cm, 1 cm", radius="5 cm", whirl="0 rpm:1 rpm:3"), "whirl",
         "no bearing element holds 'rotor'"),
    ]:
        with pytest.raises(chasles.SceneError, match=text) as e:
            chasles.balance(scene, "rotor", **kwargs)
        if key:
            assert e.value.key == key
    with pytest.raises(chasles.SceneError, match="no body named 'wheel'") as e:
        chasles.balance(scene, "wheel", planes="-1 cm, 1 cm", radius="5 cm")
    assert e.value.key == "body"
    with pytest.raises(TypeError, match="planes"):
        chasles.balance(scene, "rotor", planes=3, radius="5 cm")
    with pytest.raises(TypeError, match="radius"):
        chasles.balance(scene, "rotor", planes="-1 cm, 1 cm", radius=None)
    with pytest.raises(chasles.InputError, match="radius must be a finite number"):
        chasles.balance(scene, "rotor", planes="-1 cm, 1 cm", radius=math.nan)
    held = chasles.load_scene(example(BEARINGS))
    with pytest.raises(chasles.InputError, match="whirl's N"):
        chasles.balance(held, "rotor", planes="-28 cm, 10 cm", radius="10 cm",
                        whirl=(0.0, 1.0, 1))
