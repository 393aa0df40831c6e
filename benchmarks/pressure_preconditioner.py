#!/usr/bin/env python3
"""Conjugate gradient iterations of the iterative contact solver for a
stiff and a flexible plate, with each pressure preconditioner
(Contact/Preconditioner).

    python3 benchmarks/pressure_preconditioner.py build/plate-on-halfspace [MAX_N [DIRECT_MAX_N]]

The scenes of hierarchical_scaling.py (example 2 made Galerkin + active set,
tensionless, and its bonded twin; a quarter of a uniform mesh, hierarchical
storage, iterative solver) up to MAX_N foundation nodes (default 20008): the
tensionless example with its slab (t = 0.5 m, radius of relative stiffness l
= 1.69 m, many cells), and the bonded and the tensionless one with a plate
thinned until l = h/10 (h the smaller side of the cells; Contact/Max
iterations raised to 500, as its contact boundary settles slowly, also for
the direct solver). Each with Contact/Preconditioner = auto, soil inverse
and plate on springs (the thin tensionless plate with auto only, and only up
to DIRECT_MAX_N nodes: its contact boundary takes hundreds of active-set
steps). Per run: the preconditioner used, the active-set steps, the CG
iterations in all (the constrained start's included), the most of one
contact set's solve, the contact solve and factorisation times, and, up to
DIRECT_MAX_N nodes (default 3500), the largest difference of the probes from
the direct solver on dense storage relative to each field's scale. Then
a sweep of l/h at n = 2821 (dense storage, so that the sweep is quick) for
the calibration of auto. Runs one after the other; a benchmark, not a test:
the timings depend on the machine. Writes
output/benchmarks/pressure_preconditioner.md.
"""

import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hierarchical_scaling as scaling  # noqa: E402

# example 2's slab and soil (parameters/example2.prm)
E, NU, E0, NU0 = 2.5e7, 0.15, 1e5, 0.3
PRECONDITIONERS = ["auto", "soil inverse", "plate on springs"]


def thickness_for(l_over_h, cells):
    """t with l = l_over_h * h, h = 4 m / cells (the quarter's 4 m side)."""
    l = l_over_h * 4. / cells
    rigidity = l ** 3 * E0 / (2 * (1 - NU0 ** 2))
    return (12 * rigidity * (1 - NU ** 2) / E) ** (1. / 3.)


def add_path(name, storage, solver, preconditioner, thickness):
    scaling.PATHS[name] = (
        f"subsection Foundation operator\n set Storage = {storage}\nend\n"
        f"subsection Contact\n set Solver = {solver}\n"
        f" set Preconditioner = {preconditioner}\n"
        # the thin plate's contact boundary settles slowly (also direct)
        f" set Max iterations = {500 if thickness else 50}\nend\n" +
        (f"subsection Plate\n set Thickness = {thickness}\nend\n"
         # cells of 50 thicknesses: the element that does not lock
         "subsection Discretization\n set Element = heterosis\n"
         " set Shear integration = auto\nend\n"
         # the example's checks hold its own slab's weight
         "subsection Verification\n set Checks =\nend\n"
         if thickness else ""))


def iterations(directory):
    text = open(os.path.join(directory, "log.txt")).read()
    chosen = re.findall(r"pressure preconditioner: (soil inverse|plate on "
                        r"springs)\n", text)
    predicted = [int(x) for x in re.findall(
        r"constrained conjugate gradients (\d+) iterations", text)]
    solves = [int(x) for x in re.findall(
        r"contact iteration \d+: conjugate gradients (\d+) iterations", text)]
    return (chosen[-1] if chosen else "-", sum(predicted) + sum(solves),
            max(solves) if solves else 0)


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(2)
    executable = os.path.abspath(sys.argv[1])
    max_n = int(sys.argv[2]) if len(sys.argv) > 2 else 20008
    direct_max = int(sys.argv[3]) if len(sys.argv) > 3 else 3500
    out = os.path.join(scaling.ROOT, "output", "benchmarks")
    os.makedirs(out, exist_ok=True)
    lines = ["# Pressure preconditioners", "",
             "Command: `python3 benchmarks/pressure_preconditioner.py "
             f"build/plate-on-halfspace {max_n} {direct_max}`", "",
             "| n | plate | l/h | Preconditioner | used | steps | CG its | "
             "most per set | solve [s] | factorisation [s] | probes - dense "
             "direct |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for cells in scaling.CELLS:
        n = scaling.n_of(cells)
        if n > max_n * 1.01:
            continue
        for scene, plate, l_over_h, preconditioners in [
                ("tensionless", "t = 0.5 m", 1.69 * cells / 4.,
                 PRECONDITIONERS),
                ("bonded", "l = h/10", 0.1, PRECONDITIONERS),
                ("tensionless", "l = h/10", 0.1,
                 ["auto"] if n <= direct_max else [])]:
            thickness = None if plate == "t = 0.5 m" else \
                thickness_for(l_over_h, cells)
            reference = None
            if n <= direct_max:
                add_path("direct", "dense", "direct", "auto", thickness)
                reference = scaling.run(executable, scene, "direct", cells,
                                        out)
            for preconditioner in preconditioners:
                name = "pc-" + preconditioner.replace(" ", "-") + \
                    ("-flexible" if thickness else "")
                add_path(name, "hierarchical", "iterative", preconditioner,
                         thickness)
                r = scaling.run(executable, scene, name, cells, out)
                directory = os.path.join(out, "runs",
                                         f"{scene}-{name}-{cells}")
                label = f"{plate}, {scene}"
                if r is None:
                    lines.append(f"| {n} | {label} | {l_over_h:.3g} | "
                                 f"{preconditioner} | failed | - | - | - | "
                                 "- | - | - |")
                else:
                    used, cg, most = iterations(directory)
                    diff = (f"{scaling.difference(r['cycle'], reference['cycle']):.1e}"
                            if reference else "-")
                    lines.append(
                        f"| {r['n']} | {label} | {l_over_h:.3g} | "
                        f"{preconditioner} | {used} | {r['contact_its']} | "
                        f"{cg} | {most} | {r['solve']:.2f} | "
                        f"{r['factorization']:.2f} | {diff} |")
                print(lines[-1], flush=True)

    # The calibration sweep: l/h from 0.1 to 30 at one size.
    cells = 30
    lines += ["", f"Sweep of l/h at n = {scaling.n_of(cells)} (tensionless, "
              "dense storage, iterative solver): CG iterations in all "
              "(active-set steps)", "",
              "| l/h | soil inverse | plate on springs | auto uses |",
              "|---|---|---|---|"]
    for l_over_h in [0.1, 0.3, 1, 3, 10, 30]:
        row = [f"{l_over_h:g}"]
        used = "-"
        for preconditioner in PRECONDITIONERS[1:] + ["auto"]:
            name = "sweep-" + preconditioner.replace(" ", "-")
            add_path(name, "dense", "iterative", preconditioner,
                     thickness_for(l_over_h, cells))
            r = scaling.run(executable, "tensionless", name, cells, out)
            directory = os.path.join(out, "runs",
                                     f"tensionless-{name}-{cells}")
            if preconditioner == "auto":
                used = iterations(directory)[0] if r else "failed"
            else:
                row.append(f"{iterations(directory)[1]} ({r['contact_its']})"
                           if r else "failed")
        lines.append("| " + " | ".join(row + [used]) + " |")
        print(lines[-1], flush=True)
    with open(os.path.join(out, "pressure_preconditioner.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
