// Zero-energy modes of the Mindlin plate stiffness (MindlinPlate) for every
// element (serendipity, heterosis, lagrange) and integration (reduced =
// bending and shear 2x2, selective = bending 3x3 and shear 2x2, full = both
// 3x3), thickness 0.1, D = 1, nu = 0.3, on: one square cell, one distorted
// cell, 2x2 and 4x4 meshes of unit square cells, all free; the 4x4 mesh
// with nodal springs on the w-DoFs (a foundation resists w only); the 4x4
// mesh with the hard simple support of the Navier test. The stiffness is
// restricted to the unconstrained DoFs (the element variants are cell-centre
// constraints) and its eigenvalues are computed densely (LAPACK); an
// eigenvalue is zero when it is below 1e-10 times the largest (the zeros
// found are below 1e-13, the other eigenvalues above 1e-7 times the
// largest). A free plate has 3 rigid modes (w = 1; w = x, beta_x = 1;
// w = y, beta_y = 1); any further zero is a spurious mode. The nullity of the
// w-block K_ww (null vectors with beta = 0, less the rigid translation) and
// of the rotation block K_bb (null vectors with w = 0) tell pure-w and
// pure-rotation spurious modes apart.
// Found (and asserted):
// - serendipity 2x2 (reduced): 1 spurious pure-rotation mode per cell, not
//   communicable (gone on 2x2 cells); selective and full: none.
// - lagrange 2x2 everywhere (reduced): 4, the w-mode and 3 pure-rotation
//   modes, all communicable (they survive on free meshes; springs on w leave
//   the 3 rotation modes).
// - lagrange selective: 1, the communicable w-mode (w = (3 xi^2 - 1)
//   (3 eta^2 - 1) per cell, zero gradient at the 2x2 points); any w support
//   removes it from the count.
// - heterosis selective: none (its serendipity w removes the w-mode);
//   heterosis reduced: the 3 communicable pure-rotation modes of the Q2
//   rotations with 2x2 bending, which w springs do not remove.
// - full integration: none.
// - hard simple support removes every spurious mode on 4x4 cells.

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

#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;


namespace
{
  /** Plate of thickness 0.1, D = 1, nu = 0.3, with the given variant. */



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
    result.smallest_non_zero = (result.n_zero < eigenvalues.size() ?
                                  eigenvalues[result.n_zero] / largest :
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
    AssertThrow(ok, ExcMessage("check '" + name + "' failed"));
  }



  enum class Support
  {
    free,
    w_springs,
    hard_simple_support
  };


  struct Case
  {
    std::string                       name;
    std::unique_ptr<Triangulation<2>> mesh;
    Support                           support;
  };

  /** Expected spurious modes (zero eigenvalues beyond the rigid modes) and
   * how many null vectors have beta = 0 (beyond the rigid translation) and
   * w = 0. */
  struct Expected
  {
    unsigned int spurious, w_only, beta_only;
  };
} // namespace



