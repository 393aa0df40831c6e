// Temperature curling against exact values (doc/verification.md,
// "Temperature"). A 0.25 m slab, E = 30 GPa, nu = 0.15, alpha = 1e-5 /K:
// D = 39961.64 kNm, the restrained stress E alpha dT / (2 (1 - nu)) =
// 1764.706 kPa for dT = 10 K.
//  1. The split of a profile: 30, 25, 22, 21 K from top to bottom has the
//     mean 72.5/3 K, the equivalent linear difference 9 K and the
//     remainder 4/3 K at both faces, stress -E alpha (4/3)/(1 - nu) =
//     -470.588 kPa; a linear profile has no remainder.
//  2. Free curl: weightless, on a bonded dense liquid of k -> 0 (1e-3),
//     dT = 10 K: w = alpha dT/(2 t) (x^2 + y^2) + c with mean 0, in the
//     finite element space, so exact at any point; stresses vanish.
//  3. Fully restrained interior: the centre of a 30 m slab (16 l from the
//     edges, l = 0.946 m) bonded to k = 5e4: sigma_bottom = +1764.706 kPa
//     in x and y for a warmer top.
//  4. A long strip: 3.6 m wide, 30 m long, the same soil: the exact
//     Mindlin strip with free edges (the closed form of doc/verification.md)
//     gives sigma_x(0) = 674.043, sigma_y(0) = 1601.106 and sigma_y at the
//     edge E alpha dT / 2 = 1500 kPa. The errors fall like h^2.
//  5. A heavy slab at night, tensionless: 30 m, unit weight 24 kN/m^3,
//     dT = -10 K. The corners lift, the interior lies flat at w = gamma t/k
//     and its top fibre carries the restrained +1764.706 kPa.
//  6. The goal `stress_bottom at 0,0` on the strip (the largest principal
//     stress there is sigma_y(0) = 1601.106 kPa): three goal-oriented
//     cycles converge to it, and the estimate, whose residual carries the
//     thermal moment's work, lies within a factor 3 of the true error.

#include <plate_on_halfspace/plate/thermal_load.h>
#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  const double restrained = 3e7 * 1e-5 * 10. / (2. * (1. - 0.15));

  /** A slab Lx x Ly on a dense liquid with a temperature; @p extra adds. */
  std::unique_ptr<PlateOnHalfspaceProblem>
  slab(const double       length_x,
       const double       length_y,
       const double       k,
       const std::string &contact,
       const double       difference,
       const double       unit_weight,
       const unsigned int subdivisions_x,
       const unsigned int subdivisions_y,
       const unsigned int refinements)
  {
    std::ostringstream extra;
    extra << "subsection Plate\n set Unit weight = " << unit_weight << "\nend\n"
          << "subsection Temperature\n set Difference = " << difference
          << "\nend\n";
    return TestTools::run_scene_text(
      TestTools::slab_on_dense_liquid(length_x,
                                      length_y,
                                      0.25,
                                      k,
                                      contact,
                                      subdivisions_x,
                                      subdivisions_y,
                                      refinements,
                                      extra.str()));
  }
} // namespace

