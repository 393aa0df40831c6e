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

#include <array>
#include <memory>
#include <vector>

namespace dealii
{
  class QDuffy;
}

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
   * rule of a separated cell pair (SurfaceKernel::separated_points()). Near
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

  /**
   * The part of settlement_at_points() that a split kernel's near field
   * holds (halfspace/split_kernel_operator.h): at each of @p points,
   * ∫ q_h(y) K(|x - y|) dy with K(r) = alpha / r + R(r) the kernel
   * @p near_kernel (its remainder R required), over the cells and mirror
   * images that come within @p reach of the point (by their centres and
   * diameters). The alpha / r part takes settlement_at_points()'s rules;
   * R takes Gauss rules of 3 + 3 H / (l + separation) points per
   * direction (at most the cell's own near order), so that a remainder
   * that cancels most of alpha / r near the point, as -alpha erf(r /
   * sigma) / r does, is integrated to its own accuracy. Beyond @p reach
   * the kernel must be negligible. The points are split over the threads.
   */
  std::vector<double>
  near_settlement_at_points(const FoundationSpace       &space,
                            const Vector<double>        &nodal_pressure,
                            const std::vector<Point<2>> &points,
                            const SurfaceKernel         &near_kernel,
                            const unsigned int           singular_order,
                            const double                 reach);

  /**
   * settlement_at_points() split for a compressed evaluation
   * (halfspace/compressed_settlement.h): per cell and for its nine local Q2
   * shape functions N_k (FE_Q<2>(2) numbering), with the cell's mirror
   * images (through the images of x),
   *  - far_influences(): ∫ K(|x - y|) N_k(y) dy on the cell's 3 x 3 Gauss
   *    rule, whatever the distance: a smooth function of x away from the
   *    cell, which ACA compresses well;
   *  - near_corrections(): what settlement_at_points() integrates minus
   *    that, on the cells within 2.5 of their diameters of x (the singular
   *    rule and the 5- and 6-point rules there; near_cells() finds them),
   *    zero elsewhere.
   * Their sum is settlement_at_points() where it uses the 3-point rule
   * (from 11.2 to 412 diameters, and beyond for a kernel with a
   * remainder); from 2.5 to 11.2 diameters, where settlement_at_points()
   * takes 4 points, the sum keeps 3 (about 2e-5 of a cell's integral at
   * 2.5 diameters, 1e-6 at 5: doc/formulation.md, "Goal-oriented
   * refinement"); beyond 412 it keeps 3 where the direct sum takes 2.
   * A node's influence is the sum over its cells of these times its weights
   * in the cells' expansions (FoundationSpace::Cell).
   */
  class SettlementInfluence
  {
  public:
    /** @p space must outlive this object. */
    SettlementInfluence(const FoundationSpace &space,
                        const SurfaceKernel   &kernel,
                        const unsigned int     singular_order);
    ~SettlementInfluence();

    /** Only the shape functions whose bit is set in @p needed (bit k for
     *  N_k) are integrated; the others read 0. */
    std::array<double, 9>
    far_influences(const unsigned int c,
                   const Point<2>    &x,
                   const unsigned int needed = 0x1ff) const;

    std::array<double, 9>
    near_corrections(const unsigned int c, const Point<2> &x) const;

    /** The cells whose near_corrections() at @p x may be non-zero. */
    std::vector<unsigned int>
    near_cells(const Point<2> &x) const;

    /** The cells of the space whose expansion contains node @p i. */
    const std::vector<unsigned int> &
    cells_containing(const unsigned int i) const
    {
      return node_cells[i];
    }

    const FoundationSpace &
    foundation_space() const
    {
      return space;
    }

  private:
    struct Cells;

    const FoundationSpace                 &space;
    const SurfaceKernel                    kernel;
    std::unique_ptr<const QDuffy>          duffy;
    std::vector<std::array<double, 2>>     images;
    std::unique_ptr<Cells>                 tables;
    std::vector<std::vector<unsigned int>> node_cells;
  };
} // namespace PlateOnHalfspace

#endif
