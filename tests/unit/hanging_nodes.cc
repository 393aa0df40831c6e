// Hanging nodes inside the plate and the dense foundation block
// (doc/formulation.md, "Adaptive refinement": only unconstrained w-DOFs carry
// foundation unknowns). The flexible square of parameters/flexible-square.prm
// with the Galerkin operator on
//  (a) a mesh with the cells x < 0 refined once (hanging nodes along x = 0),
//  (b) that mesh with the rest refined too, so that the refinement covers
//      the whole plate, and
//  (c) the conforming mesh refined globally once.
// Checks: (b) and (c) give the same answer (same foundation nodes, same
// deflections) to 1e-12; on (a) the foundation nodes are exactly the
// unconstrained w-DOFs, w is continuous across the hanging edge, the
// mean settlement 1^T M w / area is exact (Galerkin: = 1^T A 1 q / area, a
// property that holds on any mesh) and equilibrium holds.

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/grid/grid_generator.h>

#include <plate_on_halfspace/contact/direct_solver.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <cmath>
#include <numeric>
#include <sstream>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  struct Solved
  {
    std::unique_ptr<MindlinPlate>       plate;
    std::unique_ptr<FoundationOperator> foundation;
    ContactState                        state;
    Vector<double>                      solution;
  };

  Solved
  solve(const SceneParameters &parameters, const Triangulation<2> &mesh)
  {
    Solved result;
    result.plate = std::make_unique<MindlinPlate>(parameters.plate,
                                                  parameters.discretization);
    result.plate->setup(mesh);
    result.plate->assemble_loads(make_loads(parameters.loads, 0.));
    result.foundation = create_foundation_operator(
      parameters,
      create_soil_model(parameters),
      Parameters::FoundationOperator::Storage::dense);
    result.foundation->build(result.plate->get_foundation_space(), {});
    std::ostringstream  log;
    DirectContactSolver solver(parameters.contact, false, 0, log);
    result.state    = solver.solve(*result.plate,
                                *result.foundation,
                                result.plate->get_load_vector(),
                                {});
    result.solution = result.state.plate_solution;
    return result;
  }
} // namespace

int
main()
{
  initlog();
  SceneParameters parameters;
  parameters.read_from_string(
    "include " SOURCE_DIR "/../../parameters/flexible-square.prm\n"
    "set Output directory = results\n"
    "subsection Discretization\n set Flexibility = galerkin\n"
    " set Subdivisions x = 4\n set Subdivisions y = 4\nend\n");

  Triangulation<2> hanging, covering, conforming;
  for (Triangulation<2> *mesh : {&hanging, &covering, &conforming})
    GridGenerator::subdivided_hyper_rectangle(*mesh,
                                              {4, 4},
                                              Point<2>(-2, -2),
                                              Point<2>(2, 2));
  for (Triangulation<2> *mesh : {&hanging, &covering})
    {
      for (const auto &cell : mesh->active_cell_iterators())
        if (cell->center()[0] < 0)
          cell->set_refine_flag();
      mesh->execute_coarsening_and_refinement();
    }
  for (const auto &cell : covering.active_cell_iterators())
    if (cell->level() == 0)
      cell->set_refine_flag();
  covering.execute_coarsening_and_refinement();
  conforming.refine_global(1);

  // (b) = (c)
  const Solved b      = solve(parameters, covering),
               c      = solve(parameters, conforming);
  const auto &nodes_b = b.plate->get_foundation_space().node_locations;
  const auto &nodes_c = c.plate->get_foundation_space().node_locations;
  AssertThrow(nodes_b.size() == nodes_c.size(),
              ExcMessage("different numbers of foundation nodes"));
  double largest = 0, w_max = 0;
  for (const Point<2> &x : nodes_c)
    {
      const double wb = b.plate->point_value(b.solution, x),
                   wc = c.plate->point_value(c.solution, x);
      largest         = std::max(largest, std::abs(wb - wc));
      w_max           = std::max(w_max, std::abs(wc));
    }
  deallog << "refinement in two steps covering the plate vs global: "
          << nodes_b.size() << " foundation nodes each, largest difference of "
          << "w at the nodes "
          << (largest <= 1e-12 * w_max ? "<= 1e-12: ok" : "> 1e-12: FAILED")
          << std::endl;
  AssertThrow(largest <= 1e-12 * w_max, ExcMessage("(b) and (c) differ"));

  // (a) the hanging-node mesh
  const Solved   a     = solve(parameters, hanging);
  const auto    &plate = *a.plate;
  const IndexSet w_dofs =
    DoFTools::extract_dofs(plate.get_dof_handler(),
                           plate.get_fe().component_mask(
                             FEValuesExtractors::Scalar(0)));
  unsigned int n_free_w = 0, n_hanging_w = 0;
  for (const auto dof : w_dofs)
    (plate.get_constraints().is_constrained(dof) ? n_hanging_w : n_free_w)++;
  deallog << "hanging mesh: " << hanging.n_active_cells() << " cells, "
          << n_free_w << " unconstrained and " << n_hanging_w
          << " constrained w-DOFs (hanging and element centres), "
          << plate.get_foundation_dofs().size() << " foundation nodes"
          << std::endl;
  AssertThrow(plate.get_foundation_dofs().size() == n_free_w,
              ExcMessage("foundation nodes are not the unconstrained w-DOFs"));

  // continuity of w across the hanging edge x = 0: evaluate just left and
  // just right of it, in the fine and the coarse cells
  double jump = 0;
  for (double y = -1.9; y < 2; y += 0.1)
    jump = std::max(jump,
                    std::abs(plate.point_value(a.solution, Point<2>(-1e-9, y)) -
                             plate.point_value(a.solution, Point<2>(1e-9, y))));
  deallog << "largest jump of w across the hanging edge relative to max w "
          << (jump <= 1e-6 * w_max ? "<= 1e-6: ok" : "> 1e-6: FAILED")
          << std::endl;
  AssertThrow(jump <= 1e-6 * w_max, ExcMessage("w jumps at hanging nodes"));

  // mean settlement and equilibrium
  Vector<double> mw(a.state.w.size()), forces;
  a.foundation->mass_matrix().vmult(mw, a.state.w);
  const double scale = 100. * 4. * (1. - 0.09) / 5e4; // q B (1-nu0^2)/E0
  const double mean_exact =
    (4. * std::log(1. + std::sqrt(2.)) - 4. * (std::sqrt(2.) - 1.) / 3.) / M_PI;
  check("hanging mesh: mean settlement / (q B (1-nu0^2)/E0)",
        std::accumulate(mw.begin(), mw.end(), 0.) / (16. * scale),
        mean_exact,
        1e-5);
  a.foundation->nodal_forces(a.state.pressure_coefficients, forces);
  check("hanging mesh: contact force",
        std::accumulate(forces.begin(), forces.end(), 0.),
        1600.,
        1e-10);
}