int
main()
{
  initlog();

  std::vector<Case> cases;
  for (const auto &[name, support] :
       std::vector<std::pair<std::string, Support>>{
         {"1 cell", Support::free},
         {"1 distorted cell", Support::free},
         {"2x2 cells", Support::free},
         {"4x4 cells", Support::free},
         {"4x4 cells, w springs", Support::w_springs},
         {"4x4 cells, hard s.s.", Support::hard_simple_support}})
    cases.push_back({name, std::make_unique<Triangulation<2>>(), support});
  GridGenerator::hyper_cube(*cases[0].mesh, 0., 1.);
  // A convex cell that is not a parallelogram.
  GridGenerator::general_cell(*cases[1].mesh,
                              std::vector<Point<2>>{Point<2>(0., 0.),
                                                    Point<2>(1.2, 0.1),
                                                    Point<2>(-0.1, 0.9),
                                                    Point<2>(0.8, 1.3)});
  GridGenerator::subdivided_hyper_rectangle(*cases[2].mesh,
                                            {2, 2},
                                            Point<2>(0., 0.),
                                            Point<2>(2., 2.));
  for (const unsigned int m : {3, 4, 5})
    GridGenerator::subdivided_hyper_rectangle(*cases[m].mesh,
                                              {4, 4},
                                              Point<2>(0., 0.),
                                              Point<2>(4., 4.),
                                              /*colorize=*/true);

  const std::vector<std::string> elements     = {"serendipity",
                                                 "heterosis",
                                                 "lagrange"};
  const std::vector<std::string> integrations = {"reduced",
                                                 "selective",
                                                 "full"};
  // expected[element][integration][case], cases as above.
  const Expected none              = {0, 0, 0};
  const Expected expected[3][3][6] = {
    // serendipity: one pure-rotation mode per cell with 2x2 bending, not
    // communicable (gone on 2x2 cells).
    {{{1, 0, 1}, {1, 0, 1}, none, none, none, none},
     {none, none, none, none, none, none},
     {none, none, none, none, none, none}},
    // heterosis: the Q2 rotations with 2x2 bending have 3 pure-rotation
    // modes, communicable, not suppressed by a foundation (which acts on w
    // only); selective removes the w-mode of the lagrange element.
    {{{3, 0, 3}, {3, 0, 3}, {3, 0, 3}, {3, 0, 3}, {3, 0, 3}, none},
     {none, none, none, none, none, none},
     {none, none, none, none, none, none}},
    // lagrange: 2x2 everywhere: the w-mode and 3 pure-rotation modes, all
    // communicable; selective: the communicable w-mode (suppressed by any w
    // support).
    {{{4, 1, 3}, {4, 1, 3}, {4, 1, 3}, {4, 1, 3}, {3, 0, 3}, none},
     {{1, 1, 0}, {1, 1, 0}, {1, 1, 0}, {1, 1, 0}, none, none},
     {none, none, none, none, none, none}}};

  std::ostringstream table;
  table << "element      integration  mesh                   DoFs  zero  "
           "spurious  w-only  beta-only\n";
  for (unsigned int e = 0; e < 3; ++e)
    for (unsigned int s = 0; s < 3; ++s)
      for (unsigned int m = 0; m < cases.size(); ++m)
        {
          const SceneParameters p =
            unit_rigidity_plate(elements[e], integrations[s], 0.1);
          MindlinPlate plate(p.plate, p.discretization);
          if (cases[m].support == Support::hard_simple_support)
            plate.setup(*cases[m].mesh, hard_simple_support);
          else
            plate.setup(*cases[m].mesh);
          // Springs of the order of the stiffness entries (D = 1, h = 1).
          const double spring =
            (cases[m].support == Support::w_springs ? 1. : 0.);
          const unsigned int n_rigid =
            (cases[m].support == Support::free ? 3 : 0);

          const Spectrum all =
            spectrum(restricted_stiffness(plate, {{1, 1, 1}}, spring));
          const Spectrum ww =
            spectrum(restricted_stiffness(plate, {{1, 0, 0}}, spring));
          const Spectrum bb =
            spectrum(restricted_stiffness(plate, {{0, 1, 1}}, spring));
          const std::string name =
            elements[e] + " " + integrations[s] + ", " + cases[m].name;
          const Expected &x = expected[e][s][m];

          check_count(name + ", zero eigenvalues",
                      all.n_zero,
                      n_rigid + x.spurious);
          check_count(name + ", spurious modes with beta = 0",
                      ww.n_zero - (n_rigid > 0 ? 1 : 0),
                      x.w_only);
          check_count(name + ", spurious modes with w = 0",
                      bb.n_zero,
                      x.beta_only);
          // The spectrum is well separated: the zeros are round-off, the
          // smallest genuine eigenvalue is far above the threshold.
          check_below(name + ", largest zero eigenvalue / largest",
                      all.largest_zero,
                      1e-13);
          check_greater(name + ", smallest non-zero eigenvalue / largest",
                        all.smallest_non_zero,
                        1e-7);

          table << std::left << std::setw(13) << elements[e] << std::setw(13)
                << integrations[s] << std::setw(22) << cases[m].name
                << std::right << std::setw(5) << plate.n_unconstrained_dofs()
                << std::setw(6) << all.n_zero << std::setw(10)
                << all.n_zero - n_rigid << std::setw(8)
                << ww.n_zero - (n_rigid > 0 ? 1 : 0) << std::setw(11)
                << bb.n_zero << "\n";
        }
  deallog << "Summary (every row checked above):\n" << table.str() << std::endl;

  return 0;
}
