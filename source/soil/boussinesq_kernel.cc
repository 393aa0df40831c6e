#include <plate_on_halfspace/soil/boussinesq_kernel.h>

#include <cmath>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * One corner term of the rectangle integral,
     *   f(X,Y) = X asinh(Y/|X|) + Y asinh(X/|Y|).
     *
     * This is the antiderivative X ln(Y + r) + Y ln(X + r) of the formula in
     * the header minus X ln|X| + Y ln|Y|. Those two pieces depend on one
     * coordinate only and therefore cancel in the signed sum over the four
     * corners, but dropping them avoids the catastrophic cancellation of
     * Y + r for Y < 0 (r ~ |Y|) that the naive form suffers from when the
     * point lies outside the rectangle. A term is zero when its leading
     * factor is zero (its limit), which also avoids 0/0 at a corner that
     * coincides with the point.
     */
    double
    corner_term(const double X, const double Y)
    {
      double value = 0.;
      if (X != 0.)
        value += X * std::asinh(Y / std::abs(X));
      if (Y != 0.)
        value += Y * std::asinh(X / std::abs(Y));
      return value;
    }
  } // namespace



  double
  boussinesq_flexibility_constant(const double youngs_modulus,
                                  const double poissons_ratio)
  {
    return (1. - poissons_ratio * poissons_ratio) /
           (numbers::PI * youngs_modulus);
  }



  double
  integral_of_inverse_distance_over_rectangle(const Point<2> &x,
                                              const double    x1,
                                              const double    x2,
                                              const double    y1,
                                              const double    y2)
  {
    const double X1 = x1 - x[0];
    const double X2 = x2 - x[0];
    const double Y1 = y1 - x[1];
    const double Y2 = y2 - x[1];

    return corner_term(X2, Y2) - corner_term(X1, Y2) - corner_term(X2, Y1) +
           corner_term(X1, Y1);
  }

  double
  integral_of_inverse_distance_over_polygon(
    const Point<2>              &x,
    const std::vector<Point<2>> &vertices)
  {
    const unsigned int n           = vertices.size();
    double             signed_area = 0, size = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        const Point<2> &a = vertices[i], &b = vertices[(i + 1) % n];
        signed_area += a[0] * b[1] - b[0] * a[1];
        size = std::max(size, a.distance(b));
      }
    const double orientation = (signed_area >= 0 ? 1. : -1.);
    double       integral    = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        const Point<2> &a = vertices[i], &b = vertices[(i + 1) % n];
        const double    length = a.distance(b);
        if (length == 0.)
          continue;
        const Tensor<1, 2> t = (b - a) / length;
        // outward normal of a counter-clockwise polygon
        const Tensor<1, 2> normal({t[1], -t[0]});
        const double       h = orientation * ((a - x) * normal);
        if (std::abs(h) <= 1e-14 * size)
          continue; // x on the edge's line: no contribution
        const double ta = (a - x) * t, tb = (b - x) * t;
        integral +=
          h * (std::asinh(tb / std::abs(h)) - std::asinh(ta / std::abs(h)));
      }
    return integral;
  }
} // namespace PlateOnHalfspace
