// Properties the exact tensionless solution must have, on the paper's
// second example (parameters/example2.prm) with the Galerkin operator and
// the active-set solver:
//  - symmetric scene (mirror planes x = 0 and y = 0), symmetric answer to
//    1e-10 relative (w and q at mirrored nodes, the contact set);
//  - equilibrium, contact_force = applied_load to 1e-8, and the discrete
//    complementarity conditions to 1e-8;
//  - positive homogeneity: every load (pressures, self weight) times 1000
//    scales w, q and M by 1000 (1e-9) and leaves the contact set unchanged;
// and on the paper's first example (uniform load, parameters/example1.prm),
// whose bonded pressure is compressive everywhere: the tensionless answer
// equals the bonded one (1e-12) after one iteration.
// The paper's element exclusion on the same scene with the Galerkin
// operator is reported for comparison (it leaves tensile pressures).

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <map>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;


/** A shipped scene with the Galerkin operator and the active set. */
std::unique_ptr<PlateOnHalfspaceProblem>
solve(const std::string &scene, const std::string &extra)
{
  return solve_scene(scene,
                     "subsection Discretization\n set Flexibility = "
                     "galerkin\nend\nsubsection Contact\n set Method = "
                     "active set\nend\n" +
                       extra);
}

void
report(const std::string &what, const double value, const double tolerance)
{
  deallog << what << ": " << (value <= tolerance ? "ok" : "FAILED")
          << " (tolerance " << tolerance << ")" << std::endl;
  AssertThrow(value <= tolerance, ExcMessage(what));
}

int
main()
{
  initlog();
  deallog << std::setprecision(3);
  const auto  base    = solve("example2.prm", "");
  const auto &summary = base->summaries().back();
  const auto &state   = base->contact_state();
  const auto &space   = base->plate().get_foundation_space();
  deallog << "example2, galerkin + active set: "
          << summary.count("contact_iterations") << " iterations, "
          << summary.count("contact_nodes") << " of "
          << summary.count("n_foundation_dofs") << " nodes in contact"
          << std::endl;

  // symmetry: each node's mirror images
  std::map<std::pair<long, long>, unsigned int> node_at;
  const auto                                    key = [](const Point<2> &x) {
    return std::make_pair(std::lround(x[0] * 1e6), std::lround(x[1] * 1e6));
  };
  for (unsigned int i = 0; i < space.n_nodes(); ++i)
    node_at[key(space.node_locations[i])] = i;
  double       asymmetry          = 0;
  unsigned int mismatched_contact = 0;
  const double w_scale = state.w.linfty_norm(), q_scale = state.q.linfty_norm();
  for (unsigned int i = 0; i < space.n_nodes(); ++i)
    for (const Point<2> &mirror :
         {Point<2>(-space.node_locations[i][0], space.node_locations[i][1]),
          Point<2>(space.node_locations[i][0], -space.node_locations[i][1])})
      {
        const unsigned int j = node_at.at(key(mirror));
        asymmetry            = std::max({asymmetry,
                                         std::abs(state.w[i] - state.w[j]) / w_scale,
                                         std::abs(state.q[i] - state.q[j]) / q_scale});
        mismatched_contact += (state.in_contact[i] != state.in_contact[j]);
      }
  report("symmetric w and q at mirrored nodes", asymmetry, 1e-10);
  report("symmetric contact set", mismatched_contact, 0);
  report("equilibrium |contact_force - applied_load| / applied_load",
         std::abs(summary.number("contact_force") -
                  summary.number("applied_load")) /
           summary.number("applied_load"),
         1e-8);
  report("complementarity violation",
         summary.number("complementarity_violation"),
         1e-8);

  // positive homogeneity
  const auto     scaled         = solve("example2.prm",
                            "subsection Plate\n set Unit weight = 24520\nend\n"
                                        "subsection Loads\n set Rectangular patches = "
                                        "-2,-4,2,4,300000\nend\n");
  const auto    &scaled_state   = scaled->contact_state();
  const auto    &scaled_summary = scaled->summaries().back();
  Vector<double> w_difference = scaled_state.w, q_difference = scaled_state.q;
  w_difference.add(-1000., state.w);
  q_difference.add(-1000., state.q);
  report("loads x 1000: w x 1000",
         w_difference.linfty_norm() / scaled_state.w.linfty_norm(),
         1e-9);
  report("loads x 1000: q x 1000",
         q_difference.linfty_norm() / scaled_state.q.linfty_norm(),
         1e-9);
  report("loads x 1000: max Mx x 1000",
         std::abs(scaled_summary.number("max_Mx") -
                  1000. * summary.number("max_Mx")) /
           std::abs(scaled_summary.number("max_Mx")),
         1e-9);
  report("loads x 1000: same contact set",
         scaled_state.in_contact != state.in_contact,
         0);

  // a scene compressive everywhere when bonded
  const auto bonded      = solve("example1.prm",
                            "subsection Foundation\n set Contact = bonded\n"
                                 "end\n");
  const auto tensionless = solve("example1.prm", "");
  deallog << "example1 bonded: min q "
          << bonded->summaries().back().number("min_q") << " > 0; tensionless: "
          << tensionless->summaries().back().count("contact_iterations")
          << " iteration(s)" << std::endl;
  AssertThrow(bonded->summaries().back().number("min_q") > 0,
              ExcMessage("not compressive"));
  report("one iteration",
         tensionless->summaries().back().count("contact_iterations"),
         1);
  Vector<double> difference = bonded->solution();
  difference -= tensionless->solution();
  report("tensionless = bonded",
         difference.linfty_norm() / bonded->solution().linfty_norm(),
         1e-12);

  // the paper's heuristic on the same example, for comparison
  const auto  paper = solve("example2.prm",
                           "subsection Contact\n set Method = element "
                            "exclusion\nend\n");
  const auto &p     = paper->summaries().back();
  deallog << "example2, galerkin + element exclusion: "
          << p.count("contact_iterations") << " iterations, "
          << p.count("contact_nodes") << " nodes in contact, "
          << p.count("tensile_nodes") << " tensile, complementarity violation "
          << p.number("complementarity_violation") << std::endl;
  report("element exclusion: equilibrium",
         std::abs(p.number("contact_force") - p.number("applied_load")) /
           p.number("applied_load"),
         1e-8);
}
