// The settlement at many points through the compressed influence matrix
// (halfspace/compressed_settlement.h), which a goal's error estimate uses
// on large meshes, against the exactly integrated settlement_at_points()
// (soil/surface_settlement.h) at every point: the 4 x 4 Gauss points of
// every cell, where the estimate's half-space residual evaluates it.
// - example 2 made tensionless (Galerkin, quarter by Symmetry = xy: the
//   mirror images enter every entry), the pavement on layers (a kernel
//   with a smooth remainder R) and the bonded example 2 without symmetry;
// - at the tolerances 1e-6 and 1e-8: the largest difference relative to
//   the largest settlement within 10 times the tolerance, and the stored
//   entries a fraction of the full matrix's.
// The sampled check inside the evaluation (the uncompressed sum at 8
// points) must see the compression's error: within 10 times the tolerance
// as well.

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <plate_on_halfspace/halfspace/compressed_settlement.h>
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
  /** R = 0: settlement_at_points() then keeps the 3-point rule beyond 20
   *  cell diameters, as the compressed evaluation does for alpha / r. */
  class ZeroRemainder : public SmoothRadialFunction
  {
  public:
    double
    value(const double) const override
    {
      return 0;
    }

    double
    length_scale() const override
    {
      return 1e300;
    }
  };

  void
  compare(const std::string &label,
          const std::string &scene,
          const std::string &extra)
  {
    const auto             problem = solve_scene(scene, extra);
    const FoundationSpace &space   = problem->plate().get_foundation_space();
    Vector<double>         pressure;
    problem->foundation().nodal_pressure(problem->contact_state().q, pressure);
    const auto &soil =
      dynamic_cast<const ElasticSoil &>(problem->foundation().soil());
    const SurfaceKernel         kernel = soil.kernel(maximal_distance(space));
    const unsigned int          order  = soil.singular_quadrature_order();
    const std::vector<Point<2>> points = cell_gauss_points(problem->plate());

    const SurfaceKernel reference =
      kernel.remainder ?
        kernel :
        SurfaceKernel(kernel.alpha, std::make_shared<ZeroRemainder>());
    auto                      start = std::chrono::steady_clock::now();
    const std::vector<double> exact =
      settlement_at_points(space, pressure, points, reference, order);
    const double exact_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
    double scale = 0;
    for (const double u : exact)
      scale = std::max(scale, std::abs(u));
    deallog << label << ": " << space.n_nodes() << " foundation nodes, "
            << points.size() << " points" << std::endl;
    for (const double tolerance : {1e-6, 1e-8})
      {
        CompressedSettlementReport report;
        start                                = std::chrono::steady_clock::now();
        const std::vector<double> compressed = compressed_settlement_at_points(
          space, pressure, points, kernel, order, tolerance, &report);
        const double compressed_time =
          std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                        start)
            .count();
        double difference = 0;
        for (unsigned int p = 0; p < points.size(); ++p)
          difference = std::max(difference, std::abs(compressed[p] - exact[p]));
        std::cerr << label << " tolerance " << tolerance << ": exact "
                  << exact_time << " s, compressed " << compressed_time
                  << " s, error " << difference / scale << ", sampled "
                  << report.sampled_error << ", stored "
                  << report.compression_ratio << std::endl;
        std::ostringstream name;
        name << " tolerance " << tolerance;
        check_below(name.str() + ", largest difference / largest settlement",
                    difference / scale,
                    10 * tolerance);
        check_below(name.str() + ", sampled check's difference",
                    report.sampled_error,
                    10 * tolerance);
        check_below(name.str() + ", stored entries / points x loaded nodes",
                    report.compression_ratio,
                    0.5);
      }
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
  const std::string iterative =
    "subsection Contact\n set Method = active set\n set Solver = "
    "iterative\nend\n"
    "subsection Foundation operator\n set Storage = hierarchical\nend\n";
  compare("example 2, tensionless, quarter",
          "example2.prm",
          galerkin + " set Symmetry = xy\nend\n" + iterative);
  compare("pavement on layers",
          "pavement-on-layers.prm",
          "subsection Foundation operator\n set Storage = hierarchical\nend\n"
          "subsection Contact\n set Solver = iterative\nend\n");
  compare("example 2, bonded, whole plate",
          "example2-bonded.prm",
          galerkin + "end\n" + iterative);

  return 0;
}
