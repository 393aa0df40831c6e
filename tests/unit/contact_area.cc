// The contact area located from the fields (doc/outputs.md, "Contact
// area"; doc/verification.md, "Contact area").
// 1. A near-rigid slab (l = 57 m against L = 4 m) on a tensionless dense
//    liquid under p = p0 xi^n, xi = (x + L/2)/L, uniform in y. A rigid
//    slab's contact pressure is linear and vanishes at the contact
//    boundary xi_b; its resultant, a third of the contact length from the
//    loaded edge, balances the load's at xi = (n+1)/(n+2), so
//    xi_b = (n-1)/(n+2) and the contact area fraction is 3/(n+2): 3/4 for
//    n = 2 (on a node line of every mesh) and 3/5 for n = 3 (inside the
//    cells of every mesh), on 8, 16 and 32 rows of cells, to 1e-4 (the
//    slab's own flexibility): the area is located where the deflection
//    vanishes, to the accuracy of the deflection (n = 2: 6e-10; n = 3:
//    7.8e-5, 5.9e-5, 2.6e-5), and the stated uncertainty covers the
//    error.
// 2. The same slab in bonded contact carries the plate everywhere:
//    fraction 1, uncertainty 0.
// 3. A flexible plate on a tensionless half-space (example 2, Galerkin
//    operator): the same area under a load 1e-200 times smaller (the
//    problem is linear in the load), and on 1281 foundation nodes a stated
//    uncertainty that covers the change on the next finer mesh, which
//    halves the error of a first-order measure.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  const ResultRecord &
  rigid_slab(std::unique_ptr<PlateOnHalfspaceProblem> &problem,
             const unsigned int                        n,
             const std::string                        &contact,
             const unsigned int                        refinements,
             const std::string                        &p0 = "9")
  {
    problem = TestTools::run_scene_text(TestTools::slab_on_dense_liquid(
      4,
      2,
      0.5,
      1e3,
      contact,
      8,
      4,
      refinements,
      "subsection Loads\n set Pressure function = " + p0 + "*((x+2)/4)^" +
        std::to_string(n) +
        "\nend\n"
        "subsection Plate\n set Young's modulus = 1e12\nend\n"
        "subsection Adaptivity\n set Goal = contact area\nend\n"));
    return problem->summaries().back();
  }
} // namespace

int
main()
{
  initlog();
  std::unique_ptr<PlateOnHalfspaceProblem> problem;
  for (const unsigned int n : {2u, 3u})
    for (unsigned int refinements = 1; refinements <= 3; ++refinements)
      {
        const ResultRecord &s =
          rigid_slab(problem, n, "tensionless", refinements);
        const double exact = 3. / (n + 2);
        const double error =
          std::abs(s.number("contact_area_fraction") - exact);
        const double stated =
          s.object("goal").number("estimated_error") / 8.; // plate area 8
        const bool ok = error <= 1e-4 && error <= stated + 1e-9;
        deallog << "p0 xi^" << n << ", " << (4u << refinements)
                << " rows: contact area fraction "
                << rounded(s.number("contact_area_fraction"), 1e-4)
                << " reference " << rounded(exact, 1e-4)
                << ", error <= 1e-4 and <= the stated uncertainty: "
                << (ok ? "ok" : "FAILED") << std::endl;
        AssertThrow(ok, ExcMessage("contact area"));
      }
  {
    // the problem is linear in the load: the same area at any scale
    // (example 2 on a tensionless half-space, weightless, its band load
    // at 300 and at 3e-198 kPa)
    std::vector<double> area;
    for (const std::string pressure : {"300", "3e-198"})
      area.push_back(
        TestTools::solve_scene(
          "example2.prm",
          "subsection Plate\n set Unit weight = 0\nend\n"
          "subsection Loads\n set Rectangular patches = -2,-4,2,4," +
            pressure +
            "\nend\n"
            "subsection Discretization\n set Flexibility = galerkin\nend\n"
            "subsection Contact\n set Method = active set\nend\n")
          ->summaries()
          .back()
          .number("contact_area_fraction"));
    const bool ok = std::abs(area[1] - area[0]) <= 1e-12;
    deallog << "load x 1e-200: the same contact area (1e-12): "
            << (ok ? "ok" : "FAILED") << std::endl;
    AssertThrow(ok, ExcMessage("contact area at a tiny load"));
  }
  {
    const ResultRecord &s  = rigid_slab(problem, 2, "bonded", 1);
    const bool          ok = s.number("contact_area_fraction") == 1 &&
                    s.object("goal").number("estimated_error") == 0;
    deallog << "bonded: fraction 1, uncertainty 0: " << (ok ? "ok" : "FAILED")
            << std::endl;
    AssertThrow(ok, ExcMessage("bonded contact area"));
  }
  {
    std::vector<double> area, stated;
    for (const unsigned int refinements : {2u, 3u})
      {
        problem = TestTools::solve_scene(
          "example2.prm",
          "subsection Discretization\n set Flexibility = galerkin\n"
          " set Initial refinements = " +
            std::to_string(refinements) +
            "\nend\n"
            "subsection Contact\n set Method = active set\nend\n"
            "subsection Adaptivity\n set Refinement = global\n"
            " set Cycles = 1\n set Goal = contact area\nend\n");
        area.push_back(
          problem->summaries().back().object("goal").number("value"));
        stated.push_back(
          problem->summaries().back().object("goal").number("estimated_error"));
      }
    const bool ok = std::abs(area[1] - area[0]) <= stated[0];
    deallog << "example 2, half-space: the change on the finer mesh is "
            << "within the stated uncertainty: " << (ok ? "ok" : "FAILED")
            << std::endl;
    AssertThrow(ok, ExcMessage("half-space contact area"));
  }
}
