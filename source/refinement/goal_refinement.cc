#include <plate_on_halfspace/refinement/interface.h>
#include <plate_on_halfspace/refinement/marking.h>

namespace PlateOnHalfspace
{
  GoalOrientedRefinement::GoalOrientedRefinement(
    const Parameters::Adaptivity &adaptivity)
    : adaptivity(adaptivity)
  {}

  bool
  GoalOrientedRefinement::mark(const MindlinPlate &plate,
                               const ContactState &,
                               const GoalErrorEstimate &goal,
                               Triangulation<2>        &triangulation) const
  {
    const unsigned int n_cells = triangulation.n_active_cells();
    AssertThrow(goal.cell_indicators.size() == n_cells,
                ExcMessage("Adaptivity/Refinement = goal: the cycle has no "
                           "estimate of the goal's error to refine by."));
    const unsigned int copies =
      plate.get_foundation_space().symmetry.n_copies();
    if (!can_refine_fraction(adaptivity, copies, n_cells))
      return false;
    // A goal that only a few cells affect (a point under a flexible
    // plate) refines those few.
    mark_largest_fraction(
      goal.cell_indicators, adaptivity, copies, triangulation, false);
    return true;
  }
} // namespace PlateOnHalfspace
