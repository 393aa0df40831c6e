/**
 * The settlement of the soil surface at many points under a pressure of
 * the foundation space, through a compressed influence matrix: what a
 * goal's error estimate evaluates at the Gauss points of the contact cells
 * (doc/formulation.md, "Goal-oriented refinement"), in about
 * (points + nodes) log(points + nodes) work instead of points × cells.
 *
 * The influence matrix G (u(x_p) = sum_j G_pj q_j) has the points as rows
 * and the loaded foundation nodes as columns; hmat-oss stores it as an
 * H-matrix whose far blocks ACA+ approximates, every entry it asks for
 * integrated as settlement_at_points() integrates it
 * (soil/surface_settlement.h, SettlementInfluence), so near blocks are
 * exact to rounding. A point's extent is the point; a node's is its
 * support, so an admissible block never holds a singular entry.
 *
 * Accuracy check: the product is compared at sampled points with the
 * exactly integrated settlement; a difference beyond 10 times the
 * tolerance (relative to the sampled settlements) throws, naming
 * Foundation operator/Tolerance.
 */
#ifndef plate_on_halfspace_halfspace_compressed_settlement_h
#define plate_on_halfspace_halfspace_compressed_settlement_h

#include <deal.II/base/point.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/soil/soil_model.h>

#include <functional>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** What a compressed evaluation measured. */
  struct CompressedSettlementReport
  {
    /** Largest difference from the exactly integrated settlement at the
     *  sampled points, relative to their largest settlement. */
    double sampled_error = 0;
    /** Entries the H-matrix stores, against points × loaded nodes. */
    double compression_ratio = 0;
  };

  /**
   * settlement_at_points(space, nodal_pressure, points, kernel,
   * singular_order) (soil/surface_settlement.h) through the compressed
   * influence matrix at the relative accuracy @p tolerance (see the file
   * documentation); @p report, if given, receives what was measured.
   */
  std::vector<double>
  compressed_settlement_at_points(const FoundationSpace       &space,
                                  const Vector<double>        &nodal_pressure,
                                  const std::vector<Point<2>> &points,
                                  const SurfaceKernel         &kernel,
                                  const unsigned int           singular_order,
                                  const double                 tolerance,
                                  CompressedSettlementReport *report = nullptr);

  /**
   * The check of a fast settlement evaluation: at 8 of @p points spread
   * over them, the largest difference of @p computed from @p exact (the
   * exactly integrated settlements at the given points), relative to the
   * largest of those.
   */
  double
  sampled_settlement_error(
    const std::vector<Point<2>> &points,
    const std::vector<double>   &computed,
    const std::function<std::vector<double>(const std::vector<Point<2>> &)>
      &exact);
} // namespace PlateOnHalfspace

#endif
