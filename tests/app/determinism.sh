#!/usr/bin/env bash
# The same scene gives the same numbers: parameters/example2.prm
# made Galerkin + active set (tensionless, lift-off) run twice with one
# thread and once with two (deal.II's DEAL_II_NUM_THREADS and OpenBLAS's
# OPENBLAS_NUM_THREADS); every number of summary.json except the wall times (*time_s)
# must agree to 1e-12 relative to the largest value of its kind (all
# moments for a moment, all deflections for a deflection; the measures that
# are relative already, like complementarity_violation, as they are).
# usage: determinism.sh PROGRAM SCENE_DIRECTORY
set -u
program=$1
scenes=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
for run in one_a one_b two; do
  threads=1
  [ $run = two ] && threads=2
  printf 'include %s/example2.prm\nset Output directory = %s\nsubsection Discretization\n  set Flexibility = galerkin\nend\nsubsection Contact\n  set Method = active set\nend\nsubsection Output\n  set VTU = false\n  set Verbosity = 0\nend\n' "$scenes" "$run" >$run.prm
  DEAL_II_NUM_THREADS=$threads OPENBLAS_NUM_THREADS=$threads "$program" $run.prm ||
    { echo "FAILED: run $run"; exit 1; }
done
python3 - <<'PYTHON'
import json, sys
def numbers(node, path=""):
    if isinstance(node, dict):
        for k, v in node.items():
            if not k.endswith("time_s"):
                yield from numbers(v, path + "/" + k)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from numbers(v, path + "/" + str(i))
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield path, float(node)
runs = {r: dict(numbers(json.load(open(r + "/summary.json")))) for r in ("one_a", "one_b", "two")}
worst, worst_key = 0.0, ""
for key, a in runs["one_a"].items():
    # scale: the largest magnitude among the values of the same kind (a
    # field's minimum is judged against the field's size: min_My against
    # all moments, min_w against all deflections)
    def kind(k):
        name = k.split("/")[-1]
        name = name[4:] if name[:4] in ("max_", "min_") else name
        return "M" if name in ("Mx", "My") else name
    scale = max(abs(v) for k, v in runs["one_a"].items() if kind(k) == kind(key)) or 1.0
    # measures that are relative already (rounding-level residuals and
    # condition estimates) are compared as they are
    if key.split("/")[-1] in ("complementarity_violation", "max_penetration",
                     "coupled_matrix_rcond", "foundation_block_rcond"):
        scale = 1.0
    for other in ("one_b", "two"):
        d = abs(runs[other][key] - a) / scale
        if d > worst: worst, worst_key = d, key + " (" + other + ")"
print("largest relative difference over %d numbers: %.1e" % (len(runs["one_a"]), worst))
if worst > 0: print("  at " + worst_key)
sys.exit(0 if worst <= 1e-12 else 1)
PYTHON
