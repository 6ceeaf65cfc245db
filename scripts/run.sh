#!/usr/bin/env bash
# Sets up, builds and runs chasles. Without arguments chasles runs its built-in demonstration
# scene; any arguments are passed on (scripts/run.sh mass examples/example-8.2-two-rods.yaml).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh >&2
./scripts/build.sh -DCHASLES_SANITIZE=OFF -DCHASLES_BUILD_TESTS=OFF -DCHASLES_BUILD_BENCH=OFF >&2
exec ./build/bin/chasles "$@"
