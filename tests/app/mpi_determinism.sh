#!/usr/bin/env bash
# The same scene on 1, 2 and 4 MPI processes gives the same answer
# (doc/parallel.md): summary.json of each run against the one-process run
# by compare_summaries.py (same contact sets and counts, every number to
# the tolerance relative to its kind's scale).
#  - tensionless: parameters/example2.prm made Galerkin + active set with
#    the iterative solver (the plate by MUMPS over the ranks, the dense
#    flexibility), 1e-8;
#  - hierarchical: the same with the flexibility's rows split over the
#    ranks as H-matrices (Tolerance 1e-11) and block-Jacobi, 1e-8: the
#    difference is the compression's (1.2e-8 at 1e-10, 1.5e-9 at 1e-11).
#  - fft: the same with the split-kernel storage, each rank's near pairs
#    and far-field charges on that rank and the products summed over the
#    ranks, 1e-8: the same operator in another order of summation
#    (Tolerance 1e-8, so that the last solve stops at 1e-10 as the other
#    scenes' do, not at Tolerance / 100).
# The tensionless runs also write solution-00.vtu, the ranks' cells into
# one file together: compare_vtu.py finds each cell of the one-process file
# in it with the same values (Float32: 1e-6).
# Four processes share the two cores (--oversubscribe).
# usage: mpi_determinism.sh PROGRAM SCENE_DIRECTORY TEST_DIRECTORY
set -u
program=$1
scenes=$2
scripts=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
storage_of() {
  case $1 in
    tensionless) echo "set Storage = dense" ;;
    hierarchical) printf 'set Storage = hierarchical\n  set Tolerance = 1e-11' ;;
    fft) printf 'set Storage = fft\n  set Tolerance = 1e-8' ;;
  esac
}
vtu_of() {
  [ "$1" = tensionless ] && echo true || echo false
}
status=0
for scene in tensionless hierarchical fft; do
  for p in 1 2 4; do
    cat >$scene-$p.prm <<PRM
include $scenes/example2.prm
set Output directory = $scene-$p
subsection Discretization
  set Flexibility    = galerkin
  set Subdivisions x = 40
  set Subdivisions y = 40
end
subsection Contact
  set Method = active set
  set Solver = iterative
end
subsection Foundation operator
  $(storage_of $scene)
end
subsection Output
  set VTU       = $(vtu_of $scene)
  set Verbosity = 0
end
PRM
    mpirun --oversubscribe -np $p "$program" $scene-$p.prm >$scene-$p.log 2>&1 ||
      { echo "FAILED: $scene on $p processes"; cat $scene-$p.log; exit 1; }
  done
  for p in 2 4; do
    echo -n "$scene, $p processes against 1: "
    python3 "$scripts/compare_summaries.py" $scene-1/summary.json \
      $scene-$p/summary.json 1e-8 || status=1
    if [ "$(vtu_of $scene)" = true ]; then
      echo -n "$scene, $p processes against 1, solution-00.vtu: "
      python3 "$scripts/compare_vtu.py" $scene-1/solution-00.vtu \
        $scene-$p/solution-00.vtu 1e-6 || status=1
    fi
  done
done
exit $status
