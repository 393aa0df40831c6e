// Axle groups and aircraft main gears (Loads/Axles, doc/parameters.md,
// "Axles"), against exact bookkeeping:
//  - each type has its documented number of tyres at the documented
//    positions (a tandem's at x = +-1.311/2, y = +-1.83/2 +- 0.343/2);
//    the angle turns the layout about the group's centre;
//  - the tyres' areas times the pressure add up to the group's load, and
//    a run applies exactly that load and the soil carries it;
//  - a tandem centred on a square slab gives a symmetric answer, and the
//    same scene solved on a quarter (Symmetry = auto) gives the same.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using Parameters::AxleGroup;

namespace
{
  std::unique_ptr<PlateOnHalfspaceProblem>
  run(const std::string &axles, const std::string &symmetry)
  {
    return TestTools::run_scene_text(TestTools::slab_on_dense_liquid(
      8,
      8,
      0.3,
      5e4,
      "bonded",
      8,
      8,
      1,
      "subsection Loads\n set Axles = " + axles +
        "\nend\nsubsection Discretization\n set Symmetry = " + symmetry +
        "\nend\n"));
  }
} // namespace

int
main()
{
  initlog();

  const std::vector<unsigned int> tyres = {2, 4, 8, 12, 2, 4, 6};
  for (unsigned int t = 0; t < tyres.size(); ++t)
    {
      AxleGroup group;
      group.type          = static_cast<AxleGroup::Type>(t);
      group.centre        = Point<2>(0.1, 0.2);
      group.angle         = 30;
      group.load          = 160;
      group.tyre_pressure = 700;
      const auto patches  = group.tyre_patches(1);
      double     load     = 0;
      for (const auto &p : patches)
        load += M_PI * p.radius * p.radius * p.pressure;
      const std::string name = AxleGroup::type_names()[t];
      deallog << name << ": " << patches.size() << " tyres ("
              << (patches.size() == tyres[t] ? "as documented" : "WRONG") << ")"
              << std::endl;
      AssertThrow(patches.size() == tyres[t], ExcMessage("tyre count"));
      check(name + ": tyres' area x pressure [kN]", load, 160., 1e-14);
      const ResultRecord c =
        run(name + ", 0.1, 0.2, 30, 160, 700", "none")->summaries().back();
      check(name + ": applied load [kN]",
            c.number("applied_load"),
            160.,
            1e-12);
      check(name + ": contact force [kN]",
            c.number("contact_force"),
            160.,
            1e-10);
    }

  // the tandem's layout, and a quarter turn of a single axle
  {
    const auto   layout = AxleGroup::tyre_layout(AxleGroup::Type::tandem);
    double       error  = 0;
    unsigned int k      = 0;
    for (const double x : {-0.6555, 0.6555})
      for (const double side : {-0.915, 0.915})
        for (const double dual : {-0.1715, 0.1715})
          error =
            std::max(error, layout[k++].distance(Point<2>(x, side + dual)));
    check("tandem layout: largest distance from the documented tyres [m]",
          1. + error,
          1.,
          1e-15);
    AxleGroup single;
    single.type          = AxleGroup::Type::single;
    single.centre        = Point<2>(1, 2);
    single.angle         = 90;
    single.load          = 80;
    single.tyre_pressure = 700;
    const auto turned    = single.tyre_patches(1);
    check("single axle turned by 90 degrees: first tyre at x = 1 + 0.915",
          turned[0].centre[0],
          1.915,
          1e-14);
    check("single axle turned by 90 degrees: first tyre at y = 2",
          turned[0].centre[1],
          2.,
          1e-14);
  }

  // symmetry of a centred tandem, whole plate against a quarter
  {
    const auto   whole   = run("tandem, 0, 0, 0, 160, 700", "none");
    const auto   quarter = run("tandem, 0, 0, 0, 160, 700", "auto");
    const double scale   = whole->summaries().back().number("max_w");
    double       mirror = 0, parts = 0;
    for (const Point<2> &x :
         {Point<2>(0.6, 0.9), Point<2>(1.7, 0.3), Point<2>(3.1, 2.2)})
      for (const Point<2> &image : {Point<2>(-x[0], x[1]),
                                    Point<2>(x[0], -x[1]),
                                    Point<2>(-x[0], -x[1])})
        {
          const double w = whole->values_at(x).w;
          mirror = std::max(mirror, std::abs(whole->values_at(image).w - w));
          parts  = std::max(parts, std::abs(quarter->values_at(image).w - w));
        }
    deallog << "centred tandem: mirror images of w agree to "
            << (mirror < 1e-10 * scale ? "1e-10" : "LESS") << std::endl;
    deallog << "centred tandem: the quarter agrees with the whole plate to "
            << (parts < 1e-8 * scale ? "1e-8" : "LESS") << std::endl;
    AssertThrow(mirror < 1e-10 * scale && parts < 1e-8 * scale,
                ExcMessage("a centred tandem must give a symmetric answer"));
  }
}
