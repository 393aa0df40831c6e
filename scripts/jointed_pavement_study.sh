#!/usr/bin/env bash
# The jointed pavement of parameters/jointed-pavement{,-half-space}.prm:
# runs both scenes, prints one row per scene (the largest bottom and top
# stress with where they are, the contact area, the loaded joint's LTE
# and largest dowel force, the time) and draws, with gnuplot, the contact
# maps and the stress profiles along the wheel path y = 1.8 into
# output/jointed-pavement-study/.
# usage: bash scripts/jointed_pavement_study.sh [build/plate-on-halfspace]
set -euo pipefail
cd "$(dirname "$0")/.."
program=${1:-build/plate-on-halfspace}
scenes="jointed-pavement jointed-pavement-half-space"
mkdir -p output/jointed-pavement-study
printf "| scene | max s1 bottom [kPa] at | max s1 top [kPa] at | contact area | LTE of x = 2.25 | largest dowel force [kN] | time [s] |\n"
printf "|---|---|---|---|---|---|---|\n"
for scene in $scenes; do
  start=$(date +%s.%N)
  "$program" "parameters/$scene.prm" >"output/jointed-pavement-study/$scene.log"
  end=$(date +%s.%N)
  python3 - "$scene" "$start" "$end" <<'PY'
import json, sys
scene, start, end = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
c = json.load(open("output/%s/summary.json" % scene))["cycles"][-1]
at = lambda p: "(%.2f, %.2f)" % tuple(p)
joint = [j for j in c["joints"] if j["kind"] == "transverse" and j["x1"] == 2.25 and j["y1"] == 0][0]
print("| %s | %.0f %s | %.0f %s | %.3f | %.3f | %.2f | %.1f |" % (
    scene, c["max_principal_stress_bottom"], at(c["max_principal_stress_bottom_at"]),
    c["max_principal_stress_top"], at(c["max_principal_stress_top_at"]),
    c["contact_area_fraction"], joint["lte"] if joint["lte"] is not None else float("nan"),
    joint["max_dowel_force"], end - start))
PY
done
last=$(python3 -c 'import json; print("%02d" % json.load(open("output/jointed-pavement/summary.json"))["cycles"][-1]["cycle"])')
gnuplot -e "last='$last'" scripts/jointed_pavement_figures.gp
echo "figures: output/jointed-pavement-study/contact-maps.png output/jointed-pavement-study/stress-profiles.png"
