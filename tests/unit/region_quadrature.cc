// Quadrature on the part of a quadrilateral cell covered by a rectangle
// (quadrature_on_rectangle_part) or a disk (quadrature_on_disk_part):
// areas and moments against exact values computed independently (box
// intersections, integration over horizontal slices, circular-segment
// formulas), for axis-aligned and skewed cells, and a few properties of
// BilinearQuadrilateral (inverse_map, contains).

#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/base/quadrilateral_geometry.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  const double pi = numbers::PI;

  BilinearQuadrilateral
  rectangle_cell(const double x0,
                 const double x1,
                 const double y0,
                 const double y1)
  {
    return BilinearQuadrilateral(std::array<Point<2>, 4>{{Point<2>(x0, y0),
                                                          Point<2>(x1, y0),
                                                          Point<2>(x0, y1),
                                                          Point<2>(x1, y1)}});
  }



  /** Sum of w f(x) over the rule, f evaluated at the physical point. */
  double
  integrate(const BilinearQuadrilateral           &cell,
            const Quadrature<2>                   &quadrature,
            const std::function<double(Point<2>)> &f)
  {
    double sum = 0;
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      sum += quadrature.weight(q) * f(cell.map(quadrature.point(q)));
    return sum;
  }



  void
  check_absolute(const std::string &name,
                 const double       computed,
                 const double       reference,
                 const double       absolute_tolerance)
  {
    const bool ok = std::abs(computed - reference) <= absolute_tolerance;
    std::ostringstream tolerance;
    tolerance << absolute_tolerance;
    // the digits the tolerance resolves relative to the reference
    // (rounded()), all of them on failure, to show the difference
    const double relative =
      (reference != 0 ? absolute_tolerance / std::abs(reference) : 0.);
    const auto shown = [&](const double v) {
      std::ostringstream s;
      s << std::setprecision(17) << v;
      return ok ? rounded(v, relative) : s.str();
    };
    deallog << name << ": computed " << shown(computed) << " reference "
            << shown(reference) << " (abs. tol. " << tolerance.str() << ") "
            << (ok ? "ok" : "FAILED") << std::endl;
    AssertThrow(ok, ExcMessage("check '" + name + "' failed"));
  }



  void
  check_true(const std::string &name, const bool condition)
  {
    deallog << name << ": " << (condition ? "ok" : "FAILED") << std::endl;
    AssertThrow(condition, ExcMessage("check '" + name + "' failed"));
  }



  /** Points in the closed reference cell and positive weights. */
  void
  check_rule(const std::string &name, const Quadrature<2> &quadrature)
  {
    bool ok = true;
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      {
        const Point<2> &p = quadrature.point(q);
        ok = ok && p[0] >= -1e-12 && p[0] <= 1 + 1e-12 && p[1] >= -1e-12 &&
             p[1] <= 1 + 1e-12 && quadrature.weight(q) > 0;
      }
    check_true(name + ", points in [0,1]^2 and weights > 0", ok);
  }



  /**
   * Exact integrals of 1, x, y and x^2 y over (cell ∩ [rx0,rx1] x [ry0,ry1])
   * for a convex cell, by integrating over horizontal slices: the slice at
   * height y is an interval [xl(y), xr(y)] with piecewise linear ends, kinks
   * only at the heights of the cell's vertices and of the points where its
   * edges cross x = rx0 or x = rx1. On each piece between such heights a
   * 3-point Gauss rule in y is exact (integrands of degree <= 4 in y).
   */
  std::array<double, 4>
  slice_integrals(const BilinearQuadrilateral &cell,
                  const double                 rx0,
                  const double                 rx1,
                  const double                 ry0,
                  const double                 ry1)
  {
    const auto                 &v       = cell.get_vertices();
    const std::vector<Point<2>> polygon = {v[0], v[1], v[3], v[2]};

    std::vector<double> heights = {ry0, ry1};
    for (unsigned int i = 0; i < 4; ++i)
      {
        const Point<2> &p = polygon[i], &q = polygon[(i + 1) % 4];
        heights.push_back(p[1]);
        for (const double x : {rx0, rx1})
          if ((p[0] - x) * (q[0] - x) < 0)
            heights.push_back(p[1] +
                              (x - p[0]) / (q[0] - p[0]) * (q[1] - p[1]));
      }
    std::sort(heights.begin(), heights.end());

    const auto slice = [&](const double y) {
      double xl = 1e300, xr = -1e300;
      for (unsigned int i = 0; i < 4; ++i)
        {
          const Point<2> &p = polygon[i], &q = polygon[(i + 1) % 4];
          if ((p[1] - y) * (q[1] - y) <= 0 && p[1] != q[1])
            {
              const double x =
                p[0] + (y - p[1]) / (q[1] - p[1]) * (q[0] - p[0]);
              xl = std::min(xl, x);
              xr = std::max(xr, x);
            }
        }
      return std::make_pair(std::max(xl, rx0), std::min(xr, rx1));
    };

    const QGauss<1>       gauss(3);
    std::array<double, 4> result = {{0, 0, 0, 0}};
    for (unsigned int k = 0; k + 1 < heights.size(); ++k)
      {
        const double a = std::max(heights[k], ry0);
        const double b = std::min(heights[k + 1], ry1);
        if (!(b > a))
          continue;
        for (unsigned int q = 0; q < gauss.size(); ++q)
          {
            const double y = a + (b - a) * gauss.point(q)[0];
            const double w = gauss.weight(q) * (b - a);
            const auto   s = slice(y);
            if (!(s.second > s.first))
              continue;
            const double xl = s.first, xr = s.second;
            result[0] += w * (xr - xl);
            result[1] += w * (xr * xr - xl * xl) / 2;
            result[2] += w * y * (xr - xl);
            result[3] += w * y * (xr * xr * xr - xl * xl * xl) / 3;
          }
      }
    return result;
  }



  /** Area of the circular segment cut off by a chord at distance d. */
  double
  segment_area(const double R, const double d)
  {
    return R * R * std::acos(d / R) - d * std::sqrt(R * R - d * d);
  }
} // namespace



