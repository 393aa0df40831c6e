#!/usr/bin/env python3
"""Side-by-side table of the three variants of a paper example, from the
summary.json files that scripts/paper_examples.sh writes.

usage: python3 scripts/compare_variants.py output/example2
"""
import json
import os
import sys

directory = sys.argv[1]
variants = [("paper", "collocation + element exclusion"),
            ("exact", "Galerkin + active set"),
            ("bonded", "Galerkin, bonded")]
rows = [("contact iterations", "contact_iterations", "%d"),
        ("nodes in contact", "contact_nodes", "%d"),
        ("contact area fraction", "contact_area_fraction", "%.3f"),
        ("max w [mm]", "max_w", "%.3f", 1e3),
        ("min w [mm]", "min_w", "%.3f", 1e3),
        ("max q [kPa]", "max_q", "%.1f"),
        ("min q [kPa]", "min_q", "%.1f"),
        ("max Mx [kNm/m]", "max_Mx", "%.1f"),
        ("min Mx [kNm/m]", "min_Mx", "%.1f"),
        ("tensile nodes", "tensile_nodes", "%d"),
        ("complementarity violation", "complementarity_violation", "%.1e"),
        ("contact force / applied load - 1", None, "%.1e")]
summaries = []
for name, _ in variants:
    with open(os.path.join(directory, name, "summary.json")) as f:
        summaries.append(json.load(f)["cycles"][-1])
print("| %s | %s |" % (os.path.basename(directory),
                       " | ".join(title for _, title in variants)))
print("|---" * (len(variants) + 1) + "|")
for row in rows:
    label, key, fmt = row[0], row[1], row[2]
    scale = row[3] if len(row) > 3 else 1
    cells = []
    for s in summaries:
        value = (s["contact_force"] / s["applied_load"] - 1 if key is None
                 else s[key] * scale)
        cells.append(fmt % value)
    print("| %s | %s |" % (label, " | ".join(cells)))
