// Results are declared where they are computed (base/result_record.h):
// 1. doc/outputs.md holds every declared table of summary.json keys and the
//    table of convergence.txt's columns verbatim, and no other table of
//    keys, so the manual cannot drift from what the program writes;
// 2. a cycle's record holds only declared keys of the declared kinds (the
//    record refuses others), and summary.json holds every key a scene with
//    a goal and probes sets;
// 3. Verification/Checks tests any number of a cycle, a goal's included;
// 4. a goal whose value is 0 (the pressure where a stiff slab has lifted
//    off a tensionless dense liquid) has no relative error: null, and the
//    run ends normally.

#include <plate_on_halfspace/base/result_record.h>
#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  /** How many times @p text holds @p part. */
  unsigned int
  occurrences(const std::string &text, const std::string &part)
  {
    unsigned int n = 0;
    for (auto at = text.find(part); at != std::string::npos;
         at      = text.find(part, at + 1))
      ++n;
    return n;
  }
} // namespace

int
main()
{
  initlog();
  std::ifstream      file(SOURCE_DIR "/../../doc/outputs.md");
  std::ostringstream read;
  read << file.rdbuf();
  const std::string manual = read.str();
  AssertThrow(!manual.empty(), ExcMessage("doc/outputs.md not found"));

  // 1. every declared table verbatim, and no undeclared table of keys
  bool all_documented = true;
  for (const std::string &table : declared_tables())
    {
      const std::string expected = results_markdown_table(table);
      const bool        found    = manual.find(expected) != std::string::npos;
      deallog << "keys of " << (table.empty() ? "the top level" : table)
              << (found ? ": in doc/outputs.md, verbatim: ok" :
                          ": NOT in doc/outputs.md as declared -- FAILED")
              << std::endl;
      if (!found)
        std::cerr << "doc/outputs.md should hold, for " << table << ":\n"
                  << expected << std::endl;
      all_documented = all_documented && found;
    }
  const unsigned int documented_tables =
    occurrences(manual, "| key | unit | meaning |\n");
  deallog << "tables of keys in doc/outputs.md: "
          << (documented_tables == declared_tables().size() ?
                "as many as declared: ok" :
                "NOT as many as declared -- FAILED")
          << std::endl;
  const bool columns =
    manual.find(convergence_markdown_table()) != std::string::npos;
  deallog << "columns of convergence.txt"
          << (columns ? ": in doc/outputs.md, verbatim: ok" :
                        ": NOT in doc/outputs.md as declared -- FAILED")
          << std::endl;
  if (!columns)
    std::cerr << "doc/outputs.md should hold:\n"
              << convergence_markdown_table() << std::endl;
  AssertThrow(all_documented && documented_tables == declared_tables().size() &&
                columns,
              ExcMessage("doc/outputs.md differs from the declarations"));

  // 2. an undeclared key and a wrongly kinded value are refused
  for (const auto &[what, set] :
       std::vector<std::pair<std::string, std::function<void(ResultRecord &)>>>{
         {"an undeclared key",
          [](ResultRecord &r) { r.set("largest_deflection", 1.); }},
         {"a count set as a number",
          [](ResultRecord &r) { r.set("n_dofs", 1.); }},
         {"a location set as a number",
          [](ResultRecord &r) { r.set("max_w_at", 1.); }}})
    {
      ResultRecord record("cycles");
      bool         refused = false;
      try
        {
          set(record);
        }
      catch (const std::exception &)
        {
          refused = true;
        }
      deallog << what << (refused ? ": refused: ok" : ": accepted -- FAILED")
              << std::endl;
      AssertThrow(refused, ExcMessage(what + " accepted"));
    }

  // 2., 3. a scene that sets nested keys, and checks of a count, a number
  // and the goal's entry
  const std::string scene = TestTools::slab_on_dense_liquid(
    4,
    4,
    0.25,
    5e4,
    "tensionless",
    4,
    4,
    0,
    "subsection Loads\n set Point loads = 0.5, 0.5, 100\nend\n"
    "subsection Output\n set Probe points = 0, 0; 1, 1\nend\n"
    "subsection Adaptivity\n set Goal = w at 0.5,0.5\n"
    " set Refinement = global\n set Cycles = 3\n set Target error = 1e-9\n"
    "end\n"
    "subsection Discretization\n set Symmetry = none\nend\n"
    "subsection Verification\n set Checks = n_cells,1024,1e-12; "
    "applied_load,100,1e-12; goal.target_error,1e-9,1e-12\nend\n");
  SceneParameters parameters;
  parameters.read_from_string(scene);
  std::ostringstream      log;
  PlateOnHalfspaceProblem problem(parameters, log);
  const bool              passed = problem.run();
  const ResultRecord     &last   = problem.summaries().back();
  // the goal refines the 4 x 4 mesh once on its own (doc/parameters.md),
  // and the second and third cycles refine it again: 32 x 32 cells
  deallog << "checks of a count, a number and a goal's entry: "
          << (passed && log.str().find("check goal.target_error") !=
                          std::string::npos ?
                "passed: ok" :
                "FAILED")
          << std::endl;
  if (!passed)
    std::cerr << log.str();
  AssertThrow(passed, ExcMessage("a check failed"));
  std::ifstream      json("results/summary.json");
  std::ostringstream summary;
  summary << json.rdbuf();
  bool all_written = true;
  for (const std::string &key : last.keys())
    all_written =
      all_written && summary.str().find('"' + key + '"') != std::string::npos;
  for (const std::string &key : last.object("goal").keys())
    all_written =
      all_written && summary.str().find('"' + key + '"') != std::string::npos;
  deallog << "every key of the last cycle and its goal in summary.json: "
          << (all_written ? "ok" : "FAILED") << std::endl;
  const double goal  = last.object("goal").number("value");
  const double probe = last.items("probes")[1].number("w");
  const double at    = problem.values_at(Point<2>(0.5, 0.5)).w;
  deallog << "the goal w at 0.5,0.5 against the plate's w there: "
          << (std::abs(goal - at) <= 1e-12 * std::abs(at) ? "ok" : "FAILED")
          << "; the probe at 1,1 against the plate's w there: "
          << (std::abs(probe - problem.values_at(Point<2>(1, 1)).w) == 0 ?
                "ok" :
                "FAILED")
          << std::endl;
  AssertThrow(std::abs(goal - at) <= 1e-12 * std::abs(at) &&
                probe == problem.values_at(Point<2>(1, 1)).w,
              ExcMessage("a record's value differs from the field's"));
  AssertThrow(all_written, ExcMessage("a key missing in summary.json"));

  // 4. a stiff slab loaded near one edge lifts its far corner
  const auto lifted = TestTools::run_scene_text(TestTools::slab_on_dense_liquid(
    4,
    4,
    1.0,
    5e4,
    "tensionless",
    4,
    4,
    1,
    "subsection Loads\n set Point loads = 1.8, 0, 100\nend\n"
    "subsection Adaptivity\n set Goal = q at -2,-2\n"
    " set Refinement = adaptive\n set Cycles = 2\nend\n"
    "subsection Discretization\n set Symmetry = none\nend\n"));
  const ResultRecord &corner = lifted->summaries().back().object("goal");
  deallog << "q at the lifted corner: "
          << (corner.number("value") == 0 ? "0" : "NOT 0")
          << "; its relative error: "
          << (corner.is_number("relative_error") ? "a number -- FAILED" :
                                                   "null: ok")
          << std::endl;
  AssertThrow(corner.number("value") == 0 &&
                !corner.is_number("relative_error"),
              ExcMessage("a zero goal's relative error"));
}
