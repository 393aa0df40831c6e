// Extreme scenes other than thickness and stiffness ratio
// (thin_plate_limit, stiffness_ratio_sweep): Poisson's ratios, load
// magnitude, awkward geometry and contact on the edge of lift-off. Base
// scene: a 4 m square of parameters/flexible-square.prm made a 0.2 m
// concrete slab (E = 2.5e7) on 8 x 8 cells, Galerkin, tensionless, soil
// E0 = 5e4. Every run must converge with equilibrium to 1e-12 and the
// discrete contact conditions to 1e-12 (complementarity_violation). Exact
// or independent values:
// - Poisson's ratio of the soil enters only through E* = E0/(1 - nu0^2):
//   at fixed E* the answer must not change (1e-12) from nu0 = 0 to 0.499;
//   at fixed E0 it must fall monotonically and without a jump;
// - Poisson's ratio of the plate at fixed D, 0 ... 0.49: no jumps;
// - the tensionless problem is positively homogeneous: loads times
//   1e-6 ... 1e9 give deflections times the same factor (1e-12) and the
//   same contact set;
// - a 50 m x 1 m flexible slab (1:50, collocation): the closed-form
//   settlement of the rectangle at its centre (doc/formulation.md) to 1e-10;
// - a point load 1e-6 off a node differs from the one on it by O(1e-6);
// - a patch half off the plate: the part on it is applied (exactly, 1e-12)
//   and a warning of the run says so;
// - a load near a corner on stiff soil converges for plates from flexible
//   to stiff, and the plate lifts off almost entirely (contact < 0.1);
//   a point load on the edge of a weightless plate is refused with a clear
//   message, and carried once the plate has its weight;
// - a near-rigid disk (parameters/rigid-disk.prm) stays in full contact
//   for an eccentricity e < a/3, just lifts at e = a/3 (incipient lift-off),
//   lifts more as e grows and almost entirely (contact < 0.1) at 0.95 a;
// - a slab curled on rock, whose active set meets a tensile node that no
//   set without it carries, is carried by the exchange step
//   (ActiveSetUpdate) and not called a mechanism, with either solver and
//   its goal estimated; where it bears on isolated nodes the run warns
//   that the mesh does not resolve the contact region.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>
#include <plate_on_halfspace/scene/input_checks.h>
#include <plate_on_halfspace/soil/boussinesq_kernel.h>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

namespace
{
  const std::string slab =
    "subsection Plate\n set Thickness = 0.2\n set Young's modulus = 2.5e7\n"
    "end\nsubsection Foundation\n set Contact = tensionless\nend\n"
    "subsection Discretization\n set Subdivisions x = 8\n"
    " set Subdivisions y = 8\n set Flexibility = galerkin\nend\n"
    "subsection Output\n set Probe points = 0,0 ; 2,2 ; -2,-2\nend\n";
  const std::string corner_patch =
    "subsection Loads\n set Uniform pressure = 0\n"
    " set Rectangular patches = 0,0,2,2,100\nend\n";

  /** Solve, check convergence, equilibrium and complementarity. */
  ResultRecord
  solve(const std::string &scene,
        const std::string &extra,
        const std::string &label)
  {
    const auto          problem = solve_scene(scene, extra);
    const ResultRecord &s       = problem->summaries().back();
    AssertThrow(s.flag("converged"), ExcMessage(label + ": not converged"));
    AssertThrow(std::abs(s.number("contact_force") -
                         s.number("applied_load")) <=
                  1e-12 * std::abs(s.number("applied_load")),
                ExcMessage(label + ": equilibrium"));
    AssertThrow(s.number("complementarity_violation") <= 1e-12,
                ExcMessage(label + ": complementarity"));
    // For the record, 4 digits (the checks are the assertions above and in
    // main()): the contact solve changes later digits with the CPU.
    deallog << label << ": w(0,0) = " << std::setprecision(4)
            << (s.items("probes").empty() ? 0. :
                                            s.items("probes")[0].number("w"))
            << ", contact iterations " << s.count("contact_iterations")
            << ", contact area fraction " << s.number("contact_area_fraction")
            << std::setprecision(10) << std::endl;
    return s;
  }

