#include <deal.II/base/exceptions.h>
#include <deal.II/base/tensor.h>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/bessel.hpp>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>

#include <plate_on_halfspace/soil/layered_profile.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace PlateOnHalfspace
{
  using namespace dealii;

  namespace
  {
    /**
     * The arithmetic of the condensation: x87 extended precision (64-bit
     * significands, 3 digits more than double).
     * Stiffness condensed from a layer onto its top cancels where the layer
     * is thin against the wavelength: a stiff layer over a soft one bends
     * like a plate, whose stiffness is (k h)^4 of the entries it is the
     * difference of; a layer on a frictionless interface keeps a horizontal
     * stiffness of order (k h)^2; a nearly incompressible layer's entries
     * are differences of order 1 - 2 nu (doc/soil-models.md, "The surface
     * compliance").
     */
    using Real    = long double;
    using Matrix2 = Tensor<2, 2, Real>;

    /**
     * The static plane-strain stiffness of a layer (doc/soil-models.md,
     * "Layered soil"): the forces on its faces, [tau top, sigma top, tau
     * bottom, sigma bottom] pushing on the layer, from the displacement
     * amplitudes [u_x top, u_z top, u_x bottom, u_z bottom] of the fields
     * u_x = U sin(k x), u_z = W cos(k x), z downward. Written in E =
     * exp(-k h), so that it stays finite for any k h; the four 2 x 2
     * blocks top-top, top-bottom, bottom-top, bottom-bottom.
     */
    struct LayerStiffness
    {
      Matrix2 tt, tb, bt, bb;
    };

    LayerStiffness
    layer_stiffness(const SoilLayer &layer, const Real k)
    {
      const Real nu = layer.poissons_ratio;
      const Real mu = layer.youngs_modulus / (2. * (1. + nu));
      // c - 1 and m - 1 in the entries below cancel at nu -> 1/2: computed
      // from 1 - 2 nu, which is exact.
      const Real one_minus_2nu = 1. - 2. * nu;
      const Real c             = 1. + 2. * one_minus_2nu;
      const Real m             = one_minus_2nu * c;
      const Real s             = k * layer.thickness;
      const Real E             = std::exp(-s);
      const Real E2            = E * E;
      // 1 - E^2 and 1 - E^4 without cancellation at small k h.
      const Real one_minus_E2 = -std::expm1(-2 * s);
      const Real one_minus_E4 = -std::expm1(-4 * s);
      const Real d = c * c * one_minus_E2 * one_minus_E2 - 4 * E2 * s * s;
      const Real f = mu * k / d;

      const Real xx = 4 * (1 - nu) * (c * one_minus_E4 - 4 * E2 * s);
      const Real zz = 4 * (1 - nu) * (c * one_minus_E4 + 4 * E2 * s);
      const Real xz = 2 * (m * one_minus_E2 * one_minus_E2 - 4 * E2 * s * s);
      const Real far_xx = 8 * E * (1 - nu) * (s * (1 + E2) - c * one_minus_E2);
      const Real far_xz = 8 * E * s * one_minus_E2 * (1 - nu);
      const Real far_zz = -8 * E * (1 - nu) * (c * one_minus_E2 + s * (1 + E2));

      LayerStiffness K;
      K.tt[0][0] = f * xx;
      K.tt[0][1] = K.tt[1][0] = f * xz;
      K.tt[1][1]              = f * zz;
      K.bb[0][0]              = f * xx;
      K.bb[0][1] = K.bb[1][0] = -f * xz;
      K.bb[1][1]              = f * zz;
      K.tb[0][0]              = f * far_xx;
      K.tb[0][1]              = f * far_xz;
      K.tb[1][0]              = -f * far_xz;
      K.tb[1][1]              = f * far_zz;
      K.bt                    = transpose(K.tb);
      return K;
    }

    /** The surface stiffness of a half-space (the layer's top block as
     *  k h -> infinity). */
    Matrix2
    half_space_stiffness(const Real youngs_modulus,
                         const Real poissons_ratio,
                         const Real k)
    {
      const Real nu = poissons_ratio;
      const Real mu = youngs_modulus / (2 * (1 + nu));
      const Real f  = 2 * mu * k / (3 - 4 * nu);
      Matrix2    K;
      K[0][0] = K[1][1] = f * 2 * (1 - nu);
      K[0][1] = K[1][0] = f * (1 - 2 * nu);
      return K;
    }

    /**
     * What a frictionless interface passes up: the vertical stiffness of
     * the structure below with its top free of shear, no shear coupling.
     */
    Matrix2
    vertical_only(const Matrix2 &below)
    {
      Matrix2 seen;
      seen[1][1] = below[1][1] - below[1][0] * below[0][1] / below[0][0];
      return seen;
    }
  } // namespace

  double
  LayeredProfile::surface_compliance(const double k) const
  {
    AssertThrow(k > 0 && std::isfinite(k),
                ExcMessage("LayeredProfile: wave numbers must be > 0."));
    AssertThrow(!layers.empty(), ExcMessage("LayeredProfile: no layers."));
    const bool frictionless = interfaces == Interfaces::frictionless;
    // The stiffness seen at the top of what lies below the current layer,
    // condensed upwards: K_top = K_tt - K_tb (K_bb + S)^-1 K_bt. A rigid
    // base fixes the bottom of the last layer (bonded) or only its u_z
    // (frictionless): an infinite S in those entries.
    Matrix2 below;
    bool    rigid = (base == Base::rigid);
    if (!rigid)
      below = half_space_stiffness(base_youngs_modulus, base_poissons_ratio, k);
    for (auto layer = layers.rbegin(); layer != layers.rend(); ++layer)
      {
        const LayerStiffness K = layer_stiffness(*layer, k);
        Matrix2              top;
        if (rigid && !frictionless)
          top = K.tt;
        else if (rigid)
          {
            // u_z = 0 and no shear at the bottom: condense u_x there.
            top = K.tt;
            for (unsigned int i = 0; i < 2; ++i)
              for (unsigned int j = 0; j < 2; ++j)
                top[i][j] -= K.tb[i][0] * K.bt[0][j] / K.bb[0][0];
          }
        else
          {
            const Matrix2 seen = frictionless ? vertical_only(below) : below;
            top                = K.tt - K.tb * invert(K.bb + seen) * K.bt;
          }
        below = top;
        rigid = false;
      }
    // The surface is free of shear: the vertical compliance.
    return static_cast<double>(below[0][0] / determinant(below));
  }

  double
  LayeredProfile::compliance_remainder(const double k) const
  {
    const SoilLayer &top = layers.front();
    return k * surface_compliance(k) -
           2. * (1. - top.poissons_ratio * top.poissons_ratio) /
             top.youngs_modulus;
  }

  double
  LayeredProfile::far_field_coefficient() const
  {
    return base == Base::rigid ?
             0. :
             2. * (1. - base_poissons_ratio * base_poissons_ratio) /
               base_youngs_modulus;
  }

  double
  LayeredProfile::depth() const
  {
    double sum = 0;
    for (const SoilLayer &layer : layers)
      sum += layer.thickness;
    return sum;
  }

  double
  settlement_under_uniform_circle(const LayeredProfile &profile,
                                  const double          a,
                                  const double          p,
                                  const double          r)
  {
    AssertThrow(a > 0 && r >= 0,
                ExcMessage("settlement_under_uniform_circle: a > 0, r >= 0."));
    const SoilLayer &top = profile.layers.front();
    const double     C =
      2. * (1. - top.poissons_ratio * top.poissons_ratio) / top.youngs_modulus;
    // The top layer's half-space part in closed form: p a C Int J1(k a)
    // J0(k r) / k dk = p a C (2/pi) E(r/a) inside the circle, and
    // p a C (2/pi) (r/a) [E(a/r) - (1 - a^2/r^2) K(a/r)] outside.
    double homogeneous;
    if (r <= a)
      homogeneous = 2. / numbers::PI * boost::math::ellint_2(r / a);
    else
      homogeneous = 2. / numbers::PI * (r / a) *
                    (boost::math::ellint_2(a / r) -
                     (1. - a * a / (r * r)) * boost::math::ellint_1(a / r));
    // The rest, p a Int (k G - C)/k J1(k a) J0(k r) dk, decays like
    // exp(-2 k h1): 30-point Gauss-Legendre on intervals of half the
    // shorter Bessel period and at most 1/D wide (the compliance changes
    // on that scale) up to where the integrand is below rounding.
    const double h1    = top.thickness;
    const double k_end = 40. / std::min(h1, profile.depth());
    const double interval =
      std::min(numbers::PI / std::max({a, r, h1}), 1. / profile.depth());
    const auto integrand = [&](const double k) {
      if (k == 0.)
        return 0.5 * a * profile.far_field_coefficient() - 0.5 * a * C;
      return profile.compliance_remainder(k) / k *
             boost::math::cyl_bessel_j(1, k * a) *
             boost::math::cyl_bessel_j(0, k * r);
    };
    double remainder = 0;
    for (double k0 = 0; k0 < k_end; k0 += interval)
      remainder += boost::math::quadrature::gauss<double, 30>::integrate(
        integrand, k0, std::min(k0 + interval, k_end));
    return p * a * (C * homogeneous + remainder);
  }
} // namespace PlateOnHalfspace
