// The far field's gridding as a sparse matrix P (halfspace/
// grid_projection.h; doc/formulation.md, "Split-kernel FFT storage")
// against independent computations on patches of unequal rectangles with
// bilinear node functions and 4 x 4 Gauss points each, on a grid of
// spacing 0.07 with B-splines of order 4, 6 and 8:
//  - a 3 x 2 patch (12 rows, one task) and a 40 x 30 patch (1271 rows in
//    parallel tasks, 1200 cells, more than the rows' cache of cells holds);
//  - each row sums to the integral of its node function (the B-splines
//    are a partition of unity): area / 4 per cell of the node, to 1e-12;
//  - P^T v equals the charges spread point by point from
//    GridConvolution::stencil(), to 1e-13 of their largest;
//  - P phi equals the potentials read back point by point and tested with
//    the node functions, to 1e-13 of their largest;
//  - with the corner cell left out (another rank's), P holds exactly the
//    others' points and the corner node's row is empty: the same two
//    comparisons on the remaining cells;
//  - the memory counted before P is made covers what it holds.
// The verdicts only are printed: the sums' rounding depends on the order.

#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/halfspace/grid_convolution.h>
#include <plate_on_halfspace/halfspace/grid_projection.h>

#include <cmath>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  using CellPoints = GridProjection::CellPoints;

  /** Cell (i, j): corners x[i], x[i + 1] by y[j], y[j + 1]; cell i + j
   *  (x.size() - 1), node i + j x.size(). */
  struct Patch
  {
    std::string         name;
    std::vector<double> x, y;

    unsigned int
    node(const unsigned int i, const unsigned int j) const
    {
      return i + j * x.size();
    }

    unsigned int
    n_nodes() const
    {
      return x.size() * y.size();
    }
  };

  /** @p n lines from @p low to @p high, unevenly spaced. */
  std::vector<double>
  lines(const unsigned int n, const double low, const double high)
  {
    std::vector<double> x(n);
    for (unsigned int k = 0; k < n; ++k)
      {
        const double t = double(k) / (n - 1);
        x[k]           = low + (high - low) * (t + 0.1 * t * (1 - t));
      }
    return x;
  }

  std::vector<CellPoints>
  patch_cells(const Patch &patch)
  {
    const QGauss<2>         rule(4);
    std::vector<CellPoints> cells;
    for (unsigned int j = 0; j + 1 < patch.y.size(); ++j)
      for (unsigned int i = 0; i + 1 < patch.x.size(); ++i)
        {
          CellPoints   cell;
          const double x0 = patch.x[i], y0 = patch.y[j],
                       dx = patch.x[i + 1] - x0, dy = patch.y[j + 1] - y0;
          cell.nodes = {patch.node(i, j),
                        patch.node(i + 1, j),
                        patch.node(i, j + 1),
                        patch.node(i + 1, j + 1)};
          for (unsigned int q = 0; q < rule.size(); ++q)
            {
              const Point<2> &u = rule.point(q);
              cell.points.emplace_back(x0 + u[0] * dx, y0 + u[1] * dy);
              const double jxw = rule.weight(q) * dx * dy;
              for (const double psi : {(1 - u[0]) * (1 - u[1]),
                                       u[0] * (1 - u[1]),
                                       (1 - u[0]) * u[1],
                                       u[0] * u[1]})
                cell.weighted_values.push_back(jxw * psi);
            }
          cells.push_back(cell);
        }
    return cells;
  }

  /** Charges spread point by point: sum_q (sum_a w_qa v_a) W(x_q). */
  Vector<double>
  direct_charges(const GridConvolution         &grid,
                 const std::vector<CellPoints> &cells,
                 const std::vector<bool>       &used,
                 const Vector<double>          &v)
  {
    const unsigned int nx = grid.grid_sizes()[0];
    Vector<double>     charges(grid.n_grid_nodes());
    for (unsigned int c = 0; c < cells.size(); ++c)
      if (used[c])
        for (unsigned int q = 0; q < cells[c].points.size(); ++q)
          {
            double charge = 0;
            for (unsigned int a = 0; a < 4; ++a)
              charge +=
                cells[c].weighted_values[4 * q + a] * v[cells[c].nodes[a]];
            const auto s = grid.stencil(cells[c].points[q]);
            for (unsigned int l = 0; l < grid.order(); ++l)
              for (unsigned int k = 0; k < grid.order(); ++k)
                charges[(s.first_y + l) * nx + s.first_x + k] +=
                  charge * s.y[l] * s.x[k];
          }
    return charges;
  }

  /** Potentials read back point by point and tested with the nodes. */
  Vector<double>
  direct_tests(const GridConvolution         &grid,
               const std::vector<CellPoints> &cells,
               const std::vector<bool>       &used,
               const Vector<double>          &phi,
               const unsigned int             n_nodes)
  {
    const unsigned int nx = grid.grid_sizes()[0];
    Vector<double>     tests(n_nodes);
    for (unsigned int c = 0; c < cells.size(); ++c)
      if (used[c])
        for (unsigned int q = 0; q < cells[c].points.size(); ++q)
          {
            const auto s     = grid.stencil(cells[c].points[q]);
            double     value = 0;
            for (unsigned int l = 0; l < grid.order(); ++l)
              for (unsigned int k = 0; k < grid.order(); ++k)
                value +=
                  phi[(s.first_y + l) * nx + s.first_x + k] * s.y[l] * s.x[k];
            for (unsigned int a = 0; a < 4; ++a)
              tests[cells[c].nodes[a]] +=
                cells[c].weighted_values[4 * q + a] * value;
          }
    return tests;
  }

  void
  check(const Patch &patch, const unsigned int order)
  {
    const std::string name = patch.name + ", order " + std::to_string(order);
    const GridConvolution         grid(Point<2>(0.08, 0.03),
                               0.07,
                               {{0.75, 0.55}},
                               order,
                               [](const double r) { return std::exp(-r * r); });
    const std::vector<CellPoints> cells   = patch_cells(patch);
    const unsigned int            n_nodes = patch.n_nodes();
    const auto                    nodes_of =
      [&](const unsigned int c) -> const std::vector<unsigned int> & {
      return cells[c].nodes;
    };
    const auto tabulate = [&](const unsigned int c, CellPoints &points) {
      points = cells[c];
    };

    Vector<double> v(n_nodes), phi(grid.n_grid_nodes());
    for (unsigned int i = 0; i < n_nodes; ++i)
      v[i] = 1. + 0.5 * std::cos(1.7 * i);
    for (unsigned int g = 0; g < phi.size(); ++g)
      phi[g] = std::sin(0.013 * g) + 0.2 * std::cos(0.7 * g);

    for (const bool all : {true, false})
      {
        std::vector<bool> used(cells.size(), true);
        if (!all)
          used[0] = false;
        const std::string which =
          name + (all ? ", all cells" : ", the corner cell left out");
        GridProjection    projection(grid, used, n_nodes, nodes_of, tabulate);
        const std::size_t counted = projection.memory_needed();
        projection.assemble();

        // the row sums: P applied to a unit grid field
        Vector<double> ones(grid.n_grid_nodes()), row_sums(n_nodes);
        ones = 1.;
        projection.add_tests(ones, row_sums);
        if (all)
          {
            double worst = 0;
            for (unsigned int j = 0; j < patch.y.size(); ++j)
              for (unsigned int i = 0; i < patch.x.size(); ++i)
                {
                  double integral = 0;
                  for (unsigned int cj = (j > 0 ? j - 1 : 0);
                       cj < std::min<unsigned int>(j + 1, patch.y.size() - 1);
                       ++cj)
                    for (unsigned int ci = (i > 0 ? i - 1 : 0);
                         ci < std::min<unsigned int>(i + 1, patch.x.size() - 1);
                         ++ci)
                      integral += (patch.x[ci + 1] - patch.x[ci]) *
                                  (patch.y[cj + 1] - patch.y[cj]) / 4.;
                  worst =
                    std::max(worst,
                             std::abs(row_sums[patch.node(i, j)] - integral) /
                               integral);
                }
            check_below(which + ": rows sum to the node functions' integrals",
                        worst,
                        1e-12);
          }
        else
          require(which + ": the corner node's row is empty",
                  row_sums[patch.node(0, 0)] == 0.);

        Vector<double> charges(grid.n_grid_nodes());
        projection.spread(v, charges);
        check_below(which + ": P^T v against point-by-point spreading",
                    relative_difference(charges,
                                        direct_charges(grid, cells, used, v),
                                        Norm::max),
                    1e-13);

        Vector<double> tests(n_nodes);
        projection.add_tests(phi, tests);
        check_below(
          which + ": P phi against point-by-point tests",
          relative_difference(tests,
                              direct_tests(grid, cells, used, phi, n_nodes),
                              Norm::max),
          1e-13);

        require(which + ": memory counted before covers memory held",
                counted >= projection.memory_consumption());
      }
  }
} // namespace

int
main()
{
  initlog();
  const Patch small{"3 x 2 cells",
                    {-0.61, -0.13, 0.2, 0.77},
                    {-0.45, 0.08, 0.52}};
  const Patch large{"40 x 30 cells",
                    lines(41, -0.6, 0.77),
                    lines(31, -0.45, 0.52)};
  for (const Patch *patch : {&small, &large})
    for (const unsigned int order : {4u, 6u, 8u})
      check(*patch, order);
}
