// The quadrature of 1/r over separated cells of different sizes or shapes
// (doc/formulation.md, "Cell-pair quadrature": composite rules where a
// cell is wider than the gap between the two): CellPairIntegrator::
// integrate_kernel()'s 9 x 9 block of the quadratic shape functions of two
// cells, against an independent composite rule (6 Gauss points per
// direction on pieces at most a third of the gap wide), every entry
// within 1e-7 of the block's largest, the rules' aim (SurfaceKernel::
// separated_points()):
//  - a small square beside squares 2, 4 and 8 times as wide, at gaps of
//    one, a half and a quarter of the small cell's width, level with it
//    and diagonal (an adaptive mesh's grading and a Gmsh mesh's; the 8
//    times wider square a quarter width away is cut into the most pieces,
//    max_pieces, and still holds);
//  - a distorted quadrilateral 4 times as wide as the small square;
//  - two parallel strips 10 and 30 times longer than wide, one and two
//    widths apart;
//  - and, as the control, two equal squares one width apart (a uniform
//    mesh's nearest separated pair), which takes the plain rule.
// Also settlement_at_points() under a uniform pressure on a wide cell,
// seen from points a half and one small width away from it (exact polygon
// integrals there; within 1e-7).
// The plain rule on these pairs left 1e-7 (2 times as wide, one width) to
// 5e-4 (8 times, half a width), and 0.05 to 0.14 on the 30 : 1 strips.

#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>
#include <plate_on_halfspace/soil/soil_model.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "../tests.h"

namespace
{
  using namespace PlateOnHalfspace;

  FoundationSpace::Cell
  cell_with_own_nodes(const std::array<Point<2>, 4> &vertices,
                      const unsigned int             first)
  {
    FoundationSpace::Cell cell{BilinearQuadrilateral(vertices), {}};
    for (unsigned int i = 0; i < 9; ++i)
      cell.expansion[i] = {{first + i, 1.}};
    return cell;
  }

  /** An axis-parallel rectangle [x0, x0 + w] x [y0, y0 + h], deal.II order. */
  std::array<Point<2>, 4>
  rectangle(const double x0, const double y0, const double w, const double h)
  {
    return {{Point<2>(x0, y0),
             Point<2>(x0 + w, y0),
             Point<2>(x0, y0 + h),
             Point<2>(x0 + w, y0 + h)}};
  }

  /** The cell's points of QIterated(QGauss(6), m_x x m_y) with their
   *  weights times the Jacobian, and the Q2 shape values there. */
  struct Points
  {
    std::vector<Point<2>>              x;
    std::vector<double>                w;
    std::vector<std::array<double, 9>> phi;
  };

  Points
  composite_points(const BilinearQuadrilateral &cell, const double piece)
  {
    const auto        &v   = cell.get_vertices();
    const double       l_x = std::max(v[0].distance(v[1]), v[2].distance(v[3]));
    const double       l_y = std::max(v[0].distance(v[2]), v[1].distance(v[3]));
    const unsigned int m_x = std::ceil(l_x / piece),
                       m_y = std::ceil(l_y / piece);
    const QAnisotropic<2> rule(QIterated<1>(QGauss<1>(6), m_x),
                               QIterated<1>(QGauss<1>(6), m_y));
    Points                points;
    for (unsigned int q = 0; q < rule.size(); ++q)
      {
        points.x.push_back(cell.map(rule.point(q)));
        points.w.push_back(rule.weight(q) *
                           cell.jacobian_determinant(rule.point(q)));
        points.phi.push_back(q2_shape_values(rule.point(q)));
      }
    return points;
  }

  /** The distance between two convex cells that do not overlap: the
   *  smallest of a vertex of one to an edge of the other. */
  double
  gap(const BilinearQuadrilateral &a, const BilinearQuadrilateral &b)
  {
    const auto segment_distance =
      [](const Point<2> &p, const Point<2> &s0, const Point<2> &s1) {
        const Tensor<1, 2> d = s1 - s0;
        const double t = std::clamp((p - s0) * d / d.norm_square(), 0., 1.);
        return p.distance(s0 + t * d);
      };
    double     smallest = std::numeric_limits<double>::max();
    const auto edges    = [](const BilinearQuadrilateral &c) {
      const auto &v = c.get_vertices();
      return std::array<std::pair<Point<2>, Point<2>>, 4>{
        {{v[0], v[1]}, {v[1], v[3]}, {v[3], v[2]}, {v[2], v[0]}}};
    };
    for (const auto &[p, q] : {std::pair(&a, &b), std::pair(&b, &a)})
      for (const Point<2> &vertex : p->get_vertices())
        for (const auto &[s0, s1] : edges(*q))
          smallest = std::min(smallest, segment_distance(vertex, s0, s1));
    return smallest;
  }

