// Loads partly off the plate (doc/errors-and-limits.md, "What you wrote
// and what you get"): the plate carries only the part on it, and the run
// says so with a warning that names the entry and item, the share off the
// plate and the load applied, for every plate shape.
// - On a grid of slabs (4.5 + 4.5 by 3.6) a tyre 0.05 m over the long
//   edge: the warning names the tyre, and applied_load equals the
//   pressure times the area of the tyres on the plate, from the circular
//   segment's closed form (1e-10). It used to run without a warning,
//   because the grid's outline was taken from Plate/Length x and y.
// - On a disk, a circular patch over the rim; on a Gmsh mesh (written
//   here), a rectangular patch half off: each warned about.
// - Loads/Sweep moving the axle over the edge: a warning for each
//   position with a tyre partly off (positions 1 and 2) and none for the
//   others; sweep.csv's applied_load and summary.json's sweep applied_load
//   hold the closed-form load at every position (1e-8).
// Only verdicts are printed.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>
#include <string>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  const double pressure = 700;
  /** the tyre of a 80 kN single axle (2 tyres) at 700 kPa */
  const double radius = std::sqrt(80. / (2 * pressure * numbers::PI));

  /** The area of the disk of @p radius on the side of a line where its
   *  centre lies at the signed distance @p d (> 0: on the plate). */
  double
  disk_area_on_plate(const double d)
  {
    if (d >= radius)
      return numbers::PI * radius * radius;
    if (d <= -radius)
      return 0;
    return radius * radius * std::acos(-d / radius) +
           d * std::sqrt(radius * radius - d * d);
  }

  void
  verdict(const std::string &name, const bool ok)
  {
    deallog << name << ": " << (ok ? "ok" : "FAILED") << std::endl;
    AssertThrow(ok, ExcMessage(name + " failed"));
  }

  /** The warnings of @p problem that contain @p text. */
  unsigned int
  count_warnings(const PlateOnHalfspaceProblem &problem,
                 const std::string             &text)
  {
    unsigned int n = 0;
    for (const std::string &w : problem.warnings())
      n += w.find(text) != std::string::npos ? 1 : 0;
    return n;
  }

  std::string
  slab_grid(const double axle_y, const std::string &extra)
  {
    std::ostringstream prm;
    prm << std::setprecision(17) << "set Output directory = results\n"
        << "subsection Plate\n set Shape = slabs\n"
        << " set Slab lengths x = 4.5, 4.5\n set Slab lengths y = 3.6\n"
        << " set Thickness = 0.25\n set Young's modulus = 3e7\nend\n"
        << "subsection Foundation\n set Model = dense liquid\n"
        << " set Modulus of subgrade reaction = 5e4\n set Contact = bonded\n"
        << "end\nsubsection Joints\n set Load transfer = tied\nend\n"
        << "subsection Discretization\n set Subdivisions x = 4\n"
        << " set Subdivisions y = 4\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n"
        << "subsection Loads\n set Axles = single, 1, " << axle_y << ", 0, 80, "
        << pressure << "\n"
        << extra << "end\n";
    return prm.str();
  }
} // namespace

