#!/usr/bin/env bash
# The same scene gives the same numbers: parameters/example2.prm
# made Galerkin + active set (tensionless, lift-off) run twice with one
# thread and once with two (deal.II's DEAL_II_NUM_THREADS and OpenBLAS's
# OPENBLAS_NUM_THREADS); every number of summary.json except the wall times (*time_s)
# must agree to 1e-12 relative to the largest value of its kind (all
# moments for a moment, all deflections for a deflection; the measures that
# are relative already, like complementarity_violation, as they are), the
# peaks' locations (max_Mx_at, ...) to 1e-9 of the largest coordinate.
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
worst, worst_tolerance, worst_key = 0.0, 1e-12, ""
for key, a in runs["one_a"].items():
    # scale: the largest magnitude among the values of the same kind (a
    # field's minimum is judged against the field's size: min_My against
    # all moments, min_w against all deflections)
    # (a peak's location, max_Mx_at/0 and /1, against all peak coordinates)
    def kind(k):
        parts = k.split("/")
        if len(parts) > 1 and parts[-2].endswith("_at"):
            return "at"
        # a probe's [sxx, syy, sxy] and the stress peaks against all stresses
        if len(parts) > 1 and parts[-2] in ("stress_bottom", "stress_top"):
            return "stress"
        name = parts[-1]
        name = name[4:] if name[:4] in ("max_", "min_") else name
        if name.startswith("principal_stress"):
            return "stress"
        return "M" if name in ("Mx", "My", "principal_moment") else name
    scale = max(abs(v) for k, v in runs["one_a"].items() if kind(k) == kind(key)) or 1.0
    # measures that are relative already (rounding-level residuals and
    # condition estimates) are compared as they are
    if key.split("/")[-1] in ("complementarity_violation", "max_penetration",
                     "coupled_matrix_rcond", "foundation_block_rcond"):
        scale = 1.0
    # a peak's location is where the field's gradient vanishes: rounding in
    # the gradient moves it by rounding over the curvature (1e-11 of the
    # plate where a field is flat), so locations agree to 1e-9
    tolerance = 1e-9 if kind(key) == "at" else 1e-12
    for other in ("one_b", "two"):
        d = abs(runs[other][key] - a) / scale
        if d / tolerance > worst / worst_tolerance:
            worst, worst_tolerance, worst_key = d, tolerance, key + " (" + other + ")"
print("largest relative difference over %d numbers: %.1e (tolerance %.0e)"
      % (len(runs["one_a"]), worst, worst_tolerance))
if worst > 0: print("  at " + worst_key)
sys.exit(0 if worst <= worst_tolerance else 1)
PYTHON
