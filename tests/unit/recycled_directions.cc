// Recycled directions of the iterative contact solver (doc/formulation.md,
// "Recycled directions"): after solve(), ContactSolver::solve_linearised()
// (the goal's adjoint, a bonded sweep's next position) runs deflated
// conjugate gradients with the conjugate directions of the earlier solves
// on the same contact set. On example 2 (Galerkin; tensionless with its
// ends lifted off, and bonded) and under a second, unsymmetric load:
//  - the iterative solver's answer equals the direct solver's
//    solve_linearised() of the same load to 1e-8 (w, nodal q);
//  - the same load solved again lies in the span of the directions the
//    first linearised solve recorded: at most 2 CG iterations, and the
//    same answer to 1e-8;
//  - a third load, between the two, takes fewer iterations than the first
//    linearised solve;
//  - solve() again (a new cycle or load) forgets the directions: its
//    answer equals the first solve()'s to 1e-10.
// A plate 1000 times more flexible: under the soil inverse its first solve
// fills the record, and the second load takes fewer than half its
// iterations; under the plate on springs to 1e-12 its solves end at the
// rounding floor and keep no directions (recycled, they diverged). Both
// still match the direct solver.

#include <plate_on_halfspace/contact/direct_solver.h>
#include <plate_on_halfspace/contact/iterative_solver.h>
#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

namespace
{
  /** What the directions of a scene's solves allow. */
  enum class Record
  {
    whole,            ///< every direction of each solve is kept
    full_after_first, ///< the first solve fills the record (32 directions)
    none ///< the solves end at the rounding floor and keep no directions
  };

  void
  check(const std::string                        &name,
        const std::string                        &extra,
        const bool                                tensionless,
        const Parameters::Contact::Preconditioner preconditioner =
          Parameters::Contact::Preconditioner::automatic,
        const Record record    = Record::whole,
        const double tolerance = 1e-10)
  {
    const auto          problem    = solve_scene("example2.prm", extra);
    MindlinPlate       &plate      = problem->plate();
    FoundationOperator &foundation = problem->foundation();

    Parameters::Contact contact;
    contact.method         = Parameters::Contact::Method::active_set;
    contact.max_iterations = 100;
    contact.tolerance      = 1e-10;
    ConjugateGradientControl control;
    control.tolerance      = tolerance;
    control.preconditioner = preconditioner;
    std::ostringstream     log;
    IterativeContactSolver iterative(contact, tensionless, control, 0, log);
    DirectContactSolver    direct(contact, tensionless, 0, log);
    const Vector<double>  &load  = plate.get_load_vector();
    const ContactState     first = iterative.solve(plate, foundation, load, {});
    const ContactState reference = direct.solve(plate, foundation, load, {});
    AssertThrow(first.converged && reference.converged,
                ExcMessage("not converged"));
    AssertThrow(first.active_set == reference.active_set,
                ExcMessage("the solvers' contact sets differ"));

    // An unsymmetric load of another shape, and one between the two.
    Vector<double> second(load.size()), between(load.size());
    for (unsigned int i = 0; i < load.size(); ++i)
      {
        second[i]  = load[i] * (1. + 0.5 * std::sin(0.37 * i));
        between[i] = 0.5 * (load[i] + second[i]);
      }
    const auto iterations = [](const ContactState &state) {
      unsigned int total = 0;
      for (const auto &solve : state.linear_solves)
        total += solve.iterations;
      return total;
    };
    const auto difference = [](const ContactState &a, const ContactState &b) {
      return std::max(relative_difference(a.w, b.w, Norm::max),
                      relative_difference(a.q, b.q, Norm::max));
    };

    // prints the check and its verdict, and stops the test on a failure
    const auto verdict =
      [](const std::string &check, const bool ok, const std::string &found) {
        deallog << check << ": " << (ok ? "ok" : "FAILED") << std::endl;
        AssertThrow(ok, ExcMessage(check + ": " + found));
      };

    const ContactState recycled      = iterative.solve_linearised(second);
    const ContactState direct_second = direct.solve_linearised(second);
    const double       d_direct      = difference(recycled, direct_second);
    verdict(name + ": a second load, the direct solver's w and q to 1e-8",
            d_direct <= 1e-8,
            "differs by " + std::to_string(d_direct));

    if (record == Record::whole)
      {
        const ContactState again   = iterative.solve_linearised(second);
        const double       d_again = difference(again, recycled);
        verdict("  the same load again: at most 2 CG iterations, the same "
                "w and q to 1e-8",
                iterations(again) <= 2 && d_again <= 1e-8,
                std::to_string(iterations(again)) + " iterations, differs by " +
                  std::to_string(d_again));

        const ContactState mixed        = iterative.solve_linearised(between);
        const ContactState direct_mixed = direct.solve_linearised(between);
        verdict("  a load between the two: fewer CG iterations than the "
                "second load's, the direct solver's w and q to 1e-8",
                iterations(mixed) < iterations(recycled) &&
                  difference(mixed, direct_mixed) <= 1e-8,
                std::to_string(iterations(mixed)) + " against " +
                  std::to_string(iterations(recycled)));
      }

    if (record == Record::full_after_first)
      verdict("  the second load: fewer than half the first solve's CG "
              "iterations",
              2 * iterations(recycled) < iterations(first),
              std::to_string(iterations(recycled)) + " against " +
                std::to_string(iterations(first)));

    const ContactState repeated = iterative.solve(plate, foundation, load, {});
    const double       d_repeat = difference(repeated, first);
    verdict("  solve() again: the first solve's w and q to 1e-10",
            d_repeat <= 1e-10,
            "differs by " + std::to_string(d_repeat));
  }
} // namespace

int
main()
{
  initlog();
  const std::string galerkin =
    "subsection Discretization\n set Flexibility = galerkin\nend\n";
  check("example 2, tensionless",
        galerkin + "subsection Contact\n set Method = active set\nend\n",
        true);
  check("example 2, bonded",
        galerkin + "subsection Foundation\n set Contact = bonded\nend\n",
        false);
  // A plate 1000 times more flexible under the soil inverse: its first
  // solve takes some 240 iterations, whose directions lose their
  // conjugacy, so the Gram matrix's smallest eigenvalues are dropped
  // (on the development machine 4 to 6 of 32 directions per solve).
  check("flexible plate (E = 2.5e4), bonded, soil inverse",
        galerkin + "subsection Foundation\n set Contact = bonded\nend\n"
                   "subsection Plate\n set Young's modulus = 2.5e4\nend\n"
                   "subsection Discretization\n set Subdivisions x = 24\n"
                   " set Subdivisions y = 16\nend\n",
        false,
        Parameters::Contact::Preconditioner::soil_inverse,
        Record::full_after_first,
        1e-10);
  // The same plate under the plate on springs: its solves end at the
  // rounding floor (about 1e-11 of the settlement, above the tolerance
  // 1e-12), where the products H p have too few digits left for W^T H W;
  // such solves leave no directions (deflated, this scene diverged).
  check("flexible plate (E = 2.5e4), bonded, plate on springs",
        galerkin + "subsection Foundation\n set Contact = bonded\nend\n"
                   "subsection Plate\n set Young's modulus = 2.5e4\nend\n"
                   "subsection Discretization\n set Subdivisions x = 24\n"
                   " set Subdivisions y = 16\nend\n",
        false,
        Parameters::Contact::Preconditioner::plate_on_springs,
        Record::none,
        1e-12);
}
