#!/usr/bin/env bash
# A run on 1 and on 2 MPI processes of the same tensionless scene
# (doc/parallel.md, doc/performance.md "Distributed runs"): the paper's
# example 2 made Galerkin + active set on the quarter plate of a uniform
# mesh with N x N cells (n = 3 N^2 + 4 N + 1 foundation nodes; N = 182:
# n = 100101), hierarchical storage and the iterative solver. Prints per
# run the wall time and its split (summary.json), the active-set steps and
# conjugate gradient iterations, the foundation nodes of each rank, and the
# peak memory of each rank (GNU time around each rank), then the ratios
# P = 2 over P = 1.
# usage: bash benchmarks/mpi_scaling.sh [build/plate-on-halfspace] [N]
set -euo pipefail
cd "$(dirname "$0")/.."
program=$(realpath "${1:-build/plate-on-halfspace}")
cells=${2:-182}
if [ "$(id -u)" = 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for p in 1 2; do
  cat >"$work/scene-$p.prm" <<PRM
include $PWD/parameters/example2.prm
set Output directory = $work/out-$p
subsection Discretization
  set Flexibility          = galerkin
  set Symmetry             = xy
  set Initial refinements  = 0
  set Subdivisions x       = $((2 * cells))
  set Subdivisions y       = $((2 * cells))
end
subsection Contact
  set Method = active set
  set Solver = iterative
end
subsection Foundation operator
  set Storage = hierarchical
end
subsection Adaptivity
  set Cycles    = 1
  set Max cells = 10000000
end
subsection Output
  set VTU       = false
  set Verbosity = 1
end
PRM
  start=$(date +%s.%N)
  mpirun -np $p /usr/bin/time -f "peak %M kB" "$program" "$work/scene-$p.prm" \
    >"$work/log-$p" 2>"$work/err-$p"
  end=$(date +%s.%N)
  echo "$start $end" >"$work/wall-$p"
done
python3 - "$work" <<'PY'
import json, re, sys
work = sys.argv[1]
rows = {}
for p in (1, 2):
    c = json.load(open(f"{work}/out-{p}/summary.json"))["cycles"][-1]
    log = open(f"{work}/log-{p}").read()
    cg = [int(x) for x in re.findall(r"conjugate gradients (\d+) iterations", log)]
    peaks = [int(x) / 1024 for x in re.findall(r"peak (\d+) kB", open(f"{work}/err-{p}").read())]
    start, end = map(float, open(f"{work}/wall-{p}").read().split())
    rows[p] = dict(n=c["n_foundation_dofs"], wall=end - start,
                   integration=c["foundation_integration_time_s"],
                   compression=c["foundation_compression_time_s"],
                   factorization=c["foundation_factorization_time_s"],
                   solve=c["solve_time_s"], steps=c["contact_iterations"],
                   cg=sum(cg), last_cg=cg[-1] if cg else 0,
                   split=c["foundation_nodes_per_rank"], peaks=peaks,
                   contact=c["contact_nodes"])
print("| P | n | nodes per rank | wall [s] | integration [s] | compression [s] "
      "| H-Cholesky [s] | contact solve [s] | active-set steps | CG its (last set) "
      "| peak memory per rank [MB] |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for p, r in rows.items():
    print(f"| {p} | {r['n']} | {' + '.join(map(str, r['split']))} | {r['wall']:.1f} "
          f"| {r['integration']:.1f} | {r['compression']:.1f} | {r['factorization']:.1f} "
          f"| {r['solve']:.1f} | {r['steps']} | {r['cg']} ({r['last_cg']}) "
          f"| {' / '.join('%.0f' % m for m in r['peaks'])} |")
a, b = rows[1], rows[2]
print()
print(f"P = 2 over P = 1: wall time {b['wall'] / a['wall']:.2f}, "
      f"largest rank's memory {max(b['peaks']) / max(a['peaks']):.2f}, "
      f"CG iterations {b['cg'] / max(a['cg'], 1):.2f}, "
      f"same contact nodes: {a['contact'] == b['contact']}")
PY
