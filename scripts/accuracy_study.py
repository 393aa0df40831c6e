#!/usr/bin/env python3
"""Speed against accuracy: run one scene over a grid of settings and measure
the error of the quantities of interest against DOFs and wall time.

    python3 scripts/accuracy_study.py build/plate-on-halfspace example2
    python3 scripts/accuracy_study.py build/plate-on-halfspace flexible-square
    python3 scripts/accuracy_study.py build/plate-on-halfspace large-plate
    python3 scripts/accuracy_study.py --strategies build/plate-on-halfspace example2
    python3 scripts/accuracy_study.py --strategies build/plate-on-halfspace flexible-disk
    python3 scripts/accuracy_study.py --strategies build/plate-on-halfspace flexible-disk-bonded

--strategies runs only the refinement strategies side by side (default
global, default adaptive and one goal-oriented run per quantity) and the
reference run, not the element, operator and contact variants.

Each variant is the shipped scene (parameters/) with a few entries changed;
every refinement cycle of a run is one point. Quantities of interest: the
centre deflection w(0,0), the peak Mx (largest at the 2x2 Gauss points), the
contact area fraction and q at an interior point. The reference is the exact
value where one exists (doc/verification.md), otherwise a Richardson
extrapolation from the three finest globally refined runs of the default
settings where they converge monotonically, otherwise the finest cycle of a
separate, finer reference run (default settings, adaptive, more cycles);
the output says which, and how far the two estimates lie apart. Writes to
output/study/<scene>/:
  runs/<variant>/...     each run's result files
  study.csv              one row per variant and cycle
  study.md               the table, the reference, what 1 % and 0.1 % cost
  study.png              error against wall time and against DOFs
Wall time: a globally refined cycle could be computed directly, so it
counts alone; an adaptive or goal-oriented cycle needs the cycles before
it, so it counts with them (cumulative).

Goal-oriented refinement: for each studied quantity with a goal (w(0,0):
`w at 0,0`, peak Mx: `peak Mx`, contact area fraction: `contact area`,
only on tensionless scenes; q has none, `Refinement = goal` refuses it) a
variant "goal <quantity>" runs the default settings with `Refinement =
goal`, that `Goal` and `Initial refinements = 1` (the goal's patch-wise
reconstruction needs it; the disks keep their 2). It is scored in its own quantity only; study.md
compares global, adaptive and goal per quantity ("Strategies").
"""

import csv
import json
import math
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# the study's "default" settings, written out (a shipped scene may set
# others): the program's defaults when doc/study.md was measured; the
# program's default element is now heterosis (Shear integration = auto,
# i.e. selective), the "heterosis selective" variant
DEFAULTS = {
    "Element": "serendipity",
    "Shear integration": "reduced",
    "Flexibility": "galerkin",
}

# variant name -> (Discretization entries, Contact method, refinement
#                  [, cycles if not the scene's])
VARIANTS = {
    "default, adaptive": ({}, "active set", "adaptive"),
    "default, global": ({}, "active set", "global"),
    "serendipity selective": ({"Shear integration": "selective"}, "active set",
                              "adaptive"),
    "heterosis selective": ({"Element": "heterosis",
                             "Shear integration": "selective"}, "active set",
                            "adaptive"),
    "lagrange selective": ({"Element": "lagrange",
                            "Shear integration": "selective"}, "active set",
                           "adaptive"),
    "lagrange full": ({"Element": "lagrange", "Shear integration": "full"},
                      "active set", "adaptive"),
    "collocation, adaptive": ({"Flexibility": "collocation"}, "active set",
                              "adaptive"),
    "element exclusion": ({}, "element exclusion", "adaptive"),
    # the paper's choices: serendipity, collocation, element exclusion
    "paper's choices, global":
        ({"Flexibility": "collocation"}, "element exclusion", "global", 3),
}

