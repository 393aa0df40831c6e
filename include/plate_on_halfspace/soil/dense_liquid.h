/**
 * The dense liquid (Winkler) soil (doc/formulation.md, "Dense-liquid
 * foundation"): the settlement is the local pressure over the modulus of
 * subgrade reaction k, u = q / k. It has no kernel: its foundation
 * operator is sparse (halfspace/dense_liquid_operator.h).
 */
#ifndef plate_on_halfspace_soil_dense_liquid_h
#define plate_on_halfspace_soil_dense_liquid_h

#include <plate_on_halfspace/soil/soil_model.h>

namespace PlateOnHalfspace
{
  class DenseLiquidSoil : public SoilModel
  {
  public:
    /** @param subgrade_modulus k > 0 [force/length^3]. */
    explicit DenseLiquidSoil(const double subgrade_modulus);

    std::string
    name() const override;

    /** q_h(x) / k at each point (which must lie on the plate). */
    std::vector<double>
    settlement_at_points(const FoundationSpace       &space,
                         const Vector<double>        &nodal_pressure,
                         const std::vector<Point<2>> &points) const override;

    double
    typical_settlement(const double force, const double area) const override;

    double
    patch_stiffness(const double size) const override;

    double
    radius_of_relative_stiffness(const double flexural_rigidity) const override;

    double
    relative_stiffness(const double flexural_rigidity,
                       const double length) const override;

    double
    subgrade_modulus() const
    {
      return modulus;
    }

  private:
    const double modulus;
  };
} // namespace PlateOnHalfspace

#endif
