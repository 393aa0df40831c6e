#!/usr/bin/env python3
"""Scale: the hierarchical foundation operator with the iterative contact
solver against the dense operator.

    python3 benchmarks/hierarchical_scaling.py build/plate-on-halfspace [MAX_N [DIRECT_MAX_N [DENSE_MAX_N [SCENE [PATHS]]]]]

Scenes: parameters/example2.prm made Galerkin + active set (tensionless,
lifts off) and parameters/example2-bonded.prm (bonded), both solved on a
quarter (symmetry xy) of a uniform mesh whose Subdivisions give about
1e3, 3e3, 1e4, 2e4, 5e4, 1e5 and 1e6 foundation DOFs (N x N serendipity
cells on the quarter: n = 3 N^2 + 4 N + 1; above 1000 subdivisions, the
entry's limit, half as many refined once), up to MAX_N (default 100000).
Paths:
  hierarchical     Storage = hierarchical, Solver = iterative (all sizes);
  dense            Storage = dense, Solver = direct (LAPACK on the condensed
                   coupled matrix), up to DIRECT_MAX_N (default 3500: its
                   seven n^2 doubles and n^3 time);
  dense-iterative  Storage = dense, Solver = iterative (LAPACK Cholesky of
                   the dense flexibility as the preconditioner, three n^2
                   doubles), up to DENSE_MAX_N (default 21000);
  hierarchical-1e-8  hierarchical at Tolerance = 1e-8 instead of the
                   default 1e-6, up to DENSE_MAX_N (what probes within 1e-6
                   of dense cost);
  fft              Storage = fft (the split kernel), Solver = iterative
                   (all sizes).
PATHS (comma-separated, default all) runs only those paths; SCENE "all"
runs both scenes.
Per run: n, the time split of summary.json (plate assembly; foundation
operator: integration, compression, factorisation; contact solve = all
active-set iterations; total wall time), the peak memory of the process
(getrusage of the child), active-set and CG iterations, and the largest
difference of the probes from the dense answer (direct if run, else
dense-iterative) relative to each field's scale. Fits the growth exponent of
the total time of each path over n >= 9000 for hierarchical (9976 on: the target
range) and n >= 1e3 for the dense paths. Writes output/benchmarks/
hierarchical_scaling.{md,csv,png} (with -SCENE when only SCENE, tensionless
or bonded, is run). A benchmark, not a test: timings depend on the machine.
"""

import csv
import json
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = {
    "tensionless": ("parameters/example2.prm",
                    "subsection Discretization\n set Flexibility = galerkin\n"
                    "end\nsubsection Contact\n set Method = active set\nend\n"),
    "bonded": ("parameters/example2-bonded.prm",
               "subsection Discretization\n set Flexibility = galerkin\n"
               "end\n"),
}
PATHS = {
    "hierarchical": "subsection Foundation operator\n set Storage = "
                    "hierarchical\nend\nsubsection Contact\n set Solver = "
                    "iterative\nend\n",
    "dense": "subsection Foundation operator\n set Storage = dense\nend\n"
             "subsection Contact\n set Solver = direct\nend\n",
    "dense-iterative": "subsection Foundation operator\n set Storage = "
                       "dense\nend\nsubsection Contact\n set Solver = "
                       "iterative\nend\n",
    "fft": "subsection Foundation operator\n set Storage = fft\nend\n"
           "subsection Contact\n set Solver = iterative\nend\n",
    "hierarchical-1e-8": "subsection Foundation operator\n set Storage = "
                         "hierarchical\n set Tolerance = 1e-8\nend\n"
                         "subsection Contact\n set Solver = iterative\n"
                         "end\n",
}
# Cells per side of the quarter: n = 3 N^2 + 4 N + 1 foundation DOFs.
CELLS = [18, 32, 57, 81, 128, 182, 578]


def n_of(cells):
    return 3 * cells * cells + 4 * cells + 1