int
main()
{
  initlog();

  const auto one = [](const Point<2> &) { return 1.; };
  const auto x   = [](const Point<2> &p) { return p[0]; };
  const auto y   = [](const Point<2> &p) { return p[1]; };

  // (a) A rectangular cell entirely inside the loaded rectangle.
  {
    deallog << "(a) cell [0,2]x[1,2.5] inside the rectangle [-1,5]x[0,3]"
            << std::endl;
    const auto cell = rectangle_cell(0, 2, 1, 2.5);
    const auto q3 =
      quadrature_on_rectangle_part(cell, Point<2>(-1, 0), Point<2>(5, 3), 3);
    check_rule("n=3", q3);
    check_absolute("area", integrate(cell, q3, one), 3., 1e-13);
    // int x^2 = 8/3, int y^2 = 4.875, int x = 2, int y = 2.625
    check_absolute("x^2 y^2 + x y + 1 (n=3)",
                   integrate(cell,
                             q3,
                             [](const Point<2> &p) {
                               return p[0] * p[0] * p[1] * p[1] + p[0] * p[1] +
                                      1;
                             }),
                   8. / 3 * 4.875 + 2 * 2.625 + 3,
                   1e-12);
    // the same biquadratic through the reference coordinates, as shape
    // functions are evaluated: s = x/2, t = (y-1)/1.5
    double sum = 0;
    for (unsigned int q = 0; q < q3.size(); ++q)
      {
        const Point<2> &p = q3.point(q);
        sum += q3.weight(q) * p[0] * p[0] * p[1] * p[1];
      }
    check_absolute("s^2 t^2 in reference coordinates (n=3)",
                   sum,
                   3. / 9,
                   1e-13);
    // higher n: QGaussSimplex(4) and the collapsed Gauss rule beyond
    const auto q4 =
      quadrature_on_rectangle_part(cell, Point<2>(-1, 0), Point<2>(5, 3), 4);
    check_absolute("x^3 y^4 (n=4, degree 7)",
                   integrate(cell,
                             q4,
                             [](const Point<2> &p) {
                               return std::pow(p[0], 3) * std::pow(p[1], 4);
                             }),
                   4. * (std::pow(2.5, 5) - 1) / 5,
                   1e-11);
    const auto q5 =
      quadrature_on_rectangle_part(cell, Point<2>(-1, 0), Point<2>(5, 3), 5);
    check_rule("n=5", q5);
    check_absolute("x^4 y^5 (n=5, degree 9)",
                   integrate(cell,
                             q5,
                             [](const Point<2> &p) {
                               return std::pow(p[0], 4) * std::pow(p[1], 5);
                             }),
                   32. / 5 * (std::pow(2.5, 6) - 1) / 6,
                   1e-10);
  }

  // (b) Partial overlaps of an axis-aligned cell with rectangles: area and
  // first moments of the box intersection.
  {
    deallog << "(b) cell [1,3]x[-1,0.5] and rectangles" << std::endl;
    const auto cell = rectangle_cell(1, 3, -1, 0.5);
    const std::vector<std::array<double, 4>> rectangles = {
      {{0.25, 2.2, -3, 0}},     // overlap [1,2.2]x[-1,0]
      {{1.5, 2.5, -0.5, 0.25}}, // inside the cell
      {{2.9, 10, 0.4, 7}},      // corner [2.9,3]x[0.4,0.5]
      {{-5, 5, -5, 5}},         // the whole cell
      {{1.2, 1.7, -7, 7}},      // a strip across the cell
      {{3, 4, 0, 1}},           // touches the edge x = 3 only
      {{4, 5, 0, 1}}};          // no overlap
    for (const auto &r : rectangles)
      {
        std::ostringstream name;
        name << "[" << r[0] << "," << r[1] << "]x[" << r[2] << "," << r[3]
             << "]";
        const double a = std::max(r[0], 1.), b = std::min(r[1], 3.);
        const double c = std::max(r[2], -1.), d = std::min(r[3], 0.5);
        const auto   quadrature = quadrature_on_rectangle_part(
          cell, Point<2>(r[0], r[2]), Point<2>(r[1], r[3]), 2);
        if (!(b > a && d > c))
          {
            check_true(name.str() + " no overlap, empty rule",
                       quadrature.size() == 0);
            continue;
          }
        check_rule(name.str(), quadrature);
        check_absolute(name.str() + " area",
                       integrate(cell, quadrature, one),
                       (b - a) * (d - c),
                       1e-13);
        check_absolute(name.str() + " int x",
                       integrate(cell, quadrature, x),
                       (b * b - a * a) / 2 * (d - c),
                       1e-13);
        check_absolute(name.str() + " int y",
                       integrate(cell, quadrature, y),
                       (b - a) * (d * d - c * c) / 2,
                       1e-13);
      }
  }

  // (c) A skewed (non-parallelogram) cell.
  {
    deallog << "(c) skewed cell (0,0) (2,0.2) (0.3,1.5) (2.4,1.9)" << std::endl;
    const BilinearQuadrilateral cell(
      std::array<Point<2>, 4>{{Point<2>(0, 0),
                               Point<2>(2, 0.2),
                               Point<2>(0.3, 1.5),
                               Point<2>(2.4, 1.9)}});

    // inverse_map and contains
    double max_error = 0;
    for (const double s : {0., 0.13, 0.5, 0.77, 1.})
      for (const double t : {0., 0.29, 0.5, 0.91, 1.})
        {
          const Point<2> p(s, t);
          max_error =
            std::max(max_error, cell.inverse_map(cell.map(p)).distance(p));
        }
    check_true("inverse_map(map(p)) = p to 1e-13", max_error <= 1e-13);
    check_true("contains: interior point", cell.contains(Point<2>(1.2, 0.9)));
    check_true("contains: vertex", cell.contains(Point<2>(2.4, 1.9)));
    check_true("contains: edge midpoint", cell.contains(Point<2>(1, 0.1)));
    check_true("contains: point just outside the edge",
               !cell.contains(Point<2>(1, 0.1 - 1e-6)));
    check_true("contains: far point", !cell.contains(Point<2>(-10, 20)));
    check_true("not an axis-aligned rectangle",
               !cell.is_axis_aligned_rectangle());
    check_true("axis-aligned rectangle",
               rectangle_cell(1, 3, -1, 0.5).is_axis_aligned_rectangle());
    check_absolute("diameter",
                   cell.diameter(),
                   std::sqrt(2.4 * 2.4 + 1.9 * 1.9),
                   1e-15);

    const std::vector<std::array<double, 4>> rectangles = {
      {{0.1, 2.2, 0.1, 1.7}}, // cuts all four edges
      {{-1, 1, -1, 0.7}},     // around vertex 0
      {{1.9, 5, 0.05, 5}},    // around vertices 1 and 3
      {{-5, 5, -5, 5}}};      // the whole cell
    for (const auto &r : rectangles)
      {
        std::ostringstream name;
        name << "[" << r[0] << "," << r[1] << "]x[" << r[2] << "," << r[3]
             << "]";
        const auto exact      = slice_integrals(cell, r[0], r[1], r[2], r[3]);
        const auto quadrature = quadrature_on_rectangle_part(
          cell, Point<2>(r[0], r[2]), Point<2>(r[1], r[3]), 3);
        check_rule(name.str(), quadrature);
        check_absolute(name.str() + " area",
                       integrate(cell, quadrature, one),
                       exact[0],
                       1e-13);
        check_absolute(name.str() + " int x",
                       integrate(cell, quadrature, x),
                       exact[1],
                       1e-13);
        check_absolute(name.str() + " int y",
                       integrate(cell, quadrature, y),
                       exact[2],
                       1e-13);
        check_absolute(name.str() + " int x^2 y",
                       integrate(cell,
                                 quadrature,
                                 [](const Point<2> &p) {
                                   return p[0] * p[0] * p[1];
                                 }),
                       exact[3],
                       1e-12);
      }
    // the whole cell by the shoelace formula: polygon v0 v1 v3 v2
    check_absolute("whole cell area by shoelace",
                   slice_integrals(cell, -5, 5, -5, 5)[0],
                   0.5 * ((0 * 0.2 - 2 * 0) + (2 * 1.9 - 2.4 * 0.2) +
                          (2.4 * 1.5 - 0.3 * 1.9) + (0.3 * 0 - 0 * 1.5)),
                   1e-14);
  }

  // (d) Disk parts.
  {
    deallog << "(d) disks" << std::endl;
    const unsigned int n    = 10;
    const auto         unit = rectangle_cell(0, 1, 0, 1);

    const auto check_disk = [&](const std::string           &name,
                                const BilinearQuadrilateral &cell,
                                const Point<2>              &centre,
                                const double                 R,
                                const double                 exact_area) {
      const auto quadrature = quadrature_on_disk_part(cell, centre, R, n);
      if (exact_area == 0)
        {
          check_true(name + ", empty rule", quadrature.size() == 0);
          return quadrature;
        }
      check_rule(name, quadrature);
      check_absolute(name + ", area",
                     integrate(cell, quadrature, one),
                     exact_area,
                     1e-13);
      return quadrature;
    };

    {
      const auto cell = rectangle_cell(0, 2, 0, 1.5);
      const auto q    = check_disk(
        "disk inside the cell", cell, Point<2>(0.9, 0.8), 0.3, pi * 0.09);
      check_absolute("disk inside the cell, int x",
                     integrate(cell, q, x),
                     pi * 0.09 * 0.9,
                     1e-13);
      check_absolute("disk inside the cell, int (x-0.9)^2",
                     integrate(cell,
                               q,
                               [](const Point<2> &p) {
                                 return (p[0] - 0.9) * (p[0] - 0.9);
                               }),
                     pi * std::pow(0.3, 4) / 4,
                     1e-14);
    }
    check_disk("disk inside, touching all four edges",
               unit,
               Point<2>(0.5, 0.5),
               0.5,
               pi / 4);
    check_disk("centre at vertex 3", unit, Point<2>(1, 1), 0.4, pi * 0.16 / 4);
    {
      const auto q = check_disk(
        "centre at vertex 0", unit, Point<2>(0, 0), 0.7, pi * 0.49 / 4);
      check_absolute("centre at vertex 0, int x^2 = pi R^4/16",
                     integrate(unit,
                               q,
                               [](const Point<2> &p) { return p[0] * p[0]; }),
                     pi * std::pow(0.7, 4) / 16,
                     1e-14);
    }
    check_disk("centre on an edge", unit, Point<2>(0.5, 0), 0.3, pi * 0.09 / 2);
    check_disk("centre outside, segment",
               unit,
               Point<2>(0.5, -0.3),
               0.5,
               segment_area(0.5, 0.3));
    check_disk("centre outside close to the edge line, segment",
               unit,
               Point<2>(0.5, 1.001),
               0.45,
               segment_area(0.45, 0.001));
    check_disk("centre inside, circle crosses one edge",
               unit,
               Point<2>(0.5, 0.2),
               0.3,
               pi * 0.09 - segment_area(0.3, 0.2));
    check_disk("centre on the extension of an edge, half segment",
               unit,
               Point<2>(1.5, 0),
               0.8,
               segment_area(0.8, 0.5) / 2);
    {
      const auto q = check_disk(
        "disk containing the whole cell", unit, Point<2>(0.5, 0.5), 1, 1);
      check_absolute("disk containing the whole cell, int x",
                     integrate(unit, q, x),
                     0.5,
                     1e-14);
    }
    check_disk("disk far away", unit, Point<2>(3, 3), 1, 0);
    check_disk(
      "disk touching the cell from outside", unit, Point<2>(2, 0.5), 1, 0);

    // 2x2 meshes of [0,2]^2, the second with a displaced interior vertex and
    // edge midpoints (non-parallelogram cells): the parts add up to the disk.
    for (const bool skewed : {false, true})
      {
        Point<2> grid[3][3];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            grid[i][j] = Point<2>(i, j);
        if (skewed)
          {
            grid[1][1] = Point<2>(1.1, 0.93);
            grid[1][0] = Point<2>(0.85, 0);
            grid[0][1] = Point<2>(0, 1.2);
            grid[2][1] = Point<2>(2, 0.9);
            grid[1][2] = Point<2>(1.05, 2);
          }
        const std::string mesh = skewed ? "skewed 2x2 mesh" : "2x2 mesh";
        for (const auto &disk : {std::make_pair(Point<2>(0.83, 1.1), 0.6),
                                 std::make_pair(grid[1][1], 0.7)})
          {
            double area = 0, moment = 0;
            for (unsigned int i = 0; i < 2; ++i)
              for (unsigned int j = 0; j < 2; ++j)
                {
                  const BilinearQuadrilateral cell(
                    std::array<Point<2>, 4>{{grid[i][j],
                                             grid[i + 1][j],
                                             grid[i][j + 1],
                                             grid[i + 1][j + 1]}});
                  const auto q =
                    quadrature_on_disk_part(cell, disk.first, disk.second, n);
                  check_rule(mesh + " cell " + std::to_string(2 * j + i), q);
                  area += integrate(cell, q, one);
                  moment += integrate(cell, q, x);
                }
            const double       R = disk.second;
            std::ostringstream name;
            name << mesh << ", disk at (" << disk.first << ") R=" << R;
            check_absolute(name.str() + ", sum of areas",
                           area,
                           pi * R * R,
                           1e-12);
            check_absolute(name.str() + ", sum of int x",
                           moment,
                           pi * R * R * disk.first[0],
                           1e-12);
          }
      }
  }

  return 0;
}
