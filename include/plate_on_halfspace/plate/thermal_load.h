/**
 * The plate's temperature through its thickness and what it does
 * (doc/formulation.md, "Temperature"): a profile T(z) splits into its mean
 * (a free plate expands, no stress), its equivalent linear part (curling:
 * the thermal moment) and a self-equilibrating remainder that stresses the
 * fibres without deforming the plate.
 */
#ifndef plate_on_halfspace_plate_thermal_load_h
#define plate_on_halfspace_plate_thermal_load_h

#include <plate_on_halfspace/scene/parameters.h>

namespace PlateOnHalfspace
{
  /** The temperature's effect on the plate (see the file documentation). */
  struct ThermalLoad
  {
    /** Mean temperature over the thickness [K]. */
    double mean_temperature = 0;
    /**
     * Equivalent linear difference T_top - T_bottom [K]: the linear profile
     * with the same first moment about the mid-surface.
     */
    double equivalent_difference = 0;
    /**
     * Thermal moment M_T = D (1 + nu) alpha dT_eq / t [force length/length],
     * the same in x and y: the moment a fully restrained plate carries
     * (positive: bottom in tension, the moments' sign convention).
     */
    double moment = 0;
    /**
     * Stress of the self-equilibrating remainder T_nl at the top and the
     * bottom fibre, -E alpha T_nl/(1 - nu) [force/length^2], tension
     * positive, the same in x and y; 0 for a linear profile.
     */
    double nonlinear_stress_top = 0, nonlinear_stress_bottom = 0;
  };

  /**
   * The thermal load of @p temperature on @p plate: the profile (or the
   * linear Difference) integrated exactly as the piecewise linear
   * function through its values.
   */
  ThermalLoad
  thermal_load(const Parameters::Plate       &plate,
               const Parameters::Temperature &temperature);
} // namespace PlateOnHalfspace

#endif
