// Exact integral of 1/|x - y| over an axis-aligned rectangle
// (integral_of_inverse_distance_over_rectangle) against independent
// numerical integration, for points inside, on an edge, at a corner and
// outside (near and far) a non-square rectangle, plus the classical values
// for a square: settlement coefficients 1.1222 (centre) and 0.5611 (corner)
// of a uniformly loaded flexible square, w = coefficient q B (1 - nu^2) / E.

#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/soil/boussinesq_kernel.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  /**
   * Reference value of the integral of 1/|x - y| over the box [lo, hi] by
   * recursive subdivision, independent of the closed form:
   * - a box at least its diameter away from x: 20 x 20 Gauss points (the
   *   integrand is analytic there; error far below 1e-15);
   * - x strictly between the box's limits in a direction: split the box at
   *   x there, so that x ends up at corners;
   * - x at a corner of a box with aspect ratio <= 2: the Duffy rule on the
   *   two triangles with a vertex at x (QSplit), which removes the 1/r
   *   singularity;
   * - otherwise: halve the box along its longer side.
   */
  double
  numerical_integral(const Point<2> &x, const Point<2> &lo, const Point<2> &hi)
  {
    const double size[2]   = {hi[0] - lo[0], hi[1] - lo[1]};
    const double diameter  = lo.distance(hi);
    const auto   integrate = [&](const Quadrature<2> &quadrature) {
      double sum = 0;
      for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const Point<2> &p = quadrature.point(q);
          const Point<2>  y(lo[0] + size[0] * p[0], lo[1] + size[1] * p[1]);
          sum += quadrature.weight(q) * size[0] * size[1] / x.distance(y);
        }
      return sum;
    };

    Point<2> nearest;
    for (unsigned int d = 0; d < 2; ++d)
      nearest[d] = std::min(hi[d], std::max(lo[d], x[d]));
    if (x.distance(nearest) >= diameter)
      return integrate(QGauss<2>(20));

    for (unsigned int d = 0; d < 2; ++d)
      if (lo[d] < x[d] && x[d] < hi[d])
        {
          Point<2> upper = hi, lower = lo;
          upper[d] = x[d];
          lower[d] = x[d];
          return numerical_integral(x, lo, upper) +
                 numerical_integral(x, lower, hi);
        }

    const bool at_corner =
      (x[0] == lo[0] || x[0] == hi[0]) && (x[1] == lo[1] || x[1] == hi[1]);
    const unsigned int longer = (size[0] >= size[1] ? 0 : 1);
    if (at_corner && size[longer] <= 2. * size[1 - longer])
      return integrate(QSplit<2>(QDuffy(40, 1.0),
                                 Point<2>((x[0] - lo[0]) / size[0],
                                          (x[1] - lo[1]) / size[1])));

    Point<2> upper = hi, lower = lo;
    upper[longer] = lower[longer] = 0.5 * (lo[longer] + hi[longer]);
    return numerical_integral(x, lo, upper) + numerical_integral(x, lower, hi);
  }



} // namespace



int
main()
{
  initlog();

  // A non-square rectangle [-1,2] x [0.5,1.3].
  const double x1 = -1., x2 = 2., y1 = 0.5, y2 = 1.3;
  const std::vector<std::pair<std::string, Point<2>>> cases = {
    {"inside", Point<2>(0.3, 0.9)},
    {"inside near corner", Point<2>(1.9, 0.55)},
    {"on bottom edge", Point<2>(0.5, 0.5)},
    {"on left edge", Point<2>(-1., 1.)},
    {"corner (x2,y2)", Point<2>(2., 1.3)},
    {"corner (x1,y1)", Point<2>(-1., 0.5)},
    {"outside near top edge", Point<2>(0.4, 1.35)},
    {"outside near corner", Point<2>(2.1, 1.4)},
    {"outside on extension of edge", Point<2>(3., 0.5)},
    {"outside far", Point<2>(10., -7.)},
    {"outside very far", Point<2>(-30., 40.)}};
  for (const auto &c : cases)
    check("rectangle, " + c.first,
          integral_of_inverse_distance_over_rectangle(c.second, x1, x2, y1, y2),
          numerical_integral(c.second, Point<2>(x1, y1), Point<2>(x2, y2)),
          1e-13);

  // Squares: by symmetry and scaling, the corner of a square of side a gives
  // 2 a ln(1 + sqrt 2) and its centre 4 such quarter squares of side a/2.
  const double ln_1_sqrt2 = std::log(1. + std::sqrt(2.));
  const double side_2_centre =
    integral_of_inverse_distance_over_rectangle(Point<2>(0., 0.), -1, 1, -1, 1);
  const double side_2_corner =
    integral_of_inverse_distance_over_rectangle(Point<2>(1., 1.), -1, 1, -1, 1);
  check("square [-1,1]^2, centre", side_2_centre, 8. * ln_1_sqrt2, 1e-14);
  check("square [-1,1]^2, centre (given value)",
        side_2_centre,
        7.050988696,
        1e-10);
  check("square [-1,1]^2, corner", side_2_corner, 4. * ln_1_sqrt2, 1e-14);
  check("square [-1,1]^2, corner (given value)",
        side_2_corner,
        3.525494348,
        1e-10);

  const double unit_centre =
    integral_of_inverse_distance_over_rectangle(Point<2>(0.5, 0.5), 0, 1, 0, 1);
  const double unit_corner =
    integral_of_inverse_distance_over_rectangle(Point<2>(0., 1.), 0, 1, 0, 1);
  check("unit square, centre", unit_centre, 4. * ln_1_sqrt2, 1e-14);
  check("unit square, corner", unit_corner, 2. * ln_1_sqrt2, 1e-14);
  check("unit square, settlement coefficient centre (I/pi)",
        unit_centre / numbers::PI,
        1.1222,
        5e-5);
  check("unit square, settlement coefficient corner (I/pi)",
        unit_corner / numbers::PI,
        0.5611,
        5e-5);

  // The flexibility constant alpha = (1 - nu^2) / (pi E).
  check("flexibility constant, E = 30e6, nu = 0.25",
        boussinesq_flexibility_constant(30e6, 0.25),
        0.9375 / (numbers::PI * 30e6),
        1e-15);

  return 0;
}
