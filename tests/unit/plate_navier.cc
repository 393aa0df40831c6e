// Simply supported square plate (side a = 1, nu = 0.3, D = 1) with the
// "hard" simple support (w = 0 on all edges, tangential rotation zero:
// beta_y = 0 on x = +-a/2, beta_x = 0 on y = +-a/2), against the Navier
// series, computed here:
// - Kirchhoff, uniform load q: w(0) = 16 q a^4 / (pi^6 D) S1,
//   S1 = sum over odd m, n of s_mn / (m n (m^2 + n^2)^2),
//   s_mn = sin(m pi/2) sin(n pi/2); centre moment
//   Mx(0) = 16 q a^2 / pi^4 sum s_mn (m^2 + nu n^2) / (m n (m^2 + n^2)^2).
// - Mindlin (hard support): w = w_K - (D / (k G t)) laplace(w_K), i.e. every
//   Navier term times (1 + pi^2 (m^2 + n^2) D / (a^2 k G t)), so
//   w(0) = w_K(0) + 16 q a^2 / (pi^4 k G t) sum s_mn / (m n (m^2 + n^2));
//   the rotations are the Kirchhoff slopes, hence the moments are the
//   Kirchhoff ones for any thickness.
// - Kirchhoff, central point load P: w(0) = 4 P a^2 / (pi^4 D) sum over odd
//   m, n of 1 / (m^2 + n^2)^2 (the Mindlin point-load deflection is
//   infinite: only the thin plate is compared, see below).
// The series (m, n <= 4001) are first checked against the values of
// doc/verification.md (0.00406235, 0.04789, 0.011601, Mindlin factors 1.0005
// for a/t = 100 and 1.0518 for a/t = 10). Then the finite-element centre
// deflection and centre moment Mx for every element with reduced and
// selective integration (and full integration for a/t = 10) on 4x4, 8x8,
// 16x16 meshes (and 32x32 for serendipity, reduced) of [-a/2, a/2]^2: the
// deflection converges like h^4, the moment at the centre node like h^2;
// the tolerances of the lines are what each mesh meets. Thin plate with
// full integration: the 4x4 error is several times that of reduced
// integration (shear locking).

#include <deal.II/base/function.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <deal.II/numerics/vector_tools.h>

#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;


namespace
{
  const double pi = numbers::PI;



  struct Series
  {
    double w_kirchhoff, w_shear, mx, w_point;
  };

  /** The Navier series at the centre for a = q = D = P = 1 (w_shear still
   * to be divided by k G t). */
  Series
  navier(const double nu, const unsigned int m_max)
  {
    Series s{0, 0, 0, 0};
    for (unsigned int m = 1; m <= m_max; m += 2)
      for (unsigned int n = 1; n <= m_max; n += 2)
        {
          const double sign = (((m + n) / 2 - 1) % 2 == 0 ? 1. : -1.);
          const double mm = double(m) * m, nn = double(n) * n;
          const double k = mm + nn;
          s.w_kirchhoff += sign / (double(m) * n * k * k);
          s.w_shear += sign / (double(m) * n * k);
          s.mx += sign * (mm + nu * nn) / (double(m) * n * k * k);
          s.w_point += 1. / (k * k);
        }
    s.w_kirchhoff *= 16. / std::pow(pi, 6);
    s.w_shear *= 16. / std::pow(pi, 4);
    s.mx *= 16. / std::pow(pi, 4);
    s.w_point *= 4. / std::pow(pi, 4);
    return s;
  }



  std::string
  mesh_name(const unsigned int n)
  {
    return std::to_string(n) + "x" + std::to_string(n);
  }
} // namespace

