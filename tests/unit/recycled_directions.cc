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
  void
  check(const std::string &name,
        const std::string &extra,
        const bool         tensionless)
  {
    const auto          problem    = solve_scene("example2.prm", extra);
    MindlinPlate       &plate      = problem->plate();
    FoundationOperator &foundation = problem->foundation();

    Parameters::Contact contact;
    contact.method         = Parameters::Contact::Method::active_set;
    contact.max_iterations = 100;
    contact.tolerance      = 1e-10;
    ConjugateGradientControl control;
    control.tolerance = 1e-12;
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

    const ContactState recycled      = iterative.solve_linearised(second);
    const ContactState direct_second = direct.solve_linearised(second);
    const double       d_direct      = difference(recycled, direct_second);
    deallog << name << ": a second load, the direct solver's w and q to 1e-8: "
            << (d_direct <= 1e-8 ? "ok" : "FAILED") << std::endl;
    AssertThrow(d_direct <= 1e-8,
                ExcMessage("differs by " + std::to_string(d_direct)));

    const ContactState again    = iterative.solve_linearised(second);
    const double       d_again  = difference(again, recycled);
    const bool         again_ok = iterations(again) <= 2 && d_again <= 1e-8;
    deallog << "  the same load again: at most 2 CG iterations, the same "
               "w and q to 1e-8: "
            << (again_ok ? "ok" : "FAILED") << std::endl;
    AssertThrow(again_ok,
                ExcMessage(std::to_string(iterations(again)) +
                           " iterations, differs by " +
                           std::to_string(d_again)));

    const ContactState mixed        = iterative.solve_linearised(between);
    const ContactState direct_mixed = direct.solve_linearised(between);
    const bool         mixed_ok = iterations(mixed) < iterations(recycled) &&
                          difference(mixed, direct_mixed) <= 1e-8;
    deallog << "  a load between the two: fewer CG iterations than the "
               "second load's, the direct solver's w and q to 1e-8: "
            << (mixed_ok ? "ok" : "FAILED") << std::endl;
    AssertThrow(mixed_ok,
                ExcMessage(std::to_string(iterations(mixed)) + " against " +
                           std::to_string(iterations(recycled))));

    const ContactState repeated = iterative.solve(plate, foundation, load, {});
    const double       d_repeat = difference(repeated, first);
    deallog << "  solve() again: the first solve's w and q to 1e-10: "
            << (d_repeat <= 1e-10 ? "ok" : "FAILED") << std::endl;
    AssertThrow(d_repeat <= 1e-10,
                ExcMessage("differs by " + std::to_string(d_repeat)));
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
}
