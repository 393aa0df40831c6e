#!/usr/bin/env python3
"""Group a heaptrack profile's peak memory by the part of the program that
allocated it (doc/performance.md, "What each rank holds").

usage (heaptrack is Debian's package of that name; scripts/setup.sh does
not install it):
  heaptrack -o PROFILE build/plate-on-halfspace scene.prm
  python3 benchmarks/memory_by_part.py PROFILE.zst
  (under MPI, one profile per rank:
   mpirun -np 2 sh -c 'heaptrack -o PROFILE.$OMPI_COMM_WORLD_RANK ...')

heaptrack_print lists each call site's peak; a site is assigned to the
first part whose pattern its call stack matches, in the order below. The
sites do not all peak at once, so the parts add up to more than the peak
heap, which is printed too.
"""
import re
import subprocess
import sys

PARTS = [
    ("plate factor (CHOLMOD)", r"SparseCholesky|cholmod"),
    ("plate factor (MUMPS, Trilinos)", r"mumps|Amesos|Epetra|DistributedSparseDirect"),
    ("H-Cholesky factor", r"HierarchicalFlexibility::factorize"),
    ("H-matrix", r"hmat|Hmat|Hierarchical"),
    ("mesh, DoFs, plate matrix and constraints",
     r"MindlinPlate::setup|SparsityPattern|SparseMatrix<>::reinit|"
     r"AffineConstraints|DoFHandler|Triangulation|make_coarse"),
]
SITE = re.compile(r"^\s*([\d.]+)([KMG]?) (?:peak memory )?consumed over \d+ calls from")
UNIT = {"": 1e-6, "K": 1e-3, "M": 1.0, "G": 1e3}


def main():
    profile = sys.argv[1]
    text = subprocess.run(
        ["heaptrack_print", "-f", profile, "--print-peaks", "1",
         "--print-allocators", "0", "--print-leaks", "0",
         "--print-temporary", "0", "--print-histogram", "0",
         "--print-flamegraph", "0", "-n", "400"],
        capture_output=True, text=True, check=True).stdout
    sites, stack = [], None
    for line in text.splitlines():
        match = SITE.match(line)
        if match:
            stack = []
            sites.append((float(match.group(1)) * UNIT[match.group(2)], stack))
        elif stack is not None:
            stack.append(line.strip())
    totals = {}
    for megabytes, lines in sites:
        calls = " | ".join(lines)
        part = next((name for name, pattern in PARTS
                     if re.search(pattern, calls)), "other")
        totals[part] = totals.get(part, 0.0) + megabytes
    peak = re.search(r"peak heap memory consumption: (.*)",
                     subprocess.run(["heaptrack_print", "-f", profile],
                                    capture_output=True, text=True).stdout)
    print("peak heap:", peak.group(1) if peak else "unknown")
    for name, megabytes in sorted(totals.items(), key=lambda x: -x[1]):
        print("%8.1f MB  %s" % (megabytes, name))


if __name__ == "__main__":
    main()
