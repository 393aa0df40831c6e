// A near-rigid disk (parameters/rigid-disk.prm, relative stiffness
// K = 3.8e3) on a tensionless half-space under an eccentric point load.
// A rigid circular punch stays in full contact iff the eccentricity is at
// most a/3 (doc/verification.md, exact): at e = 0.30 a every node stays in
// contact and the tensionless answer equals the bonded one (to 1e-10); at
// e = 0.40 a part of the plate lifts off, the far side first. Both answers
// satisfy the discrete contact conditions to 1e-8 and equilibrium to 1e-8.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;


/** parameters/rigid-disk.prm on one mesh, load at (e, 0). */
std::unique_ptr<PlateOnHalfspaceProblem>
solve(const double eccentricity, const std::string &contact)
{
  std::ostringstream extra;
  extra << "subsection Foundation\n set Contact = " << contact << "\nend\n"
        << "subsection Loads\n set Point loads = " << eccentricity
        << ",0,1000\nend\n"
        << "subsection Adaptivity\n set Cycles = 1\nend\n";
  return solve_scene("rigid-disk.prm", extra.str());
}

int
main()
{
  initlog();
  for (const double e : {0.30, 0.40})
    {
      const auto          tensionless = solve(e, "tensionless");
      const auto         &s           = tensionless->summaries().back();
      const ContactState &c           = tensionless->contact_state();
      unsigned int        lifted_near = 0, lifted_far = 0;
      const auto         &nodes = tensionless->plate().get_foundation_space();
      for (unsigned int i = 0; i < c.in_contact.size(); ++i)
        if (!c.in_contact[i])
          (nodes.node_locations[i][0] > 0 ? lifted_near : lifted_far) += 1;
      deallog << "e = " << std::setprecision(2) << e << std::setprecision(10)
              << " a: nodes in contact " << s.count("contact_nodes") << " of "
              << s.count("n_foundation_dofs") << " (lifted on the load side "
              << lifted_near << ", on the far side " << lifted_far
              << "), iterations " << s.count("contact_iterations") << std::endl;
      const double equilibrium =
        std::abs(s.number("contact_force") - s.number("applied_load")) /
        s.number("applied_load");
      deallog << "  equilibrium " << (equilibrium < 1e-8 ? "ok" : "FAILED")
              << ", complementarity violation <= 1e-8 "
              << (s.number("complementarity_violation") <= 1e-8 ? "ok" :
                                                                  "FAILED")
              << std::endl;
      AssertThrow(equilibrium < 1e-8 &&
                    s.number("complementarity_violation") <= 1e-8,
                  ExcMessage("contact conditions"));
      if (e < 1. / 3.)
        {
          AssertThrow(s.count("contact_nodes") == s.count("n_foundation_dofs"),
                      ExcMessage("lift-off below a/3"));
          const auto     bonded     = solve(e, "bonded");
          Vector<double> difference = bonded->solution();
          difference -= tensionless->solution();
          const double relative =
            difference.linfty_norm() / bonded->solution().linfty_norm();
          deallog << "  full contact: ok; tensionless = bonded to 1e-10: "
                  << (relative < 1e-10 ? "ok" : "FAILED") << std::endl;
          AssertThrow(relative < 1e-10, ExcMessage("bonded differs"));
        }
      else
        {
          AssertThrow(lifted_far > 0 && lifted_near == 0,
                      ExcMessage("no lift-off above a/3"));
          deallog << "  lift-off on the far side only: ok" << std::endl;
        }
    }
}
