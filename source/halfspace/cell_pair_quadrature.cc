#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_management.h>

#include <plate_on_halfspace/base/progress.h>
#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>
#include <plate_on_halfspace/soil/boussinesq_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <set>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * Outer rule of the singular pairs: Gauss points pulled towards the
     * cell's edges by s = t^2 (3 - 2t) in each direction. The inner
     * integral, as a function of the outer point, has logarithmically
     * singular derivatives on the edges of the inner cell, which for these
     * pairs lie on the outer cell's boundary; the grading smooths that out.
     */
    Quadrature<2>
    graded_rule(const unsigned int n)
    {
      const QGauss<1>       gauss(n);
      std::vector<Point<1>> points;
      std::vector<double>   weights;
      for (unsigned int q = 0; q < n; ++q)
        {
          const double t = gauss.point(q)[0];
          points.emplace_back(t * t * (3. - 2. * t));
          weights.push_back(gauss.weight(q) * 6. * t * (1. - t));
        }
      const Quadrature<1> graded(points, weights);
      return Quadrature<2>(graded, graded);
    }

    /**
     * @p unit (a rule on the reference square) on each of the rectangles
     * into which the lines x = cuts[0][i] and y = cuts[1][j] cut the
     * reference square; cuts[d] is sorted and holds 0 and 1.
     */
    Quadrature<2>
    rule_on_pieces(const Quadrature<2>                      &unit,
                   const std::array<std::vector<double>, 2> &cuts)
    {
      std::vector<Point<2>> points;
      std::vector<double>   weights;
      for (unsigned int i = 0; i + 1 < cuts[0].size(); ++i)
        for (unsigned int j = 0; j + 1 < cuts[1].size(); ++j)
          {
            const double x0 = cuts[0][i], width = cuts[0][i + 1] - x0;
            const double y0 = cuts[1][j], height = cuts[1][j + 1] - y0;
            for (unsigned int q = 0; q < unit.size(); ++q)
              {
                const Point<2> &u = unit.point(q);
                points.emplace_back(x0 + width * u[0], y0 + height * u[1]);
                weights.push_back(unit.weight(q) * width * height);
              }
          }
      return Quadrature<2>(points, weights);
    }

    /** The distance of @p p to the segment from @p s0 to @p s1. */
    double
    segment_distance(const Point<2> &p, const Point<2> &s0, const Point<2> &s1)
    {
      const Tensor<1, 2> d      = s1 - s0;
      const double       length = d.norm_square();
      const double       t =
        length > 0 ? std::clamp((p - s0) * d / length, 0., 1.) : 0.;
      return p.distance(s0 + t * d);
    }

    /** The edges of a cell, from its vertices in deal.II's order. */
    std::array<std::pair<Point<2>, Point<2>>, 4>
    edges(const BilinearQuadrilateral &cell)
    {
      const auto &v = cell.get_vertices();
      return {{{v[0], v[1]}, {v[1], v[3]}, {v[3], v[2]}, {v[2], v[0]}}};
    }

    /** The distance between two convex cells that do not overlap: the
     *  smallest of a vertex of one to an edge of the other. */
    double
    cell_gap(const BilinearQuadrilateral &a, const BilinearQuadrilateral &b)
    {
      double     smallest = std::numeric_limits<double>::max();
      const auto edges_a = edges(a), edges_b = edges(b);
      for (const auto &[p, q] :
           {std::pair(&a, &edges_b), std::pair(&b, &edges_a)})
        for (const Point<2> &vertex : p->get_vertices())
          for (const auto &[s0, s1] : *q)
            smallest = std::min(smallest, segment_distance(vertex, s0, s1));
      return smallest;
    }
  } // namespace

  void
  symmetrise_self_image_block(const std::vector<unsigned int> &rows,
                              const std::vector<unsigned int> &columns,
                              FullMatrix<double>              &block)
  {
    const auto position = [](const std::vector<unsigned int> &list,
                             const unsigned int               node) {
      return static_cast<unsigned int>(
        std::find(list.begin(), list.end(), node) - list.begin());
    };
    FullMatrix<double> symmetric(block.m(), block.n());
    for (unsigned int i = 0; i < block.m(); ++i)
      for (unsigned int k = 0; k < block.n(); ++k)
        symmetric(i, k) =
          0.5 * (block(i, k) +
                 block(position(rows, columns[k]), position(columns, rows[i])));
    block = symmetric;
  }

  CellPairIntegrator::SingularRule::SingularRule(const Point<2> &split,
                                                 const QDuffy   &duffy)
    : at_split(q2_shape_values(split))
  {
    const QSplit<2> rule(duffy, split);
    points  = rule.get_points();
    weights = rule.get_weights();
    for (const Point<2> &y : points)
      phi.push_back(q2_shape_values(y));
  }

  CellPairIntegrator::CellPairIntegrator(
    const std::vector<FoundationSpace::Cell> &cells,
    const unsigned int                        singular_order,
    const std::vector<bool>                  &prepared)
    : cells(cells)
    , singular_order(singular_order)
    , rules{{QGauss<2>(2),
             QGauss<2>(3),
             QGauss<2>(4),
             QGauss<2>(5),
             QGauss<2>(6),
             graded_rule(singular_order)}}
    , cell_data(cells.size())
    , duffy(singular_order, 1.0)
  {
    AssertThrow(prepared.empty() || prepared.size() == cells.size(),
                ExcDimensionMismatch(prepared.size(), cells.size()));
    const Quadrature<2> &outer_rule = rules.back();
    for (const Point<2> &p : outer_rule.get_points())
      coincident_rules.emplace_back(p, duffy);
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        const FoundationSpace::Cell &cell = cells[c];
        CellData                    &data = cell_data[c];
        data.centre   = cell.geometry.map(Point<2>(0.5, 0.5));
        data.diameter = cell.geometry.diameter();
        if (!prepared.empty() && !prepared[c])
          continue;
        data.nodes = cell.nodes();
        data.node_from_q2.reinit(data.nodes.size(), 9);
        for (unsigned int i = 0; i < 9; ++i)
          for (const auto &t : cell.expansion[i])
            {
              const unsigned int a =
                std::find(data.nodes.begin(), data.nodes.end(), t.first) -
                data.nodes.begin();
              data.node_from_q2(a, i) += t.second;
            }
      }
    for (const Point<2> &p : outer_rule.get_points())
      graded_phi.push_back(q2_shape_values(p));
  }

  const std::vector<CellPairIntegrator::Table> &
  CellPairIntegrator::stored_tables(const unsigned int c) const
  {
    // The rules of most pairs are kept; the 5- and 6-point rules (pairs
    // within 2.6 diameters) and the graded one (singular pairs, integrated
    // once per configuration) are tabulated when needed: the graded one
    // alone held 8 in 9 of the points, 0.9 GB at 77441 nodes. A cell's
    // tables are made when a pair first needs them: the split kernel's
    // near field takes most blocks from translated pairs and integrates
    // few cells (doc/performance.md, "The build's transient blocks").
    const CellData &data = cell_data[c];
    std::call_once(data.tables_made, [&]() {
      // made aside: a throw leaves the flag unset and the tables empty
      std::vector<Table> tables;
      tables.reserve(n_stored_rules);
      for (unsigned int r = 0; r < n_stored_rules; ++r)
        tables.push_back(make_table(c, rules[r]));
      data.tables = std::move(tables);
    });
    return data.tables;
  }

  CellPairIntegrator::Table
  CellPairIntegrator::make_table(const unsigned int   c,
                                 const Quadrature<2> &rule) const
  {
    const BilinearQuadrilateral &geometry = cells[c].geometry;
    Table                        table;
    table.n_functions = cell_data[c].nodes.size();
    table.x.reserve(rule.size());
    table.y.reserve(rule.size());
    table.weights.reserve(rule.size());
    table.weighted_values.reserve(rule.size() * table.n_functions);
    std::vector<double> values;
    for (unsigned int q = 0; q < rule.size(); ++q)
      {
        const Point<2> &p   = rule.point(q);
        const Point<2>  x   = geometry.map(p);
        const double    JxW = rule.weight(q) * geometry.jacobian_determinant(p);
        table.x.push_back(x[0]);
        table.y.push_back(x[1]);
        table.weights.push_back(JxW);
        node_shape_values(c, p, values);
        for (const double v : values)
          table.weighted_values.push_back(JxW * v);
      }
    return table;
  }

  void
  CellPairIntegrator::tabulate(const unsigned int     c,
                               const Quadrature<2>   &rule,
                               std::vector<Point<2>> &points,
                               std::vector<double>   &weighted_values) const
  {
    const Table table = make_table(c, rule);
    points.resize(table.x.size());
    for (unsigned int q = 0; q < points.size(); ++q)
      points[q] = Point<2>(table.x[q], table.y[q]);
    weighted_values = table.weighted_values;
  }

  void
  CellPairIntegrator::node_shape_values(const unsigned int   c,
                                        const Point<2>      &p,
                                        std::vector<double> &values) const
  {
    const auto         phi  = q2_shape_values(p);
    const CellData    &data = cell_data[c];
    const unsigned int n    = data.nodes.size();
    values.assign(n, 0.);
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int i = 0; i < 9; ++i)
        values[a] += data.node_from_q2(a, i) * phi[i];
  }

  bool
  CellPairIntegrator::touching(const unsigned int k, const unsigned int l) const
  {
    // Convex cells that touch have a vertex of one on the closed other one
    // (also across hanging nodes, where a small cell's vertex lies on a
    // large cell's edge).
    const auto &gk = cells[k].geometry, &gl = cells[l].geometry;
    for (const Point<2> &v : gk.get_vertices())
      if (gl.contains(v))
        return true;
    for (const Point<2> &v : gl.get_vertices())
      if (gk.contains(v))
        return true;
    return false;
  }

  void
  CellPairIntegrator::integrate_regular(const Table             &outer,
                                        const Table             &inner,
                                        FullMatrix<double>      &block,
                                        const std::vector<bool> &rows,
                                        const std::vector<bool> &columns,
                                        const SurfaceKernel     &kernel) const
  {
    const unsigned int n_p = outer.x.size(), n_q = inner.x.size();
    const unsigned int na = outer.n_functions, nb = inner.n_functions;
    // G(p, q) = alpha / |x_p - y_q| (at most 36 x 36 points, the 6-point
    // rule's) by plain loops over flat arrays, which the compiler
    // vectorises; the remainder adds R at the same distances. Without a
    // remainder the distances are not stored: one loop for both cost the
    // half-space 5 % of its integration.
    std::array<double, 36 * 36> G;
    AssertThrow(n_p * n_q <= G.size(), ExcInternalError());
    const double alpha = kernel.alpha;
    if (kernel.remainder)
      {
        std::array<double, 36 * 36> distance;
        for (unsigned int p = 0; p < n_p; ++p)
          {
            const double  xp = outer.x[p], yp = outer.y[p];
            double *const d = distance.data() + p * n_q;
            double *const g = G.data() + p * n_q;
            for (unsigned int q = 0; q < n_q; ++q)
              {
                const double dx = xp - inner.x[q], dy = yp - inner.y[q];
                d[q] = std::sqrt(dx * dx + dy * dy);
                g[q] = alpha / d[q];
              }
          }
        kernel.remainder->add_values(distance.data(), G.data(), n_p * n_q);
      }
    else
      for (unsigned int p = 0; p < n_p; ++p)
        {
          const double  xp = outer.x[p], yp = outer.y[p];
          double *const g = G.data() + p * n_q;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const double dx = xp - inner.x[q], dy = yp - inner.y[q];
              g[q] = alpha / std::sqrt(dx * dx + dy * dy);
            }
        }
    std::array<unsigned int, 9> a_list, b_list;
    unsigned int                n_a = 0, n_b = 0;
    for (unsigned int a = 0; a < na; ++a)
      if (rows.empty() || rows[a])
        a_list[n_a++] = a;
    for (unsigned int b = 0; b < nb; ++b)
      if (columns.empty() || columns[b])
        b_list[n_b++] = b;
    // block(a, b) = sum_p sum_q U(p, a) G(p, q) V(q, b) with U, V the
    // weighted shape values: contract G with the side that has fewer
    // wanted functions first.
    const double          *U = outer.weighted_values.data();
    const double          *V = inner.weighted_values.data();
    std::array<double, 36> s;
    if (n_a <= n_b)
      for (unsigned int i = 0; i < n_a; ++i)
        {
          const unsigned int a = a_list[i];
          std::fill(s.begin(), s.begin() + n_q, 0.);
          for (unsigned int p = 0; p < n_p; ++p)
            {
              const double  u = U[p * na + a];
              const double *g = G.data() + p * n_q;
              for (unsigned int q = 0; q < n_q; ++q)
                s[q] += u * g[q];
            }
          for (unsigned int j = 0; j < n_b; ++j)
            {
              const unsigned int b   = b_list[j];
              double             sum = 0;
              for (unsigned int q = 0; q < n_q; ++q)
                sum += s[q] * V[q * nb + b];
              block(a, b) += sum;
            }
        }
    else
      for (unsigned int j = 0; j < n_b; ++j)
        {
          const unsigned int b = b_list[j];
          for (unsigned int p = 0; p < n_p; ++p)
            {
              const double *g   = G.data() + p * n_q;
              double        sum = 0;
              for (unsigned int q = 0; q < n_q; ++q)
                sum += g[q] * V[q * nb + b];
              s[p] = sum;
            }
          for (unsigned int i = 0; i < n_a; ++i)
            {
              const unsigned int a   = a_list[i];
              double             sum = 0;
              for (unsigned int p = 0; p < n_p; ++p)
                sum += U[p * na + a] * s[p];
              block(a, b) += sum;
            }
        }
  }

  void
  CellPairIntegrator::integrate_singular(const unsigned int  k,
                                         const unsigned int  l,
                                         FullMatrix<double> &q2_block) const
  {
    q2_block.reinit(9, 9);
    const BilinearQuadrilateral &inner_cell = cells[l].geometry;
    // The inner integral, as a function of the outer point, is singular on
    // the part of K's boundary that L touches, and at a vertex of L on an
    // edge of K: away from K's corners where L's vertex lies inside K's
    // edge (the cells beside a hanging node, or cells offset along an
    // edge). The graded rule then goes on the pieces of K cut through
    // such vertices, so that each singular point is a corner of a piece
    // (doc/formulation.md, "Singular pairs"; one piece left 1e-3 of a
    // block next to a hanging node at the default order).
    std::array<std::vector<double>, 2> cuts{{{0., 1.}, {0., 1.}}};
    if (k != l)
      for (const Point<2> &vertex : inner_cell.get_vertices())
        if (cells[k].geometry.contains(vertex))
          {
            const Point<2> r = cells[k].geometry.inverse_map(vertex);
            for (unsigned int d = 0; d < 2; ++d)
              if (r[d] > 1e-9 && r[d] < 1. - 1e-9)
                cuts[d].push_back(r[d]);
          }
    const bool    cut = cuts[0].size() > 2 || cuts[1].size() > 2;
    Quadrature<2> pieces;
    std::vector<std::array<double, 9>> pieces_phi;
    if (cut)
      {
        for (auto &c : cuts)
          {
            std::sort(c.begin(), c.end());
            c.erase(std::unique(c.begin(),
                                c.end(),
                                [](const double a, const double b) {
                                  return b - a < 1e-9;
                                }),
                    c.end());
          }
        pieces = rule_on_pieces(rules.back(), cuts);
        for (const Point<2> &p : pieces.get_points())
          pieces_phi.push_back(q2_shape_values(p));
      }
    const Table outer = make_table(k, cut ? pieces : rules.back()); // graded
    const std::vector<std::array<double, 9>> &outer_phi =
      cut ? pieces_phi : graded_phi;
    const auto                 &v       = inner_cell.get_vertices();
    const std::vector<Point<2>> polygon = {v[0], v[1], v[3], v[2]};
    std::array<double, 9>       t;
    for (unsigned int p = 0; p < outer.x.size(); ++p)
      {
        const Point<2> x(outer.x[p], outer.y[p]);
        // The inner singularity sits at x's reference point in L; outside
        // L (touching pairs) the nearest point of the reference square is
        // the best place to concentrate the Duffy points. Coincident pairs
        // reuse the rules built once for the outer points.
        std::unique_ptr<SingularRule> own_rule;
        const SingularRule           *rule = nullptr;
        if (k == l)
          rule = &coincident_rules[p];
        else
          {
            Point<2> split = inner_cell.inverse_map(x);
            for (unsigned int d = 0; d < 2; ++d)
              split[d] = std::min(1., std::max(0., split[d]));
            own_rule = std::make_unique<SingularRule>(split, duffy);
            rule     = own_rule.get();
          }
        // Singularity subtraction, in the Q2 basis: phi_i(y) = (phi_i(y) -
        // phi_i(split)) + phi_i(split). The first part over r is bounded
        // and the Duffy rule integrates it accurately; the second is
        // phi_i(split) times the exact integral of 1/r over the polygon L.
        const double polygon_integral =
          integral_of_inverse_distance_over_polygon(x, polygon);
        for (unsigned int i = 0; i < 9; ++i)
          t[i] = rule->at_split[i] * polygon_integral;
        for (unsigned int q = 0; q < rule->points.size(); ++q)
          {
            const Point<2> &y_ref = rule->points[q];
            const double    r     = x.distance(inner_cell.map(y_ref));
            if (r == 0.)
              continue; // a point of measure zero
            const double kernel =
              rule->weights[q] * inner_cell.jacobian_determinant(y_ref) / r;
            for (unsigned int i = 0; i < 9; ++i)
              t[i] += kernel * (rule->phi[q][i] - rule->at_split[i]);
          }
        for (unsigned int i = 0; i < 9; ++i)
          {
            const double u = outer.weights[p] * outer_phi[p][i];
            for (unsigned int j = 0; j < 9; ++j)
              q2_block(i, j) += u * t[j];
          }
      }
  }

  std::array<long long, 16>
  CellPairIntegrator::configuration(const unsigned int k,
                                    const unsigned int l) const
  {
    const auto               &vk     = cells[k].geometry.get_vertices();
    const auto               &vl     = cells[l].geometry.get_vertices();
    const Point<2>            origin = vk[0];
    const double              scale  = 1e9 / cell_data[k].diameter;
    std::array<long long, 16> key;
    for (unsigned int v = 0; v < 4; ++v)
      for (unsigned int d = 0; d < 2; ++d)
        {
          key[2 * v + d]     = std::llround((vk[v][d] - origin[d]) * scale);
          key[8 + 2 * v + d] = std::llround((vl[v][d] - origin[d]) * scale);
        }
    return key;
  }

  void
  CellPairIntegrator::integrate_singular_pairs(
    const std::vector<std::pair<unsigned int, unsigned int>> &pairs,
    const SmoothRadialFunction                               *remainder) const
  {
    if (remainder)
      {
        // Each new size of configuration from its first pair, as below.
        std::vector<std::pair<unsigned int, unsigned int>> representatives;
        {
          std::set<std::array<long long, 17>> seen;
          const std::lock_guard<std::mutex>   lock(singular_cache_mutex);
          AssertThrow(smooth_cache_function == nullptr ||
                        smooth_cache_function == remainder,
                      ExcMessage("One smooth kernel per CellPairIntegrator."));
          smooth_cache_function = remainder;
          for (const auto &pair : pairs)
            {
              const auto key =
                smooth_configuration(pair.first, pair.second, *remainder);
              if (smooth_cache.count(key) == 0 && seen.insert(key).second)
                representatives.push_back(pair);
            }
        }
        std::vector<FullMatrix<double>> blocks(representatives.size());
        parallel::apply_to_subranges(
          std::size_t(0),
          representatives.size(),
          [&](const std::size_t begin, const std::size_t end) {
            for (std::size_t p = begin; p < end; ++p)
              blocks[p] = integrate_smooth(representatives[p].first,
                                           representatives[p].second,
                                           *remainder);
          },
          1);
        const std::lock_guard<std::mutex> lock(singular_cache_mutex);
        for (std::size_t p = 0; p < representatives.size(); ++p)
          smooth_cache.emplace(smooth_configuration(representatives[p].first,
                                                    representatives[p].second,
                                                    *remainder),
                               std::move(blocks[p]));
      }
    // The first pair of each new configuration, in the order given, so
    // that the cache does not depend on which thread finishes first.
    std::vector<std::pair<unsigned int, unsigned int>> representatives;
    {
      std::set<std::array<long long, 16>> seen;
      const std::lock_guard<std::mutex>   lock(singular_cache_mutex);
      for (const auto &pair : pairs)
        {
          const auto key = configuration(pair.first, pair.second);
          if (singular_cache.count(key) == 0 && seen.insert(key).second)
            representatives.push_back(pair);
        }
    }
    std::vector<FullMatrix<double>> blocks(representatives.size());
    const unsigned int              n_tasks = MultithreadInfo::n_threads();
    ProgressReport           progress("Singular cell pairs", blocks.size());
    Threads::TaskGroup<void> tasks;
    for (unsigned int t = 0; t < n_tasks; ++t)
      tasks += Threads::new_task([&, t]() {
        for (std::size_t p = representatives.size() * t / n_tasks;
             p < representatives.size() * (t + 1) / n_tasks;
             ++p)
          {
            blocks[p] = normalised_singular_q2_block(representatives[p].first,
                                                     representatives[p].second);
            progress.add();
          }
      });
    tasks.join_all();
    progress.finish();
    const std::lock_guard<std::mutex> lock(singular_cache_mutex);
    for (std::size_t p = 0; p < representatives.size(); ++p)
      singular_cache.emplace(configuration(representatives[p].first,
                                           representatives[p].second),
                             std::move(blocks[p]));
  }

  const FullMatrix<double> &
  CellPairIntegrator::singular_q2_block(const unsigned int k,
                                        const unsigned int l) const
  {
    const auto key = configuration(k, l);
    {
      const std::lock_guard<std::mutex> lock(singular_cache_mutex);
      const auto                        found = singular_cache.find(key);
      if (found != singular_cache.end())
        return found->second;
    }
    FullMatrix<double> normalised = normalised_singular_q2_block(k, l);
    // std::map never moves its elements: the reference stays valid while
    // other threads insert. (Callers that integrate concurrently fill the
    // cache with integrate_singular_pairs() first; here the first of two
    // near-congruent pairs computed at once would win.)
    const std::lock_guard<std::mutex> lock(singular_cache_mutex);
    return singular_cache.emplace(key, std::move(normalised)).first->second;
  }

  FullMatrix<double>
  CellPairIntegrator::normalised_singular_q2_block(const unsigned int k,
                                                   const unsigned int l) const
  {
    // The rule is not symmetric in the roles of the two cells (outer Gauss
    // on one, inner Duffy on the other): average both orders, so that A is
    // exactly symmetric (its Cholesky factor reads one triangle), the block
    // does not depend on which cell comes first, and a mirror-symmetric
    // mesh gives a mirror-symmetric A.
    FullMatrix<double> forward, backward;
    integrate_singular(k, l, forward);
    if (k == l)
      backward = forward;
    else
      integrate_singular(l, k, backward);
    const double       diameter = cell_data[k].diameter;
    const double       unscale  = 1. / (diameter * diameter * diameter);
    FullMatrix<double> normalised(9, 9);
    for (unsigned int i = 0; i < 9; ++i)
      for (unsigned int j = 0; j < 9; ++j)
        normalised(i, j) = 0.5 * (forward(i, j) + backward(j, i)) * unscale;
    return normalised;
  }

  void
  CellPairIntegrator::integrate_inverse_distance(
    const unsigned int  k,
    const unsigned int  l,
    FullMatrix<double> &block) const
  {
    integrate_inverse_distance(k, l, block, {}, {});
  }

  void
  CellPairIntegrator::integrate_inverse_distance(
    const unsigned int       k,
    const unsigned int       l,
    FullMatrix<double>      &block,
    const std::vector<bool> &rows,
    const std::vector<bool> &columns) const
  {
    integrate_kernel(k, l, SurfaceKernel(1.), block, rows, columns);
  }

  void
  CellPairIntegrator::integrate_kernel(const unsigned int       k,
                                       const unsigned int       l,
                                       const SurfaceKernel     &kernel,
                                       FullMatrix<double>      &block,
                                       const std::vector<bool> &rows,
                                       const std::vector<bool> &columns,
                                       const double             accuracy) const
  {
    const CellData &dk = cell_data[k], &dl = cell_data[l];
    block.reinit(dk.nodes.size(), dl.nodes.size());
    if (singular_pair(k, l))
      {
        // B = alpha (1/r block) + (R block) in the Q2 basis, then to the
        // node shape functions: block = T_k B T_l^T
        FullMatrix<double> q2_block(9, 9);
        q2_block.add(kernel.alpha * dk.diameter * dk.diameter * dk.diameter,
                     singular_q2_block(k, l));
        if (kernel.remainder)
          q2_block.add(1., smooth_q2_block(k, l, *kernel.remainder));
        FullMatrix<double> right(9, dl.nodes.size()); // B T_l^T
        for (unsigned int i = 0; i < 9; ++i)
          for (unsigned int b = 0; b < dl.nodes.size(); ++b)
            {
              double sum = 0;
              for (unsigned int j = 0; j < 9; ++j)
                sum += q2_block(i, j) * dl.node_from_q2(b, j);
              right(i, b) = sum;
            }
        for (unsigned int a = 0; a < dk.nodes.size(); ++a)
          for (unsigned int b = 0; b < dl.nodes.size(); ++b)
            {
              double sum = 0;
              for (unsigned int i = 0; i < 9; ++i)
                sum += dk.node_from_q2(a, i) * right(i, b);
              block(a, b) = sum;
            }
        return;
      }
    if (integrate_composite(k, l, kernel, block, rows, columns, accuracy))
      return;
    const double separation =
      dk.centre.distance(dl.centre) / std::max(dk.diameter, dl.diameter);
    // Round away the last digits: on a uniform mesh many pairs sit exactly
    // on a threshold, and rounding must not send a pair and its mirror
    // image to different rules.
    const double       rounded = std::round(separation * 1e6) * 1e-6;
    const unsigned int rule    = kernel.separated_points(rounded, accuracy) - 2;
    if (rule < n_stored_rules)
      integrate_regular(stored_tables(k)[rule],
                        stored_tables(l)[rule],
                        block,
                        rows,
                        columns,
                        kernel);
    else
      integrate_regular(make_table(k, rules[rule]),
                        make_table(l, rules[rule]),
                        block,
                        rows,
                        columns,
                        kernel);
  }

  bool
  CellPairIntegrator::integrate_composite(const unsigned int       k,
                                          const unsigned int       l,
                                          const SurfaceKernel     &kernel,
                                          FullMatrix<double>      &block,
                                          const std::vector<bool> &rows,
                                          const std::vector<bool> &columns,
                                          const double accuracy) const
  {
    // A convex quadrilateral's edges, and its points' distances from its
    // centre, are at most twice its diameter (the longer diagonal): pairs
    // further apart than this hold no edge longer than widest_over_gap
    // times their gap.
    constexpr double widest_over_gap = 1.5;
    const CellData  &dk = cell_data[k], &dl = cell_data[l];
    const double     wider = std::max(dk.diameter, dl.diameter);
    if (dk.centre.distance(dl.centre) - 2. * (dk.diameter + dl.diameter) >=
        2. * wider / widest_over_gap)
      return false;
    {
      const double gap     = cell_gap(cells[k].geometry, cells[l].geometry);
      double       longest = 0;
      for (const unsigned int c : {k, l})
        for (const auto &[from, to] : edges(cells[c].geometry))
          longest = std::max(longest, from.distance(to));
      if (longest <= (1. + 1e-6) * widest_over_gap * gap)
        return false;
    }

    // A piece: a sub-rectangle of the cell's reference square, mapped.
    struct Piece
    {
      Point<2> lower, size; ///< reference corner and widths
      Point<2> centre;      ///< physical
      double   diameter;
      double   along_x, along_y; ///< its longest edge in each direction
      double   overreach; ///< longest edge over widest_over_gap x the gap
      /** The piece's table of the n-point rule at [n - 2], made when a
       *  pair asks for it (n_functions 0 until then). */
      std::array<Table, 5> tables;
    };
    const auto make_piece = [&](const BilinearQuadrilateral &cell,
                                const BilinearQuadrilateral &other,
                                const Point<2>              &lower,
                                const Point<2>              &size) {
      const auto corner = [&](const double x, const double y) {
        return cell.map(
          Point<2>(lower[0] + x * size[0], lower[1] + y * size[1]));
      };
      const BilinearQuadrilateral geometry(std::array<Point<2>, 4>{
        {corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1)}});
      const auto                  sides  = edges(geometry);
      const auto                  length = [&](const unsigned int e) {
        return sides[e].first.distance(sides[e].second);
      };
      Piece piece;
      piece.lower     = lower;
      piece.size      = size;
      piece.centre    = corner(0.5, 0.5);
      piece.diameter  = geometry.diameter();
      piece.along_x   = std::max(length(0), length(2));
      piece.along_y   = std::max(length(1), length(3));
      piece.overreach = std::max(piece.along_x, piece.along_y) /
                        (widest_over_gap * cell_gap(geometry, other));
      return piece;
    };
    // Each cell cut towards the other: the piece reaching furthest beyond
    // widest_over_gap times its own gap to the other cell is halved across
    // its long edges (or quartered), until none reaches beyond it or the
    // cell has max_pieces pieces. Every pair of pieces then has edges of at
    // most widest_over_gap times its gap, where the plain rule holds about
    // 2e-8 (doc/formulation.md, "Graded and elongated pairs"), and the
    // pieces are graded towards the gap instead of uniform. The margin of
    // 1e-6 keeps a pair at exactly widest_over_gap, and its mirror image,
    // whole despite rounding.
    const auto cut = [&](const unsigned int c, const unsigned int other) {
      const BilinearQuadrilateral &cell   = cells[c].geometry;
      const BilinearQuadrilateral &facing = cells[other].geometry;
      std::vector<Piece>           pieces = {
                  make_piece(cell, facing, Point<2>(0, 0), Point<2>(1, 1))};
      while (true)
        {
          const auto worst =
            std::max_element(pieces.begin(),
                             pieces.end(),
                             [](const Piece &a, const Piece &b) {
                               return a.overreach < b.overreach;
                             });
          if (worst->overreach <= 1. + 1e-6)
            break;
          // halved along the reference directions that are too long
          const bool split_x       = worst->along_x >= 0.5 * worst->along_y,
                     split_y       = worst->along_y >= 0.5 * worst->along_x;
          const unsigned int added = (split_x && split_y) ? 3 : 1;
          if (pieces.size() + added > max_pieces)
            break;
          const Point<2> lower = worst->lower, size = worst->size;
          const Point<2> half(split_x ? 0.5 * size[0] : size[0],
                              split_y ? 0.5 * size[1] : size[1]);
          pieces.erase(worst);
          for (unsigned int j = 0; j < (split_y ? 2u : 1u); ++j)
            for (unsigned int i = 0; i < (split_x ? 2u : 1u); ++i)
              pieces.push_back(make_piece(cell,
                                          facing,
                                          Point<2>(lower[0] + i * half[0],
                                                   lower[1] + j * half[1]),
                                          half));
        }
      return pieces;
    };
    std::array<std::vector<Piece>, 2> cut_cells = {{cut(k, l), cut(l, k)}};
    if (cut_cells[0].size() == 1 && cut_cells[1].size() == 1)
      return false;

    const auto table = [&](const unsigned int side,
                           Piece             &piece,
                           const unsigned int n) -> const Table & {
      Table &t = piece.tables[n - 2];
      if (t.n_functions == 0)
        {
          const Quadrature<2>  &gauss = rules[n - 2];
          std::vector<Point<2>> points;
          std::vector<double>   weights;
          for (unsigned int q = 0; q < gauss.size(); ++q)
            {
              const Point<2> &p = gauss.point(q);
              points.emplace_back(piece.lower[0] + p[0] * piece.size[0],
                                  piece.lower[1] + p[1] * piece.size[1]);
              weights.push_back(gauss.weight(q) * piece.size[0] *
                                piece.size[1]);
            }
          t = make_table(side == 0 ? k : l, Quadrature<2>(points, weights));
        }
      return t;
    };
    for (Piece &p : cut_cells[0])
      for (Piece &q : cut_cells[1])
        {
          const double separation =
            p.centre.distance(q.centre) / std::max(p.diameter, q.diameter);
          const unsigned int n =
            kernel.separated_points(std::round(separation * 1e6) * 1e-6,
                                    accuracy);
          integrate_regular(
            table(0, p, n), table(1, q, n), block, rows, columns, kernel);
        }
    return true;
  }

  std::array<long long, 17>
  CellPairIntegrator::smooth_configuration(const unsigned int          k,
                                           const unsigned int          l,
                                           const SmoothRadialFunction &R) const
  {
    const auto                key = configuration(k, l);
    std::array<long long, 17> sized;
    std::copy(key.begin(), key.end(), sized.begin());
    sized[16] = std::llround(cell_data[k].diameter / R.length_scale() * 1e9);
    return sized;
  }

  FullMatrix<double>
  CellPairIntegrator::integrate_smooth(const unsigned int          k,
                                       const unsigned int          l,
                                       const SmoothRadialFunction &R) const
  {
    const CellData &dk = cell_data[k], &dl = cell_data[l];
    const double    H          = std::max(dk.diameter, dl.diameter);
    const double    separation = std::max(0.,
                                       dk.centre.distance(dl.centre) -
                                         0.5 * (dk.diameter + dl.diameter));
    // 3 + 3 H / (l + d) Gauss points per direction; above 12, the cell is
    // cut into copies that each need at most 12 (a composite rule): R
    // varies on its length scale wherever the cells are, so the points
    // must follow it across a cell many times wider. At most 8 copies
    // (96 points, 10^8 kernel values a pair): beyond, the cells are more
    // than about 30 l wide, which the layered soil warns about and the
    // split-kernel storage's sigma avoids.
    const double       waves  = 3. * H / (R.length_scale() + separation);
    const unsigned int copies = std::min(
      8u, waves <= 9. ? 1u : static_cast<unsigned int>(std::ceil(waves / 9.)));
    const unsigned int order =
      std::min(12u, 3u + static_cast<unsigned int>(std::floor(waves / copies)));
    const QIterated<2> rule(QGauss<1>(order), copies);
    // Points relative to k's first vertex, so that congruent pairs see the
    // same distances up to rounding.
    const Point<2> origin = cells[k].geometry.get_vertices()[0];
    struct Points
    {
      std::vector<Point<2>>              x;
      std::vector<std::array<double, 9>> weighted_phi;
    };
    const auto tabulate = [&](const unsigned int c) {
      Points points;
      for (unsigned int q = 0; q < rule.size(); ++q)
        {
          const Point<2> &p = rule.point(q);
          const double    JxW =
            rule.weight(q) * cells[c].geometry.jacobian_determinant(p);
          points.x.emplace_back(cells[c].geometry.map(p) - origin);
          auto phi = q2_shape_values(p);
          for (double &v : phi)
            v *= JxW;
          points.weighted_phi.push_back(phi);
        }
      return points;
    };
    const Points U = tabulate(k), V = tabulate(l);
    // s(q, i) = sum_p U(p, i) R(|x_p - y_q|), then B(i, j) = sum_q s(q, i)
    // V(q, j).
    std::vector<std::array<double, 9>> s(V.x.size());
    for (unsigned int q = 0; q < V.x.size(); ++q)
      {
        s[q].fill(0.);
        for (unsigned int p = 0; p < U.x.size(); ++p)
          {
            const double kernel = R.value(U.x[p].distance(V.x[q]));
            for (unsigned int i = 0; i < 9; ++i)
              s[q][i] += kernel * U.weighted_phi[p][i];
          }
      }
    FullMatrix<double> block(9, 9);
    for (unsigned int q = 0; q < V.x.size(); ++q)
      for (unsigned int i = 0; i < 9; ++i)
        for (unsigned int j = 0; j < 9; ++j)
          block(i, j) += s[q][i] * V.weighted_phi[q][j];
    return block;
  }

  const FullMatrix<double> &
  CellPairIntegrator::smooth_q2_block(const unsigned int          k,
                                      const unsigned int          l,
                                      const SmoothRadialFunction &R) const
  {
    const auto key = smooth_configuration(k, l, R);
    {
      const std::lock_guard<std::mutex> lock(singular_cache_mutex);
      AssertThrow(smooth_cache_function == nullptr ||
                    smooth_cache_function == &R,
                  ExcMessage("One smooth kernel per CellPairIntegrator."));
      smooth_cache_function = &R;
      const auto found      = smooth_cache.find(key);
      if (found != smooth_cache.end())
        return found->second;
    }
    FullMatrix<double>                block = integrate_smooth(k, l, R);
    const std::lock_guard<std::mutex> lock(singular_cache_mutex);
    return smooth_cache.emplace(key, std::move(block)).first->second;
  }
} // namespace PlateOnHalfspace
