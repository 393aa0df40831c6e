#!/usr/bin/env bash
# Storage = auto on two MPI processes when the fft storage does not fit
# the memory (doc/parallel.md, "The fft storage on several processes"):
# the ranks on one machine add their needs and all ranks decide alike, so
# every rank takes the hierarchical storage (one warning, no hang, no
# MPI_Abort) and the run ends with the serial dense answer. The limit
# PLATE_ON_HALFSPACE_MEMORY_LIMIT = 18M lies between one rank's needs and
# the two ranks' together (at most 14 and 26 MiB on 3201 nodes: near
# field, far-field gridding and soil inverse): a check per rank would have
# let fft through. Each rank gets a different limit in a
# second run (MPMD), so that a decision per rank would split them.
# usage: mpi_fft_memory_fallback.sh PROGRAM SCENE_DIRECTORY TEST_DIRECTORY
set -u
program=$1
scenes=$2
scripts=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
if [ "$(id -u)" = 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
status=0
scene() { # output directory
  cat <<PRM
include $scenes/example2.prm
set Output directory = $1
subsection Discretization
  set Flexibility    = galerkin
  set Subdivisions x = 64
  set Subdivisions y = 64
end
subsection Contact
  set Method = active set
  set Solver = auto
end
subsection Foundation operator
  set Storage = auto
end
subsection Adaptivity
  set Cycles = 1
end
subsection Output
  set VTU       = false
  set Verbosity = 0
end
subsection Verification
  set Checks = contact_force,10776.96,1e-8 ; max_w,0.014742348335,1e-5
end
PRM
}
check() { # name, exit status, log, output directory
  local storage warnings
  storage=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['cycles'][-1]['foundation_storage'])" "$4/summary.json" 2>/dev/null)
  warnings=$(grep -c "does not fit" "$3")
  if [ "$2" = 0 ] && [ "$storage" = hierarchical ] && [ "$warnings" = 1 ] &&
    ! grep -q "FAILED" "$3"; then
    echo "$1: exit 0, storage $storage, $warnings warning: ok"
  else
    echo "$1: exit $2, storage '$storage', $warnings warnings: FAILED"
    cat "$3"
    status=1
  fi
}
scene same >same.prm
PLATE_ON_HALFSPACE_MEMORY_LIMIT=18M timeout 600 mpirun -np 2 "$program" same.prm >same.log 2>&1
check "the same limit on both ranks" $? same.log same
scene split >split.prm
timeout 600 mpirun -np 1 -x PLATE_ON_HALFSPACE_MEMORY_LIMIT=18M "$program" split.prm : \
  -np 1 -x PLATE_ON_HALFSPACE_MEMORY_LIMIT=1G "$program" split.prm >split.log 2>&1
check "18M on rank 0, 1G on rank 1" $? split.log split
exit $status
