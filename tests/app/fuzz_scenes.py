#!/usr/bin/env python3
"""Fuzz-style test of the executable: randomly perturbed versions
of a small valid scene (tests/app/bad_input_base.prm made tensionless with a
patch and a point load, every second one on a dense liquid instead of the
half-space, every third one two jointed slabs with an axle swept across the
joint), a fixed seed, each run with a time limit. Every run
must either succeed (status 0, summary.json without NaN and without null
except a goal's "change" on the first cycle and "dwr" of the contact area,
"converged": true) or fail cleanly (status 1, exactly one "Error: ..." line on stderr
besides "Warning: ..." lines). A signal, a time-out, another status or a
malformed result fails the test.

usage: fuzz_scenes.py PROGRAM TESTS_APP_DIRECTORY [RUNS] [SEED]
"""
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile

program, here = sys.argv[1], sys.argv[2]
runs = int(sys.argv[3]) if len(sys.argv) > 3 else 200
seed = int(sys.argv[4]) if len(sys.argv) > 4 else 20240605
time_limit = 30  # seconds; a valid run of these scenes takes well under 1 s

base = """set Output directory = results
subsection Plate
  set Shape           = rectangle
  set Length x        = 2
  set Length y        = 1.5
  set Radius          = 1
  set Thickness       = 0.2
  set Young's modulus = 1e6
  set Poisson's ratio = 0.2
  set Unit weight     = 0
end
subsection Foundation
  set Model           = half-space
  set Young's modulus = 1e4
  set Poisson's ratio = 0.3
  set Modulus of subgrade reaction = 0
  set Contact         = tensionless
end
subsection Temperature
  set Difference = 5
  set Profile    =
end
subsection Loads
  set Uniform pressure    = 1
  set Rectangular patches = 0,0,1,0.75,100
  set Circular patches    =
  set Point loads         = -0.5,0,20
end
subsection Discretization
  set Element           = serendipity
  set Shear integration = reduced
  set Subdivisions x    = 3
  set Subdivisions y    = 2
  set Initial refinements = 1
  set Flexibility       = galerkin
end
subsection Contact
  set Method         = active set
  set Max iterations = 100
end
subsection Adaptivity
  set Cycles       = 2
  set Refinement   = adaptive
  set Goal         = w at 0,0
  set Target error = 0
end
subsection Output
  set Probe points = 0,0
  set VTU          = false
  set Verbosity    = 0
end
"""

numbers = ["0", "-1", "1e-300", "1e300", "nan", "inf", "-inf", "x", "", "1,2",
           "0.5", "0.499", "1e-6", "1e9", "2.5", "-0.2", "3", "1e999"]
choices = {
    "Shape": ["rectangle", "disk", "mesh file", "square", "slabs", ""],
    "Slab lengths x": ["1, 1", "2", "1, 0", "1, -1", "1, x", "", "0.5, 0.5, 0.5, 0.5"],
    "Slab lengths y": ["1.5", "0.75, 0.75", "0", "nan", ""],
    "Load transfer": ["free", "aggregate interlock", "dowels", "tied", "welded", ""],
    "Longitudinal load transfer": ["same", "free", "dowels", "tied", "x"],
    "Shear stiffness": ["1e6", "0", "-1", "1e300", "nan", "x"],
    "Dowel spacing": ["0.3", "0", "5", "-0.3", "x"],
    "Joint opening": ["0.006", "0", "-1", "1"],
    "Axles": ["", "single, 0, 0, 0, 40, 700", "tandem, 0, 0, 90, 80, 700",
              "single dual, 0, 0, 0", "truck, 0, 0, 0, 40, 700", "single, 9, 9, 0, 40, 700"],
    "Sweep": ["", "-0.3, 0, 0.3, 0, 3", "-0.3, 0, 0.3, 0, 1", "0, 0, 5, 0, 3",
              "-0.3, 0, 0.3, 0", "0, 0, 0, 0, 2.5"],
    "Contact": ["bonded", "tensionless", "glued"],
    "Element": ["serendipity", "heterosis", "lagrange", "quad"],
    "Shear integration": ["auto", "reduced", "selective", "full", "none"],
    "Flexibility": ["galerkin", "collocation", "winkler"],
    "Model": ["half-space", "dense liquid", "winkler", ""],
    "Profile": ["", "20,10", "5", "1,x", "20,15,10,12", "20;10", "nan,1", "1e300,-1e300"],
    "Modulus of subgrade reaction": ["0", "1e4", "-1e4", "1e-300", "1e300", "nan",
                                     "x", "5e4 kN/m3"],
    "Method": ["active set", "element exclusion", "newton"],
    "Subdivisions x": ["1", "2", "4", "0", "-3", "2.5", "1001", "x"],
    "Subdivisions y": ["1", "2", "4", "0", "-3", "2.5", "1001", "x"],
    "Initial refinements": ["0", "1", "-1", "11", "x"],
    "Cycles": ["1", "2", "0", "31"],
    "Max iterations": ["1", "2", "0", "100"],
    "Rectangular patches": ["", "0,0,1,1,100", "1,0,0,1,10", "0,0,1", "5,5,6,6,1",
                            "-3,-3,3,3,10", "0,0,1,1,nan", "0,0,1,1,-1e9", ";;", "a,b,c,d,e"],
    "Circular patches": ["", "0,0,0.3,50", "0,0,0,50", "0,0,-1,50", "9,9,1,1", "0,0,5,10"],
    "Point loads": ["", "0,0,10", "1,0.75,10", "0,0,-10", "3,0,10", "0,0", "0,0,inf",
                    "0.3333,0.25,1e9", "-1,-0.75,1e-6"],
    "Probe points": ["", "0,0", "1,0.75", "9,9", "0", "nan,0"],
    "Mesh file": ["", "no-such.msh", "triangles.msh", "."],
    "Refinement": ["global", "adaptive", "goal", "kelly", ""],
    "Goal": ["", "w at 0,0", "Mx at 0.5,0.2", "Mxy at -1,-0.75", "q at 0,0",
             "peak Mx", "peak M1", "peak q", "contact area", "mean w",
             "w at 0,0 minus 1,0.75", "w at 9,9", "Mx at", "w at 0,0 minus",
             "w at nan,0", "stress_bottom at 0,0", "stress_top at 0.5,0.2",
             "peak stress_bottom", "peak stress_top", "stress_bottom at 9,9"],
    "Target error": ["0", "1e-3", "0.5", "1", "-1", "x", "1e-300"],
}


