// The settlement at many points through the fft storage's split kernel
// (SplitKernelFftOperator::grid_settlement_at_points()), which a goal's
// error estimate uses on large meshes: the far field's grid potentials read
// at the points, the near field integrated over the cells within the
// cutoff. Against the exactly integrated settlement_at_points()
// (soil/surface_settlement.h) at every point: the 4 x 4 Gauss points of
// every cell, where the estimate's half-space residual evaluates it.
// - example 2 made tensionless (Galerkin, quarter by Symmetry = xy: the
//   mirror images enter the grid and the near field), at the tolerances
//   1e-6 and 1e-8;
// - the bonded example 2 on the whole plate;
// - example 2 after an adaptive refinement (hanging nodes, cells of two
//   sizes: sigma is the median cell, the larger cells take more points);
// - the distorted Gmsh square, a concrete slab (general quadrilaterals of
//   many shapes: the near field's pairs integrated one by one, not shared
//   by translates);
// the largest difference relative to the largest settlement within 10
// times the tolerance. Points off the grid are not served (grid_serves()).

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <plate_on_halfspace/halfspace/split_kernel_operator.h>
#include <plate_on_halfspace/plate_on_halfspace_problem.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <chrono>
#include <iostream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

namespace
{
  void
  compare(const std::string &label,
          const std::string &scene,
          const std::string &extra,
          const double       tolerance)
  {
    std::ostringstream storage;
    storage << "subsection Foundation operator\n set Storage = fft\n"
            << " set Tolerance = " << tolerance << "\nend\n"
            << "subsection Contact\n set Solver = iterative\nend\n";
    const auto             problem = solve_scene(scene, extra + storage.str());
    const FoundationSpace &space   = problem->plate().get_foundation_space();
    Vector<double>         pressure;
    problem->foundation().nodal_pressure(problem->contact_state().q, pressure);
    const auto &fft =
      dynamic_cast<const SplitKernelFftOperator &>(problem->foundation());
    const auto &soil = dynamic_cast<const ElasticSoil &>(fft.soil());
    const std::vector<Point<2>> points = cell_gauss_points(problem->plate());

    auto                      start = std::chrono::steady_clock::now();
    const std::vector<double> exact =
      settlement_at_points(space,
                           pressure,
                           points,
                           soil.kernel(maximal_distance(space)),
                           soil.singular_quadrature_order());
    const double exact_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
    double scale = 0;
    for (const double u : exact)
      scale = std::max(scale, std::abs(u));
    std::ostringstream name;
    name << label << ", tolerance " << tolerance;
    deallog << name.str() << ": " << space.n_nodes() << " foundation nodes, "
            << points.size() << " points" << std::endl;
    require(" the grid serves every point", fft.grid_serves(space, points));
    start = std::chrono::steady_clock::now();
    const std::vector<double> grid =
      fft.grid_settlement_at_points(space, pressure, points);
    const double grid_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
    double difference = 0;
    for (unsigned int p = 0; p < points.size(); ++p)
      difference = std::max(difference, std::abs(grid[p] - exact[p]));
    std::cerr << label << " tolerance " << tolerance << ": error "
              << difference / scale << ", points x loaded cells "
              << double(points.size()) *
                   FoundationOperator::n_loaded_cells(space, pressure)
              << ", exact " << exact_time << " s, grid " << grid_time << " s"
              << std::endl;
    check_below(" largest difference / largest settlement",
                difference / scale,
                10 * tolerance);
    require(" a point beyond the plate is off the grid",
            !fft.grid_serves(space, {Point<2>(1e3, 1e3)}));
  }
} // namespace

int
main()
{
  initlog();
  const std::string galerkin = "subsection Discretization\n"
                               " set Flexibility = galerkin\n"
                               " set Subdivisions x = 48\n"
                               " set Subdivisions y = 32\n";
  const std::string active_set =
    "subsection Contact\n set Method = active set\nend\n";
  for (const double tolerance : {1e-6, 1e-8})
    compare("example 2, tensionless, quarter",
            "example2.prm",
            galerkin + " set Symmetry = xy\nend\n" + active_set,
            tolerance);
  compare("example 2, bonded, whole plate",
          "example2-bonded.prm",
          galerkin + " set Symmetry = none\nend\n",
          1e-6);
  compare(
    "distorted Gmsh square",
    "flexible-square.prm",
    "subsection Plate\n set Shape = mesh file\n set Mesh file = " SOURCE_DIR
    "/../data/distorted-square.msh\n set Thickness = 0.3\n"
    " set Young's modulus = 3e7\nend\n"
    "subsection Verification\n set Checks =\nend\n"
    "subsection Discretization\n set Flexibility = galerkin\n"
    " set Initial refinements = 2\n set Symmetry = none\nend\n",
    1e-6);
  compare("example 2, tensionless, adaptive, quarter",
          "example2.prm",
          "subsection Discretization\n set Flexibility = galerkin\n"
          " set Subdivisions x = 24\n set Subdivisions y = 16\n"
          " set Symmetry = xy\nend\n"
          "subsection Adaptivity\n set Cycles = 2\n"
          " set Refinement = adaptive\n set Refine fraction = 0.3\nend\n" +
            active_set,
          1e-6);
}