int
main()
{
  initlog();

  // 1. the split of a profile
  {
    Parameters::Plate plate;
    plate.thickness      = 0.25;
    plate.youngs_modulus = 3e7;
    plate.poissons_ratio = 0.15;
    Parameters::Temperature temperature;
    temperature.expansion_coefficient = 1e-5;
    temperature.difference            = 0;
    temperature.profile               = {30, 25, 22, 21};
    const ThermalLoad load            = thermal_load(plate, temperature);
    check("profile 30,25,22,21: mean [K]",
          load.mean_temperature,
          72.5 / 3.,
          1e-14);
    check("profile 30,25,22,21: equivalent difference [K]",
          load.equivalent_difference,
          9.,
          1e-14);
    check("profile 30,25,22,21: remainder's stress at the top [kPa]",
          load.nonlinear_stress_top,
          -3e7 * 1e-5 * (4. / 3.) / 0.85,
          1e-13);
    check("profile 30,25,22,21: remainder's stress at the bottom [kPa]",
          load.nonlinear_stress_bottom,
          -3e7 * 1e-5 * (4. / 3.) / 0.85,
          1e-13);
    check("profile 30,25,22,21: thermal moment [kNm/m]",
          load.moment,
          plate.flexural_rigidity() * 1.15 * 1e-5 * 9. / 0.25,
          1e-14);
    temperature.profile      = {5, 0, -5};
    const ThermalLoad linear = thermal_load(plate, temperature);
    temperature.profile.clear();
    temperature.difference   = 10;
    const ThermalLoad direct = thermal_load(plate, temperature);
    check("profile 5,0,-5 equals Difference = 10: moment",
          linear.moment,
          direct.moment,
          1e-14);
    // the verdict, not the round-off sized values
    deallog << "profile 5,0,-5: remainder's stresses (0 expected) "
            << (std::abs(linear.nonlinear_stress_top) < 1e-12 &&
                    std::abs(linear.nonlinear_stress_bottom) < 1e-12 ?
                  "below 1e-12: ok" :
                  "ABOVE 1e-12: FAILED")
            << std::endl;
    AssertThrow(std::abs(linear.nonlinear_stress_top) < 1e-12 &&
                  std::abs(linear.nonlinear_stress_bottom) < 1e-12,
                ExcMessage("a linear profile has no remainder"));
  }

  // 2. free curl
  {
    const auto   problem   = slab(4, 3, 1e-3, "bonded", 10, 0, 4, 3, 1);
    const double curvature = 1e-5 * 10 / 0.25;
    // mean of x^2 + y^2 over [-2,2] x [-1.5,1.5]: 4/3 + 3/4
    const double centre = -0.5 * curvature * (4. / 3. + 0.75);
    for (const Point<2> &x :
         {Point<2>(0, 0), Point<2>(2, 1.5), Point<2>(-1.3, 0.4)})
      {
        const PointValues  v = problem->values_at(x);
        std::ostringstream name;
        name << "free curl: w(" << x[0] << "," << x[1] << ")";
        check(name.str(),
              v.w,
              0.5 * curvature * x.norm_square() + centre,
              1e-7);
        const FibreStresses &s       = v.stresses;
        double               largest = 0;
        for (unsigned int c = 0; c < 3; ++c)
          largest =
            std::max({largest, std::abs(s.bottom[c]), std::abs(s.top[c])});
        deallog << "free curl: largest |stress| / restrained at ("
                << std::setprecision(3) << x[0] << "," << x[1]
                << std::setprecision(10) << ") "
                << (largest / restrained < 1e-7 ? "< 1e-7" : "TOO LARGE")
                << std::endl;
        AssertThrow(largest < 1e-7 * restrained,
                    ExcMessage("free curl must not stress the slab"));
      }
  }

  // 3. fully restrained interior, bonded
  {
    const auto problem     = slab(30, 30, 5e4, "bonded", 10, 0, 15, 15, 2);
    const FibreStresses &s = problem->values_at(Point<2>(0, 0)).stresses;
    check("restrained interior, bonded: sxx bottom [kPa]",
          s.bottom[0],
          restrained,
          1e-4);
    check("restrained interior, bonded: syy bottom [kPa]",
          s.bottom[1],
          restrained,
          1e-4);
    check("restrained interior, bonded: sxx top [kPa]",
          s.top[0],
          -restrained,
          1e-4);
  }

  // 4. the long strip, two meshes
  {
    std::array<double, 3> previous{};
    for (const unsigned int refinements : {2u, 3u})
      {
        const auto problem =
          slab(3.6, 30, 5e4, "bonded", 10, 0, 4, 30, refinements);
        const FibreStresses centre =
          problem->values_at(Point<2>(0, 0)).stresses;
        const FibreStresses edge =
          problem->values_at(Point<2>(1.8, 0)).stresses;
        const std::array<double, 3> errors = {{centre.bottom[0] / 674.043 - 1.,
                                               centre.bottom[1] / 1601.106 - 1.,
                                               edge.bottom[1] / 1500. - 1.}};
        const std::string           mesh =
          "strip, " + std::to_string(refinements) + " refinements: ";
        check(mesh + "sigma_x(0) bottom [kPa]",
              centre.bottom[0],
              674.043,
              refinements == 2 ? 6e-3 : 1.6e-3);
        check(mesh + "sigma_y(0) bottom [kPa]",
              centre.bottom[1],
              1601.106,
              refinements == 2 ? 4e-4 : 1.2e-4);
        check(mesh + "sigma_y(b/2) bottom [kPa]",
              edge.bottom[1],
              1500.,
              refinements == 2 ? 7e-4 : 2e-4);
        if (refinements == 3)
          for (unsigned int i = 0; i < 3; ++i)
            {
              const double ratio = previous[i] / errors[i];
              deallog << "strip: error ratio of quantity " << i
                      << " between the meshes "
                      << (ratio > 3. && ratio < 5. ? "in (3, 5): h^2" :
                                                     "NOT h^2")
                      << std::endl;
              AssertThrow(ratio > 3. && ratio < 5.,
                          ExcMessage("the strip's errors must fall like h^2"));
            }
        previous = errors;
      }
  }

  // 6. a stress goal on the strip
  {
    const auto problem =
      TestTools::run_scene_text(TestTools::slab_on_dense_liquid(
        3.6,
        30,
        0.25,
        5e4,
        "bonded",
        4,
        30,
        1,
        "subsection Temperature\n set Difference = 10\nend\n"
        "subsection Adaptivity\n set Cycles = 3\n set Refinement = goal\n"
        " set Goal = stress_bottom at 0,0\nend\n"));
    for (const ResultRecord &c : problem->summaries())
      {
        const double error = 1601.106 - c.object("goal").number("value");
        const double effectivity =
          c.object("goal").number("estimated_error") / std::abs(error);
        deallog << "strip, goal stress_bottom at 0,0, cycle "
                << c.count("cycle") << ": relative error "
                << (std::abs(error) / 1601.106 < 1.5e-3 ? "< 1.5e-3" :
                                                          "TOO LARGE")
                << ", effectivity "
                << (effectivity > 1. / 3. && effectivity < 3. ? "in (1/3, 3)" :
                                                                "OUT")
                << std::endl;
        AssertThrow(std::abs(error) / 1601.106 < 1.5e-3 &&
                      effectivity > 1. / 3. && effectivity < 3.,
                    ExcMessage("the stress goal's estimate is off"));
      }
    check("strip, goal stress_bottom at 0,0, last cycle [kPa]",
          problem->summaries().back().object("goal").number("value"),
          1601.106,
          2e-4);
  }

  // 5. a heavy slab at night on a tensionless dense liquid
  {
    const auto problem = slab(30, 30, 5e4, "tensionless", -10, 24, 15, 15, 2);
    const PointValues   centre = problem->values_at(Point<2>(0, 0));
    const PointValues   corner = problem->values_at(Point<2>(15, 15));
    const ResultRecord &c      = problem->summaries().back();
    check("night: centre w = gamma t / k [m]", centre.w, 24 * 0.25 / 5e4, 5e-4);
    check("night: centre sxx top [kPa]",
          centre.stresses.top[0],
          restrained,
          1e-4);
    deallog << "night: corner lifts (w < 0): " << (corner.w < 0 ? "yes" : "NO")
            << "; contact area below 1: "
            << (c.number("contact_area_fraction") < 0.95 ? "yes" : "NO")
            << std::endl;
    AssertThrow(corner.w < 0 && c.number("contact_area_fraction") < 0.95,
                ExcMessage("the corners must lift at night"));
  }
}
