#!/usr/bin/env bash
# Sweeps under mpirun (docs/sweeps.md): the table rank 0 writes is the serial sweep's, byte for
# byte (cmp), errors are printed once and every rank exits with the same code.
# Usage: mpi_sweep_test.sh CASE CHASLES SOURCE_DIR MPIEXEC
set -uo pipefail
case_name=$1 cli=$2 src=$3 mpiexec=${4:-mpirun}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# mpirun -np N --oversubscribe chasles ARGS... (N may exceed the cores).
mpi() { local n=$1; shift; "$mpiexec" -np "$n" --oversubscribe "$cli" "$@"; }
# Runs the serial command and the same under mpirun with N ranks, stdout to files; compares.
same() {
  local n=$1 name=$2; shift 2
  "$cli" "$@" >"$name.serial" 2>"$name.serial.err"
  local s=$?
  mpi "$n" "$@" >"$name.mpi" 2>"$name.mpi.err"
  local m=$?
  [ "$s" -eq "$m" ] || fail "$name: exit $m under mpirun, $s serially"
  [ -s "$name.serial" ] || fail "$name: the serial run wrote nothing"
  cmp "$name.serial" "$name.mpi" || fail "$name: the tables differ"
  # Each warning once, as serially.
  diff <(grep '^warning' "$name.serial.err") <(grep '^warning' "$name.mpi.err") ||
    fail "$name: the warnings differ"
}
count() { grep -c -- "$1" "$2" || true; }

pendulum=$src/examples/pendulum.yaml
incline=$src/examples/example-8.3-cylinder-incline.yaml
cylinder=$src/examples/example-8.1-cylinder.yaml
grid=(--sweep 'L=0.5 m:2 m:3' --sweep 'theta0=10 deg:70 deg:2' --quantity 'event(bottom)'
      --quantity 'min(ball_vx)' --quiet)

case $case_name in
simulate)
  same 2 sim_csv simulate "$pendulum" "${grid[@]}"
  same 2 sim_full simulate "$pendulum" "${grid[@]}" --precision full --jobs 2
  same 2 sim_json simulate "$pendulum" "${grid[@]}" --format json --jobs 1
  # --keep-runs: each rank writes its own points' files, the same as the serial run's.
  mkdir s m
  (cd s && "$cli" simulate "$pendulum" "${grid[@]}" --keep-runs runs >/dev/null) || fail "serial keep-runs"
  (cd m && mpi 2 simulate "$pendulum" "${grid[@]}" --keep-runs runs >/dev/null) || fail "mpirun keep-runs"
  [ "$(ls s/runs | wc -l)" -eq 12 ] || fail "keep-runs: not 12 files"
  diff -r s/runs m/runs || fail "keep-runs: the files differ"
  ;;
solve)
  for fmt in csv json; do
    "$cli" solve "$incline" --sweep 'theta=10 deg:50 deg:5' --format "$fmt" --quiet \
      -o "serial.$fmt" || fail "serial solve $fmt"
    mpi 2 solve "$incline" --sweep 'theta=10 deg:50 deg:5' --format "$fmt" --quiet \
      -o "mpi.$fmt" || fail "mpirun solve $fmt"
    cmp "serial.$fmt" "mpi.$fmt" || fail "solve $fmt: the tables differ"
  done
  same 2 solve_stdout solve "$incline" --sweep 'theta=10 deg:50 deg:5' --quiet
  # A value that cannot be solved (R <= 0 at the second value) stops the sweep with the serial
  # message, printed once.
  "$cli" solve "$incline" --sweep 'R=0.1 m:-0.1 m:3' --quiet >/dev/null 2>serial.err
  s=$?
  mpi 2 solve "$incline" --sweep 'R=0.1 m:-0.1 m:3' --quiet >/dev/null 2>mpi.err
  m=$?
  [ "$s" -eq 2 ] && [ "$m" -eq 2 ] || fail "solve of a bad value: exit $s serially, $m under mpirun"
  [ "$(count 'chasles: error' mpi.err)" -eq 1 ] || fail "solve of a bad value: not one error line"
  diff <(grep 'chasles: error' serial.err) <(grep 'chasles: error' mpi.err) ||
    fail "solve of a bad value: another message"
  ;;
