#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/work_stream.h>

#include <plate_on_halfspace/soil/boussinesq_kernel.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <algorithm>
#include <array>

namespace PlateOnHalfspace
{
  namespace
  {
    /** A cell's pressure at the points of one Gauss rule, with JxW. */
    struct GaussTable
    {
      std::vector<Point<2>> points;
      std::vector<double>   weighted_pressure; ///< JxW q_h
    };

    /** What the point loop needs of one cell. */
    struct PressureCell
    {
      BilinearQuadrilateral     geometry;
      std::vector<Point<2>>     polygon;
      std::array<double, 9>     q2_values; ///< q_h at the cell's Q2 nodes
      Point<2>                  centre;
      double                    diameter = 0;
      std::array<GaussTable, 3> gauss; ///< 2, 3 and 5 points per direction
      /** For a smooth remainder: 3, 5 and near_order points per direction. */
      std::array<GaussTable, 3> smooth;
      unsigned int              near_order = 0;
      bool                      loaded     = false;
    };

    GaussTable
    make_table(const PressureCell &cell, const unsigned int order);

    double
    pressure_at(const PressureCell &cell, const Point<2> &reference)
    {
      const auto phi = q2_shape_values(reference);
      double     q   = 0;
      for (unsigned int i = 0; i < 9; ++i)
        q += phi[i] * cell.q2_values[i];
      return q;
    }

    PressureCell
    make_cell(const FoundationSpace::Cell &space_cell,
              const Vector<double>        &nodal_pressure)
    {
      PressureCell cell{space_cell.geometry, {}, {}, {}, 0, {}, {}, 0, false};
      const auto  &v = cell.geometry.get_vertices();
      cell.polygon   = {v[0], v[1], v[3], v[2]};
      for (unsigned int i = 0; i < 9; ++i)
        {
          cell.q2_values[i] = 0;
          for (const auto &term : space_cell.expansion[i])
            cell.q2_values[i] += term.second * nodal_pressure[term.first];
          cell.loaded = cell.loaded || cell.q2_values[i] != 0;
        }
      cell.centre = cell.geometry.map(Point<2>(0.5, 0.5));
      for (const Point<2> &p : v)
        cell.diameter = std::max(cell.diameter, 2. * p.distance(cell.centre));
      const std::array<unsigned int, 3> orders = {{2, 3, 5}};
      for (unsigned int r = 0; r < 3; ++r)
        cell.gauss[r] = make_table(cell, orders[r]);
      return cell;
    }

    GaussTable
    make_table(const PressureCell &cell, const unsigned int order)
    {
      GaussTable      table;
      const QGauss<2> rule(order);
      for (unsigned int q = 0; q < rule.size(); ++q)
        {
          const Point<2> &p = rule.point(q);
          table.points.push_back(cell.geometry.map(p));
          table.weighted_pressure.push_back(
            rule.weight(q) * cell.geometry.jacobian_determinant(p) *
            pressure_at(cell, p));
        }
      return table;
    }

    /** The rules of a smooth remainder of length scale @p l. */
    void
    add_smooth_tables(PressureCell &cell, const double l)
    {
      cell.near_order = static_cast<unsigned int>(
        std::min(12., 3. + std::floor(3. * cell.diameter / l)));
      cell.smooth[0] = cell.gauss[1];
      cell.smooth[1] = cell.gauss[2];
      if (cell.near_order > 5)
        cell.smooth[2] = make_table(cell, cell.near_order);
    }

    /** ∫_cell q_h(y) R(|x - y|) dy for a smooth R. */
    double
    smooth_integral(const PressureCell         &cell,
                    const Point<2>             &x,
                    const SmoothRadialFunction &R)
    {
      const double separation =
        std::max(0., x.distance(cell.centre) - 0.5 * cell.diameter);
      const double needed =
        3. + std::floor(3. * cell.diameter / (R.length_scale() + separation));
      const GaussTable &table = needed <= 3 ? cell.smooth[0] :
                                needed <= 5 || cell.near_order <= 5 ?
                                              cell.smooth[1] :
                                              cell.smooth[2];
      double            sum   = 0;
      for (unsigned int q = 0; q < table.points.size(); ++q)
        sum +=
          table.weighted_pressure[q] * R.value(x.distance(table.points[q]));
      return sum;
    }

