/**
 * The contact region measured from the fields (doc/outputs.md, "Contact
 * area"): where the soil carries the plate, located inside the cells
 * rather than counted by nodes.
 */
#ifndef plate_on_halfspace_contact_contact_region_h
#define plate_on_halfspace_contact_contact_region_h

#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/plate/foundation_space.h>

namespace PlateOnHalfspace
{
  class FoundationOperator;

  /**
   * Fill state.cell_contact_area and state.cell_contact_area_uncertainty
   * from its nodal pressure q and its tested gap.
   *
   * On a tensionless foundation the region is {C > 0} of the field
   *   C = q - c g,
   * with g the gap field (nodal values from B g = the tested gap, B the
   * test coupling: the soil's settlement less the plate's deflection) and
   * c the soil's patch_stiffness() at the cell's size, which
   * turns the gap into the pressure that would close it: C = q where the
   * plate presses and -c g where it has lifted off, and C = k w on a dense
   * liquid, whose region {w > 0} is then located to the accuracy of w.
   * A cell whose nodal values of C keep farther from zero than their
   * spread counts whole or not at all; in the others C is interpolated
   * with the cell's Q2 functions on 16 x 16 sub-cells, each split into
   * four triangles about its centre (so that a cell and its mirror image
   * measure alike), on which the positive part of the linear interpolant
   * is measured exactly. The uncertainty is the larger of the change when
   * C is interpolated bilinearly from its four vertex values, and half the
   * change when c is halved and doubled.
   *
   * On a bonded foundation the whole foundation carries the plate (every
   * cell of state.cell_in_foundation), with no uncertainty.
   */
  void
  measure_contact_region(const FoundationSpace    &space,
                         const FoundationOperator &foundation,
                         const bool                tensionless,
                         ContactState             &state);
} // namespace PlateOnHalfspace

#endif
