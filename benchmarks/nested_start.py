#!/usr/bin/env python3
"""Time of a tensionless run with and without the nested start
(Contact/Nested start), beside the bonded run of the same mesh.

    python3 benchmarks/nested_start.py build/plate-on-halfspace [MAX_N [BOTH_MAX_N]]

Example 2 made Galerkin + active set, and its bonded twin, as in
hierarchical_scaling.py: a quarter of a uniform mesh of N x N cells
(n = 3 N^2 + 4 N + 1 foundation nodes), fft storage, iterative solver.
The mesh is given as coarse as the mirror plane allows (an even number of
subdivisions of the whole plate, at least 16) and refined globally to N x N,
so that the nested start has coarser levels to solve on; without it the
mesh is the same. N = 56, 128, 184, 576 (n = 9633 ... 997633) up to MAX_N
(default 110000). Per size: the tensionless run with Nested start = auto
(the default: from 20000 nodes) and, up to BOTH_MAX_N (default 110000),
with Nested start = false and the bonded run. Columns: active-set steps
and CG iterations of the first cycle (the coarse solves' are in the
nested start's time), nested_start_time_s, the contact solve, the wall
time of the process, its peak memory, the total over the bonded run's,
and the largest probe difference from the run without the nested start.
Fits the growth exponent of the nested runs' totals. Runs one after the
other; a benchmark, not a test. Writes output/benchmarks/nested_start.md.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hierarchical_scaling as scaling  # noqa: E402

CELLS = [56, 128, 184, 576]
scaling.PATHS["nested"] = scaling.PATHS["fft"]
scaling.PATHS["no-nested"] = (scaling.PATHS["fft"] + "subsection Contact\n"
                              " set Nested start = false\nend\n")


def refinements(cells):
    """Global refinements that give N x N cells on the quarter from the
    coarsest whole-plate subdivisions that stay even and at least 16."""
    r, subdivisions = 0, 2 * cells
    while subdivisions % 4 == 0 and subdivisions // 2 >= 16:
        subdivisions //= 2
        r += 1
    while subdivisions > 1000:
        subdivisions //= 2
        r += 1
    return r


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(2)
    executable = os.path.abspath(sys.argv[1])
    max_n = int(sys.argv[2]) if len(sys.argv) > 2 else 110000
    both_max = int(sys.argv[3]) if len(sys.argv) > 3 else 110000
    out = os.path.join(scaling.ROOT, "output", "benchmarks")
    os.makedirs(out, exist_ok=True)
    lines = ["# Nested start", "",
             "Command: `python3 benchmarks/nested_start.py "
             f"build/plate-on-halfspace {max_n} {both_max}`", "",
             "| n | refinements | run | active-set steps | CG its | "
             "nested start [s] | contact solve [s] | total [s] | peak [MB] | "
             "total / bonded | probes − without |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    nested_rows = []
    for cells in CELLS:
        if scaling.n_of(cells) > max_n * 1.01:
            continue
        r = refinements(cells)
        runs = [("tensionless", "nested", "tensionless, nested start")]
        if scaling.n_of(cells) <= both_max * 1.01:
            runs += [("tensionless", "no-nested", "tensionless, without"),
                     ("bonded", "fft", "bonded")]
        results = [(label, scaling.run(executable, scene, path, cells, out, r))
                   for scene, path, label in runs]
        bonded = results[2][1] if len(results) > 2 else None
        without = results[1][1] if len(results) > 1 else None
        if results[0][1]:
            nested_rows.append(results[0][1])
        for label, result in results:
            if result is None:
                lines.append(f"| {scaling.n_of(cells)} | {r} | {label} | "
                             "failed | - | - | - | - | - | - | - |")
                continue
            c = result["cycle"]
            ratio = (f"{result['total'] / bonded['total']:.2f}"
                     if bonded else "-")
            probes = ("-" if without is None or label.startswith("bonded")
                      else f"{scaling.difference(c, without['cycle']):.1e}")
            lines.append(
                f"| {result['n']} | {r} | {label} | {result['contact_its']} | "
                f"{result['cg']} | {c.get('nested_start_time_s', 0):.1f} | "
                f"{result['solve']:.1f} | {result['total']:.1f} | "
                f"{result['peak_MB']:.0f} | {ratio} | {probes} |")
            print(lines[-1], flush=True)
    exponent = scaling.slope(nested_rows, 9000)
    if exponent is not None:
        lines += ["", "Growth exponent of the nested runs' totals over "
                  f"n ≥ 9000: {exponent:.2f}"]
    with open(os.path.join(out, "nested_start.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
