#!/usr/bin/env python3
"""Effectivity of the goal error estimates (doc/verification.md, "Goal error
estimates"): each case runs global refinement with Adaptivity/Goal set and
compares, per cycle, the estimate (sum of the local dual-weighted
residuals' magnitudes), the signed dual-weighted residual and the reported
bound (max of the estimate and the last change) with the true error, taken
from a closed form or from Richardson extrapolation of the last three
cycles.

    python3 scripts/goal_effectivity.py [build/plate-on-halfspace]
"""
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BINARY = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    ROOT, "build", "plate-on-halfspace")


def flexible_corner():
    a, b, d = 6.0, 3.0, math.hypot(6.0, 3.0)
    return 100 * (1 - 0.09) / (math.pi * 5e4) * (
        a * math.log((b + d) / a) + b * math.log((a + d) / b))


FLEXIBLE = """include {root}/parameters/flexible-square.prm
subsection Plate
  set Length x = 6
  set Length y = 3
end
subsection Discretization
  set Flexibility = galerkin
  set Subdivisions x = 6
  set Subdivisions y = 3
  set Initial refinements = 1
end
subsection Contact
  set Solver = direct
end
subsection Output
  set Probe points = 0,0
end
subsection Verification
  set Checks =
end
"""

EXAMPLE2 = """include {root}/parameters/{scene}.prm
subsection Discretization
  set Subdivisions x = 6
  set Subdivisions y = 4
  set Initial refinements = 1
end
subsection Verification
  set Checks =
end
"""

# the slab of parameters/infinite-plate-patch.prm on a quarter; its centre
# moment is the Hankel integral (tests/unit/hankel_reference)
PATCH = """include {root}/parameters/infinite-plate-patch.prm
subsection Discretization
  set Symmetry = xy
  set Initial refinements = 1
end
subsection Verification
  set Checks =
end
"""

# the paper's tensionless scene on the Galerkin operator with the active set
TENSIONLESS = """subsection Discretization
  set Flexibility = galerkin
end
subsection Contact
  set Method = active set
end
"""

CASES = [
    ("flexible 6 x 3, corner w", FLEXIBLE, "w at 3,1.5", 4, flexible_corner()),
    ("example 2 bonded, corner w", EXAMPLE2.replace("{scene}", "example2-bonded"),
     "w at 6,4", 4, None),
    ("example 2 bonded, centre w", EXAMPLE2.replace("{scene}", "example2-bonded"),
     "w at 0,0", 4, None),
    ("example 2 bonded, mean w", EXAMPLE2.replace("{scene}", "example2-bonded"),
     "mean w", 4, None),
    ("example 2 bonded, Mx at centre",
     EXAMPLE2.replace("{scene}", "example2-bonded"), "Mx at 0,0", 4, None),
    ("slab under a tyre patch, Mx at centre", PATCH, "Mx at 0,0", 5,
     10.803889266),
    ("example 2 tensionless, centre w",
     EXAMPLE2.replace("{scene}", "example2") + TENSIONLESS, "w at 0,0", 4, None),
    ("example 2 tensionless, contact area",
     EXAMPLE2.replace("{scene}", "example2") + TENSIONLESS, "contact area", 4,
     None),
]


def run(text, goal, cycles, directory):
    prm = os.path.join(directory, "scene.prm")
    with open(prm, "w") as f:
        f.write(text.format(root=ROOT))
        f.write("set Output directory = %s/out\n" % directory)
        f.write("subsection Adaptivity\n  set Refinement = global\n"
                "  set Goal = %s\n  set Cycles = %d\nend\n" % (goal, cycles))
        f.write("subsection Output\n  set VTU = false\nend\n")
    subprocess.run([BINARY, prm], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(directory, "out", "summary.json")) as f:
        return json.load(f)["cycles"]


def main():
    print("| case | foundation nodes | relative error | estimate effectivity |"
          " signed DWR effectivity | bound effectivity |")
    print("|---|---|---|---|---|---|")
    for name, text, goal, cycles, exact in CASES:
        with tempfile.TemporaryDirectory() as directory:
            summary = run(text, goal, cycles, directory)
        values = [c["goal"]["value"] for c in summary]
        reference = exact
        if reference is None:
            ratio = (values[-1] - values[-2]) / (values[-2] - values[-3])
            reference = values[-1] + (values[-1] - values[-2]) * ratio / (1 - ratio)
        # the extrapolated reference leaves the last cycle without a true
        # error of its own
        last = len(summary) if exact is not None else len(summary) - 1
        for c in summary[:last]:
            g = c["goal"]
            error = reference - g["value"]
            bound = g["relative_error"] * abs(g["value"])
            dwr = "%.2f" % (g["dwr"] / error) if g["dwr"] is not None else "-"
            print("| %s | %d | %.2e | %.2f | %s | %s |" % (
                name, c["n_foundation_dofs"], abs(error / reference),
                g["estimated_error"] / abs(error), dwr,
                "%.2f" % (bound / abs(error)) if g["change"] is not None else "-"))


if __name__ == "__main__":
    main()
