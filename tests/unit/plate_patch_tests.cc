// Patch tests of the Mindlin plate (MindlinPlate) for every element
// (serendipity, heterosis, lagrange) and integration (reduced, selective,
// full), on a 3x3 patch of [0,1]^2 with square cells and on the same patch
// with distorted (non-parallelogram) cells, plate thickness 0.1, D = 1,
// nu = 0.3, no load. The exact fields are imposed at the boundary DoFs,
// the interior DoFs are solved for (K_ii u_i = -K_ib u_b with the stiffness
// of the unsupported plate, whose rows and columns belong to the
// unconstrained DoFs after the element's centre constraints are condensed),
// and the interior nodal values, moments and shear strains are compared
// with the exact ones.
// - Constant moment (zero shear): w = a x^2 + b y^2 + c xy + d x + e y + f,
//   beta = grad w, so kappa = (2a, 2b, 2c) and Mx = -D (2a + 2 nu b),
//   My = -D (2b + 2 nu a), Mxy = -D (1 - nu) c everywhere, gamma = 0.
// - Constant shear: with beta = 0 imposed at all beta-DoFs (the shear part
//   of the Zienkiewicz-Taylor patch test; with beta free a constant shear
//   force needs linear moments and a cubic w, which Q2 does not contain) and
//   w = f + d x + e y at the boundary: gamma = (d, e) everywhere and w
//   linear.
// Tolerance: 1e-10 relative to the size of the field (found: <= 2e-12).
// Found (and asserted): every element and integration passes both tests on
// square cells, and the constant-shear test on distorted cells. On
// distorted cells only the lagrange element passes the constant-moment
// test: the serendipity w of the serendipity and heterosis elements does not
// contain x^2 on a non-parallelogram (x is bilinear in xi, eta, so x^2 has a
// xi^2 eta^2 term), the moment error is 2e-3 to 6e-3 of the moments; it falls
// by a factor of 10 to 27 per global refinement of the patch (the children
// of a quadrilateral approach parallelograms): a weak patch test.

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;


namespace
{
  const double nu = 0.3;



  // The exact fields.
  const double a = 0.3, b = -0.2, c = 0.25, d = 0.1, e = -0.05, f = 0.02;

  std::array<double, 3>
  constant_moment(const Point<2> &p)
  {
    const double x = p[0], y = p[1];
    return {{a * x * x + b * y * y + c * x * y + d * x + e * y + f,
             2. * a * x + c * y + d,
             2. * b * y + c * x + e}};
  }

  std::array<double, 3>
  constant_shear(const Point<2> &p)
  {
    return {{f + d * p[0] + e * p[1], 0., 0.}};
  }



  struct Errors
  {
    double       nodal      = 0; ///< max |u_h - u| at the unknown DoFs
    double       moment     = 0; ///< max |M_h - M| at the sample points
    double       shear      = 0; ///< max |gamma_h - gamma| at the sample points
    unsigned int n_unknowns = 0;
  };

  /**
   * Impose @p exact at the boundary DoFs (and at all beta-DoFs if
   * @p fix_rotations), solve for the other unconstrained DoFs with the
   * plate's stiffness, and measure the errors of the nodal values, moments
   * and shear strains against the exact state (constant moments
   * @p exact_moments, constant shear strain @p exact_shear).
   */
  Errors
  patch_test(const SceneParameters                                &p,
             const Triangulation<2>                               &mesh,
             const std::function<std::array<double, 3>(Point<2>)> &exact,
             const bool                   fix_rotations,
             const std::array<double, 3> &exact_moments,
             const Tensor<1, 2>          &exact_shear)
  {
    MindlinPlate plate(p.plate, p.discretization);
    plate.setup(mesh);
    const auto        &dof_handler = plate.get_dof_handler();
    const auto        &constraints = plate.get_constraints();
    const auto        &fe          = plate.get_fe();
    const unsigned int n           = dof_handler.n_dofs();

    std::vector<Point<2>> support_points(n);
    DoFTools::map_dofs_to_support_points(MappingQ1<2>(),
                                         dof_handler,
                                         support_points);
    std::vector<unsigned int>            component(n);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          component[dofs[i]] = fe.system_to_component_index(i).first;
      }
    const IndexSet boundary = DoFTools::extract_boundary_dofs(dof_handler);

