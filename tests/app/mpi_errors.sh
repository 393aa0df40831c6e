#!/usr/bin/env bash
# Errors on several processes. More MPI processes than the mesh can share
# (doc/parallel.md): every rank
# stops alike with one "Error:" line naming Discretization/Subdivisions,
# exit status 1, no MPI_Abort and no crash, and the earlier results in the
# output directory stay as they were. Scenes: one cell on 2 and 4
# processes, 2 x 1 cells (one cell of the quarter computed) on 4
# (rectangle, dense liquid, hierarchical storage), and a disk (3 cells of
# the quarter computed) on 16 processes (--oversubscribe). Then bad
# scenes that every rank finds alike after reading, and
# Contact/Nested start on 2 processes, where the mesh one refinement
# coarser has cells enough and where it has not.
# usage: mpi_errors.sh PROGRAM TESTS_APP_DIRECTORY
set -u
program=$1
here=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
cp "$here/bad_input_base.prm" base.prm
export OMPI_MCA_rmaps_base_oversubscribe=1
if [ "$(id -u)" = 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
passed=0
failed=0
fail() { echo "FAILED: $*"; failed=$((failed + 1)); }

# The earlier results every refused run must leave alone.
"$program" base.prm >base.log 2>&1 || { fail "the valid base scene"; cat base.log; }
snapshot() { (cd results && find . -type f -exec md5sum {} + | sort); }
snapshot >before.md5

scene() { # name, then the lines after "include base.prm"
  local name=$1
  shift
  { echo "include base.prm"; printf '%s\n' "$@"; } >"$name.prm"
}
scene one_cell "subsection Discretization" "set Subdivisions x = 1" \
  "set Subdivisions y = 1" "end"
scene two_cells "subsection Discretization" "set Subdivisions x = 2" \
  "set Subdivisions y = 1" "end"
scene two_cells_dense_liquid "subsection Foundation" "set Model = dense liquid" \
  "set Modulus of subgrade reaction = 5e4" "end" \
  "subsection Discretization" "set Subdivisions x = 2" "set Subdivisions y = 1" "end"
scene two_cells_hierarchical "subsection Foundation operator" \
  "set Storage = hierarchical" "end" "subsection Contact" \
  "set Solver = iterative" "end" "subsection Discretization" \
  "set Subdivisions x = 2" "set Subdivisions y = 1" "end"
scene disk "subsection Plate" "set Shape = disk" "set Radius = 1" "end"

check() { # scene, processes
  local name=$1 p=$2
  timeout 300 mpirun -np "$p" "$program" "$name.prm" >stdout 2>stderr
  local status=$?
  local errors
  errors=$(grep -c '^Error' stderr)
  if [ $status -ne 1 ]; then
    fail "$name on $p processes: exit status $status (1 expected)"; cat stderr
  elif [ "$errors" -ne 1 ] ||
       ! grep -q "^Error: More MPI processes than the mesh can share: $p processes for" stderr ||
       ! grep -q 'Discretization/Subdivisions x and y' stderr; then
    fail "$name on $p processes: not one 'Error: More MPI processes ...' line"; cat stderr
  elif grep -q 'MPI_ABORT\|bad_array\|terminate called\|Signal' stderr; then
    fail "$name on $p processes: aborted or crashed"; cat stderr
  elif ! snapshot | cmp -s - before.md5 || [ -e results/previous-run ] ||
       [ -e results/failed-run ]; then
    fail "$name on $p processes: the earlier results changed"
  else
    echo "$name on $p processes: $(grep '^Error' stderr)"
    passed=$((passed + 1))
  fi
}
check one_cell 2
check one_cell 4
check two_cells 4
check two_cells_dense_liquid 4
check two_cells_hierarchical 4
check disk 16

# Two processes on two cells (no symmetry cut) still run; the mpi_* tests
# check that they give the serial answer.
scene two_cells_whole "subsection Discretization" "set Subdivisions x = 2" \
  "set Subdivisions y = 1" "set Symmetry = none" "end"
if mpirun -np 2 "$program" two_cells_whole.prm >stdout 2>stderr; then
  passed=$((passed + 1))
else
  fail "two_cells on 2 processes must run"; cat stderr
fi

# Errors that every rank meets alike without being thrown as such (doc/
# parallel.md, "Choices and their reasons"): bad scenes of the table
# found after reading (a load off the plate, a scene not symmetric, a
# slab without load) and a matrix refused during the solve. Every rank
# fails at the same point: one "Error:" line, exit status 1, no MPI_Abort,
# the earlier results kept.
snapshot >before.md5 # two_cells_whole wrote new results
for name in axle_off_plate point_load_off_plate pressure_function_symmetry \
  unloaded_slab_weightless cells_too_elongated_for_quadrature; do
  cp "$here/bad_input/$name.prm" .
  timeout 300 mpirun -np 2 "$program" "$name.prm" >stdout 2>stderr
  status=$?
  if [ $status -ne 1 ] || [ "$(grep -c '^Error' stderr)" -ne 1 ] ||
     ! grep -q '^Error: ' stderr ||
     grep -q 'MPI_ABORT\|Error (rank\|terminate called\|Signal' stderr; then
    fail "$name on 2 processes: status $status, not one 'Error:' line"; cat stderr
  elif ! snapshot | cmp -s - before.md5; then
    fail "$name on 2 processes: the earlier results changed"
  else
    echo "$name on 2 processes: $(grep '^Error' stderr | cut -c1-60)"
    passed=$((passed + 1))
  fi
done

# Contact/Nested start on several processes: it applies where the mesh
# one refinement coarser has cells enough for them, and where it has not
# (one cell on 2 processes) the run starts without it, with a warning.
nested() { # name, subdivisions, initial refinements
  scene "$1" "subsection Foundation" "set Contact = tensionless" "end" \
    "subsection Contact" "set Method = active set" "set Nested start = true" \
    "end" "subsection Discretization" "set Subdivisions x = $2" \
    "set Subdivisions y = $2" "set Initial refinements = $3" \
    "set Symmetry = none" "end" "subsection Output" "set Verbosity = 1" "end"
}
nested nested_applies 2 2
nested nested_too_coarse 1 1
applied() {
  mpirun -np 2 "$program" nested_applies.prm >stdout 2>stderr &&
    grep -q '^Contact/Nested start: 65 foundation nodes one refinement coarser (seeded in turn)' stdout &&
    ! grep -q 'Warning' stderr
}
skipped_with_warning() {
  mpirun -np 2 "$program" nested_too_coarse.prm >stdout 2>stderr &&
    grep -q '^Warning: Contact/Nested start = true: the mesh one refinement coarser has too few cells for the processes; the first cycle starts without it' stderr &&
    ! grep -q '^Contact/Nested start: ' stdout
}
for outcome in applied skipped_with_warning; do
  if $outcome; then
    echo "nested start on 2 processes: $outcome"
    passed=$((passed + 1))
  else
    fail "nested start on 2 processes: not $outcome"; cat stdout stderr
  fi
done

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