  FullMatrix<double>
  reference_block(const BilinearQuadrilateral &k,
                  const BilinearQuadrilateral &l)
  {
    const double piece = gap(k, l) / 3.;
    const Points u = composite_points(k, piece), v = composite_points(l, piece);
    FullMatrix<double>    block(9, 9);
    std::array<double, 9> s;
    for (unsigned int p = 0; p < u.x.size(); ++p)
      {
        s.fill(0.);
        for (unsigned int q = 0; q < v.x.size(); ++q)
          {
            const double g = v.w[q] / u.x[p].distance(v.x[q]);
            for (unsigned int b = 0; b < 9; ++b)
              s[b] += g * v.phi[q][b];
          }
        for (unsigned int a = 0; a < 9; ++a)
          for (unsigned int b = 0; b < 9; ++b)
            block(a, b) += u.w[p] * u.phi[p][a] * s[b];
      }
    return block;
  }

  double
  reference_settlement(const BilinearQuadrilateral &k, const Point<2> &x)
  {
    const double piece = x.distance(k.map(Point<2>(0.5, 0.5))) / 8.;
    double       sum   = 0;
    const Points u     = composite_points(k, std::min(piece, 0.05));
    for (unsigned int p = 0; p < u.x.size(); ++p)
      sum += u.w[p] / u.x[p].distance(x);
    return sum;
  }

  void
  check_pair(const std::string             &name,
             const std::array<Point<2>, 4> &first,
             const std::array<Point<2>, 4> &second)
  {
    const std::vector<FoundationSpace::Cell> cells = {
      cell_with_own_nodes(first, 0), cell_with_own_nodes(second, 9)};
    const CellPairIntegrator integrator(cells, 8);
    AssertThrow(!integrator.singular_pair(0, 1), ExcInternalError());
    FullMatrix<double> block;
    integrator.integrate_kernel(0, 1, SurfaceKernel(1.), block, {}, {});
    const FullMatrix<double> reference =
      reference_block(cells[0].geometry, cells[1].geometry);
    double largest = 0, deviation = 0;
    for (unsigned int i = 0; i < 9; ++i)
      for (unsigned int j = 0; j < 9; ++j)
        {
          largest = std::max(largest, std::abs(reference(i, j)));
          deviation =
            std::max(deviation, std::abs(block(i, j) - reference(i, j)));
        }
    check_below(name + ", pair block", deviation / largest, 1e-7);
  }
} // namespace

int
main()
{
  initlog();
  const double a = 1.;
  check_pair("equal squares one width apart",
             rectangle(0, 0, a, a),
             rectangle(2 * a, 0, a, a));
  for (const double ratio : {2., 4., 8.})
    for (const double g : {1., 0.5, 0.25})
      {
        const std::string size = std::to_string(int(ratio)) +
                                 " times as wide, " +
                                 (g == 1.  ? "one width" :
                                  g == 0.5 ? "half a width" :
                                             "a quarter width");
        check_pair("square " + size + " beside",
                   rectangle(0, 0, a, a),
                   rectangle(a + g * a, 0, ratio * a, ratio * a));
        check_pair("square " + size + " diagonal",
                   rectangle(0, 0, a, a),
                   rectangle(a + g * a, a + g * a, ratio * a, ratio * a));
      }
  check_pair("distorted quadrilateral 4 times as wide, one width",
             rectangle(0, 0, a, a),
             {{Point<2>(2 * a, -a),
               Point<2>(6 * a, -0.6 * a),
               Point<2>(2.2 * a, 3 * a),
               Point<2>(5.4 * a, 3.5 * a)}});
  for (const double length : {10., 30.})
    for (const double g : {1., 2.})
      check_pair("strips " + std::to_string(int(length)) + " : 1, " +
                   std::to_string(int(g)) + " widths apart",
                 rectangle(0, 0, a, length * a),
                 rectangle(a + g * a, 0, a, length * a));

  // Settlement at points near a wide cell under a unit pressure on it.
  for (const double ratio : {4., 8.})
    for (const double g : {1., 0.5})
      {
        FoundationSpace space;
        space.cells = {
          cell_with_own_nodes(rectangle(0, 0, ratio * a, ratio * a), 0)};
        space.node_locations.resize(9);
        Vector<double> pressure(9);
        pressure = 1.;
        for (const bool diagonal : {false, true})
          {
            const Point<2> x(-g * a, diagonal ? -g * a : 0.5 * a);
            const double   computed = settlement_at_points(
              space, pressure, {x}, SurfaceKernel(1.), 8)[0];
            const double exact =
              reference_settlement(space.cells[0].geometry, x);
            check_below("settlement beside a cell " +
                          std::to_string(int(ratio)) + " times as wide, " +
                          (g == 1. ? "one width" : "half a width") +
                          (diagonal ? " diagonally" : "") + " away",
                        std::abs(computed - exact) / exact,
                        1e-7);
          }
      }
}