SCENES = {
    # the paper's example 2: tensionless, lifts off at the ends
    "example2": {
        "file": "parameters/example2.prm",
        "probe_q": (3.0, 0.0),
        "cycles": {"global": 4, "adaptive": 5, "goal": 4},
        # a finer run than any variant, for the quantities whose global
        # sequence is not monotone (no Richardson extrapolation)
        "reference run": ("adaptive", 7),
        "exact": {},
        "tensionless": True,
    },
    # a flexible uniformly loaded square: w(0,0) and q exact
    "flexible-square": {
        "file": "parameters/flexible-square.prm",
        "probe_q": (1.0, 1.0),
        "cycles": {"global": 4, "adaptive": 6, "goal": 6},
        "exact": {"w": 8.16961385005846e-3, "q": 100.0, "fraction": 1.0},
        "skip": {"Mx"},  # a flexible plate carries no moment to speak of
        "tensionless": False,
    },
    # a thin circular slab under a central tyre patch, tensionless (its
    # rim lifts off) and bonded: the peak Mx is the centre moment
    "flexible-disk": {
        "file": "parameters/flexible-disk.prm",
        "probe_q": (1.0, 0.0),
        "cycles": {"global": 5, "adaptive": 6, "goal": 7},
        "goal initial refinements": "2",
        "exact": {},
        "tensionless": True,
    },
    "flexible-disk-bonded": {
        "file": "parameters/flexible-disk.prm",
        "extra": "subsection Foundation\n  set Contact = bonded\nend\n",
        "probe_q": (1.0, 0.0),
        "cycles": {"global": 5, "adaptive": 6, "goal": 7},
        "goal initial refinements": "2",
        "exact": {"fraction": 1.0},
        "tensionless": False,
    },
    # a large slab under a tyre patch: w(0,0) is the Hankel integral
    "large-plate": {
        "file": "parameters/infinite-plate-patch.prm",
        "probe_q": (0.888, 0.0),
        "cycles": {"global": 4, "adaptive": 7, "goal": 4},
        "exact": {"w": 1.9231820e-4, "fraction": 1.0},
        "tensionless": False,
    },
}

QUANTITIES = [("w", "w(0,0)"), ("Mx", "peak Mx"), ("fraction", "contact area"),
              ("q", "q at interior point")]

# quantity -> Adaptivity/Goal; q has no goal (Refinement = goal refuses it)
GOALS = {"w": "w at 0,0", "Mx": "peak Mx", "fraction": "contact area"}


def goal_variants(scene):
    """One goal-oriented variant per studied quantity with a goal:
    name -> (Discretization entries, Contact method, "goal", cycles, Goal,
    quantity)."""
    variants = {}
    for key, label in QUANTITIES:
        if key not in GOALS or key in scene.get("skip", set()):
            continue
        if key == "fraction" and not scene["tensionless"]:
            continue  # bonded: the whole plate is in contact, nothing to aim at
        initial = scene.get("goal initial refinements", "1")
        variants[f"goal {label}"] = ({"Initial refinements": initial},
                                     "active set", "goal",
                                     scene["cycles"]["goal"], GOALS[key], key)
    return variants


def variant_goal(settings):
    """The Goal entry and the quantity of a goal variant, else (None, None)."""
    return (settings[4], settings[5]) if len(settings) > 5 else (None, None)


def scene_text(scene, name, settings, directory):
    base = open(os.path.join(ROOT, scene["file"])).read() + scene.get(
        "extra", "")
    entries, method, refinement = settings[:3]
    cycles = settings[3] if len(settings) > 3 else scene["cycles"][refinement]
    goal, _ = variant_goal(settings)
    # the other variants clear a Goal the scene may set
    goal_entry = f"  set Goal = {goal}\n" if goal else "  set Goal =\n"
    discretization = "".join(f"  set {k} = {v}\n"
                             for k, v in {**DEFAULTS, **entries}.items())
    px, py = scene["probe_q"]
    tensionless = scene["tensionless"]
    if not tensionless and method != "active set":
        return None  # the contact method only matters without tension
    text = base + f"""
set Output directory = {directory}
subsection Discretization
{discretization}end
subsection Contact
  set Method = {method}
end
subsection Adaptivity
  set Cycles = {cycles}
  set Refinement = {refinement}
  set Refine fraction = 0.3
  set Max cells = 100000
{goal_entry}end
subsection Output
  set Probe points = 0,0 ; {px},{py}
  set VTU = false
  set Verbosity = 0
end
subsection Verification
  set Checks =
end
"""
    return text