int
main()
{
  initlog();

  const double nu     = 0.3;
  const Series series = navier(nu, 4001);
  check("Navier series, w / (q a^4/D), uniform load",
        series.w_kirchhoff,
        0.00406235,
        2e-6);
  check("Navier series, Mx / (q a^2), uniform load", series.mx, 0.04789, 1e-4);
  check("Navier series, w / (P a^2/D), point load",
        series.w_point,
        0.011601,
        5e-5);

  const std::vector<std::string>       elements     = {"serendipity",
                                                       "heterosis",
                                                       "lagrange"};
  const std::map<unsigned int, double> w_tolerance  = {{4, 2e-2},
                                                       {8, 5e-4},
                                                       {16, 2e-5},
                                                       {32, 1e-6}};
  const std::map<unsigned int, double> mx_tolerance = {{4, 6e-2},
                                                       {8, 1e-2},
                                                       {16, 2e-3},
                                                       {32, 5e-4}};

  for (const double a_over_t : {100., 10.})
    {
      const double t = 1. / a_over_t;
      const double shear_rigidity =
        5. / 6. * 10.92 / (t * t * t) / (2. * (1. + nu)) * t;
      const double w_reference =
        series.w_kirchhoff + series.w_shear / shear_rigidity;
      const std::string slenderness = "a/t = " + std::to_string(int(a_over_t));
      check("Navier series, Mindlin / Kirchhoff, " + slenderness,
            w_reference / series.w_kirchhoff,
            (a_over_t == 100. ? 1.0005 : 1.0518),
            5e-5);

      std::vector<std::string> integrations = {"reduced", "selective"};
      if (a_over_t == 10.)
        integrations.push_back("full");
      for (const auto &element : elements)
        for (const auto &integration : integrations)
          {
            const SceneParameters p = unit_rigidity_plate(
              element, integration, t, "set Uniform pressure = 1\n");
            std::vector<unsigned int> meshes = {4, 8, 16};
            if (element == "serendipity" && integration == "reduced")
              meshes.push_back(32);
            // full integration (a/t = 10 only) converges more slowly
            const double factor = (integration == "full" ? 2. : 1.);
            std::map<unsigned int, CentreValues> results;
            for (const unsigned int n : meshes)
              {
                results[n]             = simply_supported_square_centre(p, n);
                const std::string name = element + " " + integration + ", " +
                                         slenderness + ", " + mesh_name(n);
                check("w centre / (q a^4/D), " + name,
                      results[n].w,
                      w_reference,
                      factor * w_tolerance.at(n));
                check("Mx centre / (q a^2), " + name,
                      results[n].mx,
                      series.mx,
                      mx_tolerance.at(n));
              }
            if (element == "serendipity" && integration == "reduced")
              {
                // observed orders between the 8x8 and 16x16 meshes
                const auto order = [&](const double fine,
                                       const double coarse,
                                       const double exact) {
                  return std::log2(std::abs(coarse - exact) /
                                   std::abs(fine - exact));
                };
                check_greater("convergence order of w, " + element + " " +
                                integration + ", " + slenderness +
                                ", 8x8 -> 16x16",
                              order(results[16].w, results[8].w, w_reference),
                              3.5);
                check_greater("convergence order of Mx, " + element + " " +
                                integration + ", " + slenderness +
                                ", 8x8 -> 16x16",
                              order(results[16].mx, results[8].mx, series.mx),
                              1.8);
              }
          }

      if (a_over_t == 100.)
        {
          // Shear locking of full integration, thin plate: on 4x4 cells the
          // error is several times that of reduced integration.
          for (const auto &element : elements)
            {
              const double reduced =
                simply_supported_square_centre(
                  unit_rigidity_plate(
                    element, "reduced", t, "set Uniform pressure = 1\n"),
                  4)
                  .w;
              const double full =
                simply_supported_square_centre(
                  unit_rigidity_plate(
                    element, "full", t, "set Uniform pressure = 1\n"),
                  4)
                  .w;
              check_greater("locking: error of full / error of reduced, " +
                              element + ", " + slenderness + ", 4x4",
                            std::abs(full - w_reference) /
                              std::abs(reduced - w_reference),
                            5.);
            }

          // Central point load P = 1, thin plate: the Kirchhoff series is
          // the reference; the Mindlin solution adds a shear deflection that
          // grows like P ln(a/h) / (2 pi k G t) under the load (3.9e-4 of
          // the Kirchhoff value per unit of ln(a/h) at a/t = 100), so the
          // FE value does not converge to it: 5e-3 on 16x16 cells.
          for (const auto &element : elements)
            for (const auto &integration : integrations)
              check("point load, w centre / (P a^2/D), " + element + " " +
                      integration + ", " + slenderness + ", 16x16",
                    simply_supported_square_centre(
                      unit_rigidity_plate(
                        element, integration, t, "set Point loads = 0,0,1\n"),
                      16)
                      .w,
                    series.w_point,
                    5e-3);
        }
    }

  return 0;
}
