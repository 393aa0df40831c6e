#!/usr/bin/env python3
"""Fuzz-style test of the executable: randomly perturbed versions
of a small valid scene (tests/app/bad_input_base.prm made tensionless with a
patch and a point load, every second one on a dense liquid instead of the
half-space, every third one two jointed slabs with an axle swept across the
joint), a fixed seed, each run with a time limit. Besides the entries'
values, lost lines and misspelt names, the perturbations also take
- paths: an Output directory or Plate/Mesh file with control characters
  (NUL included), spaces, non-ASCII letters, links (to a directory, a file,
  nowhere), a name longer than the system allows;
- includes: the scene including itself (by name, by ./name, by a link),
  a cycle of two files, a chain nested 40 deep, a missing file, a
  directory, a FIFO, a UTF-16 file, a UTF-8 file with a byte-order mark;
- load sizes: pressures and forces from 1e-300 to 1e300, patches far
  larger than the plate;
- pressure functions: malformed, unknown names, NaN or infinite values,
  regions off the plate, and their constants and quadrature.
Every run must either succeed (status 0, summary.json without NaN or
infinity and without null except a goal's "change" on the first cycle and
"dwr" of the contact area, "converged": true, every number of the CSV
files finite) or fail cleanly (status 1, exactly one "Error: ..." line on
stderr besides "Warning: ..." lines). stderr never holds a raw control
character, and no run changes or removes anything outside its output
directory (a directory and a file kept beside it, and what the links point
to, are checked after every run). A signal, a time-out, another status or
a malformed result fails the test.

usage: fuzz_scenes.py PROGRAM TESTS_APP_DIRECTORY [RUNS] [SEED]
"""
import json
import math
import os
import random
import re
import resource
import shutil
import subprocess
import sys
import tempfile

program, here = sys.argv[1], sys.argv[2]
sys.path.insert(0, here)
import compare_vtu  # noqa: E402  (its reader of DataOut's compressed VTU)
runs = int(sys.argv[3]) if len(sys.argv) > 3 else 200
seed = int(sys.argv[4]) if len(sys.argv) > 4 else 20240605
# A valid run of these scenes takes well under 1 s of CPU time. The limit
# is on the CPU time the run used, so that a machine busy with other work
# does not fail the test; a run that waits (a hang: an include of a FIFO
# did) is stopped by the wall-clock limit.
time_limit = 30  # seconds of CPU time
wall_time_limit = 120  # seconds

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
  set Pressure function   =
  set Function constants  =
  set Pressure function region =
  set Pressure function points = 6
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
  set Constrained start = true
  set Nested start = auto
  set Preconditioner = auto
