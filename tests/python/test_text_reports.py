"""The text reports a Python program gets (Run.text(), Solution.text()) are what the program
prints on standard output for the same scene and options: the report layer makes both
(docs/python.md, "Reports")."""

import os
import subprocess

import pytest

from conftest import example

CLI = os.environ.get("CHASLES_CLI")
needs_cli = pytest.mark.skipif(not CLI, reason="CHASLES_CLI (the chasles program) not given")

# Contacts with impacts, a string going slack and taut, joints with reactions in the plane,
# sliding contact coming to rest, events that stop a run, and the closed-form ball engine.
SIMULATE = [
    ("contact-bouncing-ball.yaml", []),
    ("block-thrown-up-on-a-string.yaml", []),
    ("example-8.4-sliding-ladder-planar.yaml", []),
    ("contact-box-slides-to-rest.yaml", ["--units", "US"]),
    ("pendulum.yaml", []),
    ("pool-head-on-events.yaml", []),
]
# A rolling joint with mu_s, contact points holding a box, a string over a pulley, hinges.
SOLVE = [
    ("example-8.3-cylinder-incline.yaml", []),
    ("contact-box-held-on-slope.yaml", []),
    ("atwood-machine.yaml", ["--units", "ft,slug"]),
    ("door-on-two-hinges.yaml", []),
    ("example-8.4-sliding-ladder-planar.yaml", []),
]


def cli(*args, cwd):
    out = subprocess.run([CLI, *args], cwd=cwd, capture_output=True, text=True, check=True)
    return out.stdout


def units_of(options):
    return options[options.index("--units") + 1] if "--units" in options else None


@needs_cli
@pytest.mark.parametrize("name,options", SIMULATE)
def test_run_text_is_what_simulate_prints(chasles, tmp_path, name, options):
    scene = example(name)
    # The program writes its CSV and JSON in the current folder and names them on the last line.
    printed = cli("simulate", scene, "--quiet", *options, cwd=tmp_path)
    run = chasles.run(chasles.load_scene(scene))
    assert run.text(units=units_of(options)) == printed


@needs_cli
def test_run_text_names_the_files_of_out(chasles, tmp_path):
    scene = example("pendulum.yaml")
    printed = cli("simulate", scene, "--quiet", "--out", "results", cwd=tmp_path)
    assert "Wrote results/pendulum.csv (" in printed
    assert chasles.run(chasles.load_scene(scene)).text(out="results") == printed


@needs_cli
@pytest.mark.parametrize("name,options", SOLVE)
def test_solution_text_is_what_solve_prints(chasles, tmp_path, name, options):
    scene = example(name)
    printed = cli("solve", scene, *options, cwd=tmp_path)
    solution = chasles.solve(chasles.load_scene(scene))
    assert solution.text(units=units_of(options)) == printed


def test_text_refuses_a_unit_it_does_not_know_and_a_units_that_is_not_text(chasles):
    solution = chasles.solve(chasles.load_scene(example("example-8.3-cylinder-incline.yaml")))
    with pytest.raises(chasles.InputError, match="furlong"):
        solution.text(units="furlong")
    with pytest.raises(TypeError, match="units must be a string"):
        solution.text(units=3)
