#!/usr/bin/env bash
# Serial runs started together never collide in Open MPI's start-up
# (doc/parallel.md, "Serial runs"): BATCHES batches of 8 runs of the small
# base scene start at once, each into its own output directory, and
# /tmp/ompi.* is removed before each batch and, by a cleaner in the
# background, every 50 ms while the runs start, as a tmp cleaner or the last
# exiting Open MPI run does. Without the private session of a serial run,
# 32 of 80 such runs died in orte_init on a two-core machine. Every run
# must exit 0 and leave its summary.json. ctest runs this alone (RUN_SERIAL): the removal would break
# an mpirun test running beside it.
# usage: concurrent_serial_runs.sh PROGRAM TESTS_APP_DIRECTORY [BATCHES]
set -u
program=$1
here=$2
batches=${3:-40}
per_batch=8
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failed=0
private_dirs() {
  find "${TMPDIR:-/tmp}" -maxdepth 1 -name 'plate-on-halfspace-mpi.*' 2>/dev/null | sort
}
private_dirs >dirs-before
(while :; do rm -rf /tmp/ompi.* 2>/dev/null; sleep 0.05; done) &
cleaner=$!
trap 'kill $cleaner 2>/dev/null; rm -rf "$work"' EXIT
for b in $(seq 1 "$batches"); do
  rm -rf /tmp/ompi.* 2>/dev/null
  pids=()
  for i in $(seq 1 $per_batch); do
    printf 'include %s/bad_input_base.prm\nset Output directory = run-%s-%s\n' \
      "$here" "$b" "$i" >scene-$b-$i.prm
    "$program" scene-$b-$i.prm >log-$b-$i 2>&1 &
    pids+=($!)
    echo $! >>run-pids
  done
  for i in $(seq 1 $per_batch); do
    wait "${pids[$((i - 1))]}"
    status=$?
    if [ $status -ne 0 ] || [ ! -s run-$b-$i/summary.json ]; then
      failed=$((failed + 1))
      echo "FAILED: batch $b run $i: exit status $status"
      head -5 log-$b-$i
    fi
  done
  rm -rf run-$b-* log-$b-* scene-$b-*
done
kill $cleaner 2>/dev/null
total=$((batches * per_batch))
echo "$((total - failed)) passed, $failed failed ($total runs, $per_batch at a time)"
# No private session directory outlives its run (those of this test's runs:
# plate-on-halfspace-mpi.PID.XXXXXX, so that a run of the same user outside
# the test, still going, is not counted).
left=$(private_dirs | comm -13 dirs-before - |
  sed -n 's/.*plate-on-halfspace-mpi\.\([0-9]*\)\..*/\1/p' |
  grep -cFx -f run-pids)
if [ "$left" -ne 0 ]; then
  echo "FAILED: $left private Open MPI session directories left behind"
  failed=$((failed + 1))
fi
[ "$failed" -eq 0 ]
