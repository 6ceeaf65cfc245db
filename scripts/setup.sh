#!/usr/bin/env bash
# Installs every Debian package chasles needs to build, test and run. Idempotent: it asks apt
# only for what is missing, and refreshes the package lists only when something is.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  ccache               # compiler cache: a rebuild of what was compiled before costs seconds
  libeigen3-dev        # linear algebra
  libyaml-dev          # scene files: the YAML reference parser's events, with line/column marks
  libcli11-dev         # command line
  libfmt-dev           # formatting
  libboost-dev         # Boost.Math: quadrature, special functions (header-only)
  nlohmann-json3-dev   # JSON reports
  libpugixml-dev       # robot files (URDF, MJCF, SDF) and Collada meshes: XML with byte offsets
  libmujoco-samples    # tests: mujoco-compile checks that MuJoCo compiles what audit --fix wrote
  ignition-tools libsdformat-dev  # tests/robots: ign sdf -p made the SDF versions
  libplplot-dev plplot-driver-cairo  # chasles plot: axes, legend and series drawn by PLplot (svg, pngcairo)
  libassimp-dev        # bench/ only: the comparison with chasles' own STL reader
  libgtest-dev libgmock-dev  # tests
  libpng-dev           # tests: decode the PNG of chasles plot
  libbenchmark-dev     # benchmarks in bench/
  openmpi-bin libopenmpi-dev  # mpirun -np N chasles ... --sweep: the MPI plugin and its tests
  clang-format         # formatting check
  clang libclang-rt-dev  # libFuzzer, for scripts/fuzz.sh
  python3-dev          # the Python module: Python's headers and library
  pybind11-dev         # the Python module: C++ bindings (CMake package)
  python3-pybind11     # the Python module: pybind11 for setup.py builds
  python3-numpy        # the Python module's arrays
  python3-pytest       # the Python tests (tests/python)
  python3-pandas       # to_pandas() of the module's tables
  python3-matplotlib   # the plot of docs/python.md
  python3-pip          # pip install . of the module
  python3-venv         # a virtual environment to install it into
  nodejs               # the browser report: bundles report/ with esbuild; runs tests/browser
  npm                  # installs report/'s packages (three, uplot, esbuild, puppeteer-core)
  chromium             # headless browser of the report's tests (tests/browser)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

# A node installed from elsewhere (e.g. nodesource's nodejs, which carries its own npm) counts
# as present: Debian's npm would conflict with it.
if command -v node >/dev/null && command -v npm >/dev/null; then
  kept=()
  for p in "${missing[@]}"; do
    [ "$p" = nodejs ] || [ "$p" = npm ] || kept+=("$p")
  done
  missing=("${kept[@]+"${kept[@]}"}")
fi

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
else
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The browser report's packages, exactly as report/package-lock.json pins them, from the npm
# registry (puppeteer-core drives Debian's chromium and downloads no browser). Skipped when
# node_modules was installed after the lock file last changed.
report="$(cd "$(dirname "$0")/.." && pwd)/report"
if [ -f "$report/package-lock.json" ]; then
  # npm writes node_modules/.package-lock.json at every install: newer than the lock file
  # means the install matches it.
  if [ "$report/node_modules/.package-lock.json" -nt "$report/package-lock.json" ]; then
    echo "setup: report/node_modules up to date"
  else
    echo "setup: npm ci in report/"
    (cd "$report" && PUPPETEER_SKIP_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error)
  fi
fi
