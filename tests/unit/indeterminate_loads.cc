// A weightless plate on a tensionless foundation under loads whose
// resultant lies on its outline has no determinate answer
// (doc/errors-and-limits.md, "A resultant on the outline"): a soil that
// cannot pull would have to carry the plate at that point alone, and the
// discrete answer's contact region shrinks with every refinement (its peak
// pressure quadrupled per refinement for a point load at a corner, which
// used to run and "converge"). The program must refuse such scenes on
// every mesh, and only them:
// - a point load at a corner or on an edge, on the dense liquid and on the
//   half-space, on 4 x 3 and on 8 x 6 cells: refused, the message naming
//   the load, the outline and the remedies;
// - two corner loads whose resultant lies on an edge (mirror symmetric, so
//   solved on half the plate): refused;
// - on a grid of 2 x 2 slabs with free joints: a load where the four slabs
//   meet (inside the grid, at a corner of its slab), loads on the free
//   joint x = 0 solved on the half x >= 0, and a slab pushed up while
//   another is pushed down: refused;
// - the corner load with the plate's weight, a load 1 mm from the corner,
//   one 0.2 m from an edge on the mirror plane x = 0 (solved on half the
//   plate, its whole load counted at its place), an interior load and the
//   load where four tied slabs meet run; the second and third with a
//   warning that the cells are larger than the region that carries them;
//   bonded, the corner load runs;
// - on 2 x 2 slabs with free joints and one loaded slab, weightless: the
//   slabs without load are refused when curled by a temperature difference
//   (dense liquid) and on the half-space, whose settlement reaches them (any
//   lifted position was an answer: the run's result depended on its path);
//   with the weight the half-space scene runs.
// Only verdicts are printed.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <sstream>
#include <string>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  /** A 4 m x 3 m slab, weightless unless @p extra says otherwise. */
  std::string
  slab(const std::string &soil,
       const std::string &contact,
       const unsigned int nx,
       const unsigned int ny,
       const std::string &loads)
  {
    std::ostringstream prm;
    prm << "set Output directory = results\n"
        << "subsection Plate\n set Length x = 4\n set Length y = 3\n"
        << " set Thickness = 0.25\n set Young's modulus = 3e7\nend\n"
        << "subsection Foundation\n"
        << (soil == "dense liquid" ?
              " set Model = dense liquid\n set Modulus of subgrade "
              "reaction = 5e4\n" :
              " set Model = half-space\n set Young's modulus = 1e5\n")
        << " set Contact = " << contact << "\nend\n"
        << "subsection Discretization\n set Subdivisions x = " << nx
        << "\n set Subdivisions y = " << ny << "\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n"
        << "subsection Loads\n"
        << loads << "\nend\n";
    return prm.str();
  }

  std::string
  slabs(const std::string &joints, const std::string &loads)
  {
    return "set Output directory = results\n"
           "subsection Plate\n set Shape = slabs\n set Slab lengths x = 4, "
           "4\n set Slab lengths y = 1.8, 1.8\n set Thickness = 0.25\n"
           " set Young's modulus = 3e7\nend\n"
           "subsection Foundation\n set Model = dense liquid\n"
           " set Modulus of subgrade reaction = 5e4\nend\n"
           "subsection Joints\n set Load transfer = " +
           joints +
           "\nend\n"
           "subsection Discretization\n set Subdivisions x = 4\n"
           " set Subdivisions y = 2\n set Symmetry = none\nend\n"
           "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n"
           "subsection Loads\n" +
           loads + "\nend\n";
  }

  /** Run @p scene and expect a refusal whose message holds @p parts. */
  void
  refused(const std::string              &name,
          const std::string              &scene,
          const std::vector<std::string> &parts)
  {
    std::string message;
    try
      {
        TestTools::run_scene_text(scene);
      }
    catch (const std::exception &error)
      {
        message = short_error_message(error);
      }
    bool ok = !message.empty();
    for (const std::string &part : parts)
      ok = ok && message.find(part) != std::string::npos;
    deallog << name << ": refused with a message naming " << parts.size()
            << " things: " << (ok ? "ok" : "FAILED") << std::endl;
    if (!ok)
      deallog << "  the message: <" << message << ">" << std::endl;
    AssertThrow(ok, ExcMessage(name + ": not refused as expected"));
  }

  /** Run @p scene: it must converge, with equilibrium, and warn or not. */
  void
  runs(const std::string &name,
       const std::string &scene,
       const bool         warns,
       const std::string &warning_names = "")
  {
    const auto          problem = TestTools::run_scene_text(scene);
    const ResultRecord &s       = problem->summaries().back();
    bool                warned  = false;
    for (const std::string &w : problem->warnings())
      warned = warned || (w.find("less than a third of the cells there") !=
                            std::string::npos &&
                          w.find(warning_names) != std::string::npos);
    const bool ok =
      s.flag("converged") &&
      std::abs(s.number("contact_force") - s.number("applied_load")) <=
        1e-8 * std::abs(s.number("applied_load")) &&
      warned == warns;
    deallog << name << ": runs, converges, equilibrium"
            << (warns ? ", warns that the cells are too large" : ", no warning")
            << ": " << (ok ? "ok" : "FAILED") << std::endl;
    if (!ok)
      for (const std::string &w : problem->warnings())
        deallog << "  warning: " << w << std::endl;
    AssertThrow(ok, ExcMessage(name + " failed"));
  }
} // namespace

