#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_local_storage.h>
#include <deal.II/base/work_stream.h>

#include <deal.II/numerics/rtree.h>

#include <boost/container_hash/hash.hpp>

#include <plate_on_halfspace/soil/boussinesq_kernel.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <unordered_map>

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
    make_cell(const BilinearQuadrilateral &geometry,
              const std::array<double, 9> &q2_values,
              const SurfaceKernel         &kernel)
    {
      KernelCell<N> cell{geometry, {}, q2_values, {}, 0, {}, {}, 0};
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
          cells.push_back(make_cell<1>(space_cell.geometry, q2_values, kernel));
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
    /**
     * A point and a cell as their translates with the cell's first vertex
     * at the origin, every coordinate rounded to 2^-30 of the power of two
     * of the cell's diameter (which the key holds too): the key under
     * which near_settlement_at_points() shares the pair's influences with
     * its translates. The influences are integrated on the rounded pair
     * itself, so they depend on the key alone, whichever translate met it
     * first (the same bits on any number of threads); the rounding moves
     * the point and the vertices by at most 1e-9 of the diameter.
     */
    struct TranslatedPair
    {
      using Key = std::array<long long, 9>;

      TranslatedPair(const BilinearQuadrilateral &geometry, const Point<2> &x)
      {
        const auto  &v        = geometry.get_vertices();
        const int    exponent = std::ilogb(geometry.diameter());
        const double unit     = std::ldexp(1., exponent - 30);
        const auto   round    = [&](const double offset, long long &k) {
          k = std::llround(offset / unit);
          return k * unit;
        };
        for (unsigned int i = 1; i < 4; ++i)
          for (unsigned int d = 0; d < 2; ++d)
            vertices[i][d] = round(v[i][d] - v[0][d], key[2 * (i - 1) + d]);
        for (unsigned int d = 0; d < 2; ++d)
          point[d] = round(x[d] - v[0][d], key[6 + d]);
        key[8] = exponent;
      }

      Key                     key;
      Point<2>                point;
      std::array<Point<2>, 4> vertices;
    };

    /** Influences kept per thread, at most this many (about 170 bytes
     *  each with the hash table's node: 11 MB). */
    constexpr std::size_t translated_pairs_kept = 1u << 16;

    /** Distinct cell shapes (TranslatedPair's rounding of the vertices)
     *  among @p cells, counted up to @p limit. */
    unsigned int
    n_cell_shapes(const std::vector<KernelCell<1>> &cells,
                  const unsigned int                limit)
    {
      std::set<TranslatedPair::Key> shapes;
      for (const KernelCell<1> &cell : cells)
        {
          TranslatedPair::Key key =
            TranslatedPair(cell.geometry, cell.geometry.get_vertices()[0]).key;
          shapes.insert(key);
          if (shapes.size() > limit)
            break;
        }
      return shapes.size();
    }
  } // namespace

  std::vector<double>
  near_settlement_at_points(const FoundationSpace       &space,
                            const Vector<double>        &nodal_pressure,
                            const std::vector<Point<2>> &points,
                            const SurfaceKernel         &near_kernel,
                            const unsigned int           singular_order,
                            const double                 reach)
  {
    Assert(near_kernel.remainder, ExcInternalError());
    const SurfaceKernel        inverse_distance(near_kernel.alpha);
    std::vector<KernelCell<1>> cells;
    std::vector<std::pair<BoundingBox<2>, unsigned int>> zones;
    for (const auto &space_cell : space.cells)
      {
        const std::array<double, 9> q2_values =
          space_cell.local_values(nodal_pressure);
        if (std::none_of(q2_values.begin(), q2_values.end(), [](double q) {
              return q != 0;
            }))
          continue;
        cells.push_back(
          make_cell<1>(space_cell.geometry, q2_values, near_kernel));
        const KernelCell<1> &cell   = cells.back();
        const double         radius = reach + 0.5 * cell.diameter;
        zones.emplace_back(BoundingBox<2>(
                             std::make_pair(Point<2>(cell.centre[0] - radius,
                                                     cell.centre[1] - radius),
                                            Point<2>(cell.centre[0] + radius,
                                                     cell.centre[1] + radius))),
                           cells.size() - 1);
      }
    const auto   zone_tree = pack_rtree(zones);
    const auto   images    = image_factors(space);
    const QDuffy duffy(singular_order, 1.0);

    // On a mesh of few cell shapes (uniform, or a few levels of
    // refinement) most point-cell pairs are translates of another: their
    // influences on the cell's Q2 shapes are integrated once (the
    // operator's near field shares translated pairs alike). A mesh of many
    // shapes (Gmsh, distorted) integrates each pair's pressure directly.
    const bool translates    = n_cell_shapes(cells, 64) <= 64;
    using Influences         = std::array<double, 9>;
    using Kept               = std::unordered_map<TranslatedPair::Key,
                                    Influences,
                                    boost::hash<TranslatedPair::Key>>;
    const auto pair_integral = [&](const KernelCell<1> &cell,
                                   const Point<2>      &x,
                                   Kept                &kept) {
      if (!translates)
        return kernel_integral(cell, x, duffy, inverse_distance)[0] +
               smooth_integral(cell, x, *near_kernel.remainder)[0];
      const TranslatedPair pair(cell.geometry, x);
      auto                 hit = kept.find(pair.key);
      Influences           influences;
      if (hit != kept.end())
        influences = hit->second;
      else
        {
          const KernelCell<9> shape =
            make_cell<9>(BilinearQuadrilateral(pair.vertices), {}, near_kernel);
          influences =
            kernel_integral(shape, pair.point, duffy, inverse_distance);
          add_scaled(influences,
                     1.,
                     smooth_integral(shape,
                                     pair.point,
                                     *near_kernel.remainder));
          if (kept.size() < translated_pairs_kept)
            kept.emplace(pair.key, influences);
        }
      double sum = 0;
      for (unsigned int k = 0; k < 9; ++k)
        sum += influences[k] * cell.q2_values[k];
      return sum;
    };

    Threads::ThreadLocalStorage<Kept> kept_influences;
    std::vector<double>               settlement(points.size(), 0.);
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(points.size()),
      [&](const unsigned int begin, const unsigned int end) {
        Kept &kept = kept_influences.get();
        for (unsigned int p = begin; p < end; ++p)
          {
            double sum = 0;
            for (const auto &image : images)
              {
                const Point<2> x(image[0] * points[p][0],
                                 image[1] * points[p][1]);
                for (auto it =
                       zone_tree.qbegin(boost::geometry::index::intersects(x));
                     it != zone_tree.qend();
                     ++it)
                  {
                    const KernelCell<1> &cell = cells[it->second];
                    if (x.distance(cell.centre) - 0.5 * cell.diameter < reach)
                      sum += pair_integral(cell, x, kept);
                  }
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
        tables->cells.push_back(
          make_cell<9>(space.cells[c].geometry, {}, kernel));
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