    // u = exact at the prescribed DoFs, unknowns elsewhere
    Vector<double>                       solution(n);
    std::vector<bool>                    prescribed(n, false);
    std::vector<types::global_dof_index> unknowns;
    for (types::global_dof_index i = 0; i < n; ++i)
      if (!constraints.is_constrained(i))
        {
          if (boundary.is_element(i) || (fix_rotations && component[i] > 0))
            {
              prescribed[i] = true;
              solution[i]   = exact(support_points[i])[component[i]];
            }
          else
            unknowns.push_back(i);
        }

    // K_ii u_i = -K_ib u_b (no load)
    const auto              &stiffness = plate.get_stiffness_matrix();
    LAPACKFullMatrix<double> matrix(unknowns.size());
    Vector<double>           rhs(unknowns.size());
    for (unsigned int i = 0; i < unknowns.size(); ++i)
      {
        for (unsigned int j = 0; j < unknowns.size(); ++j)
          matrix(i, j) = stiffness.el(unknowns[i], unknowns[j]);
        for (auto entry = stiffness.begin(unknowns[i]);
             entry != stiffness.end(unknowns[i]);
             ++entry)
          if (prescribed[entry->column()])
            rhs[i] -= entry->value() * solution[entry->column()];
      }
    matrix.compute_lu_factorization();
    matrix.solve(rhs);
    for (unsigned int i = 0; i < unknowns.size(); ++i)
      solution[unknowns[i]] = rhs[i];
    constraints.distribute(solution);

    Errors errors;
    errors.n_unknowns = unknowns.size();
    for (const auto i : unknowns)
      errors.nodal = std::max(errors.nodal,
                              std::abs(solution[i] -
                                       exact(support_points[i])[component[i]]));

    // moments (plate.moments) and shear strains at the 3x3 Gauss points of
    // every cell
    const QGauss<2>    points(3);
    const MappingQ1<2> mapping;
    FEValues<2> values(mapping, fe, points, update_values | update_gradients);
    std::vector<Tensor<1, 2>> grad_w(points.size());
    std::vector<Tensor<1, 2>> beta(points.size());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            const Moments m = plate.moments(cell, points.point(q), solution);
            errors.moment   = std::max({errors.moment,
                                        std::abs(m.mx - exact_moments[0]),
                                        std::abs(m.my - exact_moments[1]),
                                        std::abs(m.mxy - exact_moments[2])});
          }
        values.reinit(cell);
        values[FEValuesExtractors::Scalar(0)].get_function_gradients(solution,
                                                                     grad_w);
        values[FEValuesExtractors::Vector(1)].get_function_values(solution,
                                                                  beta);
        for (unsigned int q = 0; q < points.size(); ++q)
          errors.shear =
            std::max(errors.shear, (grad_w[q] - beta[q] - exact_shear).norm());
      }
    return errors;
  }



} // namespace



