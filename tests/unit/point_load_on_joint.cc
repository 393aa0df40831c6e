// A point load exactly on a joint is shared equally by the slabs' faces
// there (doc/loads.md, "Point loads"), so that the answer does not depend
// on which side a search meets first:
//  1. Three slabs 1.5, 2, 1.5 m with free joints at x = -1 and x = 1 on a
//     dense liquid, four 50 kN point loads on the joints, mirror
//     symmetric: the whole plate (Symmetry = none) and the quarter (auto)
//     give the same deflections, and on the whole plate the two outer
//     slabs the same peak stress.
//  2. Two 2.5 m slabs with a free joint at x = 0, 100 kN at the joint's
//     middle: each slab carries half, so both slabs' peak stresses agree
//     (a free joint: two free edges under 50 kN each), as on the half the
//     mirror plane computes.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  std::string
  scene(const std::string &lengths_x,
        const std::string &point_loads,
        const std::string &symmetry)
  {
    std::ostringstream prm;
    prm << "set Output directory = results\n"
        << "subsection Plate\n set Shape = slabs\n set Slab lengths x = "
        << lengths_x << "\n set Slab lengths y = 3.6\n set Thickness = 0.25\n"
        << " set Young's modulus = 3e7\n set Unit weight = 24\nend\n"
        << "subsection Joints\n set Load transfer = free\nend\n"
        << "subsection Foundation\n set Model = dense liquid\n"
        << " set Modulus of subgrade reaction = 5e4\nend\n"
        << "subsection Loads\n set Point loads = " << point_loads << "\nend\n"
        << "subsection Discretization\n set Subdivisions x = 2\n"
        << " set Subdivisions y = 4\n set Symmetry = " << symmetry << "\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n";
    return prm.str();
  }

  double
  slab_stress(const ResultRecord &summary, const unsigned int slab)
  {
    return summary.items("slabs")[slab].number("max_principal_stress_bottom");
  }
} // namespace

int
main()
{
  initlog();

  // 1. loads on two joints, whole plate against the quarter
  {
    const std::string loads = "1,0.3,50 ; -1,0.3,50 ; 1,-0.3,50 ; -1,-0.3,50";
    const auto        whole =
      TestTools::run_scene_text(scene("1.5, 2, 1.5", loads, "none"));
    const auto part =
      TestTools::run_scene_text(scene("1.5, 2, 1.5", loads, "auto"));
    const ResultRecord &a = whole->summaries().back();
    const ResultRecord &b = part->summaries().back();
    for (const std::string key :
         {"max_w", "min_w", "contact_area_fraction", "applied_load"})
      check("loads on joints, " + key + ": quarter against whole plate",
            b.number(key),
            a.number(key),
            1e-8);
    check("loads on joints: outer slab 3 against outer slab 1, peak stress",
          slab_stress(a, 2),
          slab_stress(a, 0),
          1e-8);
  }

  // 2. a load at the middle of a free joint: half on each slab
  {
    const auto whole =
      TestTools::run_scene_text(scene("2.5, 2.5", "0,0,100", "none"));
    const auto part =
      TestTools::run_scene_text(scene("2.5, 2.5", "0,0,100", "auto"));
    const ResultRecord &a = whole->summaries().back();
    check("load on a joint: slab 2 against slab 1, peak stress",
          slab_stress(a, 1),
          slab_stress(a, 0),
          1e-8);
    check("load on a joint: max w, quarter against whole plate",
          part->summaries().back().number("max_w"),
          a.number("max_w"),
          1e-8);
  }
}