def unexpected_nulls(value, key=None, parent=None):
    """The keys holding null in a summary, except the documented ones
    (doc/outputs.md): the goal block's change and dwr, a joint's lte where
    neither side deflects downward, and the sweep envelope's min_lte then."""
    if value is None:
        documented = ((parent == "goal" and key in ("change", "dwr")) or
                      (parent == "joints" and key == "lte") or
                      (parent == "envelope" and key == "min_lte"))
        return [] if documented else [key]
    if isinstance(value, dict):
        return [n for k, v in value.items()
                for n in unexpected_nulls(v, k, key)]
    if isinstance(value, list):
        return [n for v in value for n in unexpected_nulls(v, key, parent)]
    return []


dense_liquid = base.replace("Model           = half-space",
                            "Model           = dense liquid").replace(
    "Modulus of subgrade reaction = 0", "Modulus of subgrade reaction = 2e4")


jointed = base.replace("  set Shape           = rectangle",
                       "  set Shape           = slabs\n  set Slab lengths x  = 1, 1\n"
                       "  set Slab lengths y  = 1.5").replace(
    "subsection Temperature",
    "subsection Joints\n  set Load transfer = dowels\n"
    "  set Longitudinal load transfer = tied\n  set Shear stiffness = 1e6\n"
    "  set Dowel spacing = 0.3\n  set Joint opening = 0.006\nend\n"
    "subsection Temperature").replace(
    "  set Point loads         = -0.5,0,20",
    "  set Point loads         = -0.5,0,20\n"
    "  set Axles               = single, 0, 0, 90, 40, 700\n"
    "  set Sweep               = 0, -0.3, 0, 0.3, 3")


def perturb(rng, scene):
    lines = scene.splitlines()
    for _ in range(rng.randint(1, 3)):
        i = rng.randrange(1, len(lines))  # keep the output directory
        line = lines[i]
        if "=" in line and rng.random() < 0.8:
            name = line.split("set", 1)[1].split("=")[0].strip()
            pool = choices.get(name, numbers)
            lines[i] = line.split("=")[0] + "= " + rng.choice(pool)
        else:
            kind = rng.randrange(4)
            if kind == 0:
                del lines[i]  # a lost line, e.g. an 'end'
            elif kind == 1 and line:
                j = rng.randrange(len(line))
                lines[i] = line[:j] + line[j + 1:]  # a lost character
            elif kind == 2:
                lines.insert(i, lines[i])  # a repeated line
            else:
                lines[i] = line.replace("set ", "set  X", 1)  # a misspelt name
    return "\n".join(lines) + "\n"


def main():
    rng = random.Random(seed)
    work = tempfile.mkdtemp()
    shutil.copy(os.path.join(here, "triangles.msh"), work)
    counts = {"ran": 0, "refused": 0}
    failures = []
    try:
        for n in range(runs):
            scene = perturb(rng, jointed if n % 3 == 2 else
                            dense_liquid if n % 2 else base)
            with open(os.path.join(work, "scene.prm"), "w") as f:
                f.write(scene)
            shutil.rmtree(os.path.join(work, "results"), ignore_errors=True)
            try:
                p = subprocess.run([program, "scene.prm"], cwd=work, capture_output=True,
                                   text=True, timeout=time_limit)
            except subprocess.TimeoutExpired:
                failures.append((n, "time-out", scene))
                continue
            errors = [l for l in p.stderr.splitlines() if not l.startswith("Warning: ")]
            if p.returncode == 0:
                try:
                    text = open(os.path.join(work, "results", "summary.json")).read()
                    summary = json.loads(text)
                    ok = ("NaN" not in text and not unexpected_nulls(summary)
                          and summary["converged"])
                except (OSError, ValueError, KeyError):
                    ok = False
                if ok and not errors:
                    counts["ran"] += 1
                else:
                    failures.append((n, "status 0 but bad summary.json or stderr", scene))
            elif p.returncode == 1 and len(errors) == 1 and errors[0].startswith("Error: "):
                counts["refused"] += 1
            else:
                failures.append((n, "status %d, stderr %r" % (p.returncode, p.stderr[-500:]), scene))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("seed %d: %d scenes, %d ran, %d refused cleanly, %d failed"
          % (seed, runs, counts["ran"], counts["refused"], len(failures)))
    for n, why, scene in failures[:5]:
        print("FAILED scene %d: %s\n%s" % (n, why, scene))
    return 1 if failures else 0


sys.exit(main())
