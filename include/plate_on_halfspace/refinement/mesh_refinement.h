/**
 * Marking cells for the next cycle of the adaptive loop (doc/formulation.md,
 * "Adaptive refinement"): the Kelly indicator of w and beta, raised on the
 * plate edge and on the contact boundary, where the contact pressure is
 * singular or changes sign, and on the edges of load patches and under
 * point loads, where the load is discontinuous or concentrated.
 */
#ifndef plate_on_halfspace_refinement_mesh_refinement_h
#define plate_on_halfspace_refinement_mesh_refinement_h

#include <deal.II/grid/tria.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/scene/parameters.h>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * Set refinement (and coarsening) flags on @p triangulation for the next
   * cycle. @p loads are the scene's (whole-plate) loads. Returns false, and sets
   * no flag, when refining would exceed Adaptivity/Max cells.
   */
  bool
  mark_cells_for_refinement(const Parameters::Adaptivity &adaptivity,
                            const MindlinPlate           &plate,
                            const Vector<double>         &solution,
                            const ContactState           &contact,
                            const Parameters::Loads      &loads,
                            Triangulation<2>             &triangulation);
} // namespace PlateOnHalfspace

#endif
