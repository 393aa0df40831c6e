// A symmetric scene solved on the whole plate (Symmetry = none), on half of
// it (x, y) and on a quarter (xy) must give the same answer: the mirror
// images in the Boussinesq kernel, beta_n = 0 on the planes, the loads on
// the planes and the whole-plate sums (mirror_symmetry.h). Checked to 1e-8
// relative, over adaptive cycles (the marking of the computed part follows
// the whole plate's), for
//  - the paper's example 2 as shipped (tensionless, collocation, element
//    exclusion) with extra point loads in mirror pairs and on the planes,
//  - the same with the defaults (Galerkin, active set),
//  - the rigid disk (bonded, Galerkin, curved boundary).
// Then: auto finds the planes a scene has, an explicit plane that the scene
// does not have is refused with a message.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <algorithm>
#include <cmath>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

namespace
{
  /** Largest difference of two runs' numbers, each relative to the largest
   *  magnitude of that quantity in the whole-plate run. */
  double
  largest_difference(const PlateOnHalfspaceProblem &whole,
                     const PlateOnHalfspaceProblem &part)
  {
    const auto &a = whole.summaries(), &b = part.summaries();
    AssertThrow(a.size() == b.size(), ExcMessage("different cycle counts"));
    double     worst   = 0;
    const auto compare = [&worst](const std::vector<double> &x,
                                  const std::vector<double> &y) {
      double scale = 0;
      for (const double v : x)
        scale = std::max(scale, std::abs(v));
      for (unsigned int i = 0; i < x.size(); ++i)
        worst =
          std::max(worst, std::abs(x[i] - y[i]) / std::max(scale, 1e-300));
    };
    const auto collect = [](const ResultRecord &s) {
      std::vector<std::vector<double>> values = {
        {s.number("applied_load")},
        {s.number("contact_force")},
        {s.number("max_w"), s.number("min_w")},
        {s.number("max_q"), s.number("min_q")},
        {s.number("max_Mx"),
         s.number("min_Mx"),
         s.number("max_My"),
         s.number("min_My")},
        {s.number("contact_area_fraction")},
        {double(s.count("contact_nodes"))},
        {},  // probe w
        {},  // probe q
        {}}; // probe moments
      for (const ResultRecord &p : s.items("probes"))
        {
          values[7].push_back(p.number("w"));
          values[8].push_back(p.number("q"));
          values[9].push_back(p.number("Mx"));
          values[9].push_back(p.number("My"));
        }
      return values;
    };
    for (unsigned int c = 0; c < a.size(); ++c)
      {
        const auto x = collect(a[c]), y = collect(b[c]);
        for (unsigned int k = 0; k < x.size(); ++k)
          compare(x[k], y[k]);
      }
    return worst;
  }

  void
  compare_symmetries(const std::string              &name,
                     const std::string              &scene,
                     const std::string              &extra,
                     const std::vector<std::string> &symmetries)
  {
    const auto whole =
      solve_scene(scene,
                  extra + "subsection Discretization\n set Symmetry = none\n"
                          "end\n");
    const auto &last = whole->summaries().back();
    deallog << name << ", whole plate: " << whole->summaries().size()
            << " cycles, last " << last.count("n_cells") << " cells, "
            << last.count("n_foundation_dofs") << " foundation nodes"
            << std::endl;
    for (const std::string &symmetry : symmetries)
      {
        const auto part =
          solve_scene(scene,
                      extra + "subsection Discretization\n set Symmetry = " +
                        symmetry + "\nend\n");
        const auto  &s          = part->summaries().back();
        const double difference = largest_difference(*whole, *part);
        deallog << name << ", symmetry " << symmetry << ": last "
                << s.count("n_cells") << " cells, "
                << s.count("n_foundation_dofs")
                << " foundation nodes, largest relative difference "
                << (difference < 1e-8 ? "< 1e-8: ok" : "> 1e-8: FAILED")
                << std::endl;
        AssertThrow(difference < 1e-8,
                    ExcMessage(name + ": symmetry " + symmetry +
                               " differs from the whole plate"));
        AssertThrow(
          s.count("n_cells") *
              part->plate().get_foundation_space().symmetry.n_copies() ==
            last.count("n_cells"),
          ExcMessage("the computed part is not the right part"));
      }
  }
} // namespace

int
main()
{
  initlog();
  // probes off the cell interfaces (moments jump there)
  const std::string probes =
    "subsection Output\n set Probe points = 0.3,0.2 ; 5.1,3.3 ; -2.7,-1.1 ; "
    "-4.4,2.9\nend\n";
  const std::string adaptive = "subsection Adaptivity\n set Cycles = 2\n"
                               " set Refinement = adaptive\nend\n";
  const std::string point_loads =
    "subsection Loads\n set Point loads = 0,0,200 ; 3,1,50 ; -3,1,50 ; "
    "3,-1,50 ; -3,-1,50 ; 4,0,80 ; -4,0,80\nend\n";
  compare_symmetries("example 2 (paper's method)",
                     "example2.prm",
                     probes + adaptive + point_loads,
                     {"x", "y", "xy"});
  compare_symmetries("example 2 (galerkin, active set)",
                     "example2.prm",
                     probes + adaptive + point_loads +
                       "subsection Discretization\n set Flexibility = "
                       "galerkin\nend\nsubsection Contact\n set Method = "
                       "active set\nend\n",
                     {"x", "y", "xy"});
  compare_symmetries("rigid disk",
                     "rigid-disk.prm",
                     "subsection Adaptivity\n set Cycles = 2\nend\n",
                     {"xy"});

  // auto: a load off the plane y = 0 leaves only x = 0
  const auto auto_x =
    solve_scene("example2.prm",
                "subsection Loads\n set Point loads = 2,1,10 ; -2,1,10\nend\n"
                "subsection Discretization\n set Symmetry = auto\nend\n");
  deallog << "point loads at (2,1) and (-2,1), Symmetry = auto: "
          << auto_x->plate().get_foundation_space().symmetry.name()
          << std::endl;
  AssertThrow(auto_x->plate().get_foundation_space().symmetry.name() == "x",
              ExcMessage("auto did not find the plane x = 0"));
  // an odd number of cells across x = 0 straddles it
  const auto odd =
    solve_scene("example2.prm",
                "subsection Discretization\n set Subdivisions x = 9\n"
                " set Symmetry = auto\nend\n");
  deallog << "9 x 10 cells, Symmetry = auto: "
          << odd->plate().get_foundation_space().symmetry.name() << std::endl;
  for (const std::string &extra :
       {std::string("subsection Loads\n set Point loads = 2,1,10\nend\n"
                    "subsection Discretization\n set Symmetry = x\nend\n"),
        std::string("subsection Discretization\n set Subdivisions x = 9\n"
                    " set Symmetry = xy\nend\n")})
    try
      {
        solve_scene("example2.prm", extra);
        AssertThrow(false, ExcMessage("an asymmetric scene was reduced"));
      }
    catch (const std::exception &e)
      {
        const std::string message = short_error_message(e);
        AssertThrow(message.find("Discretization/Symmetry") !=
                      std::string::npos,
                    ExcMessage(message));
        deallog << "refused: " << message << std::endl;
      }
}
