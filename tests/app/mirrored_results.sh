#!/usr/bin/env bash
# What a symmetric run (Discretization/Symmetry = auto, x, y) writes about
# the whole plate must be what the whole-plate run (none) writes
# (doc/outputs.md): the goal Mxy at a point of the mirrored-away part,
# which changes sign in one mirror plane and not in two, and the tested
# gap of nodes-00.csv on the mirror planes, whose basis functions the
# computed part holds only in part, and probes on cell edges and vertices
# (the mean of the cells there; on a mirror plane, of the mirrored cells
# too), goals at such points, which must equal the probe there, and the
# nodes of a joint on a mirror plane, one on each side.
# Compared to 1e-9 of the field's scale.
# usage: mirrored_results.sh PROGRAM
set -u
program=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failed=0
fail() { echo "FAILED: $*"; failed=$((failed + 1)); }

# scene SYMMETRY DIRECTORY GOAL PROBES
scene() {
  cat >"$2.prm" <<EOF2
set Output directory = $2
subsection Plate
  set Length x    = 6
  set Length y    = 4
  set Thickness   = 0.25
  set Young's modulus = 3e7
  set Unit weight = 24
end
subsection Foundation
  set Young's modulus = 1e5
  set Contact         = tensionless
end
subsection Temperature
  set Difference = -10
end
subsection Loads
  set Circular patches = 1,0.5,0.3,700 ; -1,0.5,0.3,700 ; 1,-0.5,0.3,700 ; -1,-0.5,0.3,700
end
subsection Discretization
  set Subdivisions x = 4
  set Subdivisions y = 4
  set Symmetry       = $1
end
subsection Adaptivity
  set Goal = $3
end
subsection Output
  set Probe points = $4
  set VTU          = false
  set Verbosity    = 0
end
EOF2
  "$program" "$2.prm" >"$2.log" 2>&1 || fail "$2: exit status $?"
}

for symmetry in none auto x y; do
  scene $symmetry $symmetry "Mxy at -1.2,0.7" \
    "-1.5,-0.83 ; -1.5,1 ; 0,0.5 ; 0.7,0 ; 1.2,-0.3"
done

# Goals at a point on a cell edge (x = 1.5), a vertex (1.5,1) and a mirror
# plane (x = 0, y = 0): the mean of the cells there, as the probe there;
# and 2e-10 off the plane, beyond the tolerance 1.7e-10 of a point on an
# edge, where the whole plate's reading is one cell's.
edge_goals="Mx:1.5,0.7 Mxy:1.5,1 stress_bottom:1.5,1 Mxy:0,0.7 Mx:0,-1
Mxy:-2e-10,0.7"
for goal in $edge_goals; do
  for symmetry in none auto; do
    scene $symmetry "edge-$symmetry-${goal/:/-}" "${goal%%:*} at ${goal#*:}" \
      "${goal#*:}"
  done
done

python3 - $edge_goals <<'EOF' || failed=$((failed + 1))
import csv, json, sys

def goal(symmetry):
    run = json.load(open(symmetry + "/summary.json"))
    return run["symmetry"], run["cycles"][-1]["goal"]["value"]

def nodes(symmetry):
    rows = {}
    for r in csv.DictReader(open(symmetry + "/nodes-00.csv")):
        rows[(round(float(r["x"]), 9), round(float(r["y"]), 9))] = r
    return rows

bad = 0
_, reference = goal("none")
whole = nodes("none")
for symmetry in ["auto", "x", "y"]:
    used, value = goal(symmetry)
    ok = abs(value - reference) <= 1e-9 * abs(reference)
    print("Symmetry = %s (%s): goal Mxy at -1.2,0.7 %s the whole plate's: %s"
          % (symmetry, used, "equals" if ok else "differs from",
             "ok" if ok else "FAILED (%.9g against %.9g)" % (value, reference)))
    bad += not ok
    probes = json.load(open(symmetry + "/summary.json"))["cycles"][-1]["probes"]
    whole_probes = json.load(open("none/summary.json"))["cycles"][-1]["probes"]
    scale = max(max(abs(p["Mx"]), abs(p["My"])) for p in whole_probes)
    worst = 0
    for p, r in zip(probes, whole_probes):
        values = [p["Mx"], p["My"]] + p["stress_bottom"] + p["stress_top"]
        expected = [r["Mx"], r["My"]] + r["stress_bottom"] + r["stress_top"]
        worst = max([worst] + [abs(a - b) / scale for a, b in
                               zip(values[:2], expected[:2])])
        stress_scale = max(abs(v) for v in expected[2:])
        worst = max([worst] + [abs(a - b) / stress_scale for a, b in
                               zip(values[2:], expected[2:])])
    ok = len(probes) == len(whole_probes) == 5 and worst <= 1e-9
    print("Symmetry = %s: probes on cell edges and vertices within 1e-9 of "
          "the whole plate's: %s" % (symmetry, "ok" if ok else
                                     "FAILED (%.2g)" % worst))
    bad += not ok
    part = nodes(symmetry)
    if sorted(part) != sorted(whole):
        print("Symmetry = %s: nodes-00.csv lists other nodes: FAILED" % symmetry)
        bad += 1
        continue
    for column in ["w", "q", "gap"]:
        scale = max(abs(float(r[column])) for r in whole.values())
        worst = max(abs(float(part[k][column]) - float(whole[k][column]))
                    for k in whole) / scale
        ok = worst <= 1e-9
        print("Symmetry = %s: nodes-00.csv %s within 1e-9 of the whole "
              "plate's: %s" % (symmetry, column, "ok" if ok else
                               "FAILED (%.2g)" % worst))
        bad += not ok

