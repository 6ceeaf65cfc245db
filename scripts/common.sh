# Sourced by scripts/build.sh, test.sh and fuzz.sh: the compiler cache, and the one
# configuration of the sanitizer build.

# ccache, when installed (scripts/setup.sh installs it), keyed so that a fresh clone in another
# folder hits what an earlier clone compiled: paths under the checkout are hashed relative to it
# (CCACHE_BASEDIR), the build folder is not hashed (CCACHE_NOHASHDIR; line tables then name the
# first clone's folder), and a file's timestamps are not compared, only its contents.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
export CCACHE_SLOPPINESS=${CCACHE_SLOPPINESS:-include_file_mtime,include_file_ctime,time_macros}
export CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-8G}
ccache_args() {
  if command -v ccache >/dev/null; then
    echo "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
  else
    echo "-UCMAKE_CXX_COMPILER_LAUNCHER"
  fi
}

# With clang and libFuzzer (scripts/setup.sh installs both) the tests and the fuzz targets share
# one build, build-asan/: every object carries AddressSanitizer and UndefinedBehaviorSanitizer,
# the readers and commands also libFuzzer's coverage (CHASLES_FUZZ_COVERAGE in CMakeLists.txt),
# compiled once at -O1 with line tables. CI runs the tests there and then
# fuzzes with the same objects, so the library is compiled twice per CI run (ordinary, sanitized)
# and not three times. Without libFuzzer it falls back to GCC's sanitizers (CHASLES_SANITIZE),
# and scripts/fuzz.sh says it is skipped.

# True when clang++ can link a libFuzzer target.
have_libfuzzer() {
  command -v clang++ >/dev/null &&
    echo 'extern "C" int LLVMFuzzerTestOneInput(const char*, long) { return 0; }' |
    clang++ -x c++ -fsanitize=fuzzer - -o /dev/null 2>/dev/null
}

# Configures the sanitizer build in $1 (created if need be); extra arguments go to cmake.
configure_sanitize() {
  local build=$1 want=g++
  shift
  have_libfuzzer && want=clang++
  # A folder configured with the other compiler is reconfigured from scratch (CMake keeps the
  # compiler of a folder's first configuration).
  if [ -f "$build/CMakeCache.txt" ] &&
    ! grep -q "^CMAKE_CXX_COMPILER:[A-Z]*=.*/$want\$" "$build/CMakeCache.txt"; then
    echo "$build: configured with another compiler; configuring it again for $want"
    rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"
  fi
  if [ "$want" = clang++ ]; then
    # -O1 with line tables only: the sanitizers dominate the run time, and reports still name
    # file and line. No NDEBUG: Eigen's and the library's assertions stay on.
    CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Sanitize \
      -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -gline-tables-only" -DCHASLES_FUZZ=ON \
      -DCHASLES_SANITIZE=OFF -DCHASLES_BUILD_BENCH=OFF -DCHASLES_WERROR=OFF \
      $(ccache_args) "$@" >/dev/null
  else
    CXX=g++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCHASLES_SANITIZE=ON -DCHASLES_FUZZ=OFF \
      -DCHASLES_BUILD_BENCH=OFF -DCHASLES_WERROR=ON $(ccache_args) "$@" >/dev/null
  fi
}
