/**
 * The homogeneous elastic half-space (doc/formulation.md, "Half-space";
 * the paper's (P2)): the Boussinesq kernel alpha / r, alpha = (1 - nu0^2) /
 * (pi E0), with no remainder.
 */
#ifndef plate_on_halfspace_soil_half_space_h
#define plate_on_halfspace_soil_half_space_h

#include <plate_on_halfspace/soil/soil_model.h>

namespace PlateOnHalfspace
{
  class HomogeneousHalfSpace : public ElasticSoil
  {
  public:
    /** From the flexibility constant alpha = (1 - nu0^2) / (pi E0). */
    HomogeneousHalfSpace(const double alpha, const unsigned int singular_order);

    std::string
    name() const override;

    SurfaceKernel
    kernel(const double max_distance) const override;

    double
    typical_settlement(const double force, const double area) const override;

    double
    patch_stiffness(const double size) const override;

    double
    radius_of_relative_stiffness(const double flexural_rigidity) const override;

    double
    relative_stiffness(const double flexural_rigidity,
                       const double length) const override;

  private:
    const double alpha;
  };
} // namespace PlateOnHalfspace

#endif
