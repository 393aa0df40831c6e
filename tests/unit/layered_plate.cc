// Plates on a layered soil (doc/soil-models.md), through the whole program:
//  - a flexible disk under a uniform pressure p on a clay layer over
//    bedrock settles like the soil under p on the disk's circle alone,
//    the kernel's Hankel integral (settlement_under_uniform_circle,
//    layered_profile.h), in its middle: the plate (radius of relative
//    stiffness l about a/60) resists only the settlement profile's
//    curvature (measured 5.5e-6 relative at the centre; tolerance 1e-4);
//  - a tensionless weightless slab on a base layer over the subgrade,
//    loaded at its middle so that part of it lifts, ends with exact
//    complementarity (no tensile pressure, no penetration, the contact
//    force equal to the load) on the dense storage, and to the iterative
//    solver's tolerance on the hierarchical one, whose answers agree.
//  - goal refinement for the corner settlement of a 6 x 3 plate far more
//    flexible than the soil (tests/unit/goal_oriented_refinement on two
//    layers over bedrock): the estimate against the true error on every
//    cycle, the exact settlement being the top layer's closed form for the
//    rectangle plus the tabulated remainder (checked in
//    tests/unit/layered_soil) integrated in polar coordinates about the
//    corner by adaptive Gauss-Kronrod.
// A near-rigid disk on such a layer is compared with an axisymmetric finite
// element model in tests/unit/layered_kernel_fem.cc.

#include <deal.II/base/numbers.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <plate_on_halfspace/soil/layered_profile.h>
#include <plate_on_halfspace/soil/layered_soil.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "../tests.h"

#include "../test_tools.h"

namespace
{
  using namespace PlateOnHalfspace;

  std::string
  flexible_disk_scene(const unsigned int cycles)
  {
    std::ostringstream prm;
    prm << "set Output directory = results\n"
        << "subsection Plate\n set Shape = disk\n set Radius = 2\n"
        << " set Thickness = 0.02\n set Young's modulus = 3e5\n"
        << " set Poisson's ratio = 0.3\nend\n"
        << "subsection Foundation\n set Model = layered\n"
        << " set Layers = 2, 1e4, 0.3\n set Base = rigid\n"
        << " set Contact = bonded\nend\n"
        << "subsection Loads\n set Uniform pressure = 100\nend\n"
        << "subsection Discretization\n set Initial refinements = 2\n"
        << " set Symmetry = xy\nend\n"
        << "subsection Adaptivity\n set Cycles = " << cycles
        << "\n set Refinement = adaptive\n set Refine fraction = 0.3\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n";
    return prm.str();
  }

  std::string
  lifting_slab_scene(const std::string &storage)
  {
    std::ostringstream prm;
    prm << "set Output directory = results\n"
        << "subsection Plate\n set Length x = 4\n set Length y = 3\n"
        << " set Thickness = 0.25\n set Young's modulus = 3e7\n"
        << " set Poisson's ratio = 0.15\nend\n"
        << "subsection Foundation\n set Model = layered\n"
        << " set Layers = 0.3, 4e5, 0.3\n set Young's modulus = 5e4\n"
        << " set Poisson's ratio = 0.4\n set Contact = tensionless\nend\n"
        << "subsection Loads\n set Circular patches = 0,0,0.15,700\nend\n"
        << "subsection Discretization\n set Subdivisions x = 8\n"
        << " set Subdivisions y = 6\n set Initial refinements = 2\n"
        << " set Symmetry = none\nend\n"
        << "subsection Foundation operator\n set Storage = " << storage
        << "\n set Tolerance = 1e-8\nend\n"
        << "subsection Contact\n set Method = active set\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n";
    return prm.str();
  }

  /** Two layers over bedrock under the goal test's plate. */
  LayeredProfile
  goal_soil()
  {
    LayeredProfile soil;
    soil.layers = {{1., 2e5, 0.3}, {3., 5e4, 0.35}};
    soil.base   = LayeredProfile::Base::rigid;
    return soil;
  }

  /** The settlement at the corner of the a x b rectangle under p. */
  double
  corner_settlement(const LayeredProfile &soil,
                    const double          a,
                    const double          b,
                    const double          p)
  {
    const SoilLayer &top   = soil.layers.front();
    const double     alpha = (1. - top.poissons_ratio * top.poissons_ratio) /
                         (numbers::PI * top.youngs_modulus);
    const double d = std::hypot(a, b);
    const double singular =
      alpha * (a * std::log((b + d) / a) + b * std::log((a + d) / b));
    const TabulatedLayeredRemainder remainder(soil, 1.1 * d, 1e-10);
    using Rule = boost::math::quadrature::gauss_kronrod<double, 31>;
    // Over the angle, the ray from the corner to the far edge x = a
    // (theta < atan(b/a)) or y = b.
    const auto ray = [&](const double theta) {
      const double length = std::min(a / std::cos(theta), b / std::sin(theta));
      return Rule::integrate(
        [&](const double rho) { return remainder.value(rho) * rho; },
        0.,
        length,
        10,
        1e-13);
    };
    const double corner_angle = std::atan2(b, a);
    const double smooth =
      Rule::integrate(ray, 0., corner_angle, 10, 1e-12) +
      Rule::integrate(ray, corner_angle, 0.5 * numbers::PI, 10, 1e-12);
    return p * (singular + smooth);
  }

