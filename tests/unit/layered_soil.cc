// The layered soil (doc/soil-models.md, "Layered soil"), against exact
// values and limits:
//  - the surface compliance G(k) of layers of the half-space's own
//    material over that half-space is Boussinesq's 2 (1 - nu^2)/(E k), and
//    the tabulated remainder of that profile vanishes;
//  - a uniformly loaded circle on such layers settles by the exact
//    2 (1 - nu^2) p a / E at its centre and 4 (1 - nu^2) p a / (pi E) at its
//    edge; on a layer 1e4 times the circle's radius over a stiffer base,
//    by the top material's value (the difference is O(a/h));
//  - a thin layer on a rough rigid base has G -> h / E_oed as k h -> 0;
//  - the tabulated remainder agrees with the same Hankel integral
//    integrated independently (30-point Gauss-Legendre per half period, no
//    far-field subtraction, no spline), also for profiles at the ends of
//    the accepted range: stiffness contrasts of 1e4 and 1e6 either way, a
//    nearly incompressible layer and a buried layer 1e-6 thick (there the
//    reference resolves the compliance's small-k scales, down to the
//    in-plane length E1 h1 / mu of a stiff bonded layer, by Gauss-Legendre
//    on thirds of decades of k);
//  - through the whole program: such layers give the half-space's
//    deflections, pressures and moments to 1e-10; a plate on a two-layer
//    soil matches the infinite plate's Hankel integral
//      w(0) = (P/(pi a)) Int_0^inf J1(k a) (1 + c k^2) /
//             (D k^4 + (1 + c k^2) / G(k)) dk,  c = D/(k_s G_p t),
//    (tests/unit/hankel_reference.cc with the half-space's E* k / 2
//    replaced by the layers' 1/G(k)); and a slab on a thin layer over a
//    rough rigid base approaches the dense liquid of k = E_oed / h as h
//    shrinks.

#include <deal.II/base/numbers.h>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/bessel.hpp>

#include <plate_on_halfspace/soil/dense_liquid.h>
#include <plate_on_halfspace/soil/layered_soil.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

namespace
{
  using namespace PlateOnHalfspace;

  double
  boussinesq_compliance(const double E, const double nu, const double k)
  {
    return 2. * (1. - nu * nu) / (E * k);
  }

  LayeredProfile
  own_material_profile(const double E, const double nu)
  {
    LayeredProfile profile;
    profile.layers              = {{0.3, E, nu}, {2., E, nu}, {40., E, nu}};
    profile.base_youngs_modulus = E;
    profile.base_poissons_ratio = nu;
    return profile;
  }

  /** R(r) = 1/(2 pi) Int (k G - C1) J0(k r) dk, 30-point Gauss-Legendre
   *  per half period of J0 and per 1/D, D the layers' depth. */
  double
  remainder_by_quadrature(const LayeredProfile &profile, const double r)
  {
    const double h1    = profile.layers.front().thickness;
    const double k_end = 40. / h1;
    const double period =
      std::min(numbers::PI / std::max(r, h1), 1. / profile.depth());
    double     sum = 0;
    const auto f   = [&](const double k) {
      return k == 0. ? 0. :
                         profile.compliance_remainder(k) *
                         boost::math::cyl_bessel_j(0, k * r);
    };
    for (double k0 = 0; k0 < k_end; k0 += period)
      sum += boost::math::quadrature::gauss<double, 30>::integrate(
        f, k0, std::min(k0 + period, k_end));
    // The integrand at k = 0 is finite (C_b - C1): the rule never samples
    // the end point.
    return sum / (2. * numbers::PI);
  }

  /**
   * The same R(r), the small wave numbers resolved on their own: 30-point
   * Gauss-Legendre on each third of a decade of k from 1e-16/h1 up to
   * min(1/h1, pi/(2 r)), then remainder_by_quadrature()'s panels. The
   * piece below 1e-16/h1 is below rounding.
   */
  double
  remainder_resolving_small_k(const LayeredProfile &profile, const double r)
  {
    const double h1    = profile.layers.front().thickness;
    const double k_end = 40. / h1;
    const double split =
      std::min(1. / h1, numbers::PI / (2. * std::max(r, h1)));
    const auto f = [&](const double k) {
      return profile.compliance_remainder(k) *
             boost::math::cyl_bessel_j(0, k * r);
    };
    double       sum   = 0;
    const double ratio = std::cbrt(10.);
    for (double k0 = 1e-16 * split; k0 < split; k0 *= ratio)
      sum += boost::math::quadrature::gauss<double, 30>::integrate(
        f, k0, std::min(ratio * k0, split));
    const double period =
      std::min(numbers::PI / std::max(r, h1), 1. / profile.depth());
    for (double k0 = split; k0 < k_end; k0 += period)
      sum += boost::math::quadrature::gauss<double, 30>::integrate(
        f, k0, std::min(k0 + period, k_end));
    return sum / (2. * numbers::PI);
  }

