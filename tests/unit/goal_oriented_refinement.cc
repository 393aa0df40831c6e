// Goal-oriented refinement on the exact case of doc/verification.md ("Goal
// error estimates"): a 6 x 3 plate far more flexible than the soil under a
// uniform pressure on the Galerkin half-space. The pressure is the load,
// so the corner settlement is the closed form
//   w = q (1 - nu0^2) / (pi E0) (a ln((b + d)/a) + b ln((a + d)/b)),
// d = sqrt(a^2 + b^2) (doc/formulation.md, "Half-space"). Checked:
//  - the estimate of the corner settlement's error against the true error
//    on every cycle (effectivity within 10 %), and the signed
//    dual-weighted residual against the signed error;
//  - Refinement = goal stops at Target error = 2e-3 with the true error
//    below the target, and says so in summary.json;
//  - it needs fewer DOFs than global refinement for a smaller error.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  const double a = 6, b = 3, pressure = 100, E0 = 5e4, nu0 = 0.3;

  double
  exact_corner_settlement()
  {
    const double d = std::hypot(a, b);
    return pressure * (1 - nu0 * nu0) / (M_PI * E0) *
           (a * std::log((b + d) / a) + b * std::log((a + d) / b));
  }

  std::vector<ResultRecord>
  run(const std::string &refinement,
      const unsigned int cycles,
      const double       target)
  {
    std::ostringstream prm;
    prm << "include " << SOURCE_DIR << "/../../parameters/flexible-square.prm\n"
        << "set Output directory = results-" << refinement << "\n"
        << "subsection Plate\n set Length x = 6\n set Length y = 3\nend\n"
        << "subsection Discretization\n set Flexibility = galerkin\n"
        << " set Subdivisions x = 6\n set Subdivisions y = 3\n"
        << " set Initial refinements = 1\nend\n"
        << "subsection Contact\n set Solver = direct\nend\n"
        << "subsection Adaptivity\n set Refinement = " << refinement
        << "\n set Goal = w at 3,1.5\n set Cycles = " << cycles
        << "\n set Target error = " << target << "\nend\n"
        << "subsection Output\n set Probe points = 0,0\n set Verbosity = 0\n"
        << "end\nsubsection Verification\n set Checks =\nend\n";
    return TestTools::run_scene_text(prm.str())->summaries();
  }
} // namespace

int
main()
{
  initlog();
  const double exact  = exact_corner_settlement();
  const double target = 2e-3;

  const std::vector<ResultRecord> goal      = run("goal", 10, target);
  bool                            effective = true;
  for (const ResultRecord &c : goal)
    {
      const double true_error = exact - c.object("goal").number("value");
      const double effectivity =
        c.object("goal").number("estimated_error") / std::abs(true_error);
      const double signed_effectivity =
        c.object("goal").number("dwr") / true_error;
      effective = effective && c.object("goal").is_number("dwr") &&
                  std::abs(effectivity - 1) < 0.1 &&
                  std::abs(signed_effectivity - 1) < 0.1;
      deallog << "goal cycle " << c.count("cycle") << ": dofs "
              << c.count("n_dofs") << ", relative error "
              << std::setprecision(2) << std::abs(true_error / exact)
              << ", effectivity " << std::fixed << effectivity << ", signed "
              << signed_effectivity << std::defaultfloat << std::setprecision(6)
              << std::endl;
    }
  deallog << "effectivity and signed effectivity within 10 % on every "
             "cycle: "
          << (effective ? "OK" : "FAILED") << std::endl;

  const ResultRecord &last = goal.back();
  const double        reached =
    std::abs(exact - last.object("goal").number("value")) / exact;
  const bool stopped  = goal.size() < 10;
  const bool below    = reached <= target;
  const bool reported = last.object("goal").number("relative_error") <= target;
  std::ifstream     file("results-goal/summary.json");
  const std::string text((std::istreambuf_iterator<char>(file)),
                         std::istreambuf_iterator<char>());
  const bool        said_met = text.find("\"met\": true") != std::string::npos;
  deallog << "Target error " << target << " stops the loop after "
          << goal.size()
          << " of 10 cycles: " << (stopped && reported ? "OK" : "FAILED")
          << std::endl;
  deallog << "true error at the stop below the target: "
          << (below ? "OK" : "FAILED") << std::endl;
  deallog << "summary.json says the target was met: "
          << (said_met ? "OK" : "FAILED") << std::endl;

  const std::vector<ResultRecord> global = run("global", 2, 0);
  const ResultRecord             &g      = global.back();
  const double                    global_error =
    std::abs(exact - g.object("goal").number("value")) / exact;
  deallog << "global refinement: dofs " << g.count("n_dofs")
          << ", relative error " << std::setprecision(2) << global_error
          << std::setprecision(6) << std::endl;
  deallog << "goal refinement smaller error with fewer dofs: "
          << (reached < global_error &&
                  last.count("n_dofs") < g.count("n_dofs") ?
                "OK" :
                "FAILED")
          << std::endl;
}
