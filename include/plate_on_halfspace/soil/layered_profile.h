/**
 * A horizontally layered elastic soil and its surface response per wave
 * number (doc/soil-models.md, "Layered soil"): the layers' static stiffness
 * matrices (Kausel and Roësset's formulation, written with decaying
 * exponentials only, so that thick layers and large wave numbers stay
 * finite) condensed from the base up to the surface.
 */
#ifndef plate_on_halfspace_soil_layered_profile_h
#define plate_on_halfspace_soil_layered_profile_h

#include <vector>

namespace PlateOnHalfspace
{
  /** One layer: thickness, Young's modulus, Poisson's ratio (the scene's
   * units). */
  struct SoilLayer
  {
    double thickness, youngs_modulus, poissons_ratio;
  };

  /** The layers top down over their base (Foundation/Layers, Base). */
  struct LayeredProfile
  {
    enum class Base
    {
      half_space,
      rigid
    };
    enum class Interfaces
    {
      bonded,
      frictionless
    };

    std::vector<SoilLayer> layers;
    Base                   base = Base::half_space;
    /** The half-space under the layers (Base = half-space). */
    double     base_youngs_modulus = 0, base_poissons_ratio = 0;
    Interfaces interfaces = Interfaces::bonded;

    /**
     * The surface compliance G(k) (length^3/force): the settlement amplitude of
     * the surface under a vertical pressure of unit amplitude with wave number
     * @p k > 0 (cos(k x) in plane strain, J0(k r) axisymmetrically: the
     * same function), the surface free of shear. G(k) -> 2 (1 - nu1^2) /
     * (E1 k) as k -> infinity (the top layer's half-space).
     */
    double
    surface_compliance(const double k) const;


    /**
     * k G(k) - 2 (1 - nu1^2) / E1: the compliance less the top layer's
     * half-space, times k. Computed without the cancellation of the
     * difference at large k h1 (it decays like exp(-2 k h1)).
     */
    double
    compliance_remainder(const double k) const;

    /** lim_{k -> 0} k G(k): 2 (1 - nu_b^2) / E_b over a half-space, 0 over
     *  a rigid base. */
    double
    far_field_coefficient() const;

    /** Sum of the thicknesses. */
    double
    depth() const;
  };

  /**
   * The settlement w(r) at distance @p r from the centre of a circle of
   * radius @p a under the uniform pressure @p p on the surface of
   * @p profile: w(r) = p a Int_0^inf G(k) J1(k a) J0(k r) dk, integrated
   * independently of the program's tabulated kernel: the top layer's
   * half-space part in closed form (elliptic integrals), the rest by
   * 30-point Gauss-Legendre on half periods of the Bessel factors.
   */
  double
  settlement_under_uniform_circle(const LayeredProfile &profile,
                                  const double          a,
                                  const double          p,
                                  const double          r);
} // namespace PlateOnHalfspace

#endif
