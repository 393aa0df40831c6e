// The flexible square of parameters/flexible-square.prm on a Gmsh mesh whose
// cells are general quadrilaterals (tests/data/distorted-square.msh, no cell
// a rectangle), with the Galerkin operator: its singular quadrature must
// work on any straight-sided cell. The mean settlement is exact up to the
// quadrature of A whatever the mesh (1^T M w = 1^T A 1, see
// flexible_square_galerkin.cc): 0.946402 q B (1-nu0^2)/E0. Equilibrium to
// 1e-10. The paper's collocation operator must refuse this mesh with a
// message naming the entry.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

std::string
scene(const std::string &flexibility)
{
  std::ostringstream prm;
  prm << "include " << SOURCE_DIR << "/../../parameters/flexible-square.prm\n"
      << "set Output directory = results\n"
      << "subsection Plate\n set Shape = mesh file\n set Mesh file = "
      << SOURCE_DIR << "/../data/distorted-square.msh\nend\n"
      << "subsection Discretization\n set Flexibility = " << flexibility
      << "\n set Initial refinements = 1\nend\n"
      << "subsection Verification\n set Checks =\nend\n"
      << "subsection Output\n set Verbosity = 0\nend\n";
  return prm.str();
}

int
main()
{
  initlog();
  const double scale = 100. * 4. * (1. - 0.09) / 5e4; // q B (1-nu0^2)/E0
  const double mean_exact =
    (4. * std::log(1. + std::sqrt(2.)) - 4. * (std::sqrt(2.) - 1.) / 3.) / M_PI;
  {
    SceneParameters parameters;
    parameters.read_from_string(scene("galerkin"));
    std::ostringstream      log;
    PlateOnHalfspaceProblem problem(parameters, log);
    problem.run();
    const double mean  = integral_of_deflection(problem) / (16. * scale);
    const double error = std::abs(mean - mean_exact) / mean_exact;
    const auto  &s     = problem.summaries().back();
    // the values to the digits the tolerances resolve (rounded())
    deallog << "cells " << s.count("n_cells") << ", mean settlement "
            << rounded(mean, 1e-5) << " reference " << rounded(mean_exact, 1e-5)
            << " relative error " << std::setprecision(2) << error
            << std::setprecision(10) << " (tol. 1e-5) "
            << (error < 1e-5 ? "ok" : "FAILED") << std::endl;
    const double equilibrium =
      std::abs(s.number("contact_force") - s.number("applied_load")) /
      s.number("applied_load");
    deallog << "contact force " << rounded(s.number("contact_force"), 1e-10)
            << " applied load " << rounded(s.number("applied_load"), 1e-10)
            << " (rel. tol. 1e-10) " << (equilibrium < 1e-10 ? "ok" : "FAILED")
            << std::endl;
    AssertThrow(error < 1e-5 && equilibrium < 1e-10, ExcMessage("failed"));
  }
  {
    SceneParameters parameters;
    parameters.read_from_string(scene("collocation"));
    std::ostringstream      log;
    PlateOnHalfspaceProblem problem(parameters, log);
    bool                    refused = false;
    try
      {
        problem.run();
      }
    catch (const std::exception &e)
      {
        refused = true;
        deallog << "collocation refused: " << short_error_message(e)
                << std::endl;
      }
    AssertThrow(refused, ExcMessage("collocation accepted a distorted mesh"));
  }
}
