// An edge load on a dense liquid (doc/verification.md, "Edge load"): a
// 0.25 m slab (E = 30 GPa, nu = 0.15) on k = 50 MN/m^3, bonded, 700 kPa on
// a 0.3 m x 0.3 m patch touching the free edge, far from corners. The
// reference is the exact Reissner-Mindlin plate on the half-plane with a
// free edge, by a Fourier transform along the edge
// (scripts/edge_load_reference.py): the edge stress sigma_y(0,0) =
// 2273.7394 kPa and w(0,0) = 5.51571072e-4 m. The slab is 8 m x 12 m
// (its other edges 8 and 6 m away, 6 to 8 radii of relative stiffness),
// which shifts w by about 1e-4. The goal-oriented loop on the edge stress
// stops at its target; the stress is within 1e-4 of the exact value and
// the reported error bound covers the true error.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

int
main()
{
  initlog();
  const auto problem =
    TestTools::run_scene_text(TestTools::slab_on_dense_liquid(
      8,
      12,
      0.25,
      5e4,
      "bonded",
      8,
      12,
      1,
      "subsection Loads\n set Rectangular patches = -4, -0.15, -3.7, 0.15, "
      "700\nend\n"
      "subsection Adaptivity\n set Cycles = 9\n set Refinement = goal\n"
      " set Goal = stress_bottom at -4,0\n set Target error = 1e-4\nend\n"
      "subsection Output\n set Probe points = -4,0 ; -3.85,0 ; -4,0.5\nend\n"));
  const auto  &summaries = problem->summaries();
  const auto  &last      = summaries.back();
  const double exact     = 2273.7394;
  deallog << "cycles " << summaries.size() << ", last "
          << (last.object("goal").number("relative_error") <= 1e-4 ?
                "met the target" :
                "did not meet the target")
          << std::endl;
  check("edge stress sigma_y(0,0) [kPa]",
        last.object("goal").number("value"),
        exact,
        1e-4);
  const double true_error =
    std::abs(last.object("goal").number("value") - exact) / exact;
  deallog << "the reported bound covers the true error: "
          << (last.object("goal").number("relative_error") >= true_error ?
                "yes" :
                "NO")
          << std::endl;
  AssertThrow(last.object("goal").number("relative_error") >= true_error,
              ExcMessage("the bound does not cover the true error"));
  check("w(0,0) [m]", last.items("probes")[0].number("w"), 5.51571072e-4, 3e-4);
  check("w(a/2,0) [m]",
        last.items("probes")[1].number("w"),
        4.95095874e-4,
        3e-4);
  check("w(0,0.5) [m]",
        last.items("probes")[2].number("w"),
        4.76016991e-4,
        3e-4);
}
