#!/usr/bin/env bash
# Conjugate gradient iterations of Contact/Solver = iterative per contact
# iteration as the mesh is refined globally, beside the direct solver's
# wall time and peak memory, and the largest relative difference of the
# probes' w and q between the two (iterative_contact_solver.h).
# Three scenes: the paper's example 2 on a tensionless half-space (Galerkin,
# active set), a thin concrete slab (t = 0.1 m) on the flexible square,
# bonded, and the near-rigid disk under an eccentric point load (e = 0.4 a,
# tensionless, part of it lifts off; from 2 initial refinements, one level
# fewer than the others). Whole plates (Symmetry = none). The dense
# direct path bounds the sizes (n up to about 5000 at 2 refinements).
# usage: bash benchmarks/iterative_contact_iterations.sh [build/plate-on-halfspace] [max refinements]
set -euo pipefail
cd "$(dirname "$0")/.."
program=${1:-build/plate-on-halfspace}
max=${2:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() { # name scene first-refinement last-refinement extra-entries
  local name=$1 scene=$2 first=$3 last=$4 extra=$5
  echo "== $name"
  for r in $(seq "$first" "$last"); do
    for solver in direct iterative; do
      cat >"$work/$solver.prm" <<PRM
include parameters/$scene
set Output directory = $work/out-$solver
subsection Discretization
  set Initial refinements = $r
  set Symmetry = none
end
subsection Contact
  set Solver = $solver
end
subsection Adaptivity
  set Cycles = 1
end
subsection Output
  set VTU = false
  set Verbosity = 1
end
subsection Verification
  set Checks =
end
$extra
PRM
      /usr/bin/time -f "%e s, %M kB" "$program" "$work/$solver.prm" \
        >"$work/$solver.log" 2>&1
    done
    python3 - "$work" "$r" <<'PY'
import json, re, sys
work, r = sys.argv[1], sys.argv[2]
log = open(f"{work}/iterative.log").read()
n = re.search(r"(\d+) foundation nodes", log).group(1)
cg = re.findall(r"conjugate gradients (\d+) iterations", log)
times = {s: open(f"{work}/{s}.log").read().strip().splitlines()[-1]
         for s in ("direct", "iterative")}
a = json.load(open(f"{work}/out-direct/summary.json"))["cycles"][-1]
b = json.load(open(f"{work}/out-iterative/summary.json"))["cycles"][-1]
d = max(abs(p[k] - q[k]) / abs(p[k])
        for p, q in zip(a["probes"], b["probes"]) for k in ("w", "q")
        if p[k] != 0)
print(f"refinements {r}: n = {n}, CG iterations per contact iteration "
      f"{','.join(cg)}; contact iterations {a['contact_iterations']} / "
      f"{b['contact_iterations']}, nodes in contact {a['contact_nodes']} / "
      f"{b['contact_nodes']}; direct {times['direct']}; iterative "
      f"{times['iterative']}; probes differ by {d:.1e}")
PY
  done
}

run "example 2, tensionless, Galerkin + active set" example2.prm 0 "$max" \
  "subsection Discretization
  set Flexibility = galerkin
end
subsection Contact
  set Method = active set
end"
run "thin slab (t = 0.1 m, E = 30 GPa) on the flexible square, bonded" \
  flexible-square.prm 0 "$max" "subsection Plate
  set Thickness = 0.1
  set Young's modulus = 3e7
end
subsection Discretization
  set Flexibility = galerkin
  set Subdivisions x = 8
  set Subdivisions y = 8
end"
run "rigid disk, point load at e = 0.4 a, tensionless" rigid-disk.prm 2 $((1 + max)) \
  "subsection Foundation
  set Contact = tensionless
end
subsection Loads
  set Point loads = 0.4,0,1000
end"
