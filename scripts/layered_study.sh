#!/usr/bin/env bash
# The layered scenes of parameters/ against the soils a user would put in
# their place (doc/study.md, "Layered soils"): for each scene, the layered
# run, the homogeneous half-space of its deepest layer's material (the
# layering ignored), and the half-space and the dense liquid with the same
# radius of relative stiffness l as the layers (the program logs l and D).
# The derived scenes include the layered one and replace its Foundation;
# they are written to output/layered-study/. Prints one markdown row per
# run: the peak fibre stresses with where they are, the contact area, the
# settlement range and the time.
# usage: bash scripts/layered_study.sh [build/plate-on-halfspace] [scenes...]
set -euo pipefail
cd "$(dirname "$0")/.."
program=${1:-build/plate-on-halfspace}
shift || true
scenes=${*:-pavement-on-layers raft-on-clay}
study=output/layered-study
mkdir -p "$study"

run() { # scene file, label, output directory: runs it and prints its row
  local start end
  start=$(date +%s.%N)
  "$program" "$1" >"$study/$2.log"
  end=$(date +%s.%N)
  python3 - "$3" "$2" "$start" "$end" <<'PY'
import json, sys
directory, label, start, end = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
summary = json.load(open(directory + "/summary.json"))
c = summary["cycles"][-1]
at = lambda p: "(%.2f, %.2f)" % tuple(p)
print("| %s | %.0f %s | %.0f %s | %.3f | %.2f | %.2f | %.1f |" % (
    label, c["max_principal_stress_bottom"], at(c["max_principal_stress_bottom_at"]),
    c["max_principal_stress_top"], at(c["max_principal_stress_top_at"]),
    c["contact_area_fraction"], 1e3 * c["min_w"], 1e3 * c["max_w"], end - start))
PY
}

derive() { # scene, label, foundation lines: writes the derived scene
  cat >"$study/$2.prm" <<PRM
include parameters/$1.prm
set Output directory = $study/$2
subsection Foundation
  set Layers     =
  set Base       = half-space
  set Interfaces = bonded
$3
end
PRM
}

printf "| run | max s1 bottom [kPa] at | max s1 top [kPa] at | contact area | min w [mm] | max w [mm] | time [s] |\n"
printf "|---|---|---|---|---|---|---|\n"
for scene in $scenes; do
  run "parameters/$scene.prm" "$scene" "output/$scene"
  read -r l D < <(sed -n "s/.*: l = \([^ ]*\) for the plate's D = \([^ ]*\) .*/\1 \2/p" \
    "$study/$scene.log" | head -1)
  read -r E_deep nu_deep < <(sed -n 's/^ *set Layers *= *//p' "parameters/$scene.prm" |
    awk -F';' '{n = split($NF, f, ","); print f[2] + 0, f[3] + 0}')
  # The same l: l^4 = D/k for the dense liquid, l^3 = 2 D (1 - nu0^2)/E0
  # for the half-space (doc/soil-models.md); only E0/(1 - nu0^2) matters
  # to the plate, so nu0 = 0.35 is no choice.
  read -r k E0 < <(awk -v l="$l" -v D="$D" \
    'BEGIN { printf "%.6g %.6g\n", D / l^4, 2 * D * (1 - 0.35^2) / l^3 }')
  derive "$scene" "$scene-deepest-half-space" "  set Model = half-space
  set Young's modulus = $E_deep
  set Poisson's ratio = $nu_deep"
  derive "$scene" "$scene-same-l-half-space" "  set Model = half-space
  set Young's modulus = $E0
  set Poisson's ratio = 0.35"
  derive "$scene" "$scene-same-l-dense-liquid" "  set Model = dense liquid
  set Modulus of subgrade reaction = $k"
  for variant in deepest-half-space same-l-half-space same-l-dense-liquid; do
    run "$study/$scene-$variant.prm" "$scene-$variant" "$study/$scene-$variant"
  done
  echo "<!-- $scene: l = $l, D = $D; same l: E0 = $E0 (nu0 = 0.35), k = $k;" \
    "deepest layer E = $E_deep, nu = $nu_deep -->"
done
