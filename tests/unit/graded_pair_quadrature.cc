// The quadrature of 1/r over separated cells of different sizes or shapes
// (doc/formulation.md, "Graded and elongated pairs": each cell cut into
// pieces graded towards the other until no piece's edge exceeds 1.5 times
// its gap): CellPairIntegrator::integrate_kernel()'s 9 x 9 block of the
// quadratic shape functions of two cells, against an independent adaptive
// rule (the larger of two sub-rectangles quartered until their gap is at
// least its diameter, then 8 Gauss points per direction on each), every
// entry within 1e-7 of the block's largest, the rules' aim
// (SurfaceKernel::separated_points()):
//  - a small square beside squares 2, 4 and 8 times as wide, at gaps of
//    one, a half and a quarter of the small cell's width, level with it
//    and diagonal (an adaptive mesh's grading and a Gmsh mesh's), and
//    beside squares 16, 32 and 64 times as wide down to a tenth of its
//    width away;
//  - a distorted quadrilateral 4 times as wide as the small square;
//  - equal squares 0.03 and 0.01 widths apart (a thin cell between);
//  - two parallel strips 10 and 30 times longer than wide, one and two
//    widths apart, and 30 : 1 strips end to end;
//  - a flat cell (a near-triangle whose base is twice its diagonals and
//    50 times its height) with a small square 5 to 6.5 of its diagonals
//    beyond its tip, within 2e-7 (the worst, 1.0e-7: the rules' error
//    model is fitted on squares);
//  - and, as the control, two equal squares one width apart (a uniform
//    mesh's nearest separated pair), which takes the plain rule.
// Also settlement_at_points() under a uniform pressure on a wide cell,
// seen from points a half and one small width away from it (exact polygon
// integrals there; within 1e-7).
// The plain rule on these pairs left 1e-7 (2 times as wide, one width) to
// 5e-4 (8 times, half a width), and 0.05 to 0.14 on the 30 : 1 strips;
// uniform pieces (at most 64) left 1e-6 to 5e-4 from 16 times as wide.

#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>
#include <plate_on_halfspace/soil/soil_model.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "../tests.h"

#include "../foundation_cells.h"

namespace
{
  using namespace PlateOnHalfspace;

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

  /** A sub-rectangle [lower, lower + size] of a cell's reference square. */
  struct Part
  {
    Point<2> lower, size;
  };

  BilinearQuadrilateral
  mapped(const BilinearQuadrilateral &cell, const Part &part)
  {
    const auto corner = [&](const double x, const double y) {
      return cell.map(Point<2>(part.lower[0] + x * part.size[0],
                               part.lower[1] + y * part.size[1]));
    };
    return BilinearQuadrilateral(std::array<Point<2>, 4>{
      {corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1)}});
  }

  /** The 8 x 8 Gauss points of @p part of @p cell, as Points. */
  Points
  part_points(const BilinearQuadrilateral &cell, const Part &part)
  {
    const QGauss<2> rule(8);
    Points          points;
    for (unsigned int q = 0; q < rule.size(); ++q)
      {
        const Point<2> r(part.lower[0] + rule.point(q)[0] * part.size[0],
                         part.lower[1] + rule.point(q)[1] * part.size[1]);
        points.x.push_back(cell.map(r));
        points.w.push_back(rule.weight(q) * part.size[0] * part.size[1] *
                           cell.jacobian_determinant(r));
        points.phi.push_back(q2_shape_values(r));
      }
    return points;
  }

  /**
   * Adds the pair of parts to @p block: 8 x 8 Gauss points on each once
   * their gap is at least the larger part's diameter, else the
   * larger part quartered (an adaptive rule, independent of the
   * integrator's).
   */
  void
  add_reference(const BilinearQuadrilateral &k,
                const Part                  &a,
                const BilinearQuadrilateral &l,
                const Part                  &b,
                FullMatrix<double>          &block)
  {
    const BilinearQuadrilateral ka = mapped(k, a), lb = mapped(l, b);
    if (gap(ka, lb) < std::max(ka.diameter(), lb.diameter()))
      {
        const bool split_a = ka.diameter() >= lb.diameter();
        const Part whole   = split_a ? a : b;
        for (unsigned int j = 0; j < 2; ++j)
          for (unsigned int i = 0; i < 2; ++i)
            {
              const Part quarter{
                Point<2>(whole.lower[0] + 0.5 * i * whole.size[0],
                         whole.lower[1] + 0.5 * j * whole.size[1]),
                Point<2>(0.5 * whole.size[0], 0.5 * whole.size[1])};
              if (split_a)
                add_reference(k, quarter, l, b, block);
              else
                add_reference(k, a, l, quarter, block);
            }
        return;
      }
    const Points          u = part_points(k, a), v = part_points(l, b);
    std::array<double, 9> s;
    for (unsigned int p = 0; p < u.x.size(); ++p)
      {
        s.fill(0.);
        for (unsigned int q = 0; q < v.x.size(); ++q)
          {
            const double g = v.w[q] / u.x[p].distance(v.x[q]);
            for (unsigned int c = 0; c < 9; ++c)
              s[c] += g * v.phi[q][c];
          }
        for (unsigned int c = 0; c < 9; ++c)
          for (unsigned int d = 0; d < 9; ++d)
            block(c, d) += u.w[p] * u.phi[p][c] * s[d];
      }
  }

  FullMatrix<double>
  reference_block(const BilinearQuadrilateral &k,
                  const BilinearQuadrilateral &l)
  {
    FullMatrix<double> block(9, 9);
    const Part         whole{Point<2>(0, 0), Point<2>(1, 1)};
    add_reference(k, whole, l, whole, block);
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
             const std::array<Point<2>, 4> &second,
             const double                   bound = 1e-7)
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
    check_below(name + ", pair block", deviation / largest, bound);
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
  // Beyond an adaptive mesh's grading: a unit square beside squares 16,
  // 32 and 64 times as wide, down to a tenth of its width away; equal
  // squares with a thin cell between them; strips facing each other with
  // their short edges; a flat cell (a near-triangle, whose base is twice
  // its diagonals) beyond whose tip a small square lies.
  for (const double ratio : {16., 32., 64.})
    for (const double g : {1., 0.25, 0.1})
      check_pair("square " + std::to_string(int(ratio)) + " times as wide, " +
                   (g == 1.   ? "one width" :
                    g == 0.25 ? "a quarter width" :
                                "a tenth of a width") +
                   " beside",
                 rectangle(0, 0, a, a),
                 rectangle(a + g * a, 0, ratio * a, ratio * a));
  for (const double g : {0.03, 0.01})
    check_pair("equal squares " + std::to_string(g).substr(0, 4) +
                 " widths apart",
               rectangle(0, 0, a, a),
               rectangle(a + g * a, 0.5 * a, a, a));
  check_pair("strips 30 : 1 end to end, 0.2 widths apart",
             rectangle(0, 0, a, 30 * a),
             rectangle(0, 30.2 * a, a, 30 * a));
  for (const double g : {5., 5.5, 6.5})
    check_pair("flat cell, a small square " + std::to_string(g).substr(0, 3) +
                 " beyond its tip",
               {{Point<2>(0, 0),
                 Point<2>(10 * a, 0),
                 Point<2>(4.9 * a, 0.1 * a),
                 Point<2>(5.1 * a, 0.1 * a)}},
               rectangle(10 * a + g * a, 0, 0.1 * a, 0.1 * a),
               2e-7);
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