  std::vector<ResultRecord>
  goal_run()
  {
    std::ostringstream prm;
    prm << "include " << SOURCE_DIR << "/../../parameters/flexible-square.prm\n"
        << "set Output directory = results-goal\n"
        << "subsection Plate\n set Length x = 6\n set Length y = 3\nend\n"
        << "subsection Foundation\n set Model = layered\n"
        << " set Layers = 1, 2e5, 0.3 ; 3, 5e4, 0.35\n set Base = rigid\n"
        << "end\n"
        << "subsection Discretization\n set Flexibility = galerkin\n"
        << " set Subdivisions x = 6\n set Subdivisions y = 3\n"
        << " set Initial refinements = 1\nend\n"
        << "subsection Contact\n set Solver = direct\nend\n"
        << "subsection Adaptivity\n set Refinement = goal\n"
        << " set Goal = w at 3,1.5\n set Cycles = 4\nend\n"
        << "subsection Output\n set Probe points = 0,0\n set Verbosity = 0\n"
        << "end\nsubsection Verification\n set Checks =\nend\n";
    return TestTools::run_scene_text(prm.str())->summaries();
  }
} // namespace

int
main()
{
  initlog();

  {
    LayeredProfile clay;
    clay.layers    = {{2., 1e4, 0.3}};
    clay.base      = LayeredProfile::Base::rigid;
    const double a = 2., p = 100.;
    const auto   run = TestTools::run_scene_text(flexible_disk_scene(3));
    for (const double r : {0., 0.5 * a})
      {
        std::ostringstream name;
        name << "flexible disk on clay over bedrock: w(" << r / a
             << " a) against the soil under p on the circle";
        check(name.str(),
              run->values_at(Point<2>(r, 0)).w,
              settlement_under_uniform_circle(clay, a, p, r),
              1e-4);
      }
  }

  {
    const auto dense = TestTools::run_scene_text(lifting_slab_scene("dense"));
    const auto hierarchical =
      TestTools::run_scene_text(lifting_slab_scene("hierarchical"));
    for (const auto *run : {dense.get(), hierarchical.get()})
      {
        const ResultRecord &s = run->summaries().back();
        // The hierarchical storage's iterative solver meets the contact
        // conditions to its own tolerance
        // (tests/unit/iterative_contact_solver).
        const double      conditions = run == dense.get() ? 1e-10 : 1e-8;
        const std::string name =
          std::string("lifting slab, ") +
          (run == dense.get() ? "dense" : "hierarchical");
        check_below(name + ": complementarity violation (relative)",
                    s.number("complementarity_violation"),
                    conditions);
        check_below(name + ": tensile nodes", s.count("tensile_nodes"), 0.5);
        check_below(name + ": penetration (relative)",
                    s.number("max_penetration"),
                    conditions);
        check(name + ": contact force",
              s.number("contact_force"),
              s.number("applied_load"),
              1e-9);
        check_below(name + ": contact area fraction below 1 (it lifts)",
                    s.number("contact_area_fraction"),
                    0.99);
      }
    const Point<2> middle(0, 0), corner(2, 1.5);
    check("lifting slab: hierarchical against dense, w(0)",
          hierarchical->values_at(middle).w,
          dense->values_at(middle).w,
          1e-6);
    check("lifting slab: hierarchical against dense, w(corner)",
          hierarchical->values_at(corner).w,
          dense->values_at(corner).w,
          1e-5);
  }

  {
    // The plate is [-3, 3] x [-1.5, 1.5]; its corner settles like the
    // corner of a 6 x 3 rectangle.
    const double exact = corner_settlement(goal_soil(), 6., 3., 100.);
    for (const ResultRecord &c : goal_run())
      {
        const double       error = exact - c.object("goal").number("value");
        std::ostringstream name;
        name << "goal w at the corner on layers, cycle " << c.count("cycle");
        check(name.str() + ": estimate / |true error|",
              c.object("goal").number("estimated_error") / std::abs(error),
              1.,
              0.1);
        check(name.str() + ": signed residual / true error",
              c.object("goal").number("dwr") / error,
              1.,
              0.1);
      }
  }
}