int
main()
{
  initlog();

  Triangulation<2> square_cells, distorted_cells;
  GridGenerator::subdivided_hyper_rectangle(square_cells,
                                            {3, 3},
                                            Point<2>(0., 0.),
                                            Point<2>(1., 1.));
  GridGenerator::subdivided_hyper_rectangle(distorted_cells,
                                            {3, 3},
                                            Point<2>(0., 0.),
                                            Point<2>(1., 1.));
  // Move the interior vertices and slide the boundary vertices along the
  // boundary: the patch stays the unit square, the cells become general
  // convex quadrilaterals.
  GridTools::transform(
    [](const Point<2> &p) {
      return Point<2>(p[0] + 0.09 * std::sin(numbers::PI * p[0]) *
                               std::cos(2.1 * p[1] + 0.3),
                      p[1] + 0.08 * std::sin(numbers::PI * p[1]) *
                               std::cos(1.7 * p[0] - 0.5));
    },
    distorted_cells);
  unsigned int n_non_parallelograms = 0;
  double       smallest_cell        = 1.;
  for (const auto &cell : distorted_cells.active_cell_iterators())
    {
      smallest_cell = std::min(smallest_cell, cell->measure());
      if ((cell->vertex(0) + cell->vertex(3) - cell->vertex(1) -
           cell->vertex(2))
            .norm() > 1e-2)
        ++n_non_parallelograms;
    }
  check_greater("distorted patch, cells that are not parallelograms",
                n_non_parallelograms,
                7);
  check_greater("distorted patch, smallest cell area", smallest_cell, 0.05);

  // Constant moment state: exact moments, and the scales of the errors
  // (max |beta| for the nodal values and the shear strains, max |M| for the
  // moments).
  const double                D            = 1.;
  const std::array<double, 3> moments      = {{-D * (2. * a + 2. * nu * b),
                                               -D * (2. * b + 2. * nu * a),
                                               -D * (1. - nu) * c}};
  const double                moment_scale = std::max(
    {std::abs(moments[0]), std::abs(moments[1]), std::abs(moments[2])});
  const double field_scale = 2. * std::abs(a) + std::abs(c) + std::abs(d);
  // Constant shear state: gamma = (d, e), zero moments.
  Tensor<1, 2> shear;
  shear[0]                 = d;
  shear[1]                 = e;
  const double shear_scale = shear.norm();

  const double tolerance = 1e-10;
  for (const std::string element : {"serendipity", "heterosis", "lagrange"})
    for (const std::string integration : {"reduced", "selective", "full"})
      for (const bool distorted : {false, true})
        {
          const SceneParameters p =
            unit_rigidity_plate(element, integration, 0.1);
          const Triangulation<2> &mesh =
            (distorted ? distorted_cells : square_cells);
          const std::string name = element + " " + integration + ", " +
                                   (distorted ? "distorted" : "square") +
                                   " cells";

          const Errors m = patch_test(
            p, mesh, constant_moment, false, moments, Tensor<1, 2>());
          // A serendipity w (serendipity and heterosis elements) does not
          // contain x^2 on a non-parallelogram (x is bilinear in xi, eta,
          // so x^2 has a xi^2 eta^2 term): the constant-moment state is not
          // reproduced there, but the error vanishes quickly under
          // refinement (weak patch test).
          const bool passes = (!distorted || element == "lagrange");
          if (passes)
            {
              check_below("constant moment, " + name +
                            ", nodal error / max |beta|",
                          m.nodal / field_scale,
                          tolerance);
              check_below("constant moment, " + name +
                            ", moment error / max |M|",
                          m.moment / moment_scale,
                          tolerance);
              check_below("constant moment, " + name +
                            ", shear strain / max |beta|",
                          m.shear / field_scale,
                          tolerance);
            }
          else
            {
              check_greater("constant moment, " + name +
                              ", moment error / max |M| (not passed)",
                            m.moment / moment_scale,
                            1e-4);
              Triangulation<2> refined;
              refined.copy_triangulation(mesh);
              double error = m.moment;
              for (unsigned int r = 1; r <= 2; ++r)
                {
                  refined.refine_global(1);
                  const Errors mr = patch_test(p,
                                               refined,
                                               constant_moment,
                                               false,
                                               moments,
                                               Tensor<1, 2>());
                  check_greater("constant moment, " + name + ", refined " +
                                  std::to_string(r) +
                                  "x, reduction of the moment error",
                                error / mr.moment,
                                6.);
                  error = mr.moment;
                }
            }

          const Errors s =
            patch_test(p, mesh, constant_shear, true, {{0., 0., 0.}}, shear);
          check_below("constant shear, " + name + ", nodal error / |gamma|",
                      s.nodal / shear_scale,
                      tolerance);
          check_below("constant shear, " + name + ", moment / (D |gamma|)",
                      s.moment / (D * shear_scale),
                      tolerance);
          check_below("constant shear, " + name +
                        ", shear strain error / |gamma|",
                      s.shear / shear_scale,
                      tolerance);
        }

  return 0;
}