  /** The infinite Mindlin plate's centre deflection on @p profile. */
  double
  infinite_plate_centre_deflection(const LayeredProfile &profile,
                                   const double          D,
                                   const double          c,
                                   const double          P,
                                   const double          a)
  {
    const auto f = [&](const double k) {
      if (k == 0.)
        return 0.;
      return boost::math::cyl_bessel_j(1, k * a) * (1. + c * k * k) /
             (D * k * k * k * k +
              (1. + c * k * k) / profile.surface_compliance(k));
    };
    // Half periods of J1 up to where the k^-5/2 tail is below 1e-8 of the
    // whole; the alternating tail beyond is averaged out by ending
    // between two half periods.
    const double half = numbers::PI / a;
    double       sum = 0, previous = 0;
    for (unsigned int i = 0; i < 20000; ++i)
      {
        previous = sum;
        sum +=
          boost::math::quadrature::gauss<double, 30>::integrate(f,
                                                                i * half,
                                                                (i + 1) * half);
      }
    return P / (numbers::PI * a) * 0.5 * (sum + previous);
  }

  std::string
  disk_scene(const std::string &foundation, const unsigned int cycles)
  {
    std::ostringstream prm;
    prm << "set Output directory = results\n"
        << "subsection Plate\n set Shape = disk\n set Radius = 7.5\n"
        << " set Thickness = 0.25\n set Young's modulus = 3e7\n"
        << " set Poisson's ratio = 0.15\nend\n"
        << "subsection Foundation\n set Contact = bonded\n"
        << foundation << "end\n"
        << "subsection Loads\n set Circular patches = 0,0,0.15,700\nend\n"
        << "subsection Discretization\n set Initial refinements = 1\nend\n"
        << "subsection Adaptivity\n set Cycles = " << cycles
        << "\n set Refinement = adaptive\n set Refine fraction = 0.25\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n";
    return prm.str();
  }

  std::string
  slab_scene(const std::string &foundation)
  {
    std::ostringstream prm;
    prm << "set Output directory = results\n"
        << "subsection Plate\n set Length x = 4\n set Length y = 4\n"
        << " set Thickness = 0.5\n set Young's modulus = 3e7\n"
        << " set Poisson's ratio = 0.15\nend\n"
        << "subsection Foundation\n set Contact = bonded\n"
        << foundation << "end\n"
        << "subsection Loads\n set Rectangular patches = -0.5,-0.5,0.5,0.5,"
           "500\nend\n"
        << "subsection Discretization\n set Subdivisions x = 16\n"
        << " set Subdivisions y = 16\n set Initial refinements = 1\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n";
    return prm.str();
  }
} // namespace