mass)
  for fmt in text json; do  # text: a sweep's CSV table
    "$cli" mass "$cylinder" --sweep 'R=2 cm:8 cm:4' --sweep 'ratio=0.2:0.8:3' --quantity Izz \
      --quantity center_of_mass_z --format "$fmt" --quiet -o "serial.$fmt" || fail "serial mass $fmt"
    mpi 2 mass "$cylinder" --sweep 'R=2 cm:8 cm:4' --sweep 'ratio=0.2:0.8:3' --quantity Izz \
      --quantity center_of_mass_z --format "$fmt" --quiet -o "mpi.$fmt" || fail "mpirun mass $fmt"
    cmp "serial.$fmt" "mpi.$fmt" || fail "mass $fmt: the tables differ"
  done
  ;;
failed_point)
  # theta0 = 0: the ball hangs still and 'bottom' never fires; r <= 0: no sphere. Rows with
  # their reasons, as serially; each warning printed once.
  same 2 sim_failed simulate "$pendulum" --sweep 'theta0=0 deg:30 deg:3' \
    --sweep 'r=-0.05 m:0.05 m:3' --quantity 'event(bottom)' --until 2 --quiet
  same 3 sim_failed_json simulate "$pendulum" --sweep 'theta0=0 deg:30 deg:3' \
    --sweep 'r=-0.05 m:0.05 m:3' --quantity 'event(bottom)' --until 2 --quiet --format json
  same 2 mass_failed mass "$cylinder" --sweep 'R=-2 cm:8 cm:4' --quantity Izz --quiet
  [ "$(count ',error' sim_failed.mpi)" -eq 1 ] || fail "no error column"
  # 3 x 3 points: r <= 0 fails at each theta0 (6), and theta0 = 0 with r > 0 never fires (1).
  [ "$(count 'warning' sim_failed.mpi.err)" -eq 7 ] || fail "not 7 warnings: $(cat sim_failed.mpi.err)"
  ;;
bad_scene)
  printf 'chasles: 1\nparameters: {a: 1 m}\nbodies: [{name: b, parts: [{shape: nope}]}]\n' >bad.yaml
  mpi 2 simulate bad.yaml --sweep 'a=1 m:2 m:3' --quantity t_end >out.txt 2>err.txt
  m=$?
  [ "$m" -eq 2 ] || fail "bad scene: exit $m, not 2"
  [ "$(count 'chasles: error' err.txt)" -eq 1 ] || fail "bad scene: not one error line: $(cat err.txt)"
  grep -q 'bad.yaml' err.txt || fail "bad scene: the message does not name the file"
  [ ! -s out.txt ] || fail "bad scene: something on standard output"
  mpi 3 mass bad.yaml --sweep 'a=1 m:2 m:3' --quantity mass >out.txt 2>err.txt
  m=$?
  [ "$m" -eq 2 ] || fail "bad scene (mass): exit $m, not 2"
  [ "$(count 'chasles: error' err.txt)" -eq 1 ] || fail "bad scene (mass): not one error line"
  # A bad option: one message too.
  mpi 2 simulate "$pendulum" --sweep 'L=1 m:2 m:2' --quantity t_end --no-such-option \
    >out.txt 2>err.txt
  m=$?
  [ "$m" -eq 2 ] || fail "bad option: exit $m, not 2"
  [ "$(count 'no-such-option' err.txt)" -eq 1 ] || fail "bad option: not one message: $(cat err.txt)"
  ;;
more_ranks)
  # More ranks than points: the ranks without a point send an empty part.
  same 4 few simulate "$pendulum" --sweep 'L=0.5 m:1 m:2' --quantity 'event(bottom)' --quiet
  same 3 few_solve solve "$incline" --sweep 'theta=10 deg:50 deg:2' --quiet
  # A command other than a sweep runs once, on rank 0.
  same 2 one_report mass "$cylinder"
  ;;
no_plugin)
  # Started as if by mpirun (its environment) but without the plugin: refused, exit 2.
  OMPI_COMM_WORLD_SIZE=2 OMPI_COMM_WORLD_RANK=0 CHASLES_MPI_PLUGIN=$work/none.so \
    "$cli" mass "$cylinder" >out.txt 2>err.txt
  m=$?
  [ "$m" -eq 2 ] || fail "no plugin: exit $m, not 2"
  grep -q 'MPI plugin' err.txt || fail "no plugin: no message: $(cat err.txt)"
  [ ! -s out.txt ] || fail "no plugin: a report was written"
  # A single process (mpirun -np 1, or none) needs no plugin.
  OMPI_COMM_WORLD_SIZE=1 CHASLES_MPI_PLUGIN=$work/none.so "$cli" mass "$cylinder" >out.txt ||
    fail "one process: needed the plugin"
  ;;
*)
  echo "unknown case $case_name"
  exit 1
  ;;
esac
if [ "$failures" -eq 0 ]; then
  echo "$case_name: passed"
  exit 0
fi
echo "$case_name: $failures failed"
exit 1
