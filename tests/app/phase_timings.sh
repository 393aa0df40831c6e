#!/usr/bin/env bash
# Output/Verbosity = 2 prints the wall time of each phase (deal.II's
# TimerOutput, doc/parameters.md). With Contact/Nested start the coarser
# meshes' plate setups, operators and contact solves belong to the
# nested start's own section, so that each phase's row counts the meshes
# the cycles solve: one contact solve and one operator per cycle, one plate
# setup per cycle. Example 2 (dense storage, iterative solver, 6 x 6 cells
# refined twice, two cycles), with the nested start and without.
# usage: phase_timings.sh PROGRAM PARAMETER_DIRECTORY
set -u
program=$1
parameters=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failed=0
fail() { echo "FAILED: $*"; failed=$((failed + 1)); }

calls() { # log, section: its number of calls, or "none"
  local n
  n=$(sed -n "s/^| $2 *| *\([0-9]*\) |.*/\1/p" "$1")
  echo "${n:-none}"
}

for nested in true false; do
  cat >"$nested.prm" <<EOF
include $parameters/example2.prm
set Output directory = results-$nested
subsection Discretization
  set Flexibility         = galerkin
  set Subdivisions x      = 6
  set Subdivisions y      = 6
  set Initial refinements = 2
end
subsection Foundation operator
  set Storage = dense
end
subsection Contact
  set Method       = active set
  set Solver       = iterative
  set Nested start = $nested
end
subsection Adaptivity
  set Cycles = 2
end
subsection Output
  set VTU       = false
  set Verbosity = 2
end
EOF
  "$program" "$nested.prm" >"$nested.log" 2>"$nested.err"
  status=$?
  [ $status -eq 0 ] || { fail "Nested start = $nested: exit status $status"; cat "$nested.err"; continue; }
  expected_nested=$([ $nested = true ] && echo 1 || echo none)
  for check in "nested start:$expected_nested" "contact solve:2" \
               "build foundation operator:2" "plate setup:2"; do
    section=${check%:*}
    want=${check##*:}
    got=$(calls "$nested.log" "$section")
    if [ "$got" = "$want" ]; then
      echo "Nested start = $nested: '$section' calls $got: ok"
    else
      fail "Nested start = $nested: '$section' calls $got, expected $want"
    fi
  done
done
grep -q "Contact/Nested start: 133 foundation nodes" true.log ||
  fail "the nested start did not run on 133 nodes"

echo "$failed failed"
[ $failed -eq 0 ]
