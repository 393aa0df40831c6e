#!/usr/bin/env python3
"""Compare two summary.json files number by number (doc/parallel.md).

usage: compare_summaries.py A.json B.json TOLERANCE

Every number must agree to TOLERANCE relative to the largest magnitude of
its kind in A (the column's scale: a moment against the largest moment,
min_q against max_q), give or take 1e-12 for quantities at rounding
level; every string, flag and count must agree exactly. Three kinds are
judged otherwise:
 - the solvers' relative residuals (penetration, complementarity) are
   compared absolutely;
 - a peak's location (`at`, `..._at`, against the largest coordinate of
   any location) to the square root of TOLERANCE: near a smooth extremum
   the place moves like the square root of the value;
 - an error estimate or a change between cycles to the same square root.
Timings, memory, iteration counts and the number of processes are
skipped: they describe the run, not the answer. Prints the largest
difference and exits non-zero on the first mismatch.
"""
import json
import sys

SKIPPED = ("time_s", "memory_bytes", "mpi_processes", "partitioner",
           "per_rank", "iterations")
# Measures of a solver's residual, relative already (doc/outputs.md): they
# are compared as they are, not against their own (rounding-sized) scale.
RESIDUALS = ("penetration", "complementarity_violation")  # max_ stripped
ROUNDING = 1e-12


def leaves(value, path=""):
    if isinstance(value, dict):
        for key, item in value.items():
            if not any(key.endswith(s) for s in SKIPPED):
                yield from leaves(item, path + "/" + key)
    elif isinstance(value, list):
        for i, item in enumerate(value):
            yield from leaves(item, path + "[%d]" % i)
    else:
        yield path, value


def is_location(name):
    return name == "at" or name.endswith("_at")


def kind(path):
    """The name of a leaf without its indices: its column. Every location
    is of one kind, measured against the plate's extent."""
    out, depth = "", 0
    for c in path:
        if c == "[":
            depth += 1
        elif c == "]":
            depth -= 1
        elif depth == 0:
            out += c
    name = out.split("/")[-1]
    if is_location(name):
        return "location"
    # a field's largest and smallest value share its scale
    for prefix in ("max_", "min_"):
        if name.startswith(prefix):
            return out[: len(out) - len(name)] + name[len(prefix):]
    return out


def is_estimate(name):
    """Error estimates and changes between cycles: differences of nearly
    equal numbers, known to a digit or two of their own."""
    return "error" in name or name in ("dwr", "bound", "change")


def main():
    a_path, b_path, tolerance = sys.argv[1], sys.argv[2], float(sys.argv[3])
    a = dict(leaves(json.load(open(a_path))))
    b = dict(leaves(json.load(open(b_path))))
    if a.keys() != b.keys():
        print("different entries:", sorted(set(a) ^ set(b))[:10])
        return 1
    scale = {}
    for path, value in a.items():
        if isinstance(value, float):
            scale[kind(path)] = max(scale.get(kind(path), 0.0), abs(value))
    worst, worst_path = 0.0, ""
    for path, value in a.items():
        other = b[path]
        if isinstance(value, float) or isinstance(other, float):
            if value is None or other is None:
                if value != other:
                    print("%s: %s against %s" % (path, value, other))
                    return 1
                continue
            reference = max(scale.get(kind(path), 0.0), 1e-300)
            name = kind(path).split("/")[-1]
            if name in RESIDUALS:
                reference = 1.0
            allowed = tolerance
            if name == "location" or is_estimate(name):
                # A peak's place moves like the square root of its value.
                allowed = tolerance ** 0.5
            difference = max(abs(value - other) - ROUNDING, 0) / reference
            if difference > worst:
                worst, worst_path = difference, path
            if difference > allowed:
                print("%s: %r against %r (relative %.1e > %.1e)" %
                      (path, value, other, difference, allowed))
                return 1
        elif value != other:
            print("%s: %r against %r" % (path, value, other))
            return 1
    print("%d entries agree; largest relative difference %.1e (%s)" %
          (len(a), worst, worst_path or "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
