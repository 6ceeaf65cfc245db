"""The reports a Python program gets (to_json, to_csv) are the text the program writes: the
same io-layer writers make both (docs/python.md, "Reports")."""

import json
import os
import subprocess

import numpy as np

import pytest

from conftest import example

CLI = os.environ.get("CHASLES_CLI")
needs_cli = pytest.mark.skipif(not CLI, reason="CHASLES_CLI (the chasles program) not given")
INCLINE = example("example-8.3-cylinder-incline.yaml")


def cli(*args, cwd=None):
    out = subprocess.run([CLI, *args], cwd=cwd, capture_output=True, text=True, check=True)
    return out.stdout


def test_solution_json_holds_the_solutions_own_values(chasles):
    s = chasles.solve(chasles.load_scene(INCLINE))
    j = json.loads(s.to_json())
    assert [b["name"] for b in j["bodies"]] == [b.name for b in s.bodies]
    assert j["bodies"][0]["acceleration"] == list(s.bodies[0].acceleration)
    assert [r["name"] for r in j["reactions"]] == [r.name for r in s.reactions]
    assert j["rank"] == s.rank
    assert j["checks"]["passed"] == s.certificate.passed


@needs_cli
def test_solution_json_is_what_the_program_prints(chasles):
    s = chasles.solve(chasles.load_scene(INCLINE))
    assert s.to_json() == cli("solve", INCLINE, "--format", "json")


@needs_cli
def test_sweep_csv_and_json_are_what_the_program_prints(chasles):
    t = chasles.sweep(chasles.load_scene(INCLINE), "theta=10 deg:50 deg:5")
    assert t.to_csv() == cli("solve", INCLINE, "--sweep", "theta=10 deg:50 deg:5", "--quiet")
    assert t.to_json() == cli("solve", INCLINE, "--sweep", "theta=10 deg:50 deg:5", "--quiet",
                              "--format", "json")


@needs_cli
def test_run_csv_and_json_are_the_files_the_program_writes(chasles, tmp_path):
    cli("simulate", INCLINE, "--quiet", "--out", str(tmp_path))
    csv_path = tmp_path / "example-8.3-cylinder-incline.csv"
    json_path = tmp_path / "example-8.3-cylinder-incline.json"
    run = chasles.run(chasles.load_scene(INCLINE))
    assert run.to_csv() == csv_path.read_text()
    assert run.to_json(str(csv_path)) == json_path.read_text()


@needs_cli
def test_read_csv_finds_columns_by_name_and_full_precision_reads_back_bitwise(chasles, tmp_path):
    # --full-precision writes every double with %.17g, which reads back as the same double.
    cli("simulate", INCLINE, "--quiet", "--out", str(tmp_path), "--full-precision")
    csv_path = tmp_path / "example-8.3-cylinder-incline.csv"
    run = chasles.run(chasles.load_scene(INCLINE))
    assert run.to_csv(full_precision=True) == csv_path.read_text()
    t = chasles.read_csv(str(csv_path))
    assert t.columns == run.columns
    assert t.units == run.units
    assert t.unit("t") == "s"
    assert (t.data == run.data).all()


@needs_cli
def test_principal_axes_are_columns_here_and_rows_in_the_mass_json(chasles):
    """docs/python.md: `principal_axes[:, i]` goes with `principal_moments[i]`; the mass JSON
    lists the same axes as rows, so its matrix is the transpose (Example 8.2's two rods, whose
    three moments differ)."""
    rods = example("example-8.2-two-rods.yaml")
    mp = chasles.load_scene(rods).mass_properties()["rods"]
    body = json.loads(cli("mass", rods, "--format", "json", "--units", "SI"))["bodies"][0]
    assert (np.array(body["principal_axes"]).T == mp.principal_axes).all()
    I = mp.inertia
    for i in range(3):
        e = mp.principal_axes[:, i]
        assert np.allclose(I @ e, mp.principal_moments[i] * e, rtol=0, atol=1e-15 * np.trace(I))
