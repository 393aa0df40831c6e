// Zero-energy modes of the Mindlin plate stiffness (MindlinPlate) for every
// element (serendipity, heterosis, lagrange) and integration (reduced =
// bending and shear 2x2, selective = bending 3x3 and shear 2x2, full = both
// 3x3), on free (unsupported) meshes: one square cell, one distorted cell, a
// 2x2 and a 4x4 mesh of square cells. The stiffness is restricted to the
// unconstrained DoFs (the element variants are cell-centre constraints) and
// its eigenvalues are computed densely (LAPACK); an eigenvalue is zero when
// it is below 1e-10 times the largest. A free plate has 3 rigid modes (w = 1;
// w = x, beta_x = 1; w = y, beta_y = 1); any further zero is a spurious
// mode. Besides the count, the nullity of the w-block K_ww (null vectors with
// beta = 0, minus the rigid translation) and of the beta-block K_bb (null
// vectors with w = 0) tell pure-w and pure-rotation spurious modes apart.
// The expected counts are the ones of Hughes, "The Finite Element Method",
// ch. 5 (Mindlin plates): 8-node 2x2: 1 spurious mode, not communicable to
// a mesh; 9-node 2x2 everywhere: 4 (rank deficient, some communicable);
// 9-node selective: 1, the communicable w-mode w = (3 xi^2 - 1)(3 eta^2 - 1)
// with zero gradient at the 2x2 points; heterosis selective: none; full
// integration: none.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/function.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <deal.II/numerics/vector_tools.h>

#include <plate_on_halfspace/mindlin_plate.h>
#include <plate_on_halfspace/parameters.h>

#include <algorithm>
#include <array>
#include <memory>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  /** Plate of thickness 0.1, D = 1, nu = 0.3, with the given variant. */
  SceneParameters
  parameters(const std::string &element, const std::string &integration)
  {
    const double       t = 0.1;
    std::ostringstream text;
    text << std::setprecision(17) << "subsection Plate\n"
         << "  set Thickness = " << t << "\n"
         << "  set Young's modulus = " << 10.92 / (t * t * t) << "\n"
         << "  set Poisson's ratio = 0.3\n"
         << "end\n"
         << "subsection Discretization\n"
         << "  set Element = " << element << "\n"
         << "  set Shear integration = " << integration << "\n"
         << "end\n";
    SceneParameters parameters;
    parameters.read_from_string(text.str());
    return parameters;
  }



  /** Number of zero eigenvalues (below 1e-10 times the largest) of the
   * symmetric matrix @p matrix, and the separation of the spectrum: the
   * largest "zero" and the smallest non-zero eigenvalue, relative to the
   * largest. */
  struct Spectrum
  {
    unsigned int n_zero            = 0;
    double       largest_zero      = 0;
    double       smallest_non_zero = 0;
  };

  Spectrum
  spectrum(const FullMatrix<double> &matrix)
  {
    Spectrum result;
    if (matrix.m() == 0)
      return result;
    LAPACKFullMatrix<double> lapack(matrix.m());
    lapack = matrix;
    lapack.compute_eigenvalues();
    std::vector<double> eigenvalues(matrix.m());
    for (unsigned int i = 0; i < matrix.m(); ++i)
      eigenvalues[i] = std::abs(lapack.eigenvalue(i).real());
    std::sort(eigenvalues.begin(), eigenvalues.end());
    const double largest = eigenvalues.back();
    for (const double lambda : eigenvalues)
      if (lambda < 1e-10 * largest)
        {
          ++result.n_zero;
          result.largest_zero = lambda / largest;
        }
    result.smallest_non_zero =
      (result.n_zero < eigenvalues.size() ? eigenvalues[result.n_zero] /
                                              largest :
                                            0.);
    return result;
  }



  /** The stiffness restricted to the unconstrained DoFs of the components
   * selected by @p use_component, plus @p w_spring on the diagonal of the
   * w-DoFs (nodal springs standing in for a foundation, which resists w
   * only). */
  FullMatrix<double>
  restricted_stiffness(const MindlinPlate        &plate,
                       const std::array<bool, 3> &use_component,
                       const double               w_spring = 0.)
  {
    const auto                          &dof_handler = plate.get_dof_handler();
    const auto                          &constraints = plate.get_constraints();
    const auto                          &fe          = plate.get_fe();
    std::vector<int>                     component(dof_handler.n_dofs(), -1);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          component[dofs[i]] = fe.system_to_component_index(i).first;
      }
    std::vector<types::global_dof_index> selected;
    for (types::global_dof_index i = 0; i < dof_handler.n_dofs(); ++i)
      if (!constraints.is_constrained(i) && use_component[component[i]])
        selected.push_back(i);

    const auto        &stiffness = plate.get_stiffness_matrix();
    FullMatrix<double> matrix(selected.size(), selected.size());
    for (unsigned int i = 0; i < selected.size(); ++i)
      {
        for (unsigned int j = 0; j < selected.size(); ++j)
          matrix(i, j) = stiffness.el(selected[i], selected[j]);
        if (component[selected[i]] == 0)
          matrix(i, i) += w_spring;
      }
    return matrix;
  }



  void
  check_count(const std::string &name,
              const unsigned int computed,
              const unsigned int expected)
  {
    const bool ok = (computed == expected);
    deallog << name << ": computed " << computed << " expected " << expected
            << " " << (ok ? "ok" : "FAILED") << std::endl;
    if (!getenv("DRAFT"))     AssertThrow(ok, ExcMessage("check '" + name + "' failed"));
  }



  void
  check_less(const std::string &name, const double computed, const double bound)
  {
    const bool         ok = (computed < bound);
    std::ostringstream b;
    b << bound;
    deallog << name << ": computed " << computed << " bound " << b.str()
            << " " << (ok ? "ok" : "FAILED") << std::endl;
    if (!getenv("DRAFT"))     AssertThrow(ok, ExcMessage("check '" + name + "' failed"));
  }



  struct Expected
  {
    unsigned int spurious, w_only, beta_only;
  };
} // namespace



