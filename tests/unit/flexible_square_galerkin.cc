// A very flexible square plate under a uniform pressure with the Galerkin
// half-space operator (the shipped scene parameters/flexible-square.prm with
// Flexibility = galerkin). The plate transmits the pressure unchanged, so
// q = const is exact and the deflection is the L2 projection of the exact
// settlement u = alpha ∫ q / r (doc/formulation.md, "Default variant"):
//  - the mean settlement, 1^T M w / area = 1^T A 1 / area, is exact up to
//    the quadrature of A: 0.946402 q B (1-nu0^2)/E0 (doc/verification.md; exact
//    value (4 ln(1+sqrt 2) - 4 (sqrt 2 - 1)/3) / pi);
//  - the L2 error of w against the exact settlement (closed-form rectangle
//    integral at every quadrature point) must fall on every refinement;
//  - the centre and corner values approach 1.1221997 and 0.5610999 (the
//    projection's pointwise error need not be monotone at the centre).

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <plate_on_halfspace/plate_on_halfspace_problem.h>
#include <plate_on_halfspace/soil/boussinesq_kernel.h>

#include <cmath>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

int
main()
{
  initlog();
  const double scale        = 100. * 4. * (1. - 0.09) / 5e4; // q B (1-nu0^2)/E0
  const double centre_exact = 4. * std::log(1. + std::sqrt(2.)) / M_PI;
  const double mean_exact =
    (4. * std::log(1. + std::sqrt(2.)) - 4. * (std::sqrt(2.) - 1.) / 3.) / M_PI;

  double previous_l2 = 1e300;
  for (const unsigned int n : {2u, 4u, 8u, 16u})
    {
      std::ostringstream prm;
      prm << "include " << SOURCE_DIR
          << "/../../parameters/flexible-square.prm\n"
          << "set Output directory = results\n"
          << "subsection Discretization\n set Flexibility = galerkin\n"
          << " set Symmetry = none\n"
          << " set Subdivisions x = " << n << "\n set Subdivisions y = " << n
          << "\nend\nsubsection Verification\n set Checks =\nend\n"
          << "subsection Output\n set Verbosity = 0\nend\n";
      SceneParameters parameters;
      parameters.read_from_string(prm.str());
      std::ostringstream      log;
      PlateOnHalfspaceProblem problem(parameters, log);
      problem.run();

      const double centre = problem.values_at(Point<2>(0, 0)).w / scale;
      const double corner = problem.values_at(Point<2>(2, 2)).w / scale;
      const double mean   = integral_of_deflection(problem) / (16. * scale);

      // relative L2 error of w against u = alpha q ∫ 1/r over the square
      const QGauss<2>     rule(4);
      const auto         &plate = problem.plate();
      FEValues<2>         fe_values(plate.get_fe(),
                            rule,
                            update_values | update_quadrature_points |
                              update_JxW_values);
      std::vector<double> w(rule.size());
      double              error2 = 0, norm2 = 0;
      for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
        {
          fe_values.reinit(cell);
          fe_values[FEValuesExtractors::Scalar(0)].get_function_values(
            problem.solution(), w);
          for (unsigned int q = 0; q < rule.size(); ++q)
            {
              const double u = 100. *
                               boussinesq_flexibility_constant(5e4, 0.3) *
                               integral_of_inverse_distance_over_rectangle(
                                 fe_values.quadrature_point(q), -2, 2, -2, 2);
              error2 += (w[q] - u) * (w[q] - u) * fe_values.JxW(q);
              norm2 += u * u * fe_values.JxW(q);
            }
        }
      const double e_l2 = std::sqrt(error2 / norm2);

      const double e_centre = std::abs(centre - centre_exact) / centre_exact;
      const double e_corner =
        std::abs(corner - centre_exact / 2) / (centre_exact / 2);
      const double e_mean = std::abs(mean - mean_exact) / mean_exact;
      // the values to 6 digits, the errors to 2: the digits that hold on
      // any CPU (the checks are the assertions below)
      deallog << n << "x" << n << " cells: centre " << std::setprecision(6)
              << centre << " error " << std::setprecision(2) << e_centre
              << ", corner " << std::setprecision(6) << corner << " error "
              << std::setprecision(2) << e_corner << ", mean "
              << std::setprecision(6) << mean << " error "
              << std::setprecision(2) << e_mean << ", L2 error " << e_l2
              << std::setprecision(10) << std::endl;
      AssertThrow(e_mean < 1e-5,
                  ExcMessage("mean settlement off by more than 1e-5"));
      AssertThrow(e_l2 < previous_l2,
                  ExcMessage("the L2 error did not fall with refinement"));
      if (n >= 8)
        AssertThrow(e_centre < 5e-4 && e_corner < 0.025,
                    ExcMessage("centre or corner value too far off"));
      previous_l2 = e_l2;
    }
  deallog << "mean settlement within 1e-5 on every mesh, L2 error falls on "
             "every refinement, centre within 5e-4 and corner within 2.5e-2 "
             "from 8x8 cells: ok"
          << std::endl;
}