# the goal against the probe at its point, and the symmetric run's against
# the whole plate's
thickness = 0.25
for goal in sys.argv[1:]:
    field, point = goal.split(":")
    values = {}
    for symmetry in ["none", "auto"]:
        cycle = json.load(open("edge-%s-%s-%s/summary.json"
                               % (symmetry, field, point)))["cycles"][-1]
        probe = cycle["probes"][0]
        sx, sy, sxy = probe["stress_bottom"]
        from_probe = {"Mx": probe["Mx"], "Mxy": sxy * thickness ** 2 / 6,
                      "stress_bottom": 0.5 * (sx + sy) +
                      ((0.5 * (sx - sy)) ** 2 + sxy ** 2) ** 0.5}[field]
        scale = max(abs(probe["Mx"]), abs(probe["My"])) * (
            6 / thickness ** 2 if field == "stress_bottom" else 1)
        values[symmetry] = cycle["goal"]["value"]
        ok = abs(values[symmetry] - from_probe) <= 1e-9 * scale
        print("Symmetry = %s: goal %s at %s equals the probe's: %s"
              % (symmetry, field, point, "ok" if ok else "FAILED (%.9g "
                 "against %.9g)" % (values[symmetry], from_probe)))
        bad += not ok
    ok = abs(values["auto"] - values["none"]) <= 1e-9 * scale
    print("Symmetry = auto: goal %s at %s equals the whole plate's: %s"
          % (field, point, "ok" if ok else "FAILED (%.9g against %.9g)"
             % (values["auto"], values["none"])))
    bad += not ok
sys.exit(1 if bad else 0)
EOF

# A free joint on the mirror plane y = 0 (and one tied): its two sides are
# distinct nodes of the whole plate, the computed part's and its image's.
for transfer in free tied; do
  for symmetry in none auto; do
    cat >"joint-$transfer-$symmetry.prm" <<EOF2
set Output directory = joint-$transfer-$symmetry
subsection Plate
  set Shape          = slabs
  set Slab lengths x = 3, 3, 3
  set Slab lengths y = 2, 2
  set Thickness      = 0.25
end
subsection Joints
  set Load transfer = $transfer
end
subsection Foundation
  set Model                        = dense liquid
  set Modulus of subgrade reaction = 5e4
  set Contact                      = tensionless
end
subsection Loads
  set Circular patches = 1.2,0.6,0.15,700 ; -1.2,0.6,0.15,700 ; 1.2,-0.6,0.15,700 ; -1.2,-0.6,0.15,700
end
subsection Discretization
  set Subdivisions x = 3
  set Subdivisions y = 3
  set Symmetry       = $symmetry
end
subsection Output
  set VTU       = false
  set Verbosity = 0
end
EOF2
    "$program" "joint-$transfer-$symmetry.prm" >"joint-$transfer-$symmetry.log" 2>&1 ||
      fail "joint-$transfer-$symmetry: exit status $?"
  done
done
python3 - <<'EOF' || failed=$((failed + 1))
import csv, json, sys
bad = 0
for transfer in ["free", "tied"]:
    rows, counts = {}, {}
    for symmetry in ["none", "auto"]:
        out = "joint-%s-%s/" % (transfer, symmetry)
        cycle = json.load(open(out + "summary.json"))["cycles"][-1]
        counts[symmetry] = (cycle["contact_nodes"], cycle["tensile_nodes"])
        rows[symmetry] = sorted(
            (round(float(r["x"]), 9), round(float(r["y"]), 9),
             round(float(r["w"]) * 1e6, 3), int(r["contact"]))
            for r in csv.DictReader(open(out + "nodes-00.csv")))
    ok = counts["auto"] == counts["none"] and rows["auto"] == rows["none"]
    print("%s joint on the mirror plane: Symmetry = auto's node counts and "
          "nodes-00.csv (%d rows) equal the whole plate's: %s"
          % (transfer, len(rows["none"]), "ok" if ok else "FAILED (%s, %d "
             "rows, against %s, %d)" % (counts["auto"], len(rows["auto"]),
                                        counts["none"], len(rows["none"]))))
    bad += not ok
sys.exit(1 if bad else 0)
EOF

[ $failed -eq 0 ] || { echo "$failed failed"; exit 1; }
echo "all passed"
