#include <plate_on_halfspace/plate/thermal_load.h>

namespace PlateOnHalfspace
{
  ThermalLoad
  thermal_load(const Parameters::Plate       &plate,
               const Parameters::Temperature &temperature)
  {
    // The profile's values at s = z/t from -1/2 (top) to 1/2 (bottom), z
    // downward from the mid-surface; a linear Difference is the profile
    // (dT/2, -dT/2).
    std::vector<double> values = temperature.profile;
    if (values.empty())
      values = {0.5 * temperature.difference, -0.5 * temperature.difference};
    const unsigned int segments = values.size() - 1;
    const double       h        = 1. / segments;
    // Mean = int T ds and first moment = int T s ds over [-1/2, 1/2], exact
    // for the piecewise linear T by Simpson's rule on each segment (the
    // integrands are at most quadratic there).
    double mean = 0, first_moment = 0;
    for (unsigned int i = 0; i < segments; ++i)
      {
        const double s0 = -0.5 + i * h, s1 = s0 + h, sm = s0 + 0.5 * h;
        const double t0 = values[i], t1 = values[i + 1], tm = 0.5 * (t0 + t1);
        mean += h / 6. * (t0 + 4. * tm + t1);
        first_moment += h / 6. * (t0 * s0 + 4. * tm * sm + t1 * s1);
      }
    ThermalLoad load;
    load.mean_temperature = mean;
    // The linear part T_lin(s) = -dT_eq s has the same first moment:
    // -dT_eq / 12 = first_moment.
    load.equivalent_difference = -12. * first_moment;
    const double alpha         = temperature.expansion_coefficient;
    const double nu            = plate.poissons_ratio;
    load.moment                = plate.flexural_rigidity() * (1. + nu) * alpha *
                  load.equivalent_difference / plate.thickness;
    // The remainder at the fibres: T - mean - T_lin, T_lin(-1/2) = dT/2.
    const double remainder_top =
      values.front() - mean - 0.5 * load.equivalent_difference;
    const double remainder_bottom =
      values.back() - mean + 0.5 * load.equivalent_difference;
    const double scale           = -plate.youngs_modulus * alpha / (1. - nu);
    load.nonlinear_stress_top    = scale * remainder_top;
    load.nonlinear_stress_bottom = scale * remainder_bottom;
    return load;
  }
} // namespace PlateOnHalfspace
