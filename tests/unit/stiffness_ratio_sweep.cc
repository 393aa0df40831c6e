// The plate-to-soil stiffness ratio R = E t^3 / (E0 L^3) (L = span) over
// 16 decades at the flexible end and 14 at the stiff end, up to the plate
// that a run refuses as rigid for the soil (its moments would keep fewer
// than 6 digits; doc/errors-and-limits.md, "Stiffness ratio"). Two limits
// are exact:
// - very flexible: the settlement of a uniformly loaded rectangle,
//   1.1221997 q B (1 - nu0^2) / E0 at the centre of a square (the closed
//   form of doc/formulation.md; parameters/flexible-square.prm, collocation,
//   which represents a uniform pressure exactly);
// - very stiff: the rigid plate. Its discrete value follows from the
//   half-space operator alone, w = P / (1^T M F^{-1} B 1) (a rigid
//   translation carries the load P), and for the disk of
//   parameters/rigid-disk.prm (Galerkin) it approaches the exact punch
//   P (1 - nu0^2) / (2 E0 a) = 0.0455 as the mesh is refined.
// "No loss of digits": the deviation from each limit must shrink exactly
// in proportion to R (flexible end) or 1/R (stiff end) down to 1e-8,
// i.e. its product with R^-1 or R must stay constant to 1%, while the
// condition estimate of the coupled matrix (summary.json
// "coupled_matrix_rcond") falls to 1e-12: the rigid-body correction of the
// contact solver keeps the lost digits out of the answer. Equilibrium
// holds to 1e-12 at every ratio.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>
#include <plate_on_halfspace/scene/input_checks.h>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

namespace
{
  /** Deflection of a rigid translation that carries the load @p load. */
  double
  rigid_plate_deflection(const PlateOnHalfspaceProblem &problem,
                         const double                   load)
  {
    // q = F^{-1} B 1 on the supported nodes, F from the operator's entries
    const FoundationOperator &foundation = problem.foundation();
    const unsigned int        n          = foundation.n_nodes();
    std::vector<unsigned int> nodes;
    for (unsigned int i = 0; i < n; ++i)
      if (foundation.supported_nodes()[i])
        nodes.push_back(i);
    LAPACKFullMatrix<double> flexibility;
    foundation.copy_block(nodes, flexibility);
    flexibility.compute_lu_factorization();
    Vector<double> ones(n), tested(n), q_nodes(nodes.size()), q(n), forces;
    ones = 1.;
    foundation.test_coupling().vmult(tested, ones);
    for (unsigned int i = 0; i < nodes.size(); ++i)
      q_nodes[i] = tested[nodes[i]];
    flexibility.solve(q_nodes);
    for (unsigned int i = 0; i < nodes.size(); ++i)
      q[nodes[i]] = q_nodes[i];
    foundation.nodal_forces(q, forces);
    return load / std::accumulate(forces.begin(), forces.end(), 0.);
  }

  struct Run
  {
    double ratio, w, rigid_w, rcond;
  };

  Run
  run(const std::string &scene,
      const double       ratio,
      const double       span,
      const double       thickness,
      const double       soil_modulus,
      const Point<2>    &probe,
      const double       load)
  {
    const double youngs_modulus =
      ratio * soil_modulus * std::pow(span / thickness, 3);
    std::ostringstream extra;
    extra << std::setprecision(17)
          << "subsection Plate\n set Thickness = " << thickness
          << "\n set Young's modulus = " << youngs_modulus
          << "\nend\nsubsection Adaptivity\n set Cycles = 1\nend\n";
    const auto  problem = solve_scene(scene, extra.str());
    const auto &s       = problem->summaries().back();
    const Run   result{ratio,
                     problem->values_at(probe).w,
                     rigid_plate_deflection(*problem, load),
                     s.number("coupled_matrix_rcond")};
    AssertThrow(std::isfinite(result.w) &&
                  s.number("coupled_matrix_rcond") > 0 &&
                  s.number("foundation_block_rcond") > 0,
                ExcMessage("not finite"));
    AssertThrow(std::abs(s.number("contact_force") -
                         s.number("applied_load")) <=
                  1e-12 * s.number("applied_load"),
                ExcMessage("equilibrium lost at R = " + std::to_string(ratio)));
    // For the record, at the digits that hold on any CPU (the checks below
    // look at the deviations): w to 6 digits, the condition estimates to 2.
    deallog << std::scientific << std::setprecision(1) << "R = " << ratio
            << ": w = " << std::setprecision(5) << result.w
            << ", rcond(K+S) = " << std::setprecision(1) << result.rcond
            << ", rcond(F_CC) = " << s.number("foundation_block_rcond")
            << std::defaultfloat << std::setprecision(10) << std::endl;
    return result;
  }
} // namespace