int
main()
{
  initlog();
  const std::vector<std::string> remedies = {"no determinate answer",
                                             "Move the load inward",
                                             "Plate/Unit weight",
                                             "patch"};
  for (const std::string soil : {"dense liquid", "half-space"})
    for (const unsigned int n : {1u, 2u})
      {
        std::vector<std::string> corner = remedies;
        corner.push_back("Loads/Point loads at (2, 1.5)");
        corner.push_back("on the outline of the plate");
        refused("corner load, " + soil + ", " + std::to_string(4 * n) + " x " +
                  std::to_string(3 * n) + " cells",
                slab(soil,
                     "tensionless",
                     4 * n,
                     3 * n,
                     " set Point loads = 2, 1.5, 100"),
                corner);
        std::vector<std::string> edge = remedies;
        edge.push_back("Loads/Point loads at (2, 0.3)");
        refused("edge load, " + soil + ", " + std::to_string(4 * n) + " x " +
                  std::to_string(3 * n) + " cells",
                slab(soil,
                     "tensionless",
                     4 * n,
                     3 * n,
                     " set Point loads = 2, 0.3, 100"),
                edge);
      }
  refused("two corner loads, resultant on the edge y = 1.5",
          slab("dense liquid",
               "tensionless",
               4,
               4,
               " set Point loads = 2, 1.5, 100 ; -2, 1.5, 100"),
          remedies);
  // 2 x 2 slabs: the point where the four meet is inside the grid but at
  // a corner of the slab it belongs to
  refused("free joints, load where four slabs meet",
          slabs("free", " set Point loads = 0, 0, 100"),
          {"no determinate answer",
           "resultant of the loads on slab",
           "Plate/Unit weight"});
  {
    // the same grid mirrored about x = 0, the free joint there two free
    // edges: the slabs on either side are bodies of their own
    std::string scene =
      slabs("free", " set Point loads = 0, 0.9, 100 ; 0, -0.9, 100");
    scene.replace(scene.find("set Symmetry = none"), 19, "set Symmetry = x");
    refused("free joints on the mirror plane x = 0, loads on it",
            scene,
            {"no determinate answer", "slab", "Plate/Unit weight"});
  }
  refused("free joints, one slab pushed up",
          slabs("free", " set Point loads = -2, -0.9, 100 ; 2, -0.9, -50"),
          {"no downward resultant", "slab 2 ", "Plate/Unit weight"});

  // a slab without load beyond a free joint, weightless: on a dense liquid
  // it rests where it is (tests/unit/jointed_slabs), curled it does not
  {
    std::string curled = slabs("free",
                               " set Point loads = -2, -0.9, 100\nend\n"
                               "subsection Temperature\n set Difference = -10");
    refused("free joints, curled by a temperature difference, slabs without "
            "load",
            curled,
            {"without any load", "curling it", "Plate/Unit weight"});
    const auto replace =
      [](std::string &text, const std::string &from, const std::string &to) {
        text.replace(text.find(from), from.size(), to);
      };
    std::string half_space = slabs("free", " set Point loads = -2, -0.9, 100");
    replace(half_space,
            " set Model = dense liquid\n set Modulus of subgrade reaction = "
            "5e4",
            " set Model = half-space\n set Young's modulus = 1e5");
    refused("free joints, half-space, slabs without load",
            half_space,
            {"without any load", "half-space", "Plate/Unit weight"});
    runs("free joints, half-space, slabs without load, with the weight",
         half_space + "subsection Plate\n set Unit weight = 24\nend\n",
         false);
  }
  runs("corner load on the plate with its weight",
       slab("dense liquid",
            "tensionless",
            4,
            3,
            " set Point loads = 2, 1.5, 100\nend\n"
            "subsection Plate\n set Unit weight = 24"),
       false);
  runs("corner load, bonded",
       slab("dense liquid", "bonded", 4, 3, " set Point loads = 2, 1.5, 100"),
       false);
  runs("load 1 mm from the corner",
       slab("dense liquid",
            "tensionless",
            4,
            3,
            " set Point loads = 1.999, 1.499, 100"),
       true);
  // on the mirror plane x = 0, so solved on half the plate: the warning
  // counts the whole load at its place
  runs(
    "load on the mirror plane 0.2 m from the edge",
    slab("dense liquid", "tensionless", 4, 3, " set Point loads = 0, 1.3, 100"),
    true,
    "100 at (0, 1.3), lies 0.2 from the outline");
  runs("interior load",
       slab("dense liquid",
            "tensionless",
            4,
            3,
            " set Point loads = 0.5, 0.25, 100"),
       false);
  runs("tied joints, load where four slabs meet",
       slabs("tied", " set Point loads = 0, 0, 100"),
       false);
}
