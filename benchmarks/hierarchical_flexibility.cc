// Timing of the hierarchical (H-matrix) Galerkin flexibility against the
// dense one as the mesh grows. Not a test: it prints a table and
// the growth exponents, nothing is compared.
//
// Scene: the paper's 12 m x 8 m plate (parameters/example2-bonded.prm) on
// a uniform 3k x 2k mesh of serendipity cells, the whole plate (no
// symmetry), n = foundation nodes ~ 18 k^2. For each n:
//   H build     hmat-oss assembly with ACA+ (cell-pair integration included)
//   H factor    H-Cholesky of a copy (with the check solve)
//   H product   one product A x
//   H memory    the H-matrix and its factor [MB], and the stored fraction of
//               n^2 of the H-matrix
//   product err ||A_H x - A x|| / ||A x||, dense A, where dense runs
//   solve err   ||A_H^{-1} A x - x|| / ||x||
//   dense build BoussinesqGalerkinOperator::build (assembly + LAPACK
//               Cholesky, as the program runs it) and dense Cholesky alone
// and at the end the least-squares exponent p of time ~ n^p per column.
//
// usage: benchmark_hierarchical_flexibility [tolerance] [largest dense n]
//          [k ...]
// defaults: 1e-6, 12000, k = 8 12 17 24 34

#include <deal.II/base/timer.h>

#include <deal.II/grid/tria.h>

#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/halfspace/hierarchical_flexibility.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/plate/plate_mesh.h>
#include <plate_on_halfspace/soil/boussinesq_kernel.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <vector>

using namespace PlateOnHalfspace;

namespace
{
  double
  relative_difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> d(a);
    d -= b;
    return d.l2_norm() / b.l2_norm();
  }

  /** Least-squares slope of log(y) over log(x). */
  double
  growth_exponent(const std::vector<double> &x, const std::vector<double> &y)
  {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (unsigned int i = 0; i < x.size(); ++i)
      {
        const double lx = std::log(x[i]), ly = std::log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
      }
    const double m = x.size();
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
  }
} // namespace

int
main(int argc, char **argv)
{
  const double              tolerance = argc > 1 ? std::atof(argv[1]) : 1e-6;
  const unsigned int        max_dense = argc > 2 ? std::atoi(argv[2]) : 12000;
  std::vector<unsigned int> ks;
  for (int a = 3; a < argc; ++a)
    ks.push_back(std::atoi(argv[a]));
  if (ks.empty())
    ks = {8, 12, 17, 24, 34};

  std::printf("# tolerance %g, dense up to n = %u, %u threads\n",
              tolerance,
              max_dense,
              MultithreadInfo::n_threads());
  std::printf("%7s %9s %9s %9s %9s %8s %10s %10s %10s %10s %10s\n",
              "n",
              "H_build",
              "H_factor",
              "H_vmult",
              "H_MB",
              "stored",
              "prod_err",
              "solve_err",
              "dense_bld",
              "dense_chol",
              "dense_MB");
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>>
    series;
  for (const unsigned int k : ks)
    {
      SceneParameters parameters;
      parameters.read_from_string(
        "include " SOURCE_DIR "/../parameters/example2-bonded.prm\n"
        "set Output directory = results\n"
        "subsection Discretization\n set Symmetry = none\n"
        " set Subdivisions x = " +
        std::to_string(3 * k) +
        "\n set Subdivisions y = " + std::to_string(2 * k) + "\nend\n");
      Triangulation<2> mesh;
      make_plate_mesh(parameters.plate, parameters.discretization, mesh);
      MindlinPlate plate(parameters.plate, parameters.discretization);
      plate.setup(mesh);
      const FoundationSpace &space = plate.get_foundation_space();
      const double           alpha =
        boussinesq_flexibility_constant(parameters.foundation.youngs_modulus,
                                        parameters.foundation.poissons_ratio);
      const unsigned int order =
        parameters.discretization.singular_quadrature_order;
      const unsigned int n = space.n_nodes();

      HierarchicalFlexibility::Settings settings;
      settings.tolerance        = tolerance;
      settings.factor_tolerance = tolerance; // the exact H-Cholesky
      HierarchicalFlexibility hierarchical(settings);
      Timer                   timer;
      hierarchical.build(space, alpha, order);
      const double h_build = timer.wall_time();
      timer.restart();
      hierarchical.factorize();
      const double h_factor = timer.wall_time();

      Vector<double> x(n), y_h;
      for (unsigned int i = 0; i < n; ++i)
        x[i] = 1. + std::cos(0.37 * i) + 0.3 * std::sin(2.1 * i * i);
      timer.restart();
      hierarchical.vmult(y_h, x);
      const double h_vmult = timer.wall_time();

      double product_error = NAN, solve_error = NAN, dense_build = NAN,
             dense_cholesky = NAN, dense_mb = NAN;
      if (n <= max_dense)
        {
          BoussinesqGalerkinOperator dense(alpha, order, false); // the plain A
          timer.restart();
          dense.build(space, {});
          dense_build = timer.wall_time();
          // the Cholesky factorisation of A
          timer.restart();
          const auto factor = dense.make_approximate_inverse();
          dense_cholesky    = timer.wall_time();
          dense_mb =
            (dense.memory_consumption() + factor->memory_consumption()) / 1e6;
          Vector<double> y_dense(n), q_h;
          dense.flexibility_matrix().vmult(y_dense, x);
          product_error = relative_difference(y_h, y_dense);
          hierarchical.solve(q_h, y_dense);
          solve_error = relative_difference(q_h, x);
        }
      std::printf(
        "%7u %9.2f %9.2f %9.4f %9.1f %8.4f %10.2e %10.2e %10.2f %10.2f "
        "%10.1f\n",
        n,
        h_build,
        h_factor,
        h_vmult,
        hierarchical.memory_consumption() / 1e6,
        hierarchical.compression_ratio(),
        product_error,
        solve_error,
        dense_build,
        dense_cholesky,
        dense_mb);
      std::fflush(stdout);
      const auto add = [&](const std::string &name, const double t) {
        if (std::isfinite(t) && t > 0)
          {
            series[name].first.push_back(n);
            series[name].second.push_back(t);
          }
      };
      add("H_build", h_build);
      add("H_factor", h_factor);
      add("H_build+factor", h_build + h_factor);
      add("H_vmult", h_vmult);
      add("H_memory", hierarchical.memory_consumption());
      add("dense_build", dense_build);
      add("dense_cholesky", dense_cholesky);
    }
  std::printf("# growth exponents p (time or memory ~ n^p, least squares)\n");
  for (const auto &[name, points] : series)
    if (points.first.size() >= 2)
      std::printf("%-16s %5.2f  (n = %g ... %g)\n",
                  name.c_str(),
                  growth_exponent(points.first, points.second),
                  points.first.front(),
                  points.first.back());
}