    /** ∫_cell q_h(y) / |x - y| dy for x near the cell. */
    double
    near_inverse_distance_integral(const PressureCell &cell,
                                   const Point<2>     &x,
                                   const QDuffy       &duffy)
    {
      // q_h(y) = (q_h(y) - q_h(split)) + q_h(split): the first part over
      // r is bounded (Duffy rule split at x's reference point, clamped
      // onto the cell), the second is exact (polygon integral).
      Point<2> split = cell.geometry.inverse_map(x);
      for (unsigned int d = 0; d < 2; ++d)
        split[d] = std::min(1., std::max(0., split[d]));
      const double    q_split = pressure_at(cell, split);
      const QSplit<2> rule(duffy, split);
      double          sum =
        q_split * integral_of_inverse_distance_over_polygon(x, cell.polygon);
      for (unsigned int q = 0; q < rule.size(); ++q)
        {
          const Point<2> &y = rule.point(q);
          const double    r = x.distance(cell.geometry.map(y));
          if (r == 0.)
            continue; // a point of measure zero
          sum += rule.weight(q) * cell.geometry.jacobian_determinant(y) *
                 (pressure_at(cell, y) - q_split) / r;
        }
      return sum;
    }

    /**
     * ∫_cell q_h(y) K(|x - y|) dy for the kernel K(r) = alpha / r + R(r):
     * from 1.5 cell diameters on, the whole kernel on the cell-pair rule
     * of that distance (SurfaceKernel::separated_rule()); nearer, the
     * singular 1/r rule and R's own rule.
     */
    double
    kernel_integral(const PressureCell  &cell,
                    const Point<2>      &x,
                    const QDuffy        &duffy,
                    const SurfaceKernel &kernel)
    {
      const double distance = x.distance(cell.centre) / cell.diameter;
      if (distance >= 1.5)
        {
          const GaussTable &table = cell.gauss[kernel.separated_rule(distance)];
          double            sum = 0, smooth = 0;
          for (unsigned int q = 0; q < table.points.size(); ++q)
            {
              const double r = x.distance(table.points[q]);
              sum += table.weighted_pressure[q] / r;
              if (kernel.remainder)
                smooth +=
                  table.weighted_pressure[q] * kernel.remainder->value(r);
            }
          return kernel.alpha * sum + smooth;
        }
      double integral =
        kernel.alpha * near_inverse_distance_integral(cell, x, duffy);
      if (kernel.remainder)
        integral += smooth_integral(cell, x, *kernel.remainder);
      return integral;
    }
  } // namespace

  std::vector<double>
  settlement_at_points(const FoundationSpace       &space,
                       const Vector<double>        &nodal_pressure,
                       const std::vector<Point<2>> &points,
                       const SurfaceKernel         &kernel,
                       const unsigned int           singular_order)
  {
    std::vector<PressureCell> cells;
    for (const auto &space_cell : space.cells)
      {
        PressureCell cell = make_cell(space_cell, nodal_pressure);
        if (kernel.remainder)
          add_smooth_tables(cell, kernel.remainder->length_scale());
        if (cell.loaded)
          cells.push_back(std::move(cell));
      }
    // the images' pressure acts at the mirrored point: |R x - y| for the
    // reflection R of the computed part's y
    std::vector<std::array<double, 2>> images = {{{1., 1.}}};
    for (const auto &r : space.symmetry.reflections())
      images.push_back(r);

    const QDuffy        duffy(singular_order, 1.0);
    std::vector<double> settlement(points.size(), 0.);
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(points.size()),
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int p = begin; p < end; ++p)
          {
            double sum = 0;
            for (const auto &image : images)
              {
                const Point<2> x(image[0] * points[p][0],
                                 image[1] * points[p][1]);
                for (const PressureCell &cell : cells)
                  sum += kernel_integral(cell, x, duffy, kernel);
              }
            settlement[p] = sum;
          }
      },
      16);
    return settlement;
  }
} // namespace PlateOnHalfspace