int
main()
{
  initlog();

  // the single axle's tyres at y = axle_y -+ 0.915 (doc/parameters.md)
  const double outline = 1.8, track = 0.915;
  {
    const double y       = outline - track + 0.05; // tyre 0.05 m over
    const auto   problem = TestTools::run_scene_text(slab_grid(y, ""));
    verdict("slabs, tyre over the edge: one warning naming the tyre and "
            "the share off the plate",
            problem->warnings().size() == 1 &&
              count_warnings(*problem, "Loads/Axles: group 1 (single), tyre") ==
                1 &&
              count_warnings(*problem, "% of its load is off the plate") == 1);
    const double expected =
      pressure * (numbers::PI * radius * radius + disk_area_on_plate(-0.05));
    verdict("slabs, tyre over the edge: applied_load = the part on the "
            "plate (1e-10)",
            std::abs(problem->summaries().back().number("applied_load") -
                     expected) <= 1e-10 * expected);
  }
  {
    const auto problem = TestTools::run_scene_text(
      "set Output directory = results\n"
      "subsection Plate\n set Shape = disk\n set Radius = 1\nend\n"
      "subsection Foundation\n set Contact = bonded\nend\n"
      "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n"
      "subsection Loads\n set Circular patches = 0.95, 0, 0.1, 100\nend\n");
    verdict("disk, patch over the rim: warned",
            count_warnings(*problem,
                           "Loads/Circular patches: patch 1 lies partly off "
                           "the plate") == 1);
  }
  {
    std::ofstream("two_cells.msh")
      << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n"
         "2 1 0 0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n6 2 1 0\n$EndNodes\n"
         "$Elements\n2\n1 3 2 0 1 1 2 5 4\n2 3 2 0 1 2 3 6 5\n$EndElements\n";
    const auto problem = TestTools::run_scene_text(
      "set Output directory = results\n"
      "subsection Plate\n set Shape = mesh file\n"
      " set Mesh file = two_cells.msh\nend\n"
      "subsection Foundation\n set Contact = bonded\nend\n"
      "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n"
      "subsection Loads\n set Rectangular patches = 1.5, 0.2, 2.5, 0.4, "
      "100\nend\n");
    verdict("Gmsh mesh, patch half off: warned with 50 %",
            count_warnings(*problem,
                           "Loads/Rectangular patches: patch 1 lies partly "
                           "off the plate: 50 % of its load") == 1);
    verdict("Gmsh mesh, patch half off: applied_load = 10 (1e-12)",
            std::abs(problem->summaries().back().number("applied_load") - 10) <=
              1e-11);
  }
  {
    // offsets 0, 0.2, 0.4: the outer tyre's centre 0.285 and 0.085 inside
    // the edge and 0.115 beyond it (its radius is 0.135)
    const double y0      = outline - track - 0.285;
    const auto   problem = TestTools::run_scene_text(
      slab_grid(y0, " set Sweep = 0, 0, 0, 0.4, 3\n"));
    unsigned int per_position[3] = {0, 0, 0};
    for (unsigned int k = 0; k < 3; ++k)
      per_position[k] =
        count_warnings(*problem,
                       "Loads/Sweep: at position " + std::to_string(k) + " ");
    verdict("sweep: warnings at positions 1 and 2 only, one each",
            problem->warnings().size() == 2 && per_position[0] == 0 &&
              per_position[1] == 1 && per_position[2] == 1);

    std::vector<double> expected;
    for (const double offset : {0., 0.2, 0.4})
      {
        const double d = outline - (y0 + track + offset);
        expected.push_back(
          pressure * (numbers::PI * radius * radius + disk_area_on_plate(d)));
      }
    std::ifstream csv("results/sweep.csv");
    std::string   header;
    std::getline(csv, header);
    const bool last_column =
      header.size() >= 13 &&
      header.compare(header.size() - 13, 13, ",applied_load") == 0;
    std::vector<double> column;
    for (std::string line; std::getline(csv, line);)
      column.push_back(std::stod(line.substr(line.rfind(',') + 1)));
    bool matches = last_column && column.size() == 3;
    for (unsigned int k = 0; matches && k < 3; ++k)
      matches = std::abs(column[k] - expected[k]) <= 1e-8 * expected[k];
    verdict("sweep.csv: applied_load per position = the part on the plate "
            "(1e-8)",
            matches);

    std::ifstream      json_file("results/summary.json");
    std::ostringstream json;
    json << json_file.rdbuf();
    const std::string   text  = json.str();
    const auto          sweep = text.find("\"sweep\"");
    const auto          list  = text.find("\"applied_load\": [", sweep);
    std::vector<double> listed;
    if (sweep != std::string::npos && list != std::string::npos)
      {
        std::string numbers =
          text.substr(list + 17, text.find(']', list) - list - 17);
        std::replace(numbers.begin(), numbers.end(), ',', ' ');
        std::istringstream in(numbers);
        for (double v; in >> v;)
          listed.push_back(v);
      }
    bool same = listed.size() == 3;
    for (unsigned int k = 0; same && k < 3; ++k)
      same = std::abs(listed[k] - expected[k]) <= 1e-8 * expected[k];
    verdict("summary.json: sweep applied_load per position (1e-8)", same);
  }
}
