// A patch thinner than the mirror planes' tolerance (1e-10 of the plate)
// across a plane of a symmetric scene (doc/formulation.md, "Symmetry"):
// the computed part must carry its share of the load, however thin. The
// scenes: a 2 m square plate under 10 kPa with
//  - a strip -1e-10 < x < 1e-10, |y| < 0.5 at 1e10 kPa (2 kN) across x = 0;
//  - a disk of radius 1e-11 centred on y = 0 at 1e22 kPa (pi 1e0 kN).
// Checked: applied_load with Symmetry = auto (which solves a half or a
// quarter) against the exact total (1e-6: the disk's own integration) and
// against Symmetry = none (1e-12). Before, both patches were dropped.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  ResultRecord
  run(const std::string &name,
      const std::string &patch,
      const std::string &symmetry)
  {
    std::ostringstream prm;
    prm << "set Output directory = results-" << name << "-" << symmetry
        << "\nsubsection Plate\n set Length x = 2\n set Length y = 2\n"
        << " set Thickness = 0.2\n set Young's modulus = 1e6\nend\n"
        << "subsection Foundation\n set Young's modulus = 1e4\n"
        << " set Contact = bonded\nend\n"
        << "subsection Loads\n set Uniform pressure = 10\n " << patch
        << "\nend\nsubsection Discretization\n set Subdivisions x = 2\n"
        << " set Subdivisions y = 2\n set Symmetry = " << symmetry
        << "\nend\nsubsection Output\n set VTU = false\n"
        << " set Verbosity = 0\nend\n";
    return TestTools::run_scene_text(prm.str())->summaries().back();
  }

  void
  check(const std::string &name, const std::string &patch, const double exact)
  {
    const double whole = run(name, patch, "none").number("applied_load");
    const double part  = run(name, patch, "auto").number("applied_load");
    deallog << name << ": applied_load with Symmetry = auto "
            << std::setprecision(8) << part << ", exact " << exact
            << ", tolerance 1e-6: "
            << (std::abs(part - exact) <= 1e-6 * exact ? "ok" : "FAILED")
            << "; against Symmetry = none, tolerance 1e-12: "
            << (std::abs(part - whole) <= 1e-12 * whole ? "ok" : "FAILED")
            << std::setprecision(6) << std::endl;
  }
} // namespace

int
main()
{
  initlog();
  check("strip across x = 0",
        "set Rectangular patches = -1e-10,-0.5,1e-10,0.5,1e10",
        42);
  check("disk on y = 0", "set Circular patches = 0.3,0,1e-11,1e22", 40 + M_PI);
}
