#!/usr/bin/env python3
"""What a layered soil costs against the homogeneous half-space.

    python3 benchmarks/layered_soil.py build/plate-on-halfspace [MAX_REFINEMENTS [DENSE_MAX_REFINEMENTS [BONDED_REFINEMENTS [REPEATS]]]]

1. The kernel table: the slab below on 1, 3 and 10 layers over a
   half-space (one coarse cycle); the wall seconds of the tabulation and
   its knots, from the log line "Layered soil: kernel tabulated on ...".
2. Integration and whole runs, mesh by mesh: the pavement slab of
   parameters/pavement-on-layers.prm (4.5 m x 3.6 m x 0.25 m, its weight, a
   tyre at the edge, tensionless, whole plate, globally refined from 6 x 5
   cells) on its base, subbase and subgrade over bedrock, and on the
   homogeneous half-space of the subgrade (E = 50 MPa, nu = 0.4), with dense
   storage up to DENSE_MAX_REFINEMENTS (default 3) and hierarchical storage
   up to MAX_REFINEMENTS (default 4, about 2.3e4 foundation nodes; 5 gives
   9.3e4). Per run,
   from summary.json: the foundation nodes, the integration, compression
   and factorisation seconds, the contact solve and the whole run; and the
   ratio layered / homogeneous of the integration (without the layered
   kernel's tabulation, given apart) and of the whole run, and the
   conjugate gradient iterations of the contact solve in all, and the
   active-set steps: the soils differ in where the slab lifts off, so
   these runs compare two contact problems as well as two operators.
3. The same operator on the same contact problem: the slab bonded (the
   whole plate in contact, one solve), hierarchical storage, at the
   comma-separated BONDED_REFINEMENTS (default 4; 5 gives 9.3e4 nodes),
   layered against homogeneous: integration, compression, factorisation,
   CG iterations and the whole run.
Each run is made REPEATS times (default 1) and the one of median
integration time reported: on a 2-core machine one run's integration
varies by 20 %.
Prints markdown tables. A benchmark, not a test: timings depend on the
machine and its load.
"""

import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SLAB = """set Output directory = {out}
subsection Plate
  set Length x        = 4.5
  set Length y        = 3.6
  set Thickness       = 0.25
  set Young's modulus = 3e7
  set Poisson's ratio = 0.15
  set Unit weight     = 24
end
subsection Foundation
{foundation}
  set Contact = {contact}
end
subsection Loads
  set Circular patches = 0,1.65,0.15,700
end
subsection Discretization
  set Subdivisions x      = 6
  set Subdivisions y      = 5
  set Initial refinements = {refinements}
  set Symmetry            = none
end
subsection Contact
  set Method = active set
end
subsection Foundation operator
  set Storage = {storage}
end
subsection Output
  set VTU       = false
  set Verbosity = 1
end
"""

PAVEMENT = ("  set Model = layered\n"
            "  set Layers = 0.15, 5e6, 0.2 ; 0.3, 2e5, 0.35 ; 2.55, 5e4, 0.4\n"
            "  set Base = rigid\n")
SUBGRADE = "  set Young's modulus = 5e4\n  set Poisson's ratio = 0.4\n"


def ten_layers(n):
    """n layers from 0.1 m (E = 5 GPa) down to the subgrade, over it."""
    layers = []
    for i in range(n):
        layers.append("%.3g, %.4g, %.2f" % (0.1 * 1.5 ** i, 5e6 / 2.0 ** i,
                                            0.2 + 0.2 * i / max(n - 1, 1)))
    return ("  set Model = layered\n  set Layers = %s\n" % " ; ".join(layers)
            + SUBGRADE)


def run(program, work, foundation, refinements, storage,
        contact="tensionless"):
    out = os.path.join(work, "out")
    scene = os.path.join(work, "scene.prm")
    with open(scene, "w") as f:
        f.write(SLAB.format(out=out, foundation=foundation,
                            refinements=refinements, storage=storage,
                            contact=contact))
    start = time.time()
    log = subprocess.run([program, scene], check=True, capture_output=True,
                         text=True, cwd=ROOT).stdout
    total = time.time() - start
    cycle = json.load(open(os.path.join(out, "summary.json")))["cycles"][-1]
    return log, cycle, total


def measure_once(program, work, foundation, refinements, storage,
                 contact):
    """summary.json's last cycle, the wall seconds, the tabulation seconds,
    the CG iterations and the active-set steps of one run."""
    log, c, total = run(program, work, foundation, refinements, storage,
                        contact)
    m = re.search(r"kernel tabulated on .* in (\S+) s", log)
    tabulation = float(m.group(1)) if m else 0.
    cg = sum(int(n) for n in re.findall(
        r"conjugate gradients (\d+) iterations", log))
    steps = max([int(n) for n in re.findall(
        r"contact iteration (\d+):", log)] or [1])
    return c, total, tabulation, cg, steps