def run(executable, scene, path, cells, out, refinements=None):
    directory = os.path.join(out, "runs", f"{scene}-{path}-{cells}")
    os.makedirs(directory, exist_ok=True)
    prm = os.path.join(directory, "scene.prm")
    base, extra = SCENES[scene]
    # Subdivisions allows at most 1000: an even count above halves and
    # refines once (the same mesh); REFINEMENTS gives the same mesh as
    # 2 cells / 2^REFINEMENTS subdivisions refined that often
    if refinements is None:
        refinements = 1 if 2 * cells > 1000 else 0
    subdivisions = 2 * cells // (2 ** refinements)
    with open(prm, "w") as f:
        f.write(f"include {os.path.join(ROOT, base)}\n"
                f"set Output directory = {directory}\n{extra}{PATHS[path]}"
                "subsection Discretization\n set Symmetry = xy\n"
                f" set Initial refinements = {refinements}\n"
                f" set Subdivisions x = {subdivisions}\n"
                f" set Subdivisions y = {subdivisions}\nend\n"
                "subsection Adaptivity\n set Cycles = 1\n"
                " set Max cells = 10000000\nend\n"
                "subsection Output\n set VTU = false\n set Verbosity = 1\n"
                "end\n")
    start = time.time()
    log = open(os.path.join(directory, "log.txt"), "w")
    process = subprocess.Popen([executable, prm], stdout=log,
                               stderr=subprocess.STDOUT)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.time() - start
    if status != 0:
        print(f"  {scene} {path} n = {n_of(cells)}: failed, see {directory}")
        return None
    summary = json.load(open(os.path.join(directory, "summary.json")))
    c = summary["cycles"][-1]
    text = open(os.path.join(directory, "log.txt")).read()
    cg = [int(t.split()[0]) for t in text.split("conjugate gradients ")[1:]]
    return {"scene": scene, "path": path, "cells": cells,
            "n": c["n_foundation_dofs"], "assembly": c["assembly_time_s"],
            "foundation": c["foundation_time_s"],
            "integration": c["foundation_integration_time_s"],
            "compression": c["foundation_compression_time_s"],
            "factorization": c["foundation_factorization_time_s"],
            "solve": c["solve_time_s"],
            "total": wall, "peak_MB": usage.ru_maxrss / 1024.,
            "contact_its": c["contact_iterations"],
            "cg": sum(cg) if cg else None, "cycle": c}


def difference(a, b):
    scales = {"w": max(abs(a["max_w"]), abs(a["min_w"])),
              "Mx": max(abs(a["max_Mx"]), abs(a["min_Mx"])),
              "q": max(abs(a["max_q"]), abs(a["min_q"]))}
    return max(abs(pa[k] - pb[k]) / scales[k]
               for pa, pb in zip(a["probes"], b["probes"]) for k in scales)


