#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <plate_on_halfspace/contact/contact_region.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/soil/soil_model.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace PlateOnHalfspace
{
  namespace
  {
    /** Sub-cells per direction of a cell the contact boundary crosses. */
    constexpr unsigned int subdivisions = 16;

    /** The area of the triangle @p a, @p b, @p c. */
    double
    triangle_area(const Point<2> &a, const Point<2> &b, const Point<2> &c)
    {
      return 0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) -
                            (c[0] - a[0]) * (b[1] - a[1]));
    }

    /**
     * The area of the part of a triangle of area @p area where the linear
     * interpolant of its vertex values @p f is positive.
     */
    double
    positive_part(std::array<double, 3> f, const double area)
    {
      std::sort(f.begin(), f.end());
      if (f[0] >= 0)
        return f[2] > 0 ? area : 0.;
      if (f[2] <= 0)
        return 0;
      if (f[1] <= 0)
        // one vertex above zero: a corner triangle similar to the whole
        return area * f[2] * f[2] / ((f[2] - f[0]) * (f[2] - f[1]));
      // one vertex below zero: the whole less its corner triangle
      return area - area * f[0] * f[0] / ((f[1] - f[0]) * (f[2] - f[0]));
    }

    /**
     * A cell's sub-cells: the physical points of their corners and
     * centres, mapped once for every field measured on the cell.
     */
    struct SubCells
    {
      static constexpr unsigned int m = subdivisions;

      explicit SubCells(const FoundationSpace::Cell &cell)
        : area(cell.geometry.area())
      {
        for (unsigned int i = 0; i <= m; ++i)
          for (unsigned int j = 0; j <= m; ++j)
            corner[i][j] = cell.geometry.map(corner_point(i, j));
        for (unsigned int i = 0; i < m; ++i)
          for (unsigned int j = 0; j < m; ++j)
            centre[i][j] = cell.geometry.map(centre_point(i, j));
      }

      static Point<2>
      corner_point(const unsigned int i, const unsigned int j)
      {
        return Point<2>(double(i) / m, double(j) / m);
      }

      static Point<2>
      centre_point(const unsigned int i, const unsigned int j)
      {
        return Point<2>((i + 0.5) / m, (j + 0.5) / m);
      }

      /** The cell's area, as FoundationSpace::area() sums it. */
      double                                         area;
      std::array<std::array<Point<2>, m + 1>, m + 1> corner;
      std::array<std::array<Point<2>, m>, m>         centre;
    };

    /**
     * The area of the cell of @p cells where @p value (a function of the
     * reference point) is positive: its interpolant on the sub-cells'
     * triangles.
     */
    template <typename Value>
    double
    positive_area(const SubCells &cells, const Value &value)
    {
      constexpr unsigned int                       m = SubCells::m;
      std::array<std::array<double, m + 1>, m + 1> f;
      for (unsigned int i = 0; i <= m; ++i)
        for (unsigned int j = 0; j <= m; ++j)
          f[i][j] = value(SubCells::corner_point(i, j));
      // wholly in or out: the cell's own area, so that full contact reads
      // exactly 1
      const auto [low, high] = std::minmax_element(&f[0][0], &f[m][m] + 1);
      if (*low > 0)
        return cells.area;
      if (*high <= 0)
        return 0.;
      // four triangles about each sub-cell's centre: the same measure for
      // a cell and its mirror image
      double area = 0;
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < m; ++j)
          {
            const double f_c = value(SubCells::centre_point(i, j));
            const std::array<std::pair<unsigned int, unsigned int>, 4> ring = {
              {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
            for (unsigned int k = 0; k < 4; ++k)
              {
                const auto [a0, a1] = ring[k];
                const auto [b0, b1] = ring[(k + 1) % 4];
                area += positive_part({{f[a0][a1], f[b0][b1], f_c}},
                                      triangle_area(cells.corner[a0][a1],
                                                    cells.corner[b0][b1],
                                                    cells.centre[i][j]));
              }
          }
      return area;
    }

    /**
     * The nodal values g of the gap field whose tests are @p tested_gap:
     * B g = tested_gap, B the test coupling (doc/outputs.md, "Contact
     * area"). On a dense liquid g = q/k - w exactly. Where some node has no
     * foundation cell (the paper's element exclusion) B is singular, and
     * the tested gap over the integral of its test function stands in.
     */
    Vector<double>
    pointwise_gap(const FoundationOperator &foundation,
                  const Vector<double>     &tested_gap)
    {
      const SparseMatrix<double> &tests = foundation.test_coupling();
      const unsigned int          n     = tested_gap.size();
      Vector<double>              ones(n), integrals(n), gap(n);
      ones = 1.;
      tests.vmult(integrals, ones);
      bool every_node_supported = true;
      for (unsigned int i = 0; i < n; ++i)
        every_node_supported =
          every_node_supported && integrals[i] > 0 && tests.diag_element(i) > 0;
      if (every_node_supported)
        {
          SolverControl                            control(200,
                                1e-13 * tested_gap.l2_norm(),
                                false,
                                false);
          SolverGMRES<Vector<double>>              solver(control);
          PreconditionJacobi<SparseMatrix<double>> jacobi;
          jacobi.initialize(tests);
          try
            {
              solver.solve(tests, gap, tested_gap, jacobi);
              return gap;
            }
          catch (const SolverControl::NoConvergence &)
            {
              // the lumped values below
            }
        }
      for (unsigned int i = 0; i < n; ++i)
        gap[i] = integrals[i] > 0 ? tested_gap[i] / integrals[i] : 0.;
      return gap;
    }
  } // namespace

  void
  measure_contact_region(const FoundationSpace    &space,
                         const FoundationOperator &foundation,
                         const bool                tensionless,
                         ContactState             &state)
  {
    const unsigned int n_cells = space.cells.size();
    state.cell_contact_area.assign(n_cells, 0.);
    state.cell_contact_area_uncertainty.assign(n_cells, 0.);

    if (!tensionless)
      {
        for (unsigned int c = 0; c < n_cells; ++c)
          if (state.cell_in_foundation.empty() || state.cell_in_foundation[c])
            state.cell_contact_area[c] = space.cells[c].geometry.area();
        return;
      }

    const Vector<double> gap = pointwise_gap(foundation, state.gap);
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const FoundationSpace::Cell &cell = space.cells[c];
        const double                 area = cell.geometry.area();
        const double                 stiffness =
          foundation.soil().patch_stiffness(std::sqrt(area));
        const std::vector<unsigned int> nodes = cell.nodes();
        // C = q - factor c g at a node, relative to the cell's largest
        // |q| and |c g|: the measure is the same at any load scale (the
        // triangles' products would underflow for tiny loads)
        double scale = 0;
        for (const unsigned int i : nodes)
          scale = std::max(
            {scale, std::abs(state.q[i]), std::abs(stiffness * gap[i])});
        if (!(scale > 0))
          continue;
        const auto at = [&](const unsigned int i, const double factor) {
          return state.q[i] / scale - factor * (stiffness * gap[i] / scale);
        };
        // The interpolant stays within its nodal values but for an
        // overshoot below their spread, so a cell whose nodal values keep
        // that far from zero is wholly in or out; the others are measured.
        double low = std::numeric_limits<double>::max(), high = -low;
        for (const unsigned int i : nodes)
          {
            low  = std::min(low, at(i, 1.));
            high = std::max(high, at(i, 1.));
          }
        if (low > high - low)
          {
            state.cell_contact_area[c] = area;
            continue;
          }
        if (-high > high - low)
          continue;
        const auto quadratic = [&](const double factor) {
          return [&, factor](const Point<2> &p) {
            const std::array<double, 9> phi = q2_shape_values(p);
            double                      sum = 0;
            for (unsigned int j = 0; j < 9; ++j)
              for (const auto &[node, weight] : cell.expansion[j])
                sum += phi[j] * weight * at(node, factor);
            return sum;
          };
        };
        std::array<double, 4> corner;
        for (unsigned int v = 0; v < 4; ++v)
          corner[v] = quadratic(1.)(Point<2>(v % 2, v / 2));
        const auto bilinear = [&](const Point<2> &p) {
          return (1 - p[0]) * (1 - p[1]) * corner[0] +
                 p[0] * (1 - p[1]) * corner[1] + (1 - p[0]) * p[1] * corner[2] +
                 p[0] * p[1] * corner[3];
        };
        const SubCells sub_cells(cell);
        const double   located     = positive_area(sub_cells, quadratic(1.));
        state.cell_contact_area[c] = located;
        state.cell_contact_area_uncertainty[c] =
          std::max(std::abs(located - positive_area(sub_cells, bilinear)),
                   0.5 * std::abs(positive_area(sub_cells, quadratic(0.5)) -
                                  positive_area(sub_cells, quadratic(2.))));
      }
  }
} // namespace PlateOnHalfspace
