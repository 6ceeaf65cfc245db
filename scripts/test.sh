#!/usr/bin/env bash
# Sets up, builds and runs every test. `scripts/test.sh --sanitize` does the same in a separate
# build with AddressSanitizer and UndefinedBehaviorSanitizer (build-asan/, configured by
# scripts/common.sh; with clang it holds the fuzz targets too); `scripts/test.sh --tsan` builds
# the library and the shared-Model tests (tests/threads) with ThreadSanitizer and runs them.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
# shellcheck source=scripts/common.sh
source scripts/common.sh
if [ "${1:-}" = "--tsan" ]; then
  build=${BUILD_DIR:-build-tsan}
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCHASLES_WERROR=ON -DCHASLES_SANITIZE=OFF \
    -DCHASLES_SANITIZE_THREAD=ON -DCHASLES_BUILD_TESTS=ON -DCHASLES_BUILD_BENCH=OFF \
    $(ccache_args) >/dev/null
  cmake --build "$build" -j "${JOBS:-2}" --target threads
  TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" "$build/tests/threads"
  exit 0
elif [ "${1:-}" = "--sanitize" ]; then
  export BUILD_DIR=${BUILD_DIR:-build-asan}
  configure_sanitize "$BUILD_DIR" -DCHASLES_BUILD_TESTS=ON
  cmake --build "$BUILD_DIR" -j "${JOBS:-2}"
else
  # Every option stated: CMake remembers them per build folder, and scripts/run.sh builds the
  # same folder without tests.
  ./scripts/build.sh -DCHASLES_WERROR=ON -DCHASLES_SANITIZE=OFF -DCHASLES_BUILD_TESTS=ON \
    -DCHASLES_BUILD_BENCH=ON
fi
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure --no-tests=error -j 2
