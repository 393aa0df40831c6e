/**
 * The results of a grid of slabs (doc/outputs.md, "Joints"): each slab's
 * peak fibre stresses and what each joint carries.
 */
#ifndef plate_on_halfspace_plate_slab_results_h
#define plate_on_halfspace_plate_slab_results_h

#include <deal.II/lac/vector.h>

namespace PlateOnHalfspace
{
  using namespace dealii;

  class MindlinPlate;
  class ResultRecord;

  /**
   * With more than one slab: the arrays "slabs" and "joints" of a cycle's
   * @p record, the joints' LTE relative to @p standing (the plate under its
   * standing loads; empty: none). A slab or joint of the mirrored part
   * reports its image.
   */
  void
  add_slab_and_joint_results(const MindlinPlate   &plate,
                             const Vector<double> &solution,
                             const Vector<double> &standing,
                             ResultRecord         &record);
} // namespace PlateOnHalfspace

#endif
