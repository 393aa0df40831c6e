#!/usr/bin/env bash
# The same slab on the two foundation models, mesh by mesh: a pavement slab
# (4.5 m x 3.6 m x 0.25 m, self weight, a tyre at the edge) on a
# tensionless dense liquid (k = 50 MPa/m) and on the half-space with the
# equivalent modulus of doc/formulation.md ("Dense-liquid foundation":
# E0 from the same radius of relative stiffness). Prints, per mesh, the
# foundation nodes of the whole plate, the phases and total of each model
# and the ratio half-space / dense liquid. The half-space rows stop at
# --max-halfspace refinements (its cost grows like n log n with the
# hierarchical storage, several minutes at 10^5 nodes).
# usage: bash benchmarks/dense_liquid.sh [build/plate-on-halfspace]
#        [max refinements] [max half-space refinements]
set -euo pipefail
cd "$(dirname "$0")/.."
program=${1:-build/plate-on-halfspace}
max=${2:-5}
max_halfspace=${3:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() { # refinements, foundation lines; prints "nodes build solve total"
  cat >"$work/scene.prm" <<PRM
set Output directory = $work/out
subsection Plate
  set Length x        = 4.5
  set Length y        = 3.6
  set Thickness       = 0.25
  set Young's modulus = 3e7
  set Poisson's ratio = 0.15
  set Unit weight     = 24
end
subsection Foundation
$2
  set Contact = tensionless
end
subsection Loads
  set Circular patches = 0,1.6,0.15,700
end
subsection Discretization
  set Subdivisions x      = 6
  set Subdivisions y      = 5
  set Initial refinements = $1
  set Symmetry            = none
end
subsection Output
  set VTU       = false
  set Verbosity = 2
end
PRM
  "$program" "$work/scene.prm" >"$work/log"
  phase() { grep "| $1" "$work/log" | awk -F'|' '{gsub(/s/,"",$4); print $4+0}'; }
  nodes=$(grep -o "[0-9]* foundation nodes" "$work/log" | head -1 | cut -d' ' -f1)
  total=$(grep "Total wallclock" "$work/log" | awk -F'|' '{gsub(/s/,"",$3); print $3+0}')
  echo "$nodes $(phase 'build foundation') $(phase 'contact solve') $total"
}

dense_liquid="  set Model = dense liquid
  set Modulus of subgrade reaction = 5e4"
# l^4 = D/k (dense liquid) and l^3 = 2 D (1 - nu0^2)/E0 (half-space) equal:
# E0 = 2 D (1 - nu0^2)/l^3 with l = (D/k)^(1/4), D = 39962 kNm, nu0 = 0.35.
half_space="  set Young's modulus = 82970
  set Poisson's ratio = 0.35"

printf "%8s | %9s %9s %9s | %9s %9s %9s | %8s\n" nodes "k build" "k solve" \
  "k total" "E0 build" "E0 solve" "E0 total" "ratio"
for r in $(seq 2 "$max"); do
  read -r n kb ks kt <<<"$(run "$r" "$dense_liquid")"
  if [ "$r" -le "$max_halfspace" ]; then
    read -r _ hb hs ht <<<"$(run "$r" "$half_space")"
    ratio=$(awk -v a="$ht" -v b="$kt" 'BEGIN{printf "%.0f", a/b}')
  else
    hb=- hs=- ht=- ratio=-
  fi
  printf "%8d | %9s %9s %9s | %9s %9s %9s | %8s\n" "$n" "$kb" "$ks" "$kt" \
    "$hb" "$hs" "$ht" "$ratio"
done