def run_variant(executable, scene, scene_name, name, settings, out):
    directory = os.path.join(out, "runs", name.replace(" ", "_").replace(
        ",", "").replace("(", "").replace(")", ""))
    text = scene_text(scene, name, settings, directory)
    if text is None:
        return []
    os.makedirs(directory, exist_ok=True)
    prm = os.path.join(directory, "scene.prm")
    with open(prm, "w") as f:
        f.write(text)
    result = subprocess.run([executable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        print(f"  {name}: failed: {result.stderr.strip()}", file=sys.stderr)
    summary_file = os.path.join(directory, "summary.json")
    if not os.path.exists(summary_file):
        return []
    summary = json.load(open(summary_file))
    rows, elapsed = [], 0.0
    for c in summary["cycles"]:
        elapsed += c["wall_time_s"]
        adaptive = settings[2] != "global"
        probes = c["probes"]
        rows.append({
            "variant": name, "cycle": c["cycle"], "cells": c["n_cells"],
            "dofs": c["n_dofs"], "foundation_dofs": c["n_foundation_dofs"],
            "time": elapsed if adaptive else c["wall_time_s"],
            "w": probes[0]["w"], "Mx": c["max_Mx"],
            "fraction": c["contact_area_fraction"], "q": probes[1]["q"],
            "symmetry": summary["symmetry"],
            "goal": variant_goal(settings)[1] or "",
            "goal_estimate": (c["goal"]["relative_error"]
                              if "goal" in c else ""),
        })
    return rows


def richardson(values):
    """Limit of the last three values of a sequence halving h each step,
    with the observed order; the finest value if the sequence does not
    converge monotonically."""
    a, b, c = values[-3:]
    if (b - a) * (c - b) <= 0 or abs(b - a) <= abs(c - b):
        return c, None
    ratio = (b - a) / (c - b)
    order = math.log(ratio, 2)
    return c + (c - b) / (ratio - 1), order


def main():
    args = sys.argv[1:]
    strategies_only = "--strategies" in args
    args = [a for a in args if a != "--strategies"]
    if len(args) < 2 or args[1] not in SCENES:
        print(__doc__)
        sys.exit(2)
    executable = os.path.abspath(args[0])
    scene_name = args[1]
    scene = SCENES[scene_name]
    variants = dict(VARIANTS)
    if strategies_only:
        variants = {k: v for k, v in variants.items()
                    if k in ("default, global", "default, adaptive")}
    variants.update(goal_variants(scene))
    out = os.path.join(ROOT, "output", "study", scene_name)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)

    rows = []
    for name, settings in variants.items():
        print(f"running {name} ...", flush=True)
        rows += run_variant(executable, scene, scene_name, name, settings, out)

    reference_rows = []
    if "reference run" in scene:
        refinement, cycles = scene["reference run"]
        print(f"running the reference run ({refinement}, {cycles} cycles) ...",
              flush=True)
        reference_rows = run_variant(executable, scene, scene_name,
                                     "reference run",
                                     ({}, "active set", refinement, cycles),
                                     out)

    # reference values
    reference, how = {}, {}
    finest = [r for r in rows if r["variant"] == "default, global"]
    for key, label in QUANTITIES:
        if key in scene.get("skip", set()):
            continue
        if key in scene["exact"]:
            reference[key] = scene["exact"][key]
            how[key] = "exact"
        elif len(finest) >= 3:
            value, order = richardson([r[key] for r in finest])
            fine = reference_rows[-1] if reference_rows else None
            if order is None and fine:
                value = fine[key]
                how[key] = (f"finest cycle of the reference run "
                            f"({fine['foundation_dofs']} foundation dofs); "
                            "the global default runs do not converge "
                            "monotonically")
            else:
                how[key] = ("Richardson extrapolation of the three finest "
                            "global default runs" +
                            (f" (observed order {order:.2f})" if order else
                             " (not monotone: finest value)"))
                if fine:
                    how[key] += (f"; the reference run's finest cycle "
                                 f"({fine['foundation_dofs']} foundation "
                                 f"dofs) lies "
                                 f"{abs(fine[key] - value) / abs(value):.1e} "
                                 "from it")
            reference[key] = value
    for r in rows + reference_rows:
        for key in reference:
            r["err_" + key] = abs(r[key] - reference[key]) / max(
                abs(reference[key]), 1e-300)

    keys = list(rows[0].keys())
    for r in rows:
        for k in r:
            if k not in keys:
                keys.append(k)
    with open(os.path.join(out, "study.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=keys)
        writer.writeheader()
        writer.writerows(rows + reference_rows)

    # what 1 % costs: the first cycle from which the error stays below 1 %
    def cost(variant, key, bound=0.01):
        goal = variant_goal(variants[variant])[1]
        if goal is not None and goal != key:
            return None  # a goal variant is scored in its own quantity
        vrows = [r for r in rows if r["variant"] == variant]
        for i, r in enumerate(vrows):
            if all(s.get("err_" + key, 1) < bound for s in vrows[i:]):
                return r
        return None

    lines = [f"# Accuracy study: {scene_name}", "",
             f"Command: `python3 scripts/accuracy_study.py "
             f"{'--strategies ' if strategies_only else ''}"
             f"build/plate-on-halfspace {scene_name}`", "",
             f"Symmetry used: {rows[0]['symmetry']} (the dense block of the "
             "computed part only).", "",
             "Variants: the defaults are serendipity, reduced shear "
             "integration, Galerkin, active set; \"paper's choices\" are "
             "serendipity, collocation and element exclusion (the paper's "
             "method), refined globally. \"goal <quantity>\": the defaults "
             "with Initial refinements = 1, Refinement = goal and that "
             "quantity as Goal, scored in that quantity only.", "",
             "References:", ""]
    for key, label in QUANTITIES:
        if key in reference:
            lines.append(f"- {label}: {reference[key]:.8g} ({how[key]})")
    lines += ["", "## Every run", "",
              "| variant | cycle | dofs | foundation dofs | time [s] | " +
              " | ".join(f"err {label}" for key, label in QUANTITIES
                         if key in reference) + " |",
              "|---|---|---|---|---|" + "---|" * len(reference)]
    for r in rows + reference_rows:
        lines.append(
            f"| {r['variant']} | {r['cycle']} | {r['dofs']} | "
            f"{r['foundation_dofs']} | {r['time']:.2f} | " +
            " | ".join(f"{r['err_' + key]:.2e}"
                       if r["goal"] in ("", key) else "(" +
                       f"{r['err_' + key]:.2e})"
                       for key, _ in QUANTITIES if key in reference) + " |")
    for bound, label in ((0.01, "1 %"), (0.001, "0.1 %")):
        lines += ["", f"## What {label} costs", "",
                  f"First cycle from which the error stays below {label} "
                  "(dofs / wall time; '-' = not reached in the runs).", "",
                  "| variant | " + " | ".join(
                      name for key, name in QUANTITIES if key in reference) +
                  " |",
                  "|---|" + "---|" * len(reference)]
        for variant in variants:
            if not any(r["variant"] == variant for r in rows):
                continue
            cells = []
            for key, _ in QUANTITIES:
                if key not in reference:
                    continue
                goal = variant_goal(variants[variant])[1]
                if goal is not None and goal != key:
                    cells.append("")
                    continue
                r = cost(variant, key, bound)
                cells.append(f"{r['dofs']} / {r['time']:.2f} s" if r else "-")
            lines.append(f"| {variant} | " + " | ".join(cells) + " |")

    # the strategies side by side, per quantity
    def reached(variant):
        vrows = [r for r in rows if r["variant"] == variant]
        return (f"{vrows[-1]['dofs']} dofs, {vrows[-1]['time']:.1f} s"
                if vrows else "did not run")
    lines += ["", "## Strategies", "",
              "Per quantity: global and Kelly-adaptive refinement of the "
              "defaults, and goal-oriented refinement with that quantity as "
              "Goal; DOFs / wall time of the first cycle from which the "
              "error stays below the bound ('-': not reached; the last "
              "cycle of the run in the last column).", "",
              "| quantity | strategy | 1 % | 0.1 % | finest error | "
              "last cycle |", "|---|---|---|---|---|---|"]
    for key, label in QUANTITIES:
        if key not in reference:
            continue
        for strategy, variant in (("global", "default, global"),
                                  ("adaptive", "default, adaptive"),
                                  ("goal", f"goal {label}")):
            if variant not in variants:
                continue
            vrows = [r for r in rows if r["variant"] == variant]
            cells = []
            for bound in (0.01, 0.001):
                r = cost(variant, key, bound)
                cells.append(f"{r['dofs']} / {r['time']:.2f} s" if r else "-")
            finest = f"{vrows[-1]['err_' + key]:.2e}" if vrows else "-"
            lines.append(f"| {label} | {strategy} | " + " | ".join(cells) +
                         f" | {finest} | {reached(variant)} |")
    with open(os.path.join(out, "study.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    # the plot: error against time (top) and DOFs (bottom) per quantity
    plotted = [key for key, _ in QUANTITIES if key in reference]
    data = os.path.join(out, "plot-data.txt")
    plotted_variants = [v for v in variants
                        if any(r["variant"] == v for r in rows)]
    with open(data, "w") as f:
        for v in plotted_variants:
            f.write(f'"{v}"\n')
            for r in rows:
                if r["variant"] == v:
                    f.write(f"{r['dofs']} {r['time']} " + " ".join(
                        f"{max(r['err_' + key], 1e-16)}"
                        if r["goal"] in ("", key) else "NaN"
                        for key in plotted)
                        + "\n")
            f.write("\n\n")
    terminals = subprocess.run(["gnuplot", "-e", "set terminal"],
                               capture_output=True, text=True)
    cairo = "pngcairo" in terminals.stdout + terminals.stderr
    script = [f"set terminal {'pngcairo' if cairo else 'png'} size "
              f"{420 * len(plotted) + 300},800 font ',9'",
              f"set output '{os.path.join(out, 'study.png')}'",
              f"set multiplot layout 2,{len(plotted)} title "
              f"'{scene_name}: relative error against wall time and DOFs' "
              f"margins 0.05,{1 - 300 / (420 * len(plotted) + 300):.3f},0.08,0.93 "
              "spacing 0.06,0.1",
              "set logscale xy", "set format y '10^{%L}'", "set grid",
              "set key off"]
    labels = dict(QUANTITIES)
    for axis, column in (("wall time [s]", 2), ("DOFs", 1)):
        for k, key in enumerate(plotted):
            if axis == "DOFs" and k == len(plotted) - 1:
                # one key for all panels, right of them
                script.append("set key at screen 0.99,0.5 right center "
                              "vertical font ',9'")
            script += [f"set xlabel '{axis}'",
                       f"set title '{labels[key]}'",
                       "plot " + ", ".join(
                           f"'{data}' index {i} using {column}:{3 + k} "
                           f"with linespoints title \"{v}\""
                           for i, v in enumerate(plotted_variants))]
            script.append("set key off")
    script.append("unset multiplot")
    subprocess.run(["gnuplot"], input="\n".join(script), text=True,
                   check=False)
    print(f"\nwrote {out}/study.md, study.csv, study.png")


if __name__ == "__main__":
    main()