def slope(rows, smallest):
    points = [(math.log(r["n"]), math.log(r["total"])) for r in rows
              if r["n"] >= smallest]
    if len(points) < 2:
        return None
    mx = sum(p[0] for p in points) / len(points)
    my = sum(p[1] for p in points) / len(points)
    return sum((x - mx) * (y - my) for x, y in points) / \
        sum((x - mx) ** 2 for x, _ in points)


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(2)
    executable = os.path.abspath(sys.argv[1])
    max_n = int(sys.argv[2]) if len(sys.argv) > 2 else 100000
    direct_max = int(sys.argv[3]) if len(sys.argv) > 3 else 3500
    dense_max = int(sys.argv[4]) if len(sys.argv) > 4 else 21000
    only = sys.argv[5] if len(sys.argv) > 5 else None
    if only == "all":
        only = None
    if only is not None and only not in SCENES:
        print(__doc__)
        sys.exit(2)
    if len(sys.argv) > 6:
        chosen = sys.argv[6].split(",")
        if any(p not in PATHS for p in chosen):
            print(__doc__)
            sys.exit(2)
        for p in list(PATHS):
            if p not in chosen:
                del PATHS[p]
    scenes = [only] if only else list(SCENES)
    name = "hierarchical_scaling" + (f"-{only}" if only else "") + \
        (f"-{sys.argv[6].replace(',', '-')}" if len(sys.argv) > 6 else "")
    out = os.path.join(ROOT, "output", "benchmarks")
    os.makedirs(out, exist_ok=True)
    limits = {"hierarchical": max_n, "dense": direct_max,
              "dense-iterative": dense_max, "hierarchical-1e-8": dense_max,
              "fft": max_n}
    rows = []
    for scene in scenes:
        for cells in CELLS:
            if n_of(cells) > max_n * 1.01:
                continue
            results = {}
            for path in PATHS:
                if n_of(cells) <= limits[path] * 1.01:
                    results[path] = run(executable, scene, path, cells, out)
            reference = results.get("dense") or results.get("dense-iterative")
            for path, r in results.items():
                if r:
                    r["difference"] = difference(reference["cycle"],
                                                 r["cycle"]) \
                        if reference else None
                    rows.append(r)
                    print(f"{scene:11s} {path:15s} n = {r['n']:6d}: total "
                          f"{r['total']:8.2f} s (foundation "
                          f"{r['foundation']:7.2f} s, solve "
                          f"{r['solve']:7.2f} s), peak {r['peak_MB']:7.0f} MB",
                          flush=True)
    lines = ["# Hierarchical against dense", "",
             "Command: `python3 benchmarks/hierarchical_scaling.py "
             f"build/plate-on-halfspace {max_n} {direct_max} {dense_max}"
             f"{' ' + (only or 'all') if len(sys.argv) > 5 else ''}"
             f"{' ' + sys.argv[6] if len(sys.argv) > 6 else ''}`", "",
             "| scene | path | n | plate assembly [s] | integration [s] | "
             "compression [s] | factorisation [s] | contact solve [s] | "
             "total [s] | peak memory [MB] | active-set its | CG its | "
             "probes vs dense |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        d = "-" if r["difference"] is None else f"{r['difference']:.1e}"
        lines.append(f"| {r['scene']} | {r['path']} | {r['n']} | "
                     f"{r['assembly']:.2f} | {r['integration']:.2f} | "
                     f"{r['compression']:.2f} | {r['factorization']:.2f} | "
                     f"{r['solve']:.2f} | {r['total']:.2f} | "
                     f"{r['peak_MB']:.0f} | {r['contact_its']} | "
                     f"{r['cg'] if r['cg'] is not None else '-'} | {d} |")
    lines += ["", "Growth exponent of the total time (least squares; "
              "hierarchical over n >= 9000 (the sizes from about 1e4), dense over n >= 1e3):", ""]
    for scene in scenes:
        for path in PATHS:
            s = slope([r for r in rows if r["scene"] == scene and
                       r["path"] == path],
                      9000 if path.startswith("hierarchical") or
                      path == "fft" else 1000)
            lines.append(f"- {scene}, {path}: "
                         f"{'-' if s is None else f'{s:.2f}'}")
    lines += ["", "Hierarchical against the fastest dense path at the same "
              "n (total time):", ""]
    for scene in scenes:
        for h in [r for r in rows if r["scene"] == scene and
                  r["path"] == "hierarchical"]:
            dense = [r["total"] for r in rows if r["scene"] == scene and
                     r["n"] == h["n"] and r["path"].startswith("dense")]
            if dense:
                lines.append(f"- {scene}, n = {h['n']}: "
                             f"{min(dense) / h['total']:.1f} x faster")
    with open(os.path.join(out, name + ".md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    with open(os.path.join(out, name + ".csv"), "w",
              newline="") as f:
        keys = [k for k in rows[0] if k != "cycle"]
        writer = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    data = os.path.join(out, name + ".dat")
    series = [(s, p) for s in scenes for p in PATHS]
    with open(data, "w") as f:
        for s, p in series:
            f.write(f'"{s}, {p}"\n')
            for r in rows:
                if r["scene"] == s and r["path"] == p:
                    f.write(f"{r['n']} {r['total']} {r['peak_MB']}\n")
            f.write("\n\n")
    script = [
        "set terminal pngcairo size 1100,450 font ',10'",
        f"set output '{os.path.join(out, name + '.png')}'",
        "set multiplot layout 1,2", "set logscale xy", "set grid",
        "set key bottom right", "set xrange [800:150000]", "set xlabel 'foundation DOFs n'",
        "set ylabel 'wall time [s]'", "set title 'total time'",
        "plot " + ", ".join(f"'{data}' index {i} using 1:2 with linespoints "
                            f"title '{s}, {p}'"
                            for i, (s, p) in enumerate(series)),
        "set ylabel 'peak memory [MB]'", "set title 'peak memory'",
        "plot " + ", ".join(f"'{data}' index {i} using 1:3 with linespoints "
                            f"title '{s}, {p}'"
                            for i, (s, p) in enumerate(series)),
        "unset multiplot"]
    subprocess.run(["gnuplot"], input="\n".join(script), text=True)
    print(f"wrote {out}/{name}.md, .csv, .png")


if __name__ == "__main__":
    main()
