// Refinement cycles (Adaptivity/Cycles, Refinement = global | adaptive) on
// the flexible uniformly loaded square with the Galerkin operator: both
// converge to the exact centre settlement 1.1221997 q B (1-nu0^2)/E0
// (doc/verification.md, exact). Global refinement: the error falls on every
// cycle, to below 2e-5; adaptive refinement: the error does not grow after
// the first cycles (see below). The result files must hold one row
// (convergence.txt) and one entry (summary.json) per cycle.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

namespace
{
  std::vector<double>
  centre_errors(const std::string &refinement, const unsigned int cycles)
  {
    const double scale = 100. * 4. * (1. - 0.09) / 5e4; // q B (1-nu0^2)/E0
    const double exact = 4. * std::log(1. + std::sqrt(2.)) / M_PI * scale;
    const auto   problem =
      solve_scene("flexible-square.prm",
                  "subsection Discretization\n set Flexibility = galerkin\n"
                  " set Symmetry = auto\n"
                  " set Subdivisions x = 2\n set Subdivisions y = 2\nend\n"
                  "subsection Adaptivity\n set Cycles = " +
                    std::to_string(cycles) + "\n set Refinement = " +
                    refinement + "\n set Refine fraction = 0.3\nend\n");

    std::vector<double> errors;
    deallog << refinement << " refinement (symmetry "
            << problem->plate().get_foundation_space().symmetry.name()
            << "):" << std::endl;
    for (const ResultRecord &s : problem->summaries())
      {
        const double error =
          std::abs(s.items("probes")[0].number("w") - exact) / exact;
        errors.push_back(error);
        deallog << "  cycle " << s.count("cycle") << ": " << s.count("n_cells")
                << " cells, " << s.count("n_foundation_dofs")
                << " foundation dofs, centre error " << std::setprecision(2)
                << error << std::setprecision(10) << std::endl;
      }

    // one row per cycle in convergence.txt (org-mode table: a header row,
    // then one "| ... |" line per cycle) and one entry in summary.json
    std::ifstream table("results/convergence.txt");
    std::string   line;
    unsigned int  rows = 0;
    while (std::getline(table, line))
      rows += (line.size() > 1 && line[0] == '|' && line[1] != '-');
    std::ifstream  summary_file("results/summary.json");
    nlohmann::json summary;
    summary_file >> summary;
    deallog << "  convergence.txt rows (with header): " << rows
            << ", summary.json cycles: " << summary["cycles"].size()
            << std::endl;
    AssertThrow(rows == cycles + 1 && summary["cycles"].size() == cycles,
                ExcMessage("not one row / entry per cycle"));
    AssertThrow(summary["cycles"].back().contains("solve_time_s"),
                ExcMessage("no time split in summary.json"));
    return errors;
  }
} // namespace

int
main()
{
  initlog();
  const std::vector<double> global   = centre_errors("global", 5);
  const std::vector<double> adaptive = centre_errors("adaptive", 6);
  for (unsigned int c = 1; c < global.size(); ++c)
    AssertThrow(global[c] < global[c - 1],
                ExcMessage("global: the error did not fall in cycle " +
                           std::to_string(c)));
  deallog << "global: the error falls on every cycle: ok" << std::endl;
  check_greater("global: error reduction from cycle 1 to the last",
                global[1] / global.back(),
                100);
  AssertThrow(global.back() < 2e-5,
              ExcMessage("global: centre settlement not within 2e-5"));
  deallog << "global: final centre settlement within 2e-5 of the exact "
             "value: ok"
          << std::endl;
  // The adaptive indicator (Kelly + singular places) refines where the
  // gradient of w jumps most, the plate edge of the flexible plate, not the
  // centre (after the sign change of cycle 2): the centre error stalls near
  // 1.1e-3 until the edge is resolved
  // (cycle 8, beyond this test). It must not grow meanwhile.
  for (unsigned int c = 4; c < adaptive.size(); ++c)
    AssertThrow(adaptive[c] <= adaptive[c - 1] * (1 + 1e-3),
                ExcMessage("adaptive: the error grew in cycle " +
                           std::to_string(c)));
  deallog << "adaptive: the error does not grow from cycle 4 on: ok"
          << std::endl;
  check_greater("adaptive: error reduction from cycle 0 to the last",
                adaptive[0] / adaptive.back(),
                25);
}
