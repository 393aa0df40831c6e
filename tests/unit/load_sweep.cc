// Loads/Sweep (doc/verification.md, "Critical position"): two dowelled
// slabs 4 x 3.6 x 0.25 m, a single axle with dual tyres (80 kN, 700 kPa)
// moved across the joint x = 0. Each position of the sweep must equal an
// independent run with the axle placed there, on the same mesh:
//  1. bonded on a dense liquid (one factorisation for all positions), to
//     1e-9;
//  2. bonded on the half-space with the direct solver, to 1e-9;
//  3. tensionless on a dense liquid at night (the slabs curl up and lift
//     off; each position warm-started from the last), to the contact
//     solver's tolerance, with the same contact area;
// and the envelope in summary.json must be the extreme of sweep.csv's
// column and name its position.

#include <deal.II/base/utilities.h>

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  std::string
  scene(const std::string &foundation,
        const std::string &axle_x,
        const std::string &extra)
  {
    std::ostringstream prm;
    prm << "set Output directory = results\n"
        << "subsection Plate\n set Shape = slabs\n set Slab lengths x = 4, 4\n"
        << " set Slab lengths y = 3.6\n set Thickness = 0.25\n"
        << " set Young's modulus = 3e7\n set Poisson's ratio = 0.15\nend\n"
        << "subsection Foundation\n"
        << foundation << "\nend\n"
        << "subsection Joints\n set Load transfer = dowels\nend\n"
        << "subsection Loads\n set Axles = single dual, " << axle_x
        << ", 0, 0, 80, 700\nend\n"
        << "subsection Discretization\n set Subdivisions x = 6\n"
        << " set Subdivisions y = 6\n set Symmetry = none\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n"
        << extra;
    return prm.str();
  }

  std::vector<std::vector<double>>
  read_sweep_csv()
  {
    std::ifstream                    file("results/sweep.csv");
    std::string                      line;
    std::vector<std::vector<double>> rows;
    std::getline(file, line);
    while (std::getline(file, line))
      {
        std::vector<double> row;
        for (const std::string &field : Utilities::split_string_list(line))
          row.push_back(field.empty() ? std::nan("") :
                                        Utilities::string_to_double(field));
        rows.push_back(row);
      }
    return rows;
  }

  void
  compare(const std::string &name,
          const std::string &foundation,
          const std::string &extra,
          const double       tolerance)
  {
    TestTools::run_scene_text(scene(foundation,
                                    "0",
                                    extra +
                                      "subsection Loads\n set Sweep = -1.5, 0, "
                                      "1.5, 0, 5\nend\n"));
    const auto           rows = read_sweep_csv();
    std::ifstream        file("results/summary.json");
    const nlohmann::json summary = nlohmann::json::parse(file);
    AssertThrow(rows.size() == 5, ExcMessage("five positions expected"));
    // columns: 6 max_s1_bottom, 9 max_s1_top, 12 contact area, 13 min lte
    double largest_difference = 0;
    for (const unsigned int step : {0u, 1u, 3u, 4u})
      {
        const double       x = rows[step][1];
        std::ostringstream axle;
        axle << x;
        const auto single =
          TestTools::run_scene_text(scene(foundation, axle.str(), extra));
        const auto &c      = single->summaries().back();
        largest_difference = std::max(
          {largest_difference,
           std::abs(rows[step][6] - c.number("max_principal_stress_bottom")) /
             c.number("max_principal_stress_bottom"),
           std::abs(rows[step][9] - c.number("max_principal_stress_top")) /
             std::abs(c.number("max_principal_stress_top")),
           std::abs(rows[step][12] - c.number("contact_area_fraction")),
           std::abs(rows[step][13] - c.items("joints")[0].number("lte"))});
      }
    std::ostringstream bound;
    bound << tolerance;
    deallog << name << ": sweep against single runs: "
            << (largest_difference <= tolerance ? "within " : "BEYOND ")
            << bound.str() << std::endl;
    AssertThrow(largest_difference <= tolerance,
                ExcMessage(name + ": the sweep differs from single runs"));

    // the envelope names the largest bottom stress and its position
    const auto  &envelope = summary["sweep"]["envelope"];
    unsigned int best     = 0;
    for (unsigned int k = 1; k < rows.size(); ++k)
      if (rows[k][6] > rows[best][6])
        best = k;
    const unsigned int step =
      envelope["max_principal_stress_bottom"]["step"].get<unsigned int>();
    const double value =
      envelope["max_principal_stress_bottom"]["value"].get<double>();
    AssertThrow(
      std::abs(value - rows[best][6]) <= 1e-9 * rows[best][6] &&
        std::abs(rows[step][6] - rows[best][6]) <= 1e-9 * rows[best][6] &&
        envelope["max_principal_stress_bottom"]["position"][0].get<double>() ==
          rows[step][1],
      ExcMessage("the envelope is not the column's largest"));
    // the stress for the record, 4 digits (the solve changes later digits
    // with the CPU); the checks are the assertions above
    deallog << name << ": largest bottom stress " << std::setprecision(4)
            << rows[best][6]
            << " with the axle at x = " << std::abs(rows[best][1])
            << std::setprecision(10) << std::endl;
  }
} // namespace

int
main()
{
  initlog();
  compare("bonded, dense liquid",
          " set Model = dense liquid\n set Modulus of subgrade reaction = 5e4"
          "\n set Contact = bonded",
          "",
          1e-9);
  compare("bonded, half-space, direct solver",
          " set Young's modulus = 1e5\n set Contact = bonded",
          "subsection Contact\n set Solver = direct\nend\n",
          1e-9);
  compare("tensionless, dense liquid, night",
          " set Model = dense liquid\n set Modulus of subgrade reaction = 5e4"
          "\n set Contact = tensionless",
          "subsection Plate\n set Unit weight = 24\nend\n"
          "subsection Temperature\n set Difference = -10\nend\n",
          1e-7);
}
