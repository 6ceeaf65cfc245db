"""Shared helpers of the Python tests: the checkout's paths and a relative comparison."""

import os

import numpy as np
import pytest

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# Standard gravity, the scenes' `gravity: standard` [m/s^2].
G0 = 9.80665


def example(name):
    """Path of a scene in examples/."""
    return os.path.join(SOURCE_DIR, "examples", name)


def assert_rel(actual, expected, rel=1e-9, scale=None):
    """|actual - expected| <= rel * scale (scale: |expected|'s largest entry unless given)."""
    actual = np.asarray(actual, dtype=float)
    expected = np.asarray(expected, dtype=float)
    s = np.max(np.abs(expected)) if scale is None else scale
    assert s > 0 or np.all(actual == expected)
    err = np.max(np.abs(actual - expected))
    assert err <= rel * s, f"{actual} != {expected} (error {err:.3g}, allowed {rel * s:.3g})"


@pytest.fixture
def chasles():
    import chasles as c
    return c
