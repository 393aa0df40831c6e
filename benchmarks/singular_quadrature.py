"""What Discretization/Singular quadrature order buys: example 2 tensionless
on the quarter of a uniform mesh (the scene of hierarchical_scaling.py),
fft storage at Tolerance 1e-10 (so that the storage's own error stays
far below the quadrature's), solved at each order; each run against the
highest order.

    python3 benchmarks/singular_quadrature.py build/plate-on-halfspace [CELLS [ORDERS]]

CELLS: subdivisions of the quarter per direction (default 32: 3201
foundation nodes); ORDERS: comma-separated (default 6,8,10,12,16,20,24,30).
Prints, per order: the integration time of the near field, the total wall
time, max q, and the largest difference of the probes (w, Mx, q) from the
highest order relative to each field's scale, and of max q. Runs go to
output/benchmarks/singular_quadrature/. A benchmark, not a test.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hierarchical_scaling as scaling  # noqa: E402


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(2)
    executable = os.path.abspath(sys.argv[1])
    cells = int(sys.argv[2]) if len(sys.argv) > 2 else 32
    orders = [int(o) for o in (sys.argv[3] if len(sys.argv) > 3 else
                               "6,8,10,12,16,20,24,30").split(",")]
    out = os.path.join(scaling.ROOT, "output", "benchmarks",
                       "singular_quadrature")
    rows = {}
    for order in orders:
        path = f"fft-order-{order}"
        scaling.PATHS[path] = (
            scaling.PATHS["fft"].replace(
                "Storage = fft\n", "Storage = fft\n set Tolerance = 1e-10\n")
            + "subsection Discretization\n"
            f" set Singular quadrature order = {order}\nend\n")
        row = scaling.run(executable, "tensionless", path, cells, out)
        if row is None:
            sys.exit(1)
        rows[order] = row
    reference = rows[max(orders)]["cycle"]
    print(f"n = {reference['n_foundation_dofs']}, against order "
          f"{max(orders)}\n")
    print("| order | integration [s] | total [s] | max q | probes "
          "difference | max q difference |")
    print("|---|---|---|---|---|---|")
    for order in orders:
        c = rows[order]["cycle"]
        print(f"| {order} | {c['foundation_integration_time_s']:.2f} | "
              f"{rows[order]['total']:.1f} | {c['max_q']:.7g} | "
              f"{scaling.difference(c, reference):.1e} | "
              f"{abs(c['max_q'] - reference['max_q']) / reference['max_q']:.1e} |")


if __name__ == "__main__":
    main()