int
main()
{
  initlog();
  const double E = 1e5, nu = 0.35;

  {
    const LayeredProfile profile = own_material_profile(E, nu);
    double               worst   = 0;
    for (double k = 1e-3; k <= 1e3; k *= 1.7)
      worst = std::max(worst,
                       std::abs(profile.surface_compliance(k) /
                                  boussinesq_compliance(E, nu, k) -
                                1.));
    check_below("own material: |G / G_Boussinesq - 1| over k = 1e-3..1e3",
                worst,
                1e-10);
    const TabulatedLayeredRemainder table(profile, 30., 1e-9);
    const double                    alpha = (1. - nu * nu) / (numbers::PI * E);
    double                          largest = 0;
    for (double r = 0; r <= 30.; r += 0.173)
      largest = std::max(largest,
                         std::abs(table.value(r)) / (alpha / std::max(r, 0.3)));
    check_below("own material: |R(r)| / (alpha / r)", largest, 1e-10);

    const double a = 0.2, p = 600.;
    const double D = 2.5e4;
    check("own material: radius of relative stiffness -> the half-space's",
          LayeredSoil(profile, 8).radius_of_relative_stiffness(D),
          std::cbrt(2. * D * (1. - nu * nu) / E),
          1e-9);

    check("own material: circle's centre settlement",
          settlement_under_uniform_circle(profile, a, p, 0.),
          2. * (1. - nu * nu) * p * a / E,
          1e-9);
    check("own material: circle's edge settlement",
          settlement_under_uniform_circle(profile, a, p, a),
          4. * (1. - nu * nu) * p * a / (numbers::PI * E),
          1e-9);
  }

  {
    LayeredProfile thick;
    thick.layers              = {{2000., 5e4, 0.3}};
    thick.base_youngs_modulus = 5e5;
    thick.base_poissons_ratio = 0.2;
    const double a = 0.2, p = 600.;
    check("layer 1e4 a thick: circle's centre settlement -> the layer's "
          "half-space",
          settlement_under_uniform_circle(thick, a, p, 0.),
          2. * (1. - 0.09) * p * a / 5e4,
          2e-4);
  }

  {
    LayeredProfile thin;
    const double   h = 0.05, E1 = 5e4, nu1 = 0.3;
    thin.layers        = {{h, E1, nu1}};
    thin.base          = LayeredProfile::Base::rigid;
    const double E_oed = E1 * (1. - nu1) / ((1. + nu1) * (1. - 2. * nu1));
    check("thin layer on a rough rigid base, k h = 1e-3: G E_oed / h",
          thin.surface_compliance(1e-3 / h) * E_oed / h,
          1.,
          1e-6);

    // The radius of relative stiffness of a plate (l about 1 m, 100 h) on
    // the layer: Westergaard's on the dense liquid k = E_oed / h.
    const double D = 1e4;
    check("thin layer on a rough rigid base: radius of relative stiffness "
          "-> the dense liquid's",
          LayeredSoil(thin, 8).radius_of_relative_stiffness(D),
          DenseLiquidSoil(E_oed / h).radius_of_relative_stiffness(D),
          1e-3);
  }

  {
    LayeredProfile two;
    two.layers              = {{0.3, 4e5, 0.3}, {1.5, 8e4, 0.35}};
    two.base_youngs_modulus = 3e4;
    two.base_poissons_ratio = 0.4;
    const TabulatedLayeredRemainder table(two, 25., 1e-9);
    const double                    alpha = (1. - 0.09) / (numbers::PI * 4e5);
    double                          worst = 0;
    for (const double r : {0., 0.05, 0.3, 1.1, 4.7, 12.5, 25.})
      {
        const double independent = remainder_by_quadrature(two, r);
        worst                    = std::max(worst,
                         std::abs(table.value(r) - independent) /
                           (alpha / std::max(r, 0.3) + std::abs(independent)));
      }
    check_below("two layers over a half-space: tabulated R against "
                "adaptive quadrature, over alpha/r + |R|",
                worst,
                1e-8);
    check_below("two layers over a half-space: the table's own error "
                "estimate",
                table.error(),
                1e-9);
  }

  {
    // Frictionless interfaces: a layer on one keeps a horizontal stiffness
    // of order (k h)^2, lost to rounding at the smallest wave numbers;
    // top layers of 0.2 to 0.5 m put the rule's nodes at different k.
    double worst = 0;
    for (const double h1 : {0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5})
      {
        LayeredProfile frictionless;
        frictionless.layers              = {{h1, 3e5, 0.35}, {4., 4e4, 0.4}};
        frictionless.base_youngs_modulus = 2e5;
        frictionless.base_poissons_ratio = 0.3;
        frictionless.interfaces = LayeredProfile::Interfaces::frictionless;
        const TabulatedLayeredRemainder table(frictionless, 6.3, 1e-9);
        const double alpha = (1. - 0.35 * 0.35) / (numbers::PI * 3e5);
        for (const double r : {0., 0.6, 6.3})
          {
            const double independent = remainder_by_quadrature(frictionless, r);
            worst =
              std::max(worst,
                       std::abs(table.value(r) - independent) /
                         (alpha / std::max(r, h1) + std::abs(independent)));
          }
      }
    check_below("frictionless two layers, top 0.2 to 0.5 m: tabulated R "
                "against adaptive quadrature, over alpha/r + |R|",
                worst,
                1e-8);
  }

  {
    // The ends of the accepted range (doc/soil-models.md, "Limits"), each
    // tabulated for a 6 m plate and checked against the independent
    // quadrature that resolves the small wave numbers.
    struct Case
    {
      std::string    name;
      LayeredProfile profile;
    };
    std::vector<Case> cases(6);
    cases[0].name           = "stiff layer 1e4 times its half-space";
    cases[0].profile.layers = {{1., 1e9, 0.3}};
    cases[1].name           = "stiff layer 1e6 times its half-space";
    cases[1].profile.layers = {{0.3, 1e11, 0.3}};
    cases[2].name           = "soft layer on a half-space 1e6 times stiffer";
    cases[2].profile.layers = {{0.5, 1e5, 0.3}};
    cases[3].name           = "nearly incompressible layer, nu = 0.4999999";
    cases[3].profile.layers = {{1., 1e5, 0.4999999}};
    cases[4].name           = "buried layer 1e-6 thick";
    cases[4].profile.layers = {{1., 1e5, 0.3},
                               {1e-6, 1e4, 0.3},
                               {1., 1e5, 0.3}};
    cases[5].name           = "stiff layer 1e4 times the layer on a rigid base";
    cases[5].profile.layers = {{0.2, 1e9, 0.2}, {2., 1e5, 0.3}};
    cases[5].profile.base   = LayeredProfile::Base::rigid;
    for (Case &c : cases)
      {
        c.profile.base_youngs_modulus = 1e5;
        c.profile.base_poissons_ratio = 0.3;
      }
    cases[2].profile.base_youngs_modulus = 1e11;
    for (const Case &c : cases)
      {
        const SoilLayer &top = c.profile.layers.front();
        const double alpha   = (1. - top.poissons_ratio * top.poissons_ratio) /
                             (numbers::PI * top.youngs_modulus);
        const TabulatedLayeredRemainder table(c.profile, 6.3, 1e-9);
        double                          worst = 0;
        for (const double r : {0., 0.07, 0.6, 2.1, 6.3})
          {
            const double independent =
              remainder_resolving_small_k(c.profile, r);
            worst = std::max(worst,
                             std::abs(table.value(r) - independent) /
                               (alpha / std::max(r, top.thickness) +
                                std::abs(independent)));
          }
        check_below(c.name + ": tabulated R against the small-k resolving "
                             "quadrature, over alpha/r + |R|",
                    worst,
                    1e-8);
      }
  }

  // Through the whole program.
  {
    const auto half = TestTools::run_scene_text(
      disk_scene(" set Young's modulus = 1e5\n set Poisson's ratio = 0.35\n",
                 3));
    const auto same = TestTools::run_scene_text(disk_scene(
      " set Model = layered\n set Young's modulus = 1e5\n"
      " set Poisson's ratio = 0.35\n"
      " set Layers = 0.3, 1e5, 0.35 ; 2, 1e5, 0.35 ; 40, 1e5, 0.35\n",
      3));
    for (const Point<2> &x : {Point<2>(0, 0), Point<2>(0.888, 0)})
      {
        const auto a = half->values_at(x), b = same->values_at(x);
        check("program, own-material layers: w", b.w, a.w, 1e-10);
        check("program, own-material layers: Mx", b.mx, a.mx, 1e-10);
      }
    check("program, own-material layers: largest q",
          same->summaries().back().number("max_q"),
          half->summaries().back().number("max_q"),
          1e-10);
  }

  {
    // Pavement slab on a base over the subgrade (infinite plate).
    LayeredProfile two;
    two.layers              = {{0.3, 4e5, 0.3}};
    two.base_youngs_modulus = 1e5;
    two.base_poissons_ratio = 0.35;
    const double t = 0.25, Ep = 3e7, nup = 0.15;
    const double D  = Ep * t * t * t / (12. * (1. - nup * nup));
    const double Gp = Ep / (2. * (1. + nup));
    const double c  = D / (5. / 6. * Gp * t);
    const double a = 0.15, P = 700. * numbers::PI * a * a;
    const double reference = infinite_plate_centre_deflection(two, D, c, P, a);
    const auto   layered   = TestTools::run_scene_text(
      disk_scene(" set Model = layered\n set Young's modulus = 1e5\n"
                     " set Poisson's ratio = 0.35\n set Layers = 0.3, 4e5, 0.3\n",
                 5));
    check("program, base over subgrade: w(0) against the infinite plate",
          layered->values_at(Point<2>(0, 0)).w,
          reference,
          2e-3);
  }

  {
    // A thin layer on a rough rigid base: the dense liquid k = E_oed / h.
    const double E1 = 5e4, nu1 = 0.3;
    const double E_oed    = E1 * (1. - nu1) / ((1. + nu1) * (1. - 2. * nu1));
    double       previous = 0;
    for (const double h : {0.1, 0.05})
      {
        std::ostringstream layer, liquid;
        layer << " set Model = layered\n set Base = rigid\n set Layers = " << h
              << ", " << E1 << ", " << nu1 << "\n";
        liquid << " set Model = dense liquid\n"
               << " set Modulus of subgrade reaction = " << E_oed / h << "\n";
        const auto thin = TestTools::run_scene_text(slab_scene(layer.str()));
        const auto winkler =
          TestTools::run_scene_text(slab_scene(liquid.str()));
        const double       w_layer    = thin->values_at(Point<2>(0, 0)).w;
        const double       w_liquid   = winkler->values_at(Point<2>(0, 0)).w;
        const double       difference = std::abs(w_layer / w_liquid - 1.);
        std::ostringstream name;
        name << "thin layer h = " << h
             << " on a rough rigid base: |w(0) / w_dense liquid - 1|";
        check_below(name.str(), difference, h == 0.1 ? 1e-3 : 5e-4);
        if (previous > 0)
          check_below("halving h: the difference over the previous one",
                      difference / previous,
                      0.5);
        previous = difference;
      }
  }
}
