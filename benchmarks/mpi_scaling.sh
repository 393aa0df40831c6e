#!/usr/bin/env bash
# A tensionless scene on one and on several MPI processes (doc/parallel.md,
# doc/performance.md "Distributed runs"): the paper's example 2 made
# Galerkin + active set on the quarter plate of a uniform mesh with N x N
# cells (n = 3 N^2 + 4 N + 1 foundation nodes; N = 182: n = 100101)
# and the iterative solver, with the storage STORAGE from the environment:
# hierarchical (the default; rows split, block-Jacobi) or fft (near
# pairs and far-field charges split, the soil inverse whole on every
# rank).
#
# Without PARTS, three runs:
#   serial  the program alone, as one process with deal.II's threads on
#           every core;
#   P = 1   mpirun -np 1: Open MPI binds the process to one core, the
#           per-core reference for scaling out;
#   P = 2   mpirun -np 2: one rank per core.
# It prints per run the wall time and its split (summary.json), the
# active-set steps and conjugate gradient iterations, the foundation nodes
# of each rank, and the peak memory of each rank (GNU time around each
# rank), then the ratios.
#
# With PARTS (numbers of processes, e.g. 1 2 4 8), one run per number, the
# processes sharing the cores (--oversubscribe): how the block-Jacobi
# preconditioner's conjugate gradient iterations grow with the number of
# METIS parts, and each rank's memory with it. Its wall times mean nothing
# where the processes outnumber the cores.
# usage: [STORAGE=fft] bash benchmarks/mpi_scaling.sh [build/plate-on-halfspace] [N] [PARTS...]
set -euo pipefail
cd "$(dirname "$0")/.."
program=$(realpath "${1:-build/plate-on-halfspace}")
cells=${2:-182}
shift $(($# < 2 ? $# : 2))
runs=("$@")
storage=${STORAGE:-hierarchical}
case $storage in
  hierarchical | fft) ;;
  *) echo "STORAGE must be hierarchical or fft, not '$storage'" >&2; exit 2 ;;
esac
[ ${#runs[@]} = 0 ] && runs=(serial 1 2)
if [ "$(id -u)" = 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for p in "${runs[@]}"; do
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
  set Storage = $storage
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
  if [ "$p" = serial ]; then
    launch=()
  elif [ $# = 0 ]; then
    launch=(mpirun -np "$p")
  else
    launch=(mpirun --oversubscribe -np "$p")
  fi
  start=$(date +%s.%N)
  "${launch[@]}" /usr/bin/time -f "peak %M kB" "$program" "$work/scene-$p.prm" \
    >"$work/log-$p" 2>"$work/err-$p"
  end=$(date +%s.%N)
  echo "$start $end" >"$work/wall-$p"
done
python3 - "$work" "${runs[@]}" <<'PY'
import json, re, sys
work, runs = sys.argv[1], sys.argv[2:]
rows = {}
for p in runs:
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
                   cg=cg, split=c["foundation_nodes_per_rank"], peaks=peaks,
                   contact=c["contact_nodes"])
if runs[0] != "serial":
    first = rows[runs[0]]
    print("| P | n | nodes per rank | active-set steps | CG its per step "
          "| CG its in all | last step | in all against P = %s "
          "| wall [s] | factorisation [s] | contact solve [s] "
          "| largest rank's peak memory [MB] |" % runs[0])
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for p, r in rows.items():
        print(f"| {p} | {r['n']} | {min(r['split'])}–{max(r['split'])} "
              f"| {r['steps']} | {', '.join(map(str, r['cg']))} | {sum(r['cg'])} "
              f"| {r['cg'][-1]} | {sum(r['cg']) / sum(first['cg']):.2f} "
              f"| {r['wall']:.1f} | {r['factorization']:.2f} | {r['solve']:.1f} "
              f"| {max(r['peaks']):.0f} |")
    sys.exit(0)
print("| run | n | nodes per rank | wall [s] | integration [s] | compression [s] "
      "| factorisation [s] | contact solve [s] | active-set steps | CG its (last step) "
      "| peak memory per rank [MB] |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for p, r in rows.items():
    print(f"| {p} | {r['n']} | {' + '.join(map(str, r['split']))} | {r['wall']:.1f} "
          f"| {r['integration']:.1f} | {r['compression']:.1f} | {r['factorization']:.1f} "
          f"| {r['solve']:.1f} | {r['steps']} | {sum(r['cg'])} ({r['cg'][-1]}) "
          f"| {' / '.join('%.0f' % m for m in r['peaks'])} |")
print()
for name, a in (("serial", rows["serial"]), ("P = 1", rows["1"])):
    b = rows["2"]
    print(f"P = 2 over {name}: wall time {b['wall'] / a['wall']:.2f}, "
          f"largest rank's memory {max(b['peaks']) / max(a['peaks']):.2f}, "
          f"CG iterations {sum(b['cg']) / max(sum(a['cg']), 1):.2f}, "
          f"same contact nodes: {a['contact'] == b['contact']}")
PY
