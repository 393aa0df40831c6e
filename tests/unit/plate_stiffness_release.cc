// The plate's stiffness K leaves memory once the iterative contact solver
// has factorised K^+ and preconditions with the soil inverse, which does
// not read K (MindlinPlate::release_stiffness(), doc/performance.md, "The
// plate's stiffness after its factor"); whatever reads K later gets it
// made again. Example 2 on a tensionless half-space (Galerkin, active set,
// the whole plate; the application's run solves it directly):
// - K copied, released and read again: the same pattern and values, bit
//   for bit.
// - K^+ belongs to the plate's setup: is_of() holds after a release and a
//   new read, not after setup_dofs() of the same mesh.
// - The iterative solver with the soil inverse: K released after its
//   solve; a second solve() of the same solver (a load sweep's next
//   position, which keeps K^+) gives the first one's w and q bit for bit.
//   With the plate on springs, which refactorises K + springs for each
//   contact set, K stays.
// - The direct solver after the release (it condenses K, made again): w
//   and q as the iterative solver's to 1e-8 of their largest values.
// Only verdicts are printed.

#include <plate_on_halfspace/contact/iterative_solver.h>
#include <plate_on_halfspace/plate/generalized_inverse.h>
#include <plate_on_halfspace/plate/plate_mesh.h>
#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

namespace
{
  bool
  same_matrix(const SparseMatrix<double> &a, const SparseMatrix<double> &b)
  {
    if (a.m() != b.m() || a.n_nonzero_elements() != b.n_nonzero_elements())
      return false;
    for (unsigned int i = 0; i < a.m(); ++i)
      {
        auto x = a.begin(i), y = b.begin(i);
        for (; x != a.end(i) && y != b.end(i); ++x, ++y)
          if (x->column() != y->column() || x->value() != y->value())
            return false;
        if (x != a.end(i) || y != b.end(i))
          return false;
      }
    return true;
  }

  ContactState
  solve_with(IterativeContactSolver &solver, PlateOnHalfspaceProblem &problem)
  {
    return solver.solve(problem.plate(),
                        problem.foundation(),
                        problem.plate().get_load_vector(),
                        {});
  }
} // namespace

int
main()
{
  initlog();
  const std::string scene =
    "subsection Discretization\n set Flexibility = galerkin\nend\n"
    "subsection Contact\n set Method = active set\nend\n";
  const auto    problem = solve_scene("example2.prm", scene);
  MindlinPlate &plate   = problem->plate();

  {
    SceneParameters parameters;
    parameters.read_from_string(scene_text("example2.prm", scene));
    Triangulation<2> mesh;
    make_plate_mesh(parameters.plate, parameters.discretization, mesh);
    MindlinPlate alone(parameters.plate, parameters.discretization);
    alone.setup(mesh);
    SparsityPattern      pattern;
    SparseMatrix<double> copy;
    pattern.copy_from(alone.get_stiffness_matrix().get_sparsity_pattern());
    copy.reinit(pattern);
    copy.copy_from(alone.get_stiffness_matrix());
    const PlateGeneralizedInverse inverse(alone);
    alone.release_stiffness();
    require("K released", !alone.holds_stiffness());
    require("K read again after the release: the same pattern and values, "
            "bit for bit",
            same_matrix(alone.get_stiffness_matrix(), copy) &&
              alone.holds_stiffness());
    require("K^+ is the plate's after a release and a new read",
            inverse.is_of(alone));
    alone.setup(mesh);
    require("K^+ is not the plate's after setup_dofs() of the same mesh",
            !inverse.is_of(alone));
  }

  Parameters::Contact contact;
  contact.method         = Parameters::Contact::Method::active_set;
  contact.max_iterations = 100;
  contact.tolerance      = 1e-10;
  std::ostringstream       log;
  ConjugateGradientControl control;
  control.tolerance      = 1e-12;
  control.preconditioner = Parameters::Contact::Preconditioner::soil_inverse;
  IterativeContactSolver solver(contact, true, control, 0, log);
  const ContactState     first = solve_with(solver, *problem);
  require("the iterative solve with the soil inverse released K",
          first.converged && !plate.holds_stiffness());
  const ContactState second = solve_with(solver, *problem);
  require("a second solve of the same solver: w and q bit for bit",
          second.converged && second.w == first.w && second.q == first.q);

  control.preconditioner =
    Parameters::Contact::Preconditioner::plate_on_springs;
  IterativeContactSolver on_springs(contact, true, control, 0, log);
  const ContactState     springs = solve_with(on_springs, *problem);
  require("with the plate on springs K stays",
          springs.converged && plate.holds_stiffness());

  plate.release_stiffness();
  SceneParameters parameters;
  parameters.read_from_string(scene_text("example2.prm", scene));
  const ContactState direct =
    create_contact_solver(parameters,
                          Parameters::Contact::Solver::direct,
                          0,
                          log)
      ->solve(plate, problem->foundation(), plate.get_load_vector(), {});
  const double dw = relative_difference(direct.w, first.w, Norm::max);
  const double dq = relative_difference(direct.q, first.q, Norm::max);
  require("the direct solver after the release: w and q as the iterative "
          "solver's to 1e-8",
          direct.converged && dw <= 1e-8 && dq <= 1e-8);
}