end
subsection Foundation operator
  set Storage = auto
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
           "0.5", "0.499", "1e-6", "1e9", "2.5", "-0.2", "3", "1e999",
           "2e-310", "1e-400", "-0.999999999"]
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
    "Model": ["half-space", "dense liquid", "layered", "winkler", ""],
    "Layers": ["", "0.3, 3e5, 0.35", "0.3, 3e5, 0.35 ; 4, 4e4, 0.4", "0, 1e5, 0.3",
               "0.3, 3e5", "0.3, x, 0.3", "1e-9, 1e5, 0.3", "0.3, 1e300, 0.3",
               "0.3, 3e5, 0.5", "1e6, 1e5, 0.3", "nan, 1, 0.3", ";;",
               "0x10, 1e5, 0.3", "0.3, 3e5, 0.35,", "1, 1e9, 0.3",
               "0.3, 1e5, 0.4999999", "1, 1e5, 0.3 ; 1e-6, 1e4, 0.3",
               "1e-20, 1e5, 0.3", "0.3, 1e-160, 0.3", "1e160, 1e5, 0.3"],
    "Base": ["half-space", "rigid", "bedrock", ""],
    "Interfaces": ["bonded", "frictionless", "rough"],
    "Profile": ["", "20,10", "5", "1,x", "20,15,10,12", "20;10", "nan,1", "1e300,-1e300",
                "1.7e308,0", "1e4,0"],
    "Difference": ["5", "-20", "0", "1e300", "5e4", "nan", "2e-310"],
    "Modulus of subgrade reaction": ["0", "1e4", "-1e4", "1e-300", "1e300", "nan",
                                     "x", "5e4 kN/m3"],
    "Method": ["active set", "element exclusion", "newton"],
    "Subdivisions x": ["1", "2", "4", "0", "-3", "2.5", "1001", "x"],
    "Subdivisions y": ["1", "2", "4", "0", "-3", "2.5", "1001", "x"],
    "Initial refinements": ["0", "1", "-1", "11", "x"],
    "Cycles": ["1", "2", "0", "31"],
    "Max iterations": ["1", "2", "0", "100"],
    "Constrained start": ["true", "false", "maybe", "", "1"],
    "Nested start": ["auto", "true", "false", "yes", ""],
    "Preconditioner": ["auto", "soil inverse", "plate on springs", "jacobi", ""],
    "Storage": ["auto", "dense", "hierarchical", "fft", "fast", ""],
    "Rectangular patches": ["", "0,0,1,1,100", "1,0,0,1,10", "0,0,1", "5,5,6,6,1",
                            "-3,-3,3,3,10", "0,0,1,1,nan", "0,0,1,1,-1e9", ";;", "a,b,c,d,e"],
    "Circular patches": ["", "0,0,0.3,50", "0,0,0,50", "0,0,-1,50", "9,9,1,1", "0,0,5,10"],
    "Point loads": ["", "0,0,10", "1,0.75,10", "0,0,-10", "3,0,10", "0,0", "0,0,inf",
                    "0.3333,0.25,1e9", "-1,-0.75,1e-6"],
    "Pressure function": ["", "5*(y+1)^2", "p0*(1-x/a)", "sin(", "z", "sqrt(x)",
                          "exp(1000*x)", "1/x", "x*y*1e300", "-10", "10,20", "x=3",
                          "1e-320", "1 + if(x>0.9, 1000, 0)", "rand()", "10;20"],
    "Function constants": ["", "p0=5, a=2", "p0=5, p0=6", "x=1", "p0", "p0=nan", "1a=2",
                           "_pi=3", "a=1;b=2", "a=3,", "pi=3", "a" * 120 + "=1"],
    "Pressure function region": ["", "0,0,0.5", "-1,-0.5,0.5,0.5", "0,0,-1", "1,1,0,0",
                                 "0,0", "9,9,1", "0,0,1;1,1,1"],
    "Pressure function points": ["6", "1", "30", "0", "31", "x"],
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
    (doc/outputs.md): the goal block's change and dwr, its relative_error
    where its value is 0 (and the goal_target's then), a joint's lte where
    neither side deflects downward, and the sweep envelope's min_lte then."""
    if value is None:
        documented = ((parent == "goal" and
                       key in ("change", "dwr", "relative_error")) or
                      (parent == "goal_target" and key == "relative_error") or
                      (parent == "joints" and key == "lte") or
                      (parent == "envelope" and key == "min_lte"))
        return [] if documented else [key]
    if isinstance(value, dict):
        return [n for k, v in value.items()
                for n in unexpected_nulls(v, k, key)]
    if isinstance(value, list):
        return [n for v in value for n in unexpected_nulls(v, key, parent)]
    return []


layered = base.replace("Model           = half-space",
                       "Model           = layered\n"
                       "  set Layers          = 0.3, 3e4, 0.35 ; 1, 2e4, 0.4\n"
                       "  set Base            = rigid\n"
                       "  set Interfaces      = bonded")


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


# Output directory and Mesh file values (doc/errors-and-limits.md): raw
# bytes, as a user's editor or printf may write them.
odd_directories = [b"results dir", "r\u00e9sultats".encode(), b"results\x00/x",
                   b"keep\x00/results", b"res\x01ults", b"results\x1b[31m",
                   b"results\x7f", b"results\rx", "r\u0085s".encode(),
                   b"results/deep/er", b"link-to-directory/results",
                   b"link-to-directory", b"link-to-file", b"dangling-link",
                   b"keep/file/results", b"r" * 300, b"-results", b"./results/"]
odd_mesh_files = [b"triangles\x00.msh", b"tri\x01angles.msh", b"link-to-mesh",
                  b"link-to-directory", b"dangling-link", b"keep"]
# Include lines; the files they name are made in the working directory.
includes = [b"scene.prm", b"./scene.prm", b"link-to-scene.prm", b"cycle-a.prm",
            b"deep-1.prm", b"no-such.prm", b"keep", b"fifo.prm",
            b"utf16.prm", b"bom.prm", b"inc\x00lude.prm", b"empty.prm"]
magnitudes = ["1e-300", "-1e-300", "1e-30", "1e30", "1e100", "1e300", "-1e300",
              "1.7e308", "4.9e-324"]
huge_patches = {
    "Rectangular patches": ["-1e14,-1e14,1e14,1e14,10", "0,0,1e300,1e300,1",
                            "-1e-9,-1e-9,1e-9,1e-9,1e12", "0,0,1e-300,1e-300,1"],
    "Circular patches": ["0,0,1e13,1", "0,0,3e14,10", "0,0,1e-9,1e20",
                         "0.1,0.1,1e300,1e-300"],
}


def make_files(work):
    """The files the path and include perturbations name."""
    def write(name, data):
        with open(os.path.join(work, name), "wb") as f:
            f.write(data)
    os.makedirs(os.path.join(work, "keep"))
    write("keep/file", b"kept\n")
    os.makedirs(os.path.join(work, "target-directory"))
    write("target-directory/file", b"kept\n")
    write("target-file", b"kept\n")
    os.symlink("target-directory", os.path.join(work, "link-to-directory"))
    os.symlink("target-file", os.path.join(work, "link-to-file"))
    os.symlink("no-such-target", os.path.join(work, "dangling-link"))
    os.symlink("triangles.msh", os.path.join(work, "link-to-mesh"))
    os.symlink("scene.prm", os.path.join(work, "link-to-scene.prm"))
    write("cycle-a.prm", b"include cycle-b.prm\n")
    write("cycle-b.prm", b"# the other half of a cycle\ninclude cycle-a.prm\n")
    for depth in range(1, 41):
        write("deep-%d.prm" % depth,
              b"include deep-%d.prm\n" % (depth + 1) if depth < 40 else b"\n")
    os.mkfifo(os.path.join(work, "fifo.prm"))
    write("utf16.prm", "# a comment\n".encode("utf-16"))
    write("bom.prm", b"\xef\xbb\xbf# a comment in a file with a byte-order mark\n")
    write("empty.prm", b"")


def untouched(work):
    """What lies beside the output directory is as make_files left it (an
    Output directory may be link-to-directory: results may then be added to
    target-directory, but its file stays)."""
    def read(name):
        with open(os.path.join(work, name), "rb") as f:
            return f.read()
    try:
        return (read("keep/file") == b"kept\n" and os.listdir(os.path.join(work, "keep")) == ["file"]
                and read("target-directory/file") == b"kept\n"
                and read("target-file") == b"kept\n"
                and read("scene.prm") == read("link-to-scene.prm")
                and os.readlink(os.path.join(work, "link-to-directory")) == "target-directory"
                and os.readlink(os.path.join(work, "link-to-file")) == "target-file"
                and os.readlink(os.path.join(work, "dangling-link")) == "no-such-target")
    except OSError:
        return False


def clean(work, kept):
    """Removes what a run added to the working directory (and to
    target-directory), so that each run starts alike."""
    for top, names in ((work, kept), (os.path.join(work, "target-directory"), ["file"])):
        for name in os.listdir(top):
            if name not in names:
                path = os.path.join(top, name)
                if os.path.isdir(path) and not os.path.islink(path):
                    shutil.rmtree(path, ignore_errors=True)
                else:
                    os.unlink(path)


def set_value(lines, name, value):
    """Sets the entry NAME (bytes) on every line that sets it."""
    for i, line in enumerate(lines):
        if re.match(rb"\s*set " + re.escape(name) + rb"\s*=", line):
            lines[i] = line.split(b"=")[0] + b"= " + value


perturbed = [0, 0, 0, 0]  # scenes with paths, includes, load sizes, none


def perturb_more(rng, scene):
    """At most one of the path, include and load-size perturbations: the
    scene's bytes and the output directory it names."""
    lines = scene.encode().splitlines()
    directory = b"results"
    kind = rng.random()
    perturbed[0 if kind < 0.15 else 1 if kind < 0.3 else 2 if kind < 0.45 else 3] += 1
    if kind < 0.1:
        directory = rng.choice(odd_directories)
        set_value(lines, b"Output directory", directory)
    elif kind < 0.15:
        set_value(lines, b"Shape", b"mesh file")
        set_value(lines, b"Mesh file", rng.choice(odd_mesh_files))
    elif kind < 0.3:
        i = rng.randrange(1, len(lines) + 1)
        lines.insert(i, b"include " + rng.choice(includes))
    elif kind < 0.45:
        for _ in range(rng.randint(1, 2)):
            name = rng.choice(["Uniform pressure", "Rectangular patches",
                               "Circular patches", "Point loads"])
            if name == "Uniform pressure":
                value = rng.choice(magnitudes)
            elif rng.random() < 0.5:
                value = rng.choice(huge_patches.get(name, ["0,0," + rng.choice(magnitudes)]))
            elif name == "Rectangular patches":
                value = "0,0,1,0.75," + rng.choice(magnitudes)
            elif name == "Circular patches":
                value = "0,0,0.3," + rng.choice(magnitudes)
            else:
                value = "-0.5,0," + rng.choice(magnitudes)
            set_value(lines, name.encode(), value.encode())
        if rng.random() < 0.5:
            set_value(lines, b"VTU", b"true")  # Float32 fields: still finite?
    return b"\n".join(lines) + b"\n", directory


def finite_results(results):
    """Every number in the result files (CSV, convergence.txt, VTU) is
    finite; "" if so, else why not."""
    for name in sorted(os.listdir(results)):
        path = os.path.join(results, name)
        shown = name.decode(errors="replace")
        if name.endswith(b".csv") or name == b"convergence.txt":
            with open(path, errors="replace") as f:
                for token in re.split(r"[\s,;]+", f.read()):
                    if re.fullmatch(r"[-+]?(nan|inf|infinity)", token, re.I):
                        return "%s holds %s" % (shown, token)
        elif name.endswith(b".vtu"):
            with open(path, errors="replace") as f:
                for dtype, attributes, body in compare_vtu.ARRAY.findall(f.read()):
                    if dtype.startswith("Float") and not all(
                            math.isfinite(v) for v in compare_vtu.decode(body, dtype)):
                        return "%s: %s is not finite" % (shown, attributes.strip())
    return ""


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
    make_files(work)
    kept = os.listdir(work) + ["scene.prm"]
    counts = {"ran": 0, "refused": 0}
    failures = []

    def not_finite(constant):
        raise ValueError("summary.json holds " + constant)
    try:
        for n in range(runs):
            scene, directory = perturb_more(rng, perturb(rng, jointed if n % 3 == 2 else
                                                            layered if n % 5 == 4 else
                                                            dense_liquid if n % 2 else base))
            with open(os.path.join(work, "scene.prm"), "wb") as f:
                f.write(scene)
            clean(work, kept)
            results = os.path.join(work.encode(), directory)
            used = resource.getrusage(resource.RUSAGE_CHILDREN)
            try:
                p = subprocess.run([program, "scene.prm"], cwd=work, capture_output=True,
                                   timeout=wall_time_limit)
            except subprocess.TimeoutExpired:
                failures.append((n, "time-out (%d s)" % wall_time_limit, scene))
                continue
            now = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = now.ru_utime + now.ru_stime - used.ru_utime - used.ru_stime
            if cpu > time_limit:
                failures.append((n, "%.0f s of CPU time" % cpu, scene))
                continue
            stderr = p.stderr.decode(errors="replace")
            errors = [l for l in stderr.splitlines() if not l.startswith("Warning: ")]
            if re.search(rb"[\x00-\x09\x0b-\x1f\x7f]|\xc2[\x80-\x9f]", p.stderr):
                failures.append((n, "a raw control character on stderr: %r" % p.stderr[-500:],
                                 scene))
            elif not untouched(work):
                failures.append((n, "a file or directory beside the results changed", scene))
            elif p.returncode == 0:
                try:
                    text = open(os.path.join(results, b"summary.json")).read()
                    summary = json.loads(text, parse_constant=not_finite)
                    why = ("unexpected null" if unexpected_nulls(summary) else
                           "not converged" if not summary["converged"] else
                           finite_results(results))
                except (OSError, ValueError, KeyError) as e:
                    why = str(e) or "no summary.json"
                if not why and not errors:
                    counts["ran"] += 1
                else:
                    failures.append((n, "status 0 but %s or stderr %r"
                                     % (why, stderr[-300:]), scene))
            elif p.returncode == 1 and len(errors) == 1 and errors[0].startswith("Error: "):
                counts["refused"] += 1
            else:
                failures.append((n, "status %d, stderr %r" % (p.returncode, stderr[-500:]), scene))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("seed %d: %d scenes, %d ran, %d refused cleanly, %d failed"
          % (seed, runs, counts["ran"], counts["refused"], len(failures)))
    print("perturbed paths in %d scenes, includes in %d, load sizes in %d"
          % tuple(perturbed[:3]))
    for n, why, scene in failures[:5]:
        print("FAILED scene %d: %s\n%s" % (n, why, scene.decode(errors="backslashreplace")))
    return 1 if failures else 0


sys.exit(main())
