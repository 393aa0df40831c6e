// Goal-oriented refinement for a point moment on a disk, against an exact
// value: parameters/infinite-plate-patch.prm (a slab of radius 7.5 m > 8 l
// bonded to the half-space under a tyre patch of radius a = 0.15 m) with
// Adaptivity/Goal = Mx at 0,0. The infinite Mindlin plate's centre moment
// is the Hankel integral of doc/verification.md ("Infinite plate under a
// patch"),
//   Mx(0) = D (1 + nu) P / (2 pi a) Int_0^inf J1(ka) k^2 /
//           (D k^4 + (1 + c k^2) E* k / 2) dk = 10.803889266 kNm/m
// (tests/unit/hankel_reference). Checked:
//  - goal refinement gets within 1.5 % with fewer DOFs than global
//    refinement has when it is still more than 4 % off;
//  - from the cycle on which the patch spans a few cells, the estimate
//    (sum of the local dual-weighted residuals' magnitudes) lies within a
//    factor 3 of the true error.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  const double exact_moment = 10.803889266;

  std::vector<ResultRecord>
  run(const std::string &refinement, const unsigned int cycles)
  {
    std::ostringstream prm;
    prm << "include " << SOURCE_DIR
        << "/../../parameters/infinite-plate-patch.prm\n"
        << "set Output directory = results-" << refinement << "\n"
        << "subsection Discretization\n set Symmetry = xy\n"
        << " set Initial refinements = 1\nend\n"
        << "subsection Adaptivity\n set Refinement = " << refinement
        << "\n set Goal = Mx at 0,0\n set Cycles = " << cycles << "\nend\n"
        << "subsection Output\n set Verbosity = 0\nend\n"
        << "subsection Verification\n set Checks =\nend\n";
    return TestTools::run_scene_text(prm.str())->summaries();
  }

  double
  relative_error(const ResultRecord &c)
  {
    return std::abs(exact_moment - c.object("goal").number("value")) /
           exact_moment;
  }
} // namespace

int
main()
{
  initlog();
  const std::vector<ResultRecord> goal    = run("goal", 6);
  bool                            bracket = true;
  for (const ResultRecord &c : goal)
    {
      const double effectivity =
        c.object("goal").number("estimated_error") /
        std::abs(exact_moment - c.object("goal").number("value"));
      if (c.count("cycle") >= 2)
        bracket = bracket && effectivity >= 1. / 3 && effectivity <= 3;
      deallog << "goal cycle " << c.count("cycle") << ": dofs "
              << c.count("n_dofs") << ", relative error "
              << std::setprecision(2) << relative_error(c) << ", effectivity "
              << std::fixed << effectivity << std::defaultfloat
              << std::setprecision(6) << std::endl;
    }
  deallog << "estimate within a factor 3 of the error from cycle 2 on: "
          << (bracket ? "OK" : "FAILED") << std::endl;

  const std::vector<ResultRecord> global = run("global", 4);
  const ResultRecord             &g      = global.back();
  const ResultRecord             &last   = goal.back();
  deallog << "global refinement: dofs " << g.count("n_dofs")
          << ", relative error " << std::setprecision(2) << relative_error(g)
          << std::setprecision(6) << std::endl;
  deallog << "goal refinement within 1.5 %: "
          << (relative_error(last) < 0.015 ? "OK" : "FAILED") << std::endl;
  deallog << "global refinement still above 4 % with more dofs: "
          << (relative_error(g) > 0.04 &&
                  g.count("n_dofs") > last.count("n_dofs") ?
                "OK" :
                "FAILED")
          << std::endl;
}