REPEATS = 1


def measure(program, work, foundation, refinements, storage,
            contact="tensionless"):
    """measure_once() REPEATS times: the run of median integration time
    (less the tabulation)."""
    runs = sorted((measure_once(program, work, foundation, refinements,
                                storage, contact)
                   for _ in range(REPEATS)),
                  key=lambda m: m[0]["foundation_integration_time_s"] - m[2])
    return runs[len(runs) // 2]


def ratios(rows):
    """Layered over homogeneous: integration (less the tabulation) and
    whole run."""
    c, total, tabulation = rows["layered"][:3]
    h, h_total = rows["homogeneous"][:2]
    return ("%.2f" % ((c["foundation_integration_time_s"] - tabulation) /
                      h["foundation_integration_time_s"]),
            "%.2f" % (total / h_total))


def main():
    program = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                              os.path.join(ROOT, "build/plate-on-halfspace"))
    max_refinements = int(sys.argv[2]) if len(sys.argv) > 2 else 4
    dense_max = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    bonded = [int(r) for r in (sys.argv[4] if len(sys.argv) > 4 else
                               "4").split(",") if r]
    global REPEATS
    REPEATS = int(sys.argv[5]) if len(sys.argv) > 5 else 1
    with tempfile.TemporaryDirectory() as work:
        print("| layers | knots | range [m] | error | tabulation [s] |")
        print("|---|---|---|---|---|")
        for n in (1, 3, 10):
            log, _, _ = run(program, work, ten_layers(n), 0, "dense")
            m = re.search(r"kernel tabulated on (\d+) knots up to r = (\S+), "
                          r"error <= (\S+) .* in (\S+) s", log)
            print("| %d | %s | %.3g | %s | %.3f |" % (
                n, m.group(1), float(m.group(2)), m.group(3),
                float(m.group(4))))
        print()
        print("| storage | nodes | soil | tabulation [s] | integration [s] "
              "| compression [s] | factorisation [s] | contact solve [s] "
              "| CG iterations | active-set steps | total [s] "
              "| integration ratio | total ratio |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for storage, top in (("dense", dense_max),
                             ("hierarchical", max_refinements)):
            for r in range(1, top + 1):
                rows = {}
                for soil, foundation in (("homogeneous", SUBGRADE),
                                         ("layered", PAVEMENT)):
                    rows[soil] = measure(program, work, foundation, r,
                                         storage)
                for soil in ("homogeneous", "layered"):
                    c, total, tabulation, cg, steps = rows[soil]
                    integration = (c["foundation_integration_time_s"] -
                                   tabulation)
                    ratio = ratios(rows) if soil == "layered" else ("", "")
                    print("| %s | %d | %s | %.2f | %.2f | %.2f | %.2f | %.2f "
                          "| %s | %d | %.1f | %s | %s |" % (
                              storage, c["n_foundation_dofs"], soil,
                              tabulation, integration,
                              c["foundation_compression_time_s"],
                              c["foundation_factorization_time_s"],
                              c["solve_time_s"], cg if cg else "-", steps,
                              total, ratio[0], ratio[1]))
                sys.stdout.flush()
        print()
        print("Bonded, hierarchical storage:")
        print()
        print("| nodes | soil | integration [s] | compression [s] "
              "| factorisation [s] | contact solve [s] | CG iterations "
              "| total [s] | integration ratio | total ratio |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        for r in bonded:
            rows = {}
            for soil, foundation in (("homogeneous", SUBGRADE),
                                     ("layered", PAVEMENT)):
                rows[soil] = measure(program, work, foundation, r,
                                     "hierarchical", "bonded")
            for soil in ("homogeneous", "layered"):
                c, total, tabulation, cg, _ = rows[soil]
                integration = c["foundation_integration_time_s"] - tabulation
                ratio = ratios(rows) if soil == "layered" else ("", "")
                print("| %d | %s | %.2f | %.2f | %.2f | %.2f | %d | %.1f "
                      "| %s | %s |" % (
                          c["n_foundation_dofs"], soil, integration,
                          c["foundation_compression_time_s"],
                          c["foundation_factorization_time_s"],
                          c["solve_time_s"], cg, total, ratio[0], ratio[1]))
            sys.stdout.flush()


if __name__ == "__main__":
    main()
