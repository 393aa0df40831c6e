#!/usr/bin/env python3
"""CG iterations and times of the solves that follow a contact solve on
the same contact set: the goal's adjoint problem and a bonded sweep's
positions (doc/formulation.md, "Recycled directions").

    python3 benchmarks/linearised_solves.py EXE[=LABEL] [EXE[=LABEL] ...] [--large]
    python3 benchmarks/linearised_solves.py EXE[=LABEL] ... --flexible

Each executable (another build, to compare) runs, one after the other:
  goal   example 2 made Galerkin + active set (tensionless), a quarter of
         46 x 46 cells refined twice (n = 25761; with --large also three
         times, n = 102305), fft storage, iterative solver, one cycle with
         Adaptivity/Goal = w at 0,0;
  sweep  example 2 bonded, the whole plate of 120 x 80 cells (n = 29041),
         fft storage, iterative solver, a tandem axle swept over 21
         positions from x = -4 to 4.
With --flexible instead:
  flexible  example 2 bonded, 24 x 16 cells (n = 1233), dense storage,
         plate moduli 2.5e4 down to 25 (the plate far more flexible than
         the soil, solves near their rounding floor), each preconditioner,
         a single axle swept over 7 positions; columns: the first solve's
         CG iterations, the positions' mean and largest, how many of the
         solves recycled directions and how many abandoned them, and the
         largest difference of sweep.csv's max_w, max_s1_bottom and
         max_s1_top from the direct solver's, relative to the column's
         largest value.
Columns: the CG iterations of the cycle's last contact solve and of the
adjoint solve (goal), or of the first solve and the mean over the sweep's
positions (sweep); summary.json's goal.time_s or the sweep's time (the
wall time less the first cycle's), the contact solve and the wall time of
the process. A benchmark, not a test: times depend on the machine.
"""

import csv
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


def flexible_scene(modulus, preconditioner, solver):
    return (f"include {ROOT}/parameters/example2-bonded.prm\n" + COMMON +
            "subsection Foundation operator\n set Storage = dense\nend\n"
            f"subsection Plate\n set Young's modulus = {modulus}\nend\n"
            f"subsection Contact\n set Solver = {solver}\n"
            f" set Preconditioner = {preconditioner}\nend\n"
            "subsection Loads\n set Rectangular patches =\n"
            " set Axles = single, 0, 1.8, 0, 100, 700\n"
            " set Sweep = -3, 0, 3, 0, 7\nend\n"
            "subsection Verification\n set Checks =\nend\n"
            "subsection Discretization\n set Subdivisions x = 24\n"
            " set Subdivisions y = 16\n set Symmetry = none\nend\n")


def sweep_columns(directory):
    rows = list(csv.DictReader(open(os.path.join(directory, "sweep.csv"))))
    return {k: [float(r[k]) for r in rows]
            for k in ["max_w", "max_s1_bottom", "max_s1_top"]}


def flexible(builds, out):
    print("| build | plate E | preconditioner | CG its: first | positions: "
          "mean / largest | recycled / abandoned | w, s1 − direct |")
    print("|---|---|---|---|---|---|---|")
    for modulus in ["2.5e4", "8e3", "6e3", "4e3", "2.5e3", "25"]:
        reference = os.path.join(out, f"direct-{modulus}")
        run(builds[0][0], flexible_scene(modulus, "auto", "direct"),
            reference)
        expected = sweep_columns(reference)
        for preconditioner in ["soil inverse", "plate on springs"]:
            for executable, label in builds:
                directory = os.path.join(out, f"{label}-{modulus}")
                _, cg, _ = run(executable,
                               flexible_scene(modulus, preconditioner,
                                              "iterative"), directory)
                found = sweep_columns(directory)
                worst = max(max(abs(a - b) for a, b in zip(found[k],
                                                           expected[k])) /
                            max(max(abs(v) for v in expected[k]), 1e-300)
                            for k in expected)
                positions = cg[1:]
                print(f"| {label} | {modulus} | {preconditioner} | {cg[0]} | "
                      f"{sum(positions) / len(positions):.0f} / "
                      f"{max(positions)} | {flexible.recycled} / "
                      f"{flexible.abandoned} | {worst:.0e} |", flush=True)


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
    flexible.recycled = text.count(" directions")
    flexible.abandoned = text.count("(abandoned)")
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
    if "--flexible" in sys.argv:
        flexible(builds, out)
        return
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
