// The foundation space of a shipped scene, built as the program builds it
// (plate_on_halfspace_problem.cc): for tests of a foundation operator on
// its own.
#ifndef plate_on_halfspace_tests_foundation_scene_h
#define plate_on_halfspace_tests_foundation_scene_h

#include <deal.II/grid/tria.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/plate/plate_mesh.h>
#include <plate_on_halfspace/scene/mirror_symmetry.h>
#include <plate_on_halfspace/soil/boussinesq_kernel.h>

#include <algorithm>
#include <string>

namespace TestTools
{
  using namespace PlateOnHalfspace;

  /** The foundation space of a scene, its alpha and quadrature order. */
  struct FoundationScene
  {
    FoundationSpace space;
    double          alpha;
    unsigned int    singular_order;
  };

  /**
   * parameters/@p file with @p extra appended, cut to its symmetric part
   * as the program does; the cells within @p graded_radius of the mesh's
   * lower left corner refined @p grading_rounds more times (round k within
   * the radius over k + 1): a graded mesh with hanging nodes.
   */
  inline FoundationScene
  make_foundation_scene(const std::string &file,
                        const std::string &extra,
                        const double       graded_radius  = 0,
                        const unsigned int grading_rounds = 2)
  {
    SceneParameters parameters;
    parameters.read_from_string("include " SOURCE_DIR "/../../parameters/" +
                                file + "\nset Output directory = results\n" +
                                extra);
    Triangulation<2> mesh;
    make_coarse_plate_mesh(parameters.plate, parameters.discretization, mesh);
    const MirrorSymmetry symmetry = choose_mirror_symmetry(
      parameters, mesh, [&](const unsigned int axis, const double tolerance) {
        return reason_loads_not_symmetric(make_loads(parameters.loads, 0.),
                                          axis,
                                          tolerance);
      });
    cut_to_computed_part(symmetry, mesh);
    mesh.refine_global(parameters.discretization.initial_refinements);
    if (graded_radius > 0)
      for (unsigned int round = 0; round < grading_rounds; ++round)
        {
          Point<2> corner = mesh.begin_active()->vertex(0);
          for (const auto &cell : mesh.active_cell_iterators())
            for (const unsigned int v : cell->vertex_indices())
              corner = Point<2>(std::min(corner[0], cell->vertex(v)[0]),
                                std::min(corner[1], cell->vertex(v)[1]));
          for (const auto &cell : mesh.active_cell_iterators())
            if (cell->center().distance(corner) < graded_radius / (1 + round))
              cell->set_refine_flag();
          mesh.execute_coarsening_and_refinement();
        }
    MindlinPlate plate(parameters.plate, parameters.discretization);
    plate.set_mirror_symmetry(symmetry);
    plate.setup(mesh);
    return {
      plate.get_foundation_space(),
      boussinesq_flexibility_constant(parameters.foundation.youngs_modulus,
                                      parameters.foundation.poissons_ratio),
      parameters.discretization.singular_quadrature_order};
  }

  /** The quarter of parameters/flexible-square.prm (Galerkin, mirror
   *  images in both centre lines) with @p cells x @p cells subdivisions. */
  inline FoundationScene
  flexible_square_quarter(const unsigned int cells)
  {
    return make_foundation_scene(
      "flexible-square.prm",
      "subsection Discretization\n set Flexibility = galerkin\n"
      " set Subdivisions x = " +
        std::to_string(cells) + "\n set Subdivisions y = " +
        std::to_string(cells) + "\n set Symmetry = xy\nend\n");
  }

  /** The plate's area with its mirror images, as the soil inverse takes
   *  it. */
  inline double
  area_with_images(const FoundationScene &scene)
  {
    return scene.space.area() * scene.space.symmetry.n_copies();
  }

  /** The soil inverse's matrices on a scene's nodes: M and L on one
   *  pattern, and the symbolic analysis its factors share. */
  struct PressureSpaceMatrices
  {
    explicit PressureSpaceMatrices(const FoundationScene &scene)
    {
      scene.space.assemble_mass_matrix({}, sparsity, mass);
      scene.space.assemble_laplace_matrix(sparsity, laplace);
      analysis.analyze(mass);
    }

    SparsityPattern      sparsity;
    SparseMatrix<double> mass, laplace;
    SparseCholesky       analysis{"L + c M"};
  };
} // namespace TestTools

#endif
