/**
 * The refinement family's interface (doc/architecture.md, "The refinement
 * family"; doc/formulation.md, "Adaptive refinement"): a strategy reads a
 * solved cycle and flags the cells of the next mesh. The driver refines,
 * sets the plate up anew and transfers the active set, whatever the
 * strategy.
 */
#ifndef plate_on_halfspace_refinement_interface_h
#define plate_on_halfspace_refinement_interface_h

#include <deal.II/grid/tria.h>

#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/refinement/dual_weighted_residual.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <memory>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** A way of making the next cycle's mesh. */
  class RefinementStrategy
  {
  public:
    virtual ~RefinementStrategy() = default;

    /**
     * Set refinement (and coarsening) flags on @p triangulation, the mesh
     * of @p plate, from the cycle's @p contact (its plate_solution, q and
     * contact flags) and the estimate of the goal's error @p goal (empty
     * cell indicators when the scene has no Adaptivity/Goal). Returns
     * false, and sets no flag, when refining would exceed Adaptivity/Max
     * cells.
     */
    virtual bool
    mark(const MindlinPlate      &plate,
         const ContactState      &contact,
         const GoalErrorEstimate &goal,
         Triangulation<2>        &triangulation) const = 0;
  };

  /** Every cell refined once. */
  class GlobalRefinement : public RefinementStrategy
  {
  public:
    explicit GlobalRefinement(const Parameters::Adaptivity &adaptivity);

    bool
    mark(const MindlinPlate      &plate,
         const ContactState      &contact,
         const GoalErrorEstimate &goal,
         Triangulation<2>        &triangulation) const override;

  private:
    const Parameters::Adaptivity adaptivity;
  };

  /**
   * Kelly's indicator of w and beta, raised on the plate edge and on the
   * contact boundary, where the contact pressure is singular or changes
   * sign, and on the edges of load patches and under point loads, where
   * the load is discontinuous or concentrated; a fixed fraction of the
   * whole plate's cells is refined (and coarsened).
   */
  class KellyRefinement : public RefinementStrategy
  {
  public:
    /** @p loads are the scene's (whole-plate) loads. */
    KellyRefinement(const Parameters::Adaptivity &adaptivity,
                    const LoadList               &loads);

    bool
    mark(const MindlinPlate      &plate,
         const ContactState      &contact,
         const GoalErrorEstimate &goal,
         Triangulation<2>        &triangulation) const override;

  private:
    const Parameters::Adaptivity adaptivity;
    const LoadList               loads;
  };

  /**
   * The cells with the largest share of the goal's dual-weighted residual
   * (doc/formulation.md, "Goal-oriented refinement"), a fixed fraction of
   * the whole plate's cells, are refined (and coarsened).
   */
  class GoalOrientedRefinement : public RefinementStrategy
  {
  public:
    explicit GoalOrientedRefinement(const Parameters::Adaptivity &adaptivity);

    bool
    mark(const MindlinPlate      &plate,
         const ContactState      &contact,
         const GoalErrorEstimate &goal,
         Triangulation<2>        &triangulation) const override;

  private:
    const Parameters::Adaptivity adaptivity;
  };

  /** The strategy of Adaptivity/Refinement. */
  std::unique_ptr<RefinementStrategy>
  create_refinement_strategy(const SceneParameters &parameters);
} // namespace PlateOnHalfspace

#endif
