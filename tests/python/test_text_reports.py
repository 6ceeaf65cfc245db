"""The text reports a Python program gets (Run.text(), Solution.text()) are what the program
prints on standard output for the same scene and options: the report layer makes both
(docs/python.md, "Reports")."""

import json
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


# A body of parts with a hole, a mesh assembly, and a scene's own units with --units over them.
MASS = [
    ("example-8.1-cylinder.yaml", []),
    ("plate-with-hole.yaml", []),
    ("mesh-bracket-assembly.yaml", ["--units", "mm,g"]),
]
# A marble in a trough (oscillatory modes), a sleeping top (gyroscopic), a pendulum.
MODES = [
    ("cylinder-in-trough.yaml", []),
    ("sleeping-top.yaml", []),
    ("pendulum.yaml", []),
]


@needs_cli
@pytest.mark.parametrize("name,options", MASS)
def test_mass_text_is_what_mass_prints(chasles, tmp_path, name, options):
    scene = example(name)
    printed = cli("mass", scene, *options, cwd=tmp_path)
    assert chasles.mass_text(chasles.load_scene(scene), units=units_of(options)) == printed


@needs_cli
@pytest.mark.parametrize("name,options", MODES)
def test_modes_text_is_what_modes_prints(chasles, tmp_path, name, options):
    scene = example(name)
    printed = cli("modes", scene, *options, cwd=tmp_path)
    assert chasles.modes_text(chasles.load_scene(scene)) == printed


@needs_cli
def test_modes_sweep_text_is_what_modes_sweep_prints(chasles, tmp_path):
    scene = example("sleeping-top.yaml")
    sweep = "spin=20 rad/s:80 rad/s:7"
    printed = cli("modes", scene, "--sweep", sweep, cwd=tmp_path)
    assert chasles.modes_text(chasles.load_scene(scene), sweep=sweep) == printed


@needs_cli
@pytest.mark.parametrize("name", ["pendulum.yaml", "contact-bouncing-ball.yaml",
                                  "pool-head-on-events.yaml"])
def test_run_path_is_what_the_json_names(chasles, tmp_path, name):
    scene = example(name)
    cli("simulate", scene, "--quiet", "--out", ".", cwd=tmp_path)
    summary = json.loads((tmp_path / (name[:-5] + ".json")).read_text())
    run = chasles.run(chasles.load_scene(scene))
    assert run.run_path.path == summary["run_path"]["path"]
    assert run.run_path.reason == summary["run_path"]["reason"]
