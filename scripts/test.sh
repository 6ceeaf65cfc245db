#!/usr/bin/env bash
# Sets up, builds and runs every test. `scripts/test.sh --sanitize` does the same in a separate
# build with AddressSanitizer and UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
if [ "${1:-}" = "--sanitize" ]; then
  export BUILD_DIR=${BUILD_DIR:-build-asan} BUILD_TYPE=Debug
  ./scripts/build.sh -DCHASLES_WERROR=ON -DCHASLES_SANITIZE=ON -DCHASLES_BUILD_TESTS=ON \
    -DCHASLES_BUILD_BENCH=OFF
else
  # Every option stated: CMake remembers them per build folder, and scripts/run.sh builds the
  # same folder without tests.
  ./scripts/build.sh -DCHASLES_WERROR=ON -DCHASLES_SANITIZE=OFF -DCHASLES_BUILD_TESTS=ON \
    -DCHASLES_BUILD_BENCH=ON
fi
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure --no-tests=error -j 2
