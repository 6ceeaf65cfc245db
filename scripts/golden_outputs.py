#!/usr/bin/env python3
"""Golden outputs: every example through `chasles mass`, `solve` and `simulate` (text, JSON,
the CSV and JSON files), a sweep of each command, `modes` and `balance`, and the browser
report's data, recorded once and compared on every test run.

Usage:
  golden_outputs.py --cli PATH [--source DIR] [--golden DIR] (--record | --check) [--jobs N]

--record writes tests/golden/<case>.txt; --check runs the same commands and compares. The
comparison is textual, except that numbers compare within 1e-9 relative (or both within
1e-12 of zero): the outputs print up to 17 digits, and the last bits of a result may differ
between machines whose libm picks other code paths (FMA variants of sin, exp, ...) for the same
binary. Anything else that changes (a word, a key, a column, a number beyond 1e-9) fails the
check with the case and the first difference; a deliberate change is recorded again with
--record, and the commit that makes it says why.
"""

import argparse
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import tempfile

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?(?:inf|nan)")
REL = 1e-9
ZERO = 1e-12

# Sweeps, modes and balance runs beyond the per-example commands (docs/sweeps.md, docs/modes.md).
EXTRA = {
    "sweep-mass": ["mass", "examples/example-8.1-cylinder.yaml", "--sweep", "R=2 cm:8 cm:4",
                   "--quantity", "cylinder.Izz"],
    "sweep-solve": ["solve", "examples/spool-pulled-by-string.yaml", "--sweep",
                    "theta=30 deg:75 deg:4"],
    "sweep-simulate": ["simulate", "examples/pendulum.yaml", "--sweep", "L=0.5 m:2 m:3",
                       "--sweep", "theta0=10 deg:70 deg:3", "--quantity", "event(bottom)",
                       "--quiet"],
    "modes-bicycle": ["modes", "examples/whipple-bicycle.yaml", "--format", "json"],
    "modes-sweep-top": ["modes", "examples/sleeping-top.yaml", "--sweep",
                        "spin=20 rad/s:80 rad/s:7"],
    "balance-disk": ["balance", "examples/unbalanced-disk-rotor.yaml", "--body", "rotor",
                     "--planes", "-25 cm, 25 cm", "--radius", "15 cm", "--speed", "3000 rpm",
                     "--grade", "6.3", "--format", "json"],
    "html-dzhanibekov": ["simulate", "examples/dzhanibekov.yaml", "--quiet", "--html",
                         "{out}/report.html", "--until", "2"],
}


def cases(source):
    out = {}
    examples = sorted(f for f in os.listdir(os.path.join(source, "examples"))
                      if f.endswith(".yaml"))
    for f in examples:
        name, path = f[:-5], "examples/" + f
        out[name + ".mass"] = ["mass", path]
        out[name + ".mass-json"] = ["mass", path, "--format", "json"]
        out[name + ".solve"] = ["solve", path]
        out[name + ".solve-json"] = ["solve", path, "--format", "json"]
        out[name + ".simulate"] = ["simulate", path, "--quiet", "--out", "{out}"]
    out.update(EXTRA)
    return out


def run_case(cli, source, args):
    """The case's exit code, stdout, stderr and files written, as one text."""
    with tempfile.TemporaryDirectory(prefix="chasles_golden_") as out:
        cmd = [cli] + [a.replace("{out}", out) for a in args]
        p = subprocess.run(cmd, cwd=source, capture_output=True, text=True, timeout=600)
        text = "exit: {}\n--- stdout\n{}--- stderr\n{}".format(p.returncode, p.stdout, p.stderr)
        for f in sorted(os.listdir(out)):
            with open(os.path.join(out, f), encoding="utf-8") as fh:
                body = fh.read()
            if f.endswith(".html"):
                body = report_data(body)
            text += "--- file {}\n{}".format(f, body)
        return text.replace(out, "<out>")


def report_data(html):
    """The browser report's embedded data (its JSON script blocks), not its renderer."""
    blocks = re.findall(r'<script type="application/json" id="chasles-data">(.*?)</script>', html, re.S)
    return "\n".join(blocks) + "\n" if blocks else "(no data block)\n"


def same_number(a, b):
    try:
        x, y = float(a), float(b)
    except ValueError:
        return a == b
    if x == y or (x != x and y != y):
        return True
    if abs(x) <= ZERO and abs(y) <= ZERO:
        return True
    return abs(x - y) <= REL * max(abs(x), abs(y))


def first_difference(want, got):
    """None when the texts agree (numbers within tolerance), else a description."""
    wl, gl = want.split("\n"), got.split("\n")
    for i in range(max(len(wl), len(gl))):
        w = wl[i] if i < len(wl) else "<missing>"
        g = gl[i] if i < len(gl) else "<missing>"
        if w == g:
            continue
        wn, gn = NUMBER.findall(w), NUMBER.findall(g)
        if NUMBER.sub("#", w) == NUMBER.sub("#", g) and len(wn) == len(gn) and all(
                same_number(a, b) for a, b in zip(wn, gn)):
            continue
        return "line {}:\n  recorded: {}\n  now:      {}".format(i + 1, w[:300], g[:300])
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", required=True)
    ap.add_argument("--source", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument("--golden", default=None)
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--record", action="store_true")
    mode.add_argument("--check", action="store_true")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--no-html", action="store_true",
                    help="leave out the browser report's case (a build without the report)")
    a = ap.parse_args()
    golden = a.golden or os.path.join(a.source, "tests", "golden")
    cli = os.path.abspath(a.cli)
    all_cases = cases(a.source)
    skipped = set()
    if a.no_html:
        skipped = {c for c, args in all_cases.items() if "--html" in args}
        all_cases = {c: args for c, args in all_cases.items() if c not in skipped}
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        results = dict(zip(all_cases, pool.map(lambda c: run_case(cli, a.source, all_cases[c]),
                                               all_cases)))
    if a.record:
        if skipped:
            print("record with every case (a build with the browser report)")
            return 2
        shutil.rmtree(golden, ignore_errors=True)
        os.makedirs(golden)
        for name, text in results.items():
            with open(os.path.join(golden, name + ".txt"), "w", encoding="utf-8") as fh:
                fh.write(text)
        print("recorded {} cases in {}".format(len(results), golden))
        return 0
    failures = []
    recorded = {f[:-4] for f in os.listdir(golden) if f.endswith(".txt")} - skipped
    for name in sorted(recorded - set(results)):
        failures.append("{}: recorded, but no longer a case".format(name))
    for name, text in sorted(results.items()):
        path = os.path.join(golden, name + ".txt")
        if not os.path.exists(path):
            failures.append("{}: a case with no recorded output (record it)".format(name))
            continue
        with open(path, encoding="utf-8") as fh:
            diff = first_difference(fh.read(), text)
        if diff:
            failures.append("{}: {}".format(name, diff))
    for f in failures:
        print(f)
    print("{} of {} cases agree with their recorded outputs".format(
        len(results) - len(failures), len(results)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
