/**
 * The settlement of the soil surface under a pressure field of the
 * foundation space, at arbitrary points (doc/formulation.md, "Half-space",
 * (P3)): what the error estimate of a goal needs between the nodes
 * (doc/formulation.md, "Goal-oriented refinement").
 */
#ifndef plate_on_halfspace_soil_surface_settlement_h
#define plate_on_halfspace_soil_surface_settlement_h

#include <deal.II/base/point.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/soil/soil_model.h>

#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * u(x) = ∫ q_h(y) K(|x - y|) dy at each of @p points, K(r) = alpha / r +
   * remainder(r) the soil's kernel (soil_model.h), q_h = sum_i
   * q_i phi_i with the nodal values @p nodal_pressure, over the cells of
   * @p space and their mirror images. Cells near x (within 1.5 of their
   * diameters) are integrated with the singularity subtracted at x's
   * reference point, the remainder by a Duffy rule of @p singular_order
   * (as the Galerkin operator's singular pairs); farther cells by the Gauss
   * rule of a separated cell pair (SurfaceKernel::separated_rule()). Near
   * x, a smooth remainder is integrated by Gauss rules of 3, 5
   * or 3 + 3 H / l points per direction (CellPairIntegrator::
   * integrate_smooth()'s choice). The points are split over the threads.
   */
  std::vector<double>
  settlement_at_points(const FoundationSpace       &space,
                       const Vector<double>        &nodal_pressure,
                       const std::vector<Point<2>> &points,
                       const SurfaceKernel         &kernel,
                       const unsigned int           singular_order);
} // namespace PlateOnHalfspace

#endif
