#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/work_stream.h>

#include <deal.II/numerics/rtree.h>

#include <plate_on_halfspace/soil/boussinesq_kernel.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <algorithm>
#include <array>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * A cell's densities at the points of one Gauss rule, times JxW: with
     * N = 1 the pressure q_h, with N = 9 the nine local Q2 shape functions
     * (the influence of each, SettlementInfluence).
     */
    template <int N>
    struct GaussTable
    {
      std::vector<Point<2>>              points;
      std::vector<std::array<double, N>> weights; ///< JxW density
    };

    /** What the point loop needs of one cell. */
    template <int N>
    struct KernelCell
    {
      BilinearQuadrilateral        geometry;
      std::vector<Point<2>>        polygon;
      std::array<double, 9>        q2_values{}; ///< q_h at the Q2 nodes (N = 1)
      Point<2>                     centre;
      double                       diameter = 0;
      std::array<GaussTable<N>, 5> gauss; ///< 2 ... 6 points per direction
      /** For a smooth remainder: 3, 5 and near_order points per direction. */
      std::array<GaussTable<N>, 3> smooth;
      unsigned int                 near_order = 0;
    };

    /** The density at a reference point: q_h (N = 1) or the Q2 shapes. */
    template <int N>
    std::array<double, N>
    density_at(const KernelCell<N> &cell, const Point<2> &reference)
    {
      const auto phi = q2_shape_values(reference);
      if constexpr (N == 1)
        {
          double q = 0;
          for (unsigned int i = 0; i < 9; ++i)
            q += phi[i] * cell.q2_values[i];
          return {{q}};
        }
      else
        return phi;
    }

    template <int N>
    GaussTable<N>
    make_table(const KernelCell<N> &cell, const unsigned int order)
    {
      GaussTable<N>   table;
      const QGauss<2> rule(order);
      for (unsigned int q = 0; q < rule.size(); ++q)
        {
          const Point<2> &p = rule.point(q);
          table.points.push_back(cell.geometry.map(p));
          const double JxW =
            rule.weight(q) * cell.geometry.jacobian_determinant(p);
          std::array<double, N> weight = density_at(cell, p);
          for (double &v : weight)
            v *= JxW;
          table.weights.push_back(weight);
        }
      return table;
    }

    /** The geometry and tables of @p space_cell; @p q2_values for N = 1. */
    template <int N>
    KernelCell<N>
    make_cell(const FoundationSpace::Cell &space_cell,
              const std::array<double, 9> &q2_values,
              const SurfaceKernel         &kernel)
    {
      KernelCell<N> cell{space_cell.geometry, {}, q2_values, {}, 0, {}, {}, 0};
      const auto   &v = cell.geometry.get_vertices();
      cell.polygon    = {v[0], v[1], v[3], v[2]};
      cell.centre     = cell.geometry.map(Point<2>(0.5, 0.5));
      for (const Point<2> &p : v)
        cell.diameter = std::max(cell.diameter, 2. * p.distance(cell.centre));
      for (unsigned int r = 0; r < cell.gauss.size(); ++r)
        cell.gauss[r] = make_table(cell, r + 2);
      if (kernel.remainder)
        {
          // the rules of a smooth remainder of length scale l
          const double l  = kernel.remainder->length_scale();
          cell.near_order = static_cast<unsigned int>(
            std::min(12., 3. + std::floor(3. * cell.diameter / l)));
          cell.smooth[0] = cell.gauss[1];
          cell.smooth[1] = cell.gauss[3];
          if (cell.near_order > 5)
            cell.smooth[2] = make_table(cell, cell.near_order);
        }
      return cell;
    }

    template <std::size_t N>
    void
    add_scaled(std::array<double, N>       &sum,
               const double                 factor,
               const std::array<double, N> &values)
    {
      for (std::size_t i = 0; i < N; ++i)
        sum[i] += factor * values[i];
    }

    /** ∫_cell density(y) R(|x - y|) dy for a smooth R. */
    template <int N>
    std::array<double, N>
    smooth_integral(const KernelCell<N>        &cell,
                    const Point<2>             &x,
                    const SmoothRadialFunction &R)
    {
      const double separation =
        std::max(0., x.distance(cell.centre) - 0.5 * cell.diameter);
      const double needed =
        3. + std::floor(3. * cell.diameter / (R.length_scale() + separation));
      const GaussTable<N>  &table = needed <= 3 ? cell.smooth[0] :
                                    needed <= 5 || cell.near_order <= 5 ?
                                                  cell.smooth[1] :
                                                  cell.smooth[2];
      std::array<double, N> sum{};
      for (unsigned int q = 0; q < table.points.size(); ++q)
        add_scaled(sum, R.value(x.distance(table.points[q])), table.weights[q]);
      return sum;
    }

    /** ∫_cell density(y) / |x - y| dy for x near the cell. */
    template <int N>
    std::array<double, N>
    near_inverse_distance_integral(const KernelCell<N> &cell,
                                   const Point<2>      &x,
                                   const QDuffy        &duffy)
    {
      // density(y) = (density(y) - density(split)) + density(split): the
      // first part over r is bounded (Duffy rule split at x's reference
      // point, clamped onto the cell), the second is exact (polygon
      // integral).
      Point<2> split = cell.geometry.inverse_map(x);
      for (unsigned int d = 0; d < 2; ++d)
        split[d] = std::min(1., std::max(0., split[d]));
      const std::array<double, N> at_split = density_at(cell, split);
      const QSplit<2>             rule(duffy, split);
      std::array<double, N>       sum{};
      add_scaled(sum,
                 integral_of_inverse_distance_over_polygon(x, cell.polygon),
                 at_split);
      for (unsigned int q = 0; q < rule.size(); ++q)
        {
          const Point<2> &y = rule.point(q);
          const double    r = x.distance(cell.geometry.map(y));
          if (r == 0.)
            continue; // a point of measure zero
          const double JxW =
            rule.weight(q) * cell.geometry.jacobian_determinant(y);
          const std::array<double, N> density = density_at(cell, y);
          for (int i = 0; i < N; ++i)
            sum[i] += JxW * (density[i] - at_split[i]) / r;
        }
      return sum;
    }

    /**
     * ∫_cell density(y) K(|x - y|) dy for the kernel K(r) = alpha / r +
     * R(r): from 1.5 cell diameters on, the whole kernel on the cell-pair
     * rule of that distance (SurfaceKernel::separated_points()); nearer, the
     * singular 1/r rule and R's own rule.
     */
    template <int N>
    std::array<double, N>
    kernel_integral(const KernelCell<N> &cell,
                    const Point<2>      &x,
                    const QDuffy        &duffy,
                    const SurfaceKernel &kernel)
    {
      const double          distance = x.distance(cell.centre) / cell.diameter;
      std::array<double, N> integral{};
      if (distance >= 1.5)
        {
          const GaussTable<N> &table =
            cell.gauss[kernel.separated_points(distance) - 2];
          std::array<double, N> smooth{};
          for (unsigned int q = 0; q < table.points.size(); ++q)
            {
              const double r = x.distance(table.points[q]);
              for (int i = 0; i < N; ++i)
                integral[i] += table.weights[q][i] / r;
              if (kernel.remainder)
                add_scaled(smooth,
                           kernel.remainder->value(r),
                           table.weights[q]);
            }
          for (int i = 0; i < N; ++i)
            integral[i] = kernel.alpha * integral[i] + smooth[i];
          return integral;
        }
      add_scaled(integral,
                 kernel.alpha,
                 near_inverse_distance_integral(cell, x, duffy));
      if (kernel.remainder)
        add_scaled(integral, 1., smooth_integral(cell, x, *kernel.remainder));
      return integral;
    }

    /** The points at which the images' pressure acts for a point x:
     *  |R x - y| for each reflection R (the identity first). */
    std::vector<std::array<double, 2>>
    image_factors(const FoundationSpace &space)
    {
      std::vector<std::array<double, 2>> images = {{{1., 1.}}};
      for (const auto &r : space.symmetry.reflections())
        images.push_back(r);
      return images;
    }
  } // namespace

  std::vector<double>
  settlement_at_points(const FoundationSpace       &space,
                       const Vector<double>        &nodal_pressure,
                       const std::vector<Point<2>> &points,
                       const SurfaceKernel         &kernel,
                       const unsigned int           singular_order)
  {
    std::vector<KernelCell<1>> cells;
    for (const auto &space_cell : space.cells)
      {
        const std::array<double, 9> q2_values =
          space_cell.local_values(nodal_pressure);
        if (std::any_of(q2_values.begin(), q2_values.end(), [](double q) {
              return q != 0;
            }))
          cells.push_back(make_cell<1>(space_cell, q2_values, kernel));
      }
    const auto images = image_factors(space);

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
                for (const KernelCell<1> &cell : cells)
                  sum += kernel_integral(cell, x, duffy, kernel)[0];
              }
            settlement[p] = sum;
          }
      },
      16);
    return settlement;
  }

  namespace
  {
    /** The distance in cell diameters below which settlement_at_points()
     *  leaves the 3-point rule. */
    constexpr double near_distance = 2.5;

    /** The index of the 3 x 3 rule in KernelCell::gauss. */
    constexpr unsigned int three_point_rule = 1;

    /**
     * @p sum += @p sign ∫ K(|y - z|) N_k(z) dz on the cell's 3 x 3 Gauss
     * rule, for the shapes N_k whose bit is set in @p needed.
     */
    void
    add_three_point_integral(const KernelCell<9>   &cell,
                             const Point<2>        &y,
                             const SurfaceKernel   &kernel,
                             const unsigned int     needed,
                             const double           sign,
                             std::array<double, 9> &sum)
    {
      const GaussTable<9> &table = cell.gauss[three_point_rule];
      unsigned int         shapes[9], n_shapes = 0;
      for (unsigned int i = 0; i < 9; ++i)
        if (needed & (1u << i))
          shapes[n_shapes++] = i;
      for (unsigned int q = 0; q < table.points.size(); ++q)
        {
          const double r = y.distance(table.points[q]);
          double       k = kernel.alpha / r;
          if (kernel.remainder)
            k += kernel.remainder->value(r);
          k *= sign;
          for (unsigned int s = 0; s < n_shapes; ++s)
            sum[shapes[s]] += k * table.weights[q][shapes[s]];
        }
    }
  } // namespace

  struct SettlementInfluence::Cells
  {
    std::vector<KernelCell<9>> cells;
    /** Each cell's box of near_distance diameters around its centre. */
    RTree<std::pair<BoundingBox<2>, unsigned int>> near_zones;
  };

  SettlementInfluence::SettlementInfluence(const FoundationSpace &space,
                                           const SurfaceKernel   &kernel,
                                           const unsigned int singular_order)
    : space(space)
    , kernel(kernel)
    , duffy(std::make_unique<QDuffy>(singular_order, 1.0))
    , images(image_factors(space))
    , tables(std::make_unique<Cells>())
    , node_cells(space.n_nodes())
  {
    tables->cells.reserve(space.cells.size());
    std::vector<std::pair<BoundingBox<2>, unsigned int>> zones;
    for (unsigned int c = 0; c < space.cells.size(); ++c)
      {
        tables->cells.push_back(make_cell<9>(space.cells[c], {}, kernel));
        const KernelCell<9> &cell   = tables->cells.back();
        const double         radius = near_distance * cell.diameter;
        zones.emplace_back(BoundingBox<2>(
                             std::make_pair(Point<2>(cell.centre[0] - radius,
                                                     cell.centre[1] - radius),
                                            Point<2>(cell.centre[0] + radius,
                                                     cell.centre[1] + radius))),
                           c);
        for (const unsigned int i : space.cells[c].nodes())
          node_cells[i].push_back(c);
      }
    tables->near_zones = pack_rtree(zones);
  }

  SettlementInfluence::~SettlementInfluence() = default;

  std::array<double, 9>
  SettlementInfluence::far_influences(const unsigned int c,
                                      const Point<2>    &x,
                                      const unsigned int needed) const
  {
    std::array<double, 9> sum{};
    for (const auto &image : images)
      add_three_point_integral(tables->cells[c],
                               Point<2>(image[0] * x[0], image[1] * x[1]),
                               kernel,
                               needed,
                               1.,
                               sum);
    return sum;
  }

  std::array<double, 9>
  SettlementInfluence::near_corrections(const unsigned int c,
                                        const Point<2>    &x) const
  {
    const KernelCell<9>  &cell = tables->cells[c];
    std::array<double, 9> sum{};
    for (const auto &image : images)
      {
        const Point<2> y(image[0] * x[0], image[1] * x[1]);
        if (y.distance(cell.centre) >= near_distance * cell.diameter)
          continue;
        add_scaled(sum, 1., kernel_integral(cell, y, *duffy, kernel));
        add_three_point_integral(cell, y, kernel, 0x1ff, -1., sum);
      }
    return sum;
  }

  std::vector<unsigned int>
  SettlementInfluence::near_cells(const Point<2> &x) const
  {
    std::vector<unsigned int> cells;
    for (const auto &image : images)
      {
        const Point<2> y(image[0] * x[0], image[1] * x[1]);
        for (auto it =
               tables->near_zones.qbegin(boost::geometry::index::intersects(y));
             it != tables->near_zones.qend();
             ++it)
          cells.push_back(it->second);
      }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    return cells;
  }
} // namespace PlateOnHalfspace
