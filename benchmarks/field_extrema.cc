// Cost of the peak search (plate/field_extrema.h) as ResultsOutput::evaluate
// runs it every cycle, against the sampling it replaced (w and q at the
// nodes, Mx and My at the 2x2 Gauss points of every cell). Not a test: it
// prints times and the peaks, nothing is compared.
//
// Scene: the paper's 12 m x 8 m plate (parameters/example2-bonded.prm) on
// a uniform 3k x 2k mesh of serendipity cells, the whole plate, about
// 24 k^2 nodes (k = 65: 25350 cells, 1.0e5 nodes). The fields are smooth
// stand-ins for a solution (interpolated, constraints distributed): a
// deflection with a few bumps, rotations with steep gradients near one
// corner, and a pressure that is zero on a lifted part.
//
// usage: benchmark_field_extrema [k ...]     defaults: k = 16 32 65

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/tria.h>

#include <deal.II/numerics/vector_tools.h>

#include <plate_on_halfspace/plate/field_extrema.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/plate/plate_mesh.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace PlateOnHalfspace;

namespace
{
  /** w, beta_x, beta_y: smooth, with peaks between nodes. */
  class StandIn : public Function<2>
  {
  public:
    StandIn()
      : Function<2>(3)
    {}
    double
    value(const Point<2> &p, const unsigned int component) const override
    {
      const double x = p[0], y = p[1];
      switch (component)
        {
          case 0:
            return 1e-2 * (1 + 0.1 * std::cos(0.7 * x) * std::cos(0.9 * y)) +
                   2e-3 * std::exp(-((x - 1.234) * (x - 1.234) +
                                     (y + 0.567) * (y + 0.567)));
          case 1:
            return 1e-3 * std::sin(1.3 * x + 0.2 * y) +
                   1e-4 * std::atan(5 * (x - 5.1)) * std::cos(y);
          default:
            return 1e-3 * std::cos(0.8 * y - 0.3 * x) +
                   1e-4 * std::atan(5 * (y - 3.3)) * std::sin(x);
        }
    }
  };

  /** A pressure that is zero where x < -3 (a lifted end). */
  class Pressure : public Function<2>
  {
  public:
    Pressure()
      : Function<2>(3)
    {}
    double
    value(const Point<2> &p, const unsigned int component) const override
    {
      if (component != 0)
        return 0;
      return std::max(0., 100. * (p[0] + 3.) + 20. * std::sin(p[1]));
    }
  };
} // namespace

int
main(int argc, char **argv)
{
  std::vector<unsigned int> ks;
  for (int a = 1; a < argc; ++a)
    ks.push_back(std::atoi(argv[a]));
  if (ks.empty())
    ks = {16, 32, 65};
  std::printf("# times [s]: old = nodal w, q and 2x2 Gauss Mx, My; new = "
              "field extrema of w, q, Mx, My (min and max) and the principal "
              "moment (max), as ResultsOutput::evaluate\n");
  std::printf("%7s %8s %9s %9s %9s   %s\n",
              "cells",
              "nodes",
              "old",
              "new",
              "new-old",
              "per field (w q Mx My M1)");
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
      Vector<double> solution(plate.get_dof_handler().n_dofs()),
        pressure(plate.get_dof_handler().n_dofs());
      VectorTools::interpolate(plate.get_dof_handler(), StandIn(), solution);
      plate.get_constraints().distribute(solution);
      VectorTools::interpolate(plate.get_dof_handler(), Pressure(), pressure);
      plate.get_constraints().distribute(pressure);
      const Vector<double> w_nodes = plate.restrict_to_foundation(solution),
                           q_nodes = plate.restrict_to_foundation(pressure);

      // the old sampling
      Timer  timer;
      double old_peaks[6];
      old_peaks[0] = *std::max_element(w_nodes.begin(), w_nodes.end());
      old_peaks[1] = *std::min_element(w_nodes.begin(), w_nodes.end());
      old_peaks[2] = *std::max_element(q_nodes.begin(), q_nodes.end());
      old_peaks[3] = *std::min_element(q_nodes.begin(), q_nodes.end());
      {
        const QGauss<2> rule(2);
        FEValues<2>     values(plate.get_fe(), rule, update_gradients);
        std::vector<Tensor<2, 2>> grad(rule.size());
        const double D = plate.flexural_rigidity(), nu = plate.poissons_ratio();
        old_peaks[4] = -1e300;
        old_peaks[5] = -1e300;
        for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
          {
            values.reinit(cell);
            values[FEValuesExtractors::Vector(1)].get_function_gradients(
              solution, grad);
            for (const auto &g : grad)
              {
                old_peaks[4] =
                  std::max(old_peaks[4], -D * (g[0][0] + nu * g[1][1]));
                old_peaks[5] =
                  std::max(old_peaks[5], -D * (g[1][1] + nu * g[0][0]));
              }
          }
      }
      const double old_time = timer.wall_time();

      // the field search
      std::vector<double> times;
      FieldExtrema        peaks[4];
      const auto          timed = [&](const auto &f) {
        Timer t;
        f();
        times.push_back(t.wall_time());
      };
      timed(
        [&] { peaks[0] = field_extrema(plate, solution, PlateQuantity::w); });
      timed(
        [&] { peaks[1] = field_extrema(plate, pressure, PlateQuantity::w); });
      timed(
        [&] { peaks[2] = field_extrema(plate, solution, PlateQuantity::mx); });
      timed(
        [&] { peaks[3] = field_extrema(plate, solution, PlateQuantity::my); });
      FieldExtremum principal;
      timed([&] {
        principal =
          field_maximum(plate, solution, PlateQuantity::principal_moment);
      });
      double new_time = 0;
      for (const double t : times)
        new_time += t;
      std::printf("%7u %8u %9.4f %9.4f %9.4f   %.4f %.4f %.4f %.4f %.4f\n",
                  mesh.n_active_cells(),
                  plate.get_foundation_space().n_nodes(),
                  old_time,
                  new_time,
                  new_time - old_time,
                  times[0],
                  times[1],
                  times[2],
                  times[3],
                  times[4]);
      std::printf("#   max w %.9e (nodes %.9e) at (%.6f, %.6f); min q %.3e "
                  "(nodes %.3e); max Mx %.6e (Gauss %.6e) at (%.6f, %.6f); "
                  "max My %.6e (Gauss %.6e); max M1 %.6e\n",
                  peaks[0].maximum.value,
                  old_peaks[0],
                  peaks[0].maximum.location[0],
                  peaks[0].maximum.location[1],
                  peaks[1].minimum.value,
                  old_peaks[3],
                  peaks[2].maximum.value,
                  old_peaks[4],
                  peaks[2].maximum.location[0],
                  peaks[2].maximum.location[1],
                  peaks[3].maximum.value,
                  old_peaks[5],
                  principal.value);
    }
}
