#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (AddressSanitizer + UndefinedBehaviorSanitizer) into
# ${FUZZ_BUILD_DIR:-build-asan}, the sanitizer build the tests share (scripts/common.sh), and
# runs each one on its corpus for a bounded time.
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET ...]     (default 60 s; targets: scene
#                                                          expression mesh cli robot plot
#                                                          report)
# A target that finds a crash, a leak, a timeout (20 s per input), an out-of-memory (2 GiB) or a
# broken promise (fuzz/fuzz_support.h) stops the script with exit 1; the input is kept under
# build-asan/artifacts/ and its report is printed. Copy it into fuzz/regressions/<target>/ once
# fixed, so the ordinary test runs replay it. New corpus entries stay in build-asan/corpus/.
# Without clang and libFuzzer the script says so and exits 0.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene expression mesh cli robot plot report)
build=${FUZZ_BUILD_DIR:-build-asan}
# shellcheck source=scripts/common.sh
source scripts/common.sh

if ! have_libfuzzer; then
  echo "fuzz: skipped (clang++ with libFuzzer is not installed; scripts/setup.sh installs it)"
  exit 0
fi

# The sanitizer build of scripts/test.sh --sanitize (scripts/common.sh): after that, nothing is
# compiled again here.
configure_sanitize "$build"
cmake --build "$build" -j "${JOBS:-2}" --target $(printf '%s_fuzz ' "${targets[@]}")

seeds() {
  case "$1" in
    scene) echo examples tests/bad_input ;;
    mesh) echo fuzz/corpus/mesh examples/meshes tests/bad_input/meshes ;;
    robot) echo fuzz/corpus/robot tests/bad_input/robots tests/robots/mjcf tests/robots/sdf ;;
    *) echo "fuzz/corpus/$1" ;;
  esac
}

mkdir -p "$build/artifacts"
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  mkdir -p "$corpus"
  log="$build/$t.log"
  regressions=()
  [ -d "fuzz/regressions/$t" ] && regressions=("fuzz/regressions/$t")
  # -close_fd_mask=2 keeps the targets' error messages (thousands a second) out of the log;
  # libFuzzer's own lines still arrive, and a failing input is re-run below to show its report.
  # shellcheck disable=SC2046
  # The outer timeout is a backstop: libFuzzer's out-of-memory report can itself hang while
  # the input is still allocating.
  if timeout --signal=KILL $((seconds + 300)) "$build/fuzz/${t}_fuzz" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -close_fd_mask=2 -print_final_stats=1 -dict="fuzz/$t.dict" \
    -artifact_prefix="$build/artifacts/$t-" "$corpus" $(seeds "$t") "${regressions[@]}" \
    >"$log" 2>&1; then
    stats=$(grep -E '^stat::(number_of_executed_units|peak_rss_mb)' "$log" | tr '\n' ' ')
    echo "fuzz: $t: ${seconds} s, no failure ($stats; corpus $(ls "$corpus" | wc -l) entries)"
  else
    echo "fuzz: $t FAILED after at most ${seconds} s; the fuzzer's log ends with:" >&2
    tail -n 30 "$log" >&2
    artifact=$(ls -t "$build/artifacts/$t-"* 2>/dev/null | head -n 1 || true)
    # Each target writes the input it is running to /tmp/chasles-fuzz-PID/ when it needs a
    # file (scene, cli, plot, report); after a kill that is where the last input is.
    if [ -z "$artifact" ]; then
      echo "fuzz: no artifact was written; look for the last input in /tmp/chasles-fuzz-*/" >&2
    fi
    if [ -n "$artifact" ]; then
      echo "fuzz: failing input: $artifact; its report:" >&2
      "$build/fuzz/${t}_fuzz" -timeout=20 -rss_limit_mb=2048 "$artifact" 2>&1 | tail -n 60 >&2 || true
    fi
    exit 1
  fi
done