int
main()
{
  initlog();

  // Meshes: one square cell, one distorted (convex, non-parallelogram)
  // cell, 2x2 and 4x4 square cells; all free.
  std::vector<std::string>                   mesh_names = {"1 cell",
                                             "1 distorted cell",
                                             "2x2 cells",
                                             "4x4 cells",
                                             "4x4 cells, hard s.s."};
  std::vector<std::unique_ptr<Triangulation<2>>> meshes;
  for (unsigned int k = 0; k < mesh_names.size(); ++k)
    meshes.emplace_back(std::make_unique<Triangulation<2>>());
  GridGenerator::hyper_cube(*meshes[0], 0., 1.);
  GridGenerator::general_cell(*meshes[1],
                              std::vector<Point<2>>{Point<2>(0., 0.),
                                                    Point<2>(1.2, 0.1),
                                                    Point<2>(-0.1, 0.9),
                                                    Point<2>(0.8, 1.3)});
  GridGenerator::subdivided_hyper_rectangle(*meshes[2],
                                            {2, 2},
                                            Point<2>(0., 0.),
                                            Point<2>(2., 2.));
  for (const unsigned int m : {3, 4})
    GridGenerator::subdivided_hyper_rectangle(*meshes[m],
                                              {4, 4},
                                              Point<2>(0., 0.),
                                              Point<2>(4., 4.),
                                              /*colorize=*/true);
  // The last mesh with the hard simple support of the Navier test: w = 0 on
  // the boundary, beta_y = 0 on x = const, beta_x = 0 on y = const.
  const auto hard_simple_support = [](const DoFHandler<2>       &dof_handler,
                                      AffineConstraints<double> &constraints) {
    const Functions::ZeroFunction<2> zero(3);
    VectorTools::interpolate_boundary_values(
      dof_handler,
      {{0, &zero}, {1, &zero}, {2, &zero}, {3, &zero}},
      constraints,
      ComponentMask(std::vector<bool>{true, false, false}));
    VectorTools::interpolate_boundary_values(
      dof_handler,
      {{2, &zero}, {3, &zero}},
      constraints,
      ComponentMask(std::vector<bool>{false, true, false}));
    VectorTools::interpolate_boundary_values(
      dof_handler,
      {{0, &zero}, {1, &zero}},
      constraints,
      ComponentMask(std::vector<bool>{false, false, true}));
  };

  const std::vector<std::string> elements     = {"serendipity",
                                             "heterosis",
                                             "lagrange"};
  const std::vector<std::string> integrations = {"reduced",
                                                 "selective",
                                                 "full"};
  // expected[element][integration][mesh]: spurious modes (beyond the 3
  // rigid ones), of which pure w (beta = 0) and pure rotation (w = 0).
  const Expected expected[3][3][5] = {
    // serendipity
    {{{1, 0, 1}, {1, 0, 1}, {0, 0, 0}, {0, 0, 0}},
     {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}},
     {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}},
    // heterosis
    {{{3, 0, 3}, {3, 0, 3}, {0, 0, 0}, {0, 0, 0}},
     {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}},
     {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}},
    // lagrange
    {{{4, 1, 3}, {4, 1, 3}, {0, 0, 0}, {0, 0, 0}},
     {{1, 1, 0}, {1, 1, 0}, {1, 1, 0}, {1, 1, 0}},
     {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}}};

  std::ostringstream table;
  table << "element      integration  mesh              DoFs  zero  "
           "spurious  w-only  beta-only\n";
  for (unsigned int e = 0; e < 3; ++e)
    for (unsigned int s = 0; s < 3; ++s)
      for (unsigned int m = 0; m < meshes.size(); ++m)
        {
          const SceneParameters p = parameters(elements[e], integrations[s]);
          MindlinPlate          plate(p.plate, p.discretization);
          if (m == 4)
            plate.setup(*meshes[m], hard_simple_support);
          else
            plate.setup(*meshes[m]);
          const unsigned int n_rigid = (m == 4 ? 0 : 1);

          const Spectrum all = spectrum(restricted_stiffness(plate, {{1, 1, 1}}));
          const Spectrum ww  = spectrum(restricted_stiffness(plate, {{1, 0, 0}}));
          const Spectrum bb  = spectrum(restricted_stiffness(plate, {{0, 1, 1}}));
          const std::string name =
            elements[e] + " " + integrations[s] + ", " + mesh_names[m];
          const Expected &x = expected[e][s][m];

          check_count(name + ", zero eigenvalues", all.n_zero, (m == 4 ? 0 : 3) + x.spurious);
          check_count(name + ", spurious pure-w modes", ww.n_zero - n_rigid, x.w_only);
          check_count(name + ", spurious pure-rotation modes",
                      bb.n_zero,
                      x.beta_only);
          // The spectrum is well separated: zeros are round-off, the
          // smallest genuine eigenvalue is far above the threshold.
          check_less(name + ", largest zero eigenvalue / largest",
                     all.largest_zero,
                     1e-13);
          check_less(name + ", 1e-10 / (smallest non-zero / largest)",
                     1e-10 / all.smallest_non_zero,
                     1e-3);

          table << std::left << std::setw(13) << elements[e] << std::setw(13)
                << integrations[s] << std::setw(17) << mesh_names[m]
                << std::right << std::setw(5) << plate.n_unconstrained_dofs()
                << std::setw(6) << all.n_zero << std::setw(10)
                << all.n_zero - (m == 4 ? 0 : 3) << std::setw(8) << ww.n_zero - n_rigid
                << std::setw(11) << bb.n_zero << "\n";
        }
  deallog << "Summary (every row checked above):\n" << table.str() << std::endl;

  return 0;
}
