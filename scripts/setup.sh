#!/usr/bin/env bash
# Set up a fresh Debian 12 machine (as root), build Release, then either run a
# shipped scene ("run", the default) or the whole test suite ("test").
#   bash scripts/setup.sh run [scene.prm]
#   bash scripts/setup.sh test
set -euo pipefail
mode=${1:-run}
scene=${2:-parameters/example2-bonded.prm}
cd "$(dirname "$0")/.."

# deal.II 9.4 (with Trilinos, UMFPACK, LAPACK), OpenBLAS (not optional: the
# reference BLAS makes every dense factorisation ~20x slower), hmat-oss (the
# hierarchical-matrix flexibility), FFTW (the split-kernel storage's far
# field), MUMPS (the plate on several processes), numdiff (the deal.II
# test macros need it), nlohmann-json (summary.json), gnuplot (plots).
packages="cmake make g++ perl libdeal.ii-dev libopenblas0-pthread
          libhmat-oss-dev libfftw3-dev libmumps-dev numdiff nlohmann-json3-dev
          gnuplot-nox python3"
missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" \
    || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "Installing:$missing"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $missing >/dev/null
fi
# OpenBLAS registers itself as the preferred libblas/liblapack alternative;
# insist on it in case another BLAS was selected by hand.
for lib in libblas.so.3 liblapack.so.3; do
  alt="${lib}-$(dpkg-architecture -qDEB_HOST_MULTIARCH)"
  target=$(update-alternatives --list "$alt" 2>/dev/null | grep openblas-pthread | head -1 || true)
  [ -n "$target" ] && update-alternatives --set "$alt" "$target" >/dev/null
done

jobs=$(nproc)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"

case "$mode" in
  run)
    ./build/plate-on-halfspace "$scene"
    ;;
  test)
    # The MPI tests (NAME.mpirun=2, app/mpi_determinism) run mpirun; Open
    # MPI refuses root unless told (doc/parallel.md).
    if [ "$(id -u)" = 0 ]; then
      export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    fi
    cd build
    ctest -j"$jobs" --output-on-failure
    ;;
  *)
    echo "usage: bash scripts/setup.sh run [scene.prm] | test" >&2
    exit 2
    ;;
esac
