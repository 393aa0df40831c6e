#include <plate_on_halfspace/soil/half_space.h>

#include <cmath>

namespace PlateOnHalfspace
{
  HomogeneousHalfSpace::HomogeneousHalfSpace(const double       alpha,
                                             const unsigned int singular_order)
    : ElasticSoil(singular_order)
    , alpha(alpha)
  {}

  std::string
  HomogeneousHalfSpace::name() const
  {
    return "half-space";
  }

  SurfaceKernel
  HomogeneousHalfSpace::kernel(const double) const
  {
    return SurfaceKernel(alpha);
  }

  double
  HomogeneousHalfSpace::typical_settlement(const double force,
                                           const double area) const
  {
    // alpha pi = (1 - nu0^2)/E0: the settlement of F over sqrt(A).
    return force / std::sqrt(area) * alpha * M_PI;
  }

  double
  HomogeneousHalfSpace::patch_stiffness(const double size) const
  {
    return 1. / (alpha * mean_inverse_distance_over_square * size);
  }

  double
  HomogeneousHalfSpace::radius_of_relative_stiffness(
    const double flexural_rigidity) const
  {
    // G(k) = 2 pi alpha / k.
    return std::cbrt(2. * M_PI * alpha * flexural_rigidity);
  }

  double
  HomogeneousHalfSpace::relative_stiffness(const double flexural_rigidity,
                                           const double length) const
  {
    return 2. * M_PI * alpha * flexural_rigidity / std::pow(length, 3);
  }
} // namespace PlateOnHalfspace
