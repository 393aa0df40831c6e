/**
 * The Boussinesq point-load kernel of the elastic half-space and its exact
 * integral over an axis-aligned rectangle (doc/formulation.md, "Half-space";
 * the paper's equations (P2)-(P5)).
 */
#ifndef plate_on_halfspace_soil_boussinesq_kernel_h
#define plate_on_halfspace_soil_boussinesq_kernel_h

#include <deal.II/base/point.h>

#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * Flexibility constant alpha = (1 - nu0^2) / (pi E0) of the half-space
   * (P2): a downward point load P causes the surface settlement alpha P / r
   * at distance r.
   */
  double
  boussinesq_flexibility_constant(const double youngs_modulus,
                                  const double poissons_ratio);

  /**
   * Exact integral of 1/|x - y| over the rectangle [x1,x2] x [y1,y2] (y the
   * integration variable) seen from the point @p x, which may lie inside, on
   * the boundary or outside the rectangle:
   *   F(X,Y) = X ln(Y + r) + Y ln(X + r),  X = x' - x_j, Y = y' - y_j,
   *   I = F(X2,Y2) - F(X1,Y2) - F(X2,Y1) + F(X1,Y1),
   * where a term is zero when its leading factor is zero (doc/formulation.md;
   * the paper's (P5) without its typesetting errors). Units: length.
   */
  double
  integral_of_inverse_distance_over_rectangle(const Point<2> &x,
                                              const double    x1,
                                              const double    x2,
                                              const double    y1,
                                              const double    y2);

  /**
   * Exact integral of 1/|x - y| over the straight-sided polygon with the
   * given vertices (either orientation, convex or not, x anywhere in the
   * plane). In polar coordinates about x the integral is the integral of
   * the polygon's radial extent over the angle, which for the edge from a to
   * b at signed distance h from x (positive when x is on the inner side) is
   * h (asinh(t_b/h) - asinh(t_a/h)), t the tangential coordinates of a and b
   * from the foot of the perpendicular through x. The rectangle formula
   * above is the special case of an axis-aligned rectangle.
   */
  double
  integral_of_inverse_distance_over_polygon(
    const Point<2>              &x,
    const std::vector<Point<2>> &vertices);
} // namespace PlateOnHalfspace

#endif