int
main()
{
  initlog();

  // Flexible end: 4 m square, 4 x 4 cells, t = 0.1, E0 = 5e4, q = 100.
  const double     flexible_w = 8.16961385005846e-3; // 1.1221997 q B/E*
  std::vector<Run> square;
  for (int e = -12; e <= 4; ++e)
    square.push_back(run("flexible-square.prm",
                         std::pow(10., e),
                         4,
                         0.1,
                         5e4,
                         Point<2>(0, 0),
                         1600));
  check("square, R = 1e-12: w(0,0), flexible limit (exact)",
        square.front().w,
        flexible_w,
        1e-9);
  check("square, R = 1e4: w(0,0), rigid limit",
        square.back().w,
        square.back().rigid_w,
        1e-5);
  // deviation / R at R = 1e-12 ... 1e-7 against its value at 1e-7
  const double flexible_slope =
    (square[5].w / flexible_w - 1) / square[5].ratio;
  for (unsigned int i = 0; i < 5; ++i)
    check("square, (w/w_flexible - 1)/R at R = 1e" +
            std::to_string(int(i) - 12),
          (square[i].w / flexible_w - 1) / square[i].ratio,
          flexible_slope,
          1e-2);

  // Stiff end: disk a = 1, t = 0.2, E0 = 1e4, P = 1000 at the centre.
  std::vector<Run> disk;
  for (int e = -8; e <= 6; ++e)
    disk.push_back(run(
      "rigid-disk.prm", std::pow(10., e), 2, 0.2, 1e4, Point<2>(0.5, 0), 1000));
  check("disk: discrete rigid limit against the exact punch",
        disk.back().rigid_w,
        0.0455,
        1e-2);
  check("disk, R = 1e6: w(0.5,0), rigid limit",
        disk.back().w,
        disk.back().rigid_w,
        1e-7);
  const double stiff_slope =
    (disk[11].w / disk[11].rigid_w - 1) * disk[11].ratio; // R = 1e3
  for (unsigned int i = 12; i < disk.size(); ++i)
    check("disk, (w/w_rigid - 1) R at R = 1e" + std::to_string(int(i) - 8),
          (disk[i].w / disk[i].rigid_w - 1) * disk[i].ratio,
          stiff_slope,
          1e-2);
  // The condition estimate falls like 1/R at the stiff end ...
  check("disk, rcond(K+S) R at R = 1e6 against R = 1e3",
        disk.back().rcond * disk.back().ratio,
        disk[11].rcond * disk[11].ratio,
        0.2);
  // Ten times stiffer the plate is refused, naming the entries.
  bool refused = false;
  try
    {
      run("rigid-disk.prm", 1e7, 2, 0.2, 1e4, Point<2>(0.5, 0), 1000);
    }
  catch (const std::exception &error)
    {
      const std::string message = one_line_message(error);
      refused =
        message.find("times stiffer than the half-space soil across "
                     "it") != std::string::npos &&
        message.find("Plate/Young's modulus at most") != std::string::npos;
    }
  require("disk, R = 1e7: refused as rigid for the soil, naming "
          "Plate/Young's modulus",
          refused);
  // ... and is reported in summary.json.
  std::ifstream summary("results/summary.json");
  std::string   text((std::istreambuf_iterator<char>(summary)),
                   std::istreambuf_iterator<char>());
  AssertThrow(text.find("\"coupled_matrix_rcond\"") != std::string::npos &&
                text.find("\"foundation_block_rcond\"") != std::string::npos,
              ExcMessage("condition estimates missing in summary.json"));
  deallog << "summary.json reports coupled_matrix_rcond and "
             "foundation_block_rcond"
          << std::endl;
}
