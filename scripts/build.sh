#!/usr/bin/env bash
# Configures and builds chasles into ${BUILD_DIR:-build}. Extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/common.sh
source scripts/common.sh
build=${BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-Release} $(ccache_args) "$@" >/dev/null
cmake --build "$build" -j "${JOBS:-2}"
