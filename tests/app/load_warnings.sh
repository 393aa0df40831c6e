#!/usr/bin/env bash
# Scenes that run with a warning about their loads (doc/errors-and-limits.md,
# "What you wrote and what you get"), through the real executable: each
# must exit 0 and print its "Warning: ..." lines on stderr, and the files
# must report what the plate carries.
# - a tyre 0.05 m over the long edge of a grid of slabs (the grid's outline
#   used to be taken from Plate/Length x and y, and no warning came);
# - Loads/Sweep moving that axle over the edge: one warning per position
#   with a tyre partly off, and sweep.csv's applied_load column;
# - a point load 1 mm from the corner of a weightless plate on a
#   tensionless soil: the warning that the cells are too large to carry it.
# usage: load_warnings.sh PROGRAM
set -u
program=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failed=0
fail() { echo "FAILED: $*"; failed=$((failed + 1)); }

cat >slabs.prm <<'EOF'
set Output directory = results
subsection Plate
  set Shape          = slabs
  set Slab lengths x = 4.5, 4.5
  set Slab lengths y = 3.6
  set Thickness      = 0.25
end
subsection Foundation
  set Model                        = dense liquid
  set Modulus of subgrade reaction = 5e4
  set Contact                      = bonded
end
subsection Discretization
  set Subdivisions x = 4
  set Subdivisions y = 4
end
subsection Output
  set VTU       = false
  set Verbosity = 0
end
EOF

run() { # name, scene text; the run must succeed
  printf '%s\n' "$2" >"$1.prm"
  "$program" "$1.prm" >"$1.stdout" 2>"$1.stderr"
  local status=$?
  [ $status -eq 0 ] || { fail "$1: exit status $status"; cat "$1.stderr"; }
}

# the outer tyre of a single axle at y = 0.935 + 0.915 = 1.85, 0.05 m over
run tyre_over_edge 'include slabs.prm
subsection Loads
  set Axles = single, 1, 0.935, 0, 80, 700
end'
if [ "$(grep -c '^Warning: ' tyre_over_edge.stderr)" -ne 1 ] ||
   ! grep -q '^Warning: Loads/Axles: group 1 (single), tyre [12] lies partly off the plate: [0-9.]* % of its load is off the plate, so only [0-9.]* of its 40 is applied' tyre_over_edge.stderr; then
  fail "tyre_over_edge: no single warning naming the tyre, the share and the load applied"
  cat tyre_over_edge.stderr
fi

# the sweep: offsets 0, 0.2, 0.4 put the outer tyre 0.285 and 0.085 inside
# the edge and 0.115 beyond it
run sweep 'include slabs.prm
subsection Loads
  set Axles = single, 1, 0.6, 0, 80, 700
  set Sweep = 0, 0, 0, 0.4, 3
end'
[ "$(grep -c '^Warning: Loads/Sweep: at position [12] (offset 0, 0\.[24]): Loads/Axles: group 1 (single), tyre [12] lies partly off the plate' sweep.stderr)" -eq 2 ] &&
  [ "$(grep -c '^Warning: ' sweep.stderr)" -eq 2 ] ||
  { fail "sweep: not one warning at each of positions 1 and 2"; cat sweep.stderr; }
python3 - results/sweep.csv results/summary.json <<'EOF' || fail "sweep: applied_load of sweep.csv or summary.json"
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
applied = [float(r["applied_load"]) for r in rows]
listed = json.load(open(sys.argv[2]))["sweep"]["applied_load"]
# all 80 on the plate at position 0, then less and less
ok = len(applied) == 3 and abs(applied[0] - 80) < 1e-9 * 80 and \
     80 > applied[1] > applied[2] > 40 and \
     all(abs(a - b) <= 1e-9 * 80 for a, b in zip(applied, listed))
sys.exit(0 if ok else 1)
EOF

run near_corner 'set Output directory = results
subsection Plate
  set Length x  = 4
  set Length y  = 3
  set Thickness = 0.25
end
subsection Foundation
  set Model                        = dense liquid
  set Modulus of subgrade reaction = 5e4
end
subsection Discretization
  set Subdivisions x = 4
  set Subdivisions y = 3
end
subsection Loads
  set Point loads = 1.999, 1.499, 100
end
subsection Output
  set VTU       = false
  set Verbosity = 0
end'
grep -q '^Warning: The resultant of the loads on the plate, 100 at (1.999, 1.499), lies 0.001 from the outline, less than a third of the cells there' near_corner.stderr ||
  { fail "near_corner: no warning about the cells"; cat near_corner.stderr; }

echo "$failed failed"
[ $failed -eq 0 ]
