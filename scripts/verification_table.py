#!/usr/bin/env python3
"""Run the shipped verification scenes and print the README's error table
(value, reference, relative error, cells, wall time) in Markdown.

usage: python3 scripts/verification_table.py [build/plate-on-halfspace]
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import time

program = sys.argv[1] if len(sys.argv) > 1 else "build/plate-on-halfspace"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (label, scene, extra parameter text)
scenes = [
    ("flexible square, collocation", "flexible-square.prm", ""),
    ("flexible square, galerkin 16x16", "flexible-square.prm",
     "subsection Discretization\n set Flexibility = galerkin\n"
     " set Subdivisions x = 16\n set Subdivisions y = 16\nend\n"
     # the L2 projection of the settlement: pointwise errors of 1e-3, 1e-2
     "subsection Verification\n set Checks = w,0,0,8.16961385005846e-3,"
     "5e-4 ; w,2,2,4.08480692502923e-3,2e-2 ; contact_force,1600,1e-10\n"
     "end\n"),
    ("rigid disk, central load", "rigid-disk.prm", ""),
    ("large plate, circular patch", "infinite-plate-patch.prm", ""),
    ("large plate on a dense liquid", "infinite-plate-dense-liquid.prm", ""),
]

check_line = re.compile(r"check (\S+) = (\S+), reference (\S+), "
                        r"relative error (\S+) (<=|>) (\S+): (\w+)")
print("| scene | quantity | value | reference | relative error | cells | "
      "time [s] |")
print("|---|---|---|---|---|---|---|")
with tempfile.TemporaryDirectory() as work:
    for label, scene, extra in scenes:
        prm = os.path.join(work, "scene.prm")
        with open(prm, "w") as f:
            f.write("include %s\nset Output directory = %s\n%s"
                    "subsection Output\n set VTU = false\nend\n"
                    % (os.path.join(root, "parameters", scene), work, extra))
        start = time.time()
        run = subprocess.run([program, prm], capture_output=True, text=True)
        elapsed = time.time() - start
        with open(os.path.join(work, "summary.json")) as f:
            cells = json.load(f)["cycles"][-1]["n_cells"]
        for line in run.stdout.splitlines():
            m = check_line.match(line)
            if m:
                quantity, value, reference, error = m.group(1, 2, 3, 4)
                print("| %s | %s | %s | %s | %s | %d | %.1f |"
                      % (label, quantity, value, reference, error, cells,
                         elapsed))
        if run.returncode != 0:
            print("| %s | run failed: %s |" % (label, run.stderr.strip()))
