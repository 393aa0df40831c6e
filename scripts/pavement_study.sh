#!/usr/bin/env bash
# The pavement slab of parameters/pavement-*.prm by day and by night, on
# the dense liquid and on the half-space with the same radius of relative
# stiffness: runs the four scenes, prints one row each (the peak fibre
# stresses with where they are, the contact area, the lift and the time)
# and draws, with gnuplot, the contact maps and the stress profiles across
# the slab through the tyre (x = 0) into output/pavement/.
# usage: bash scripts/pavement_study.sh [build/plate-on-halfspace]
set -euo pipefail
cd "$(dirname "$0")/.."
program=${1:-build/plate-on-halfspace}
scenes="pavement-day pavement-night pavement-day-half-space pavement-night-half-space"
mkdir -p output/pavement
printf "| scene | max s1 bottom [kPa] at | max s1 top [kPa] at | contact area | min w [mm] | max w [mm] | time [s] |\n"
printf "|---|---|---|---|---|---|---|\n"
for scene in $scenes; do
  start=$(date +%s.%N)
  "$program" "parameters/$scene.prm" >"output/pavement/$scene.log"
  end=$(date +%s.%N)
  python3 - "$scene" "$start" "$end" <<'PY'
import json, sys
scene, start, end = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
c = json.load(open("output/%s/summary.json" % scene))["cycles"][-1]
at = lambda p: "(%.2f, %.2f)" % tuple(p)
print("| %s | %.0f %s | %.0f %s | %.3f | %.3f | %.3f | %.1f |" % (
    scene, c["max_principal_stress_bottom"], at(c["max_principal_stress_bottom_at"]),
    c["max_principal_stress_top"], at(c["max_principal_stress_top_at"]),
    c["contact_area_fraction"], 1e3 * c["min_w"], 1e3 * c["max_w"], end - start))
PY
done
last=$(python3 -c 'import json; print("%02d" % json.load(open("output/pavement-day/summary.json"))["cycles"][-1]["cycle"])')
gnuplot -e "last='$last'" scripts/pavement_figures.gp
echo "figures: output/pavement/contact-maps.png output/pavement/stress-profiles.png"
