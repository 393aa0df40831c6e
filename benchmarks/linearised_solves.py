#!/usr/bin/env python3
"""CG iterations and times of the solves that follow a contact solve on
the same contact set: the goal's adjoint problem and a bonded sweep's
positions (doc/formulation.md, "Recycled directions").

    python3 benchmarks/linearised_solves.py EXE[=LABEL] [EXE[=LABEL] ...] [--large]

Each executable (another build, to compare) runs, one after the other:
  goal   example 2 made Galerkin + active set (tensionless), a quarter of
         46 x 46 cells refined twice (n = 25761; with --large also three
         times, n = 102305), fft storage, iterative solver, one cycle with
         Adaptivity/Goal = w at 0,0;
  sweep  example 2 bonded, the whole plate of 120 x 80 cells (n = 29041),
         fft storage, iterative solver, a tandem axle swept over 21
         positions from x = -4 to 4.
Columns: the CG iterations of the cycle's last contact solve and of the
adjoint solve (goal), or of the first solve and the mean over the sweep's
positions (sweep); summary.json's goal.time_s or the sweep's time (the
wall time less the first cycle's), the contact solve and the wall time of
the process. A benchmark, not a test: times depend on the machine.
"""

import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COMMON = ("subsection Discretization\n set Flexibility = galerkin\nend\n"
          "subsection Contact\n set Solver = iterative\nend\n"
          "subsection Foundation operator\n set Storage = fft\nend\n"
          "subsection Output\n set VTU = false\n set Verbosity = 1\nend\n")


def goal_scene(refinements):
    return (f"include {ROOT}/parameters/example2.prm\n" + COMMON +
            "subsection Contact\n set Method = active set\nend\n"
            "subsection Discretization\n set Symmetry = xy\n"
            f" set Initial refinements = {refinements}\n"
            " set Subdivisions x = 46\n set Subdivisions y = 46\nend\n"
            "subsection Adaptivity\n set Cycles = 1\n"
            " set Max cells = 10000000\n set Goal = w at 0,0\nend\n")


def sweep_scene():
    return (f"include {ROOT}/parameters/example2-bonded.prm\n" + COMMON +
            "subsection Loads\n set Axles = tandem, 0, 1.8, 0, 160, 700\n"
            " set Sweep = -4, 0, 4, 0, 21\nend\n"
            "subsection Verification\n set Checks =\nend\n"
            "subsection Discretization\n set Subdivisions x = 120\n"
            " set Subdivisions y = 80\n set Symmetry = none\nend\n")


def run(executable, scene, directory):
    os.makedirs(directory, exist_ok=True)
    prm = os.path.join(directory, "scene.prm")
    with open(prm, "w") as f:
        # after the included scene's own
        f.write(scene + f"set Output directory = {directory}\n")
    environment = dict(os.environ)
    # a build's shared library beside its executable
    environment["LD_LIBRARY_PATH"] = os.path.dirname(
        os.path.abspath(executable))
    start = time.time()
    log = subprocess.run([executable, prm], capture_output=True, text=True,
                         env=environment)
    wall = time.time() - start
    if log.returncode != 0:
        sys.exit(f"{executable} failed on {prm}:\n{log.stderr}")
    summary = json.load(open(os.path.join(directory, "summary.json")))
    text = log.stdout + log.stderr
    cg = [int(t.split()[0]) for t in text.split("conjugate gradients ")[1:]
          if t.split()[0].isdigit()]
    return summary, cg, wall


def main():
    arguments = [a for a in sys.argv[1:] if not a.startswith("--")]
    large = "--large" in sys.argv
    if not arguments:
        sys.exit(__doc__)
    builds = [a.split("=", 1) if "=" in a else (a, a) for a in arguments]
    out = tempfile.mkdtemp(prefix="linearised_solves-")
    print("| build | scene | n | CG its: last contact solve | CG its: "
          "adjoint / sweep mean | goal / sweep [s] | contact solve [s] | "
          "total [s] |")
    print("|---|---|---|---|---|---|---|---|")
    for refinements in ([2, 3] if large else [2]):
        for executable, label in builds:
            summary, cg, wall = run(executable, goal_scene(refinements),
                                    os.path.join(out, f"goal-{refinements}"))
            c = summary["cycles"][-1]
            print(f"| {label} | goal | {c['n_foundation_dofs']} | {cg[-2]} | "
                  f"{cg[-1]} | {c['goal']['time_s']:.1f} | "
                  f"{c['solve_time_s']:.1f} | {wall:.1f} |", flush=True)
    for executable, label in builds:
        summary, cg, wall = run(executable, sweep_scene(),
                                os.path.join(out, "sweep"))
        c = summary["cycles"][-1]
        positions = cg[1:]
        print(f"| {label} | sweep | {c['n_foundation_dofs']} | {cg[0]} | "
              f"{sum(positions) / len(positions):.1f} | "
              f"{wall - c['wall_time_s']:.1f} | {c['solve_time_s']:.1f} | "
              f"{wall:.1f} |", flush=True)


if __name__ == "__main__":
    main()
