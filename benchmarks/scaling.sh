#!/usr/bin/env bash
# Timings of the phases of one solve as the mesh grows, and the ratios that
# tell how each phase scales with the number n of foundation nodes: the
# dense Galerkin assembly ~ n^2, the dense factorisation ~ n^3, the
# condensation of the sparse plate (CHOLMOD, blocked solves) ~ n^1.5-2;
# the contact solver condenses the plate and factorises, so its phase holds
# both.
# Scene: parameters/rigid-disk.prm (galerkin, bonded), globally refined.
# usage: bash benchmarks/scaling.sh [build/plate-on-halfspace] [max refinements]
set -euo pipefail
cd "$(dirname "$0")/.."
program=${1:-build/plate-on-halfspace}
max=${2:-4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf "%6s %6s %10s %10s %10s %10s %10s\n" cells nodes "plate" build contact total "total/n^2"
previous=""
for r in $(seq 1 "$max"); do
  cat >"$work/scene.prm" <<PRM
include parameters/rigid-disk.prm
set Output directory = $work/out
subsection Discretization
  set Initial refinements = $r
end
subsection Adaptivity
  set Cycles = 1
end
subsection Verification
  set Checks =
end
subsection Output
  set VTU = false
  set Verbosity = 2
end
PRM
  "$program" "$work/scene.prm" >"$work/log"
  phase() { grep "| $1" "$work/log" | awk -F'|' '{gsub(/s/,"",$4); print $4+0}'; }
  cells=$(grep -o "[0-9]* cells" "$work/log" | head -1 | cut -d' ' -f1)
  nodes=$(grep -o "[0-9]* foundation nodes" "$work/log" | head -1 | cut -d' ' -f1)
  total=$(grep "Total wallclock" "$work/log" | awk -F'|' '{gsub(/s/,"",$3); print $3+0}')
  printf "%6d %6d %10.3f %10.3f %10.3f %10.3f %10.2e\n" "$cells" "$nodes" \
    "$(phase 'plate setup')" "$(phase 'build foundation')" \
    "$(phase 'contact solve')" "$total" \
    "$(awk -v t="$total" -v n="$nodes" 'BEGIN{print t/(n*n)}')"
done
