#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/boussinesq_kernel.h>
#include <plate_on_halfspace/cell_pair_quadrature.h>

#include <algorithm>
#include <cmath>
#include <memory>

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
    const unsigned int                        singular_order)
    : cells(cells)
    , singular_order(singular_order)
    , orders{2, 3, 5, 0}
    , cell_data(cells.size())
    , duffy(singular_order, 1.0)
  {
    const Quadrature<2> outer_rule = graded_rule(singular_order);
    for (const Point<2> &p : outer_rule.get_points())
      coincident_rules.emplace_back(p, duffy);
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        const FoundationSpace::Cell &cell = cells[c];
        CellData                    &data = cell_data[c];
        data.nodes                        = cell.nodes();
        data.node_from_q2.reinit(data.nodes.size(), 9);
        for (unsigned int i = 0; i < 9; ++i)
          for (const auto &t : cell.expansion[i])
            {
              const unsigned int a =
                std::find(data.nodes.begin(), data.nodes.end(), t.first) -
                data.nodes.begin();
              data.node_from_q2(a, i) += t.second;
            }
        data.centre   = cell.geometry.map(Point<2>(0.5, 0.5));
        data.diameter = cell.geometry.diameter();

        for (const unsigned int order : orders)
          {
            const Quadrature<2> rule = (order == 0) ?
                                         graded_rule(singular_order) :
                                         Quadrature<2>(QGauss<2>(order));
            Table               table;
            for (unsigned int q = 0; q < rule.size(); ++q)
              {
                const Point<2> &p = rule.point(q);
                table.points.push_back(cell.geometry.map(p));
                table.weights.push_back(rule.weight(q) *
                                        cell.geometry.jacobian_determinant(p));
                std::vector<double> values;
                node_shape_values(c, p, values);
                table.values.push_back(values);
              }
            data.tables.push_back(table);
          }
      }
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
  CellPairIntegrator::integrate_regular(const Table        &outer,
                                        const Table        &inner,
                                        FullMatrix<double> &block) const
  {
    const unsigned int na = outer.values[0].size(), nb = inner.values[0].size();
    // t(p, b) = sum_q W_q psi_b(y_q) / |x_p - y_q|, then
    // block(a, b) = sum_p W_p psi_a(x_p) t(p, b).
    std::vector<double> t(nb);
    for (unsigned int p = 0; p < outer.points.size(); ++p)
      {
        std::fill(t.begin(), t.end(), 0.);
        for (unsigned int q = 0; q < inner.points.size(); ++q)
          {
            const double kernel =
              inner.weights[q] / outer.points[p].distance(inner.points[q]);
            for (unsigned int b = 0; b < nb; ++b)
              t[b] += kernel * inner.values[q][b];
          }
        for (unsigned int a = 0; a < na; ++a)
          {
            const double wa = outer.weights[p] * outer.values[p][a];
            for (unsigned int b = 0; b < nb; ++b)
              block(a, b) += wa * t[b];
          }
      }
  }

  void
  CellPairIntegrator::integrate_singular(const unsigned int  k,
                                         const unsigned int  l,
                                         FullMatrix<double> &block) const
  {
    const BilinearQuadrilateral &inner_cell = cells[l].geometry;
    const Table       &outer = cell_data[k].tables.back(); // singular order
    const unsigned int nb    = cell_data[l].nodes.size();
    const auto        &v     = inner_cell.get_vertices();
    const std::vector<Point<2>> polygon = {v[0], v[1], v[3], v[2]};
    const FullMatrix<double>   &T       = cell_data[l].node_from_q2;
    std::array<double, 9>       t;
    for (unsigned int p = 0; p < outer.points.size(); ++p)
      {
        const Point<2> &x = outer.points[p];
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
        // to the node shape functions psi_b = sum_i T_bi phi_i
        for (unsigned int b = 0; b < nb; ++b)
          {
            double tb = 0;
            for (unsigned int i = 0; i < 9; ++i)
              tb += T(b, i) * t[i];
            for (unsigned int a = 0; a < outer.values[p].size(); ++a)
              block(a, b) += outer.weights[p] * outer.values[p][a] * tb;
          }
      }
  }

  void
  CellPairIntegrator::integrate_inverse_distance(
    const unsigned int  k,
    const unsigned int  l,
    FullMatrix<double> &block) const
  {
    block.reinit(cell_data[k].nodes.size(), cell_data[l].nodes.size());
    if (singular_pair(k, l))
      {
        // The rule is not symmetric in the roles of the two cells (outer
        // Gauss on one, inner Duffy on the other): average both orders, so
        // that A is exactly symmetric (its Cholesky factor reads one
        // triangle), the block does not depend on which cell comes first,
        // and a mirror-symmetric mesh gives a mirror-symmetric A.
        integrate_singular(k, l, block);
        FullMatrix<double> swapped(cell_data[l].nodes.size(),
                                   cell_data[k].nodes.size());
        if (k == l)
          swapped = block;
        else
          integrate_singular(l, k, swapped);
        for (unsigned int a = 0; a < block.m(); ++a)
          for (unsigned int b = 0; b < block.n(); ++b)
            block(a, b) = 0.5 * (block(a, b) + swapped(b, a));
        return;
      }
    const double separation =
      cell_data[k].centre.distance(cell_data[l].centre) /
      std::max(cell_data[k].diameter, cell_data[l].diameter);
    // Round away the last digits: on a uniform mesh many pairs sit exactly
    // on a threshold, and rounding must not send a pair and its mirror
    // image to different rules.
    const double       rounded = std::round(separation * 1e6) * 1e-6;
    const unsigned int rule    = (rounded < 2.5 ? 2 : rounded < 20 ? 1 : 0);
    integrate_regular(cell_data[k].tables[rule],
                      cell_data[l].tables[rule],
                      block);
  }
} // namespace PlateOnHalfspace