  std::string
  entry(const std::string &section, const std::string &name, const double v)
  {
    std::ostringstream s;
    s << std::setprecision(17) << "subsection " << section << "\n set " << name
      << " = " << v << "\nend\n";
    return s.str();
  }
} // namespace

int
main()
{
  initlog();

  // Soil: E* fixed (the answer must not move), then E0 fixed.
  const double              soil_star = 5e4 / (1 - 0.09);
  std::vector<double>       soil_nus  = {0., 0.1, 0.3, 0.45, 0.49, 0.499};
  std::vector<ResultRecord> at_fixed_star, at_fixed_e0;
  for (const double nu0 : soil_nus)
    {
      const std::string nu = entry("Foundation", "Poisson's ratio", nu0);
      at_fixed_star.push_back(solve(
        "flexible-square.prm",
        slab + corner_patch + nu +
          entry("Foundation", "Young's modulus", soil_star * (1 - nu0 * nu0)),
        "soil nu0 = " + std::to_string(nu0) + ", E* fixed"));
      at_fixed_e0.push_back(
        solve("flexible-square.prm",
              slab + corner_patch + nu,
              "soil nu0 = " + std::to_string(nu0) + ", E0 fixed"));
    }
  for (unsigned int i = 1; i < soil_nus.size(); ++i)
    {
      for (unsigned int k = 0; k < 3; ++k)
        AssertThrow(
          std::abs(at_fixed_star[i].items("probes")[k].number("w") -
                   at_fixed_star[0].items("probes")[k].number("w")) <=
            1e-12 * std::abs(at_fixed_star[0].items("probes")[k].number("w")),
          ExcMessage("E* invariance"));
      const double w0 = at_fixed_e0[i - 1].items("probes")[0].number("w"),
                   w1 = at_fixed_e0[i].items("probes")[0].number("w");
      // dw/dnu0 = w * d ln(E*)/dnu0-ish: bounded by 2 w per unit of nu0
      AssertThrow(w1 < w0 &&
                    (w0 - w1) <= 2 * w0 * (soil_nus[i] - soil_nus[i - 1]),
                  ExcMessage("soil Poisson sweep not monotone or jumps"));
    }
  deallog << "soil: E* fixed, w unchanged to 1e-12 for nu0 = 0 ... 0.499; "
             "E0 fixed, w(0,0) falls monotonically without jumps"
          << std::endl;

  // Plate at fixed D = E t^3 / (12 (1 - nu^2)).
  const std::vector<double> plate_nus = {0., 0.1, 0.3, 0.45, 0.49};
  std::vector<double>       plate_w;
  for (const double nu : plate_nus)
    plate_w.push_back(
      solve("flexible-square.prm",
            slab + corner_patch + entry("Plate", "Poisson's ratio", nu) +
              entry("Plate", "Young's modulus", 2.5e7 * (1 - nu * nu) / 0.91),
            "plate nu = " + std::to_string(nu) + ", D fixed")
        .items("probes")[0]
        .number("w"));
  for (unsigned int i = 1; i < plate_nus.size(); ++i)
    AssertThrow(std::abs(plate_w[i] - plate_w[i - 1]) <=
                  0.1 * plate_w[0] * (plate_nus[i] - plate_nus[i - 1]),
                ExcMessage("plate Poisson sweep jumps"));
  deallog << "plate: |dw(0,0)/dnu| < 0.1 w for nu = 0 ... 0.49" << std::endl;

  // Positive homogeneity over 15 decades of load.
  ResultRecord reference;
  for (const double factor : {1., 1e-6, 1e-3, 1e3, 1e6, 1e9})
    {
      std::ostringstream loads;
      loads << std::setprecision(17)
            << "subsection Loads\n set Uniform pressure = 0\n"
            << " set Rectangular patches = 0,0,2,2," << 100 * factor
            << "\n set Point loads = -1.5,1.5," << 50 * factor << "\nend\n";
      std::ostringstream label;
      label << "loads x " << factor;
      const ResultRecord s =
        solve("flexible-square.prm", slab + loads.str(), label.str());
      if (factor == 1.)
        reference = s;
      for (unsigned int k = 0; k < 3; ++k)
        AssertThrow(std::abs(s.items("probes")[k].number("w") / factor -
                             reference.items("probes")[k].number("w")) <=
                      1e-12 *
                        std::abs(reference.items("probes")[0].number("w")),
                    ExcMessage("not homogeneous: " + label.str()));
      AssertThrow(s.count("contact_nodes") == reference.count("contact_nodes"),
                  ExcMessage("contact set changed: " + label.str()));
    }
  deallog << "w / load factor unchanged to 1e-12 for 1e-6 ... 1e9, same "
             "contact set"
          << std::endl;

  // A 1:50 flexible slab: the closed-form settlement of the rectangle.
  const ResultRecord long_slab =
    solve("flexible-square.prm",
          "subsection Plate\n set Length x = 50\n set Length y = 1\nend\n"
          "subsection Discretization\n set Subdivisions x = 50\n"
          " set Subdivisions y = 1\nend\n"
          "subsection Output\n set Probe points = 0,0\nend\n",
          "slab 50 m x 1 m, flexible, uniform load");
  check("slab 1:50, w(0,0) against the closed form",
        long_slab.items("probes")[0].number("w"),
        100 * (1 - 0.09) / (numbers::PI * 5e4) *
          integral_of_inverse_distance_over_rectangle(
            Point<2>(0, 0), -25, 25, -0.5, 0.5),
        1e-10);

  // Loads at awkward places.
  solve("flexible-square.prm",
        slab + "subsection Loads\n set Uniform pressure = 0\n"
               " set Rectangular patches = 1.9,1.9,2,2,1000\nend\n",
        "small patch at a corner");
  // A point load on the edge of a weightless plate tilts it about the
  // edge: no contact area of finite width can carry it (the resultant of a
  // pressure on the plate lies inside it), so the program must refuse
  // (doc/errors-and-limits.md, "A resultant on the outline"); with the
  // slab's weight (24 kN/m^3) the plate is carried.
  solve("flexible-square.prm",
        slab + "subsection Plate\n set Unit weight = 24\nend\n"
               "subsection Loads\n set Uniform pressure = 0\n"
               " set Point loads = 2,0,100\nend\n",
        "point load on the edge of a 24 kN/m^3 slab");
  try
    {
      solve_scene("flexible-square.prm",
                  slab + "subsection Loads\n set Uniform pressure = 0\n"
                         " set Point loads = 2,0,100\nend\n");
      AssertThrow(false,
                  ExcMessage("a weightless plate tilting about its "
                             "edge was not refused"));
    }
  catch (const ExcMessage &error)
    {
      const std::string message = short_error_message(error);
      AssertThrow(message.find("no determinate answer") != std::string::npos &&
                    message.find("Plate/Unit weight") != std::string::npos,
                  ExcMessage("unclear refusal: " + message));
      deallog << "point load on the edge of a weightless plate: refused: "
              << message << std::endl;
    }
  const double on_node =
    solve("flexible-square.prm",
          slab + "subsection Loads\n set Uniform pressure = 0\n"
                 " set Point loads = 0.5,0.5,100\nend\n",
          "point load on a node")
      .items("probes")[0]
      .number("w");
  const double off_node =
    solve("flexible-square.prm",
          slab + "subsection Loads\n set Uniform pressure = 0\n"
                 " set Point loads = 0.500001,0.5,100\nend\n",
          "point load 1e-6 off the node")
      .items("probes")[0]
      .number("w");
  AssertThrow(std::abs(off_node - on_node) <= 1e-5 * on_node,
              ExcMessage("point load off a node jumps"));
  const std::string half_off = "subsection Loads\n set Uniform pressure = 0\n"
                               " set Rectangular patches = 1,1,3,3,100\nend\n";
  check("patch half off the plate: applied load = the part on it",
        solve("flexible-square.prm",
              slab + half_off,
              "patch half off the plate")
          .number("applied_load"),
        100.,
        1e-12);
  {
    const auto problem  = solve_scene("flexible-square.prm", slab + half_off);
    const auto warnings = warnings_but_resolution(problem->warnings());
    AssertThrow(warnings.size() == 1 &&
                  warnings[0].find("lies partly off the plate") !=
                    std::string::npos,
                ExcMessage("no warning for a patch off the plate"));
    deallog << "warning: " << warnings[0] << std::endl;
  }

  // A load near a corner (0.25 m from both edges of the 4 m slab) on stiff
  // soil (E0 = 1e8), for plates from as stiff as the soil to 1000 times
  // stiffer: the active set must converge (the checks of solve()) and the
  // weightless plate lifts off almost entirely, keeping only a region
  // around the loaded corner (larger, the stiffer the plate spreads the
  // load).
  for (const std::string modulus : {"1e8", "1e10", "1e11"})
    {
      const ResultRecord s = solve(
        "flexible-square.prm",
        slab + "subsection Plate\n set Young's modulus = " + modulus +
          "\nend\nsubsection Foundation\n set Young's modulus = 1e8\nend\n"
          "subsection Loads\n set Uniform pressure = 0\n"
          " set Point loads = 1.75,1.75,100\nend\n",
        "load near a corner on stiff soil, E = " + modulus);
      AssertThrow(s.number("contact_area_fraction") < 0.1,
                  ExcMessage("a plate loaded near a corner does not lift "
                             "off almost entirely"));
    }
  deallog << "load near a corner: contact area < 0.1 for every plate: ok"
          << std::endl;

  // Incipient lift-off of a near-rigid disk under an eccentric load.
  double previous_area = 1.;
  for (const double e : {0.3, 1. / 3, 0.34, 0.36, 0.5, 0.8, 0.95})
    {
      std::ostringstream extra;
      extra << std::setprecision(17)
            << "subsection Plate\n set Young's modulus = 3e10\nend\n"
            << "subsection Foundation\n set Contact = tensionless\nend\n"
            << "subsection Adaptivity\n set Cycles = 1\nend\n"
            << "subsection Loads\n set Point loads = " << e << ",0,1000\nend\n";
      const ResultRecord s = solve("rigid-disk.prm",
                                   extra.str(),
                                   "rigid disk, e/a = " + std::to_string(e));
      if (e < 1. / 3)
        {
          AssertThrow(s.number("contact_area_fraction") == 1.,
                      ExcMessage("lift-off below e = a/3"));
        }
      else
        {
          AssertThrow(s.number("contact_area_fraction") < previous_area,
                      ExcMessage("lift-off does not grow with e"));
        }
      previous_area = s.number("contact_area_fraction");
    }
  // the load near the edge (e = 0.95 a): only a small region around it
  // carries the disk
  AssertThrow(previous_area < 0.1,
              ExcMessage("the disk does not lift off almost entirely"));
  deallog << "rigid disk: full contact for e < a/3, lift-off growing with e, "
             "contact area < 0.1 at e = 0.95 a: ok"
          << std::endl;

  // A slab curled by a night's temperature difference on rock stiffer than
  // the concrete, on the coarse mesh of the pavement scene (l = 0.09 m
  // against cells of 0.45 m): it bears on a few nodes between its centre
  // and the tyre. The full active-set steps shrink the set to three nodes,
  // one of them tensile and no node penetrating; the resultant lies within
  // the middle third, so this is no mechanism, and the exchange of the
  // tensile node for the node that the freed tilt closes first carries on
  // to the exact discrete contact conditions (solve()'s checks).
  // The iterative solver reaches the same set of three nodes, as many as
  // the plate's rigid motions: equilibrium alone fixes the pressures there,
  // and the goal's adjoint solve on it (no resultant, so no soil scale)
  // must not search for a direction.
  const std::string curled_on_rock =
    "subsection Foundation\n set Young's modulus = 1e8\nend\n"
    "subsection Temperature\n set Difference = -20\nend\n"
    "subsection Adaptivity\n set Cycles = 1\nend\n"
    "subsection Output\n set Probe points = 0,0\nend\n";
  {
    const ResultRecord direct =
      solve("pavement-night-half-space.prm",
            curled_on_rock,
            "slab curled at -20 K on rock, 10 x 8 cells");
    AssertThrow(direct.number("contact_area_fraction") < 0.05,
                ExcMessage("a curled slab on rock bears on its centre"));
    // (its iterations and the last digits vary with the CPU: only
    // verdicts are printed)
    const auto problem =
      solve_scene("pavement-night-half-space.prm",
                  curled_on_rock +
                    "subsection Contact\n set Solver = iterative\nend\n"
                    "subsection Foundation operator\n set Storage = "
                    "dense\nend\n");
    const ResultRecord &iterative = problem->summaries().back();
    AssertThrow(iterative.flag("converged") &&
                  std::abs(iterative.number("contact_force") -
                           iterative.number("applied_load")) <=
                    1e-10 * iterative.number("applied_load") &&
                  iterative.number("complementarity_violation") <= 1e-8,
                ExcMessage("iterative solver: not carried"));
    // (the reference is itself computed: the verdict, not its digits)
    const double w_iterative = iterative.items("probes")[0].number("w"),
                 w_direct    = direct.items("probes")[0].number("w");
    AssertThrow(std::abs(w_iterative - w_direct) <= 1e-8 * std::abs(w_direct),
                ExcMessage("iterative w(0,0) differs from the direct one"));
    deallog << "  iterative w(0,0) within 1e-8 of the direct solver's: ok"
            << std::endl;
    AssertThrow(iterative.has("goal"),
                ExcMessage("no goal estimate on a three-node set"));
    // The whole plate (no mirror plane) balances on the line x = 0: the
    // third node that holds its tilt carries no pressure, either side's
    // is as valid, and the run says so.
    const auto warnings = warnings_but_resolution(problem->warnings());
    AssertThrow(warnings.size() == 1 &&
                  warnings[0].find("a knife edge") != std::string::npos,
                ExcMessage("no warning for a plate on a knife edge"));
  }
  deallog << "slab curled on rock: carried, contact area < 0.05, the goal "
             "estimated with either solver, warned of the knife edge: ok"
          << std::endl;

  // On the coarsest mesh with the tyre at the far edge the slab bears on
  // two nodes of each half and the located contact area is 0 to rounding
  // while the load is carried: the run says that the mesh does not
  // resolve the region.
  {
    const auto problem = solve_scene(
      "pavement-night-half-space.prm",
      "subsection Foundation\n set Young's modulus = 1e9\nend\n"
      "subsection Temperature\n set Difference = -30\nend\n"
      "subsection Loads\n set Circular patches = 2.1,0,0.15,700\nend\n"
      "subsection Discretization\n set Initial refinements = 0\n"
      " set Symmetry = auto\nend\n"
      "subsection Adaptivity\n set Cycles = 1\n set Refinement = global\n"
      " set Goal =\nend\n");
    const ResultRecord &s = problem->summaries().back();
    AssertThrow(s.flag("converged") && std::abs(s.number("contact_force") -
                                                s.number("applied_load")) <=
                                         1e-12 * s.number("applied_load"),
                ExcMessage("the slab on two nodes is not carried"));
    const auto warnings = warnings_but_resolution(problem->warnings());
    AssertThrow(warnings.size() == 1 &&
                  warnings[0].find("smaller than one of the cells") !=
                    std::string::npos,
                ExcMessage("no warning for an unresolved contact region"));
    AssertThrow(s.number("contact_area_fraction") < 1e-3,
                ExcMessage("the located area is not 0 to rounding"));
    deallog << "slab on two nodes: carried, contact area < 1e-3, warned "
               "that the mesh does not resolve it: ok"
            << std::endl;
  }
}
