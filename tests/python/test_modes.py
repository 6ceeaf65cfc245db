"""Small motions from Python (``chasles.modes``, docs/modes.md): numpy arrays against the
closed forms derived here."""

import math

import numpy as np
import pytest

import chasles
from conftest import G0, assert_rel, example


# examples/cylinder-in-trough.yaml: a solid cylinder (r = 5 cm) rolling inside a trough of
# radius R = 40 cm. Rolling gives its spin (R - r) theta'/r, so T = 3/4 m (R - r)^2 theta'^2,
# V = m g (R - r)(1 - cos theta) and omega^2 = 2 g / (3 (R - r)).
def test_cylinder_in_a_trough():
    m = chasles.modes(chasles.load_scene(example("cylinder-in-trough.yaml")))
    assert m["operating_point"]["kind"] == "equilibrium"
    assert m["stable"]
    oscillating = ~m["rigid"]
    assert oscillating.sum() == 1
    w = math.sqrt(2 * G0 / (3 * (0.4 - 0.05)))
    lam = m["eigenvalues"][oscillating][0]
    assert isinstance(lam, complex)
    assert_rel(lam.imag, w, rel=1e-10)
    assert_rel(m["frequency_hz"][oscillating][0], w / (2 * math.pi), rel=1e-10)
    n = len(m["coordinates"]) + len(m["speeds"])
    assert m["A"].shape == (n, n)
    assert m["shapes"].shape == (len(m["eigenvalues"]), n)
    # The mode is an eigenvector of A: A s = lambda s.
    s = m["shapes"][oscillating][0]
    residual = np.max(np.abs(m["A"] @ s - lam * s))
    assert residual <= 1e-10 * abs(lam) * np.max(np.abs(s)), residual
    assert m["finite_difference_check"] < 1e-6


# A sleeping top (examples/sleeping-top.yaml): stable exactly above
# spin^2 = 4 m g l I1 / I3^2 (I1 about the pivot, I3 about the axis).
def test_sleeping_top_threshold():
    rho, h, mass = 0.04, 0.06, 0.7
    l = h / 2
    I1 = mass * (3 * rho**2 + h**2) / 12 + mass * l**2
    I3 = mass * rho**2 / 2
    Wc = math.sqrt(4 * mass * G0 * l * I1 / I3**2)
    path = example("sleeping-top.yaml")
    above = chasles.modes(chasles.load_scene(path, set={"spin": f"{1.1 * Wc!r} rad/s"}))
    below = chasles.modes(chasles.load_scene(path, set={"spin": f"{0.9 * Wc!r} rad/s"}))
    assert above["operating_point"]["kind"] == "steady_motion"
    assert above["stable"] and not below["stable"]
    assert np.max(below["growth_rate"]) > 0


def test_no_equilibrium_is_an_error():
    text = """chasles: 1
bodies:
  - name: box
    parts: [{shape: box, size: [1 m, 1 m, 1 m], mass: 1 kg}]
gravity: standard
"""
    with pytest.raises(chasles.SceneError, match="no static equilibrium"):
        chasles.modes(chasles.load_scene_string(text, name="falls.yaml"))
