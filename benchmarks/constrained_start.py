"""Active-set steps and time of a tensionless run with and without the
constrained start (Contact/Constrained start), beside the bonded run of
the same mesh.

    python3 benchmarks/constrained_start.py build/plate-on-halfspace [MAX_N]

The scenes and meshes of hierarchical_scaling.py (example 2 made Galerkin +
active set, and its bonded twin; a quarter of a uniform mesh, hierarchical
storage, iterative solver) up to MAX_N foundation nodes (default 50000).
Per size: the active-set steps, the CG iterations in all (the constrained
start's included), the contact solve and the whole run, for the
tensionless scene with Constrained start = true (the default) and false,
and the bonded scene; then the ratios of the tensionless runs' totals to
the bonded one. Runs one after the other; a benchmark, not a test: the
timings depend on the machine. Writes output/benchmarks/constrained_start.md.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hierarchical_scaling as scaling  # noqa: E402

scaling.PATHS["seed-start"] = (scaling.PATHS["hierarchical"] +
                               "subsection Contact\n"
                               " set Constrained start = false\nend\n")
RUNS = [("tensionless", "hierarchical", "tensionless, constrained start"),
        ("tensionless", "seed-start", "tensionless, from the seed"),
        ("bonded", "hierarchical", "bonded")]


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(2)
    executable = os.path.abspath(sys.argv[1])
    max_n = int(sys.argv[2]) if len(sys.argv) > 2 else 50000
    out = os.path.join(scaling.ROOT, "output", "benchmarks")
    os.makedirs(out, exist_ok=True)
    lines = ["# Constrained start", "",
             "Command: `python3 benchmarks/constrained_start.py "
             f"build/plate-on-halfspace {max_n}`", "",
             "| n | run | active-set steps | CG its | contact solve [s] | "
             "total [s] | total / bonded |", "|---|---|---|---|---|---|---|"]
    for cells in scaling.CELLS:
        if scaling.n_of(cells) > max_n * 1.01:
            continue
        results = [(label, scaling.run(executable, scene, path, cells, out))
                   for scene, path, label in RUNS]
        bonded = results[-1][1]
        for label, r in results:
            if r is None:
                lines.append(f"| {scaling.n_of(cells)} | {label} | failed "
                             "| - | - | - | - |")
                continue
            ratio = f"{r['total'] / bonded['total']:.2f}" if bonded else "-"
            lines.append(f"| {r['n']} | {label} | {r['contact_its']} | "
                         f"{r['cg']} | {r['solve']:.2f} | {r['total']:.2f} | "
                         f"{ratio} |")
            print(lines[-1], flush=True)
    with open(os.path.join(out, "constrained_start.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
