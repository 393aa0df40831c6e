#!/usr/bin/env bash
# The hierarchical (H-matrix) Galerkin flexibility against the dense one as
# the mesh grows: n, H assembly / H-Cholesky / one product time, memory,
# stored fraction of n^2, product and solve error against dense, dense
# assembly + LAPACK Cholesky time, and the fitted growth exponents
# (benchmarks/hierarchical_flexibility.cc says what each column is).
# Scene: the paper's 12 m x 8 m plate on 3k x 2k cells, n ~ 18 k^2.
# usage: bash benchmarks/hierarchical_flexibility.sh [build dir] [tolerance]
#          [largest dense n] [k ...]
# e.g.   bash benchmarks/hierarchical_flexibility.sh build 1e-6 21000 8 12 17 24 34
# Timings are wall seconds; run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
program="$build/benchmark_hierarchical_flexibility"
[ -x "$program" ] || cmake --build "$build" --target benchmark_hierarchical_flexibility
"$program" "$@"
