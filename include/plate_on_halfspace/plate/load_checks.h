/**
 * Checks of the loads against the plate they act on, on the mesh that
 * carries them (doc/errors-and-limits.md, "What you wrote and what you
 * get"): which share of each patch and tyre lies off the plate, and
 * whether a tensionless scene has a determinate answer at all. Both read
 * the mesh, so they hold for every Plate/Shape, a Gmsh mesh included.
 */
#ifndef plate_on_halfspace_plate_load_checks_h
#define plate_on_halfspace_plate_load_checks_h

#include <plate_on_halfspace/loads/load.h>
#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  class MindlinPlate;

  /** One patch or tyre: its whole load and the part the plate carries. */
  struct LoadOnPlate
  {
    /** How messages name it ("Loads/Axles: group 1 (tandem), tyre 3"). */
    std::string entry;
    /** The area of its region, and the part of it on the plate. */
    double area = 0, covered_area = 0;
    /** Its load as given (pressure x area of a patch), if its pressure is
     *  uniform; otherwise NaN. */
    double load = 0;
    /** Its load on the plate. */
    double applied = 0;
  };

  /**
   * Every load of @p loads that covers a region of its own (patches, the
   * tyres of the axles, a pressure function's region): its area and load
   * (Load::region_area(), nominal_force()) and their parts on the plate,
   * integrated over the
   * cells of @p space and their mirror images, i.e. the whole plate.
   */
  std::vector<LoadOnPlate>
  loads_on_plate(const FoundationSpace &space, const LoadList &loads);

  /**
   * The largest relative difference, over @p loads, between a load's
   * force on the cells of @p space by its own rule (Load::on_cell()) and by
   * a rule of 3 more Gauss points per direction on each quarter of each
   * cell, relative to the integral of its |p|: how well the applied load
   * is integrated (summary.json's load_integration_error): the
   * quadrature's error for a pressure function, a jump or a peak inside a
   * cell included; the loads integrated exactly (Load::
   * integrated_exactly(): uniform pressures, patches, point loads) are
   * not checked and count as 0.
   */
  double
  load_integration_error(const FoundationSpace &space, const LoadList &loads);

  /**
   * A warning for each patch of @p loads partly off the plate: it names the
   * entry and item, the share of its load off the plate and the load
   * applied. @p where starts each warning (e.g. the sweep position).
   */
  std::vector<std::string>
  partly_off_plate_warnings(const std::vector<LoadOnPlate> &loads,
                            const std::string              &where = "");

  /** The verdict of check_load_resultant(): empty strings when fine. */
  struct ResultantVerdict
  {
    /** The scene has no determinate answer: refuse it with this. */
    std::string error;
    /** The answer is determinate but carried on a region smaller than
     *  the cells there. */
    std::string warning;
  };

  /**
   * Whether a weightless plate on a tensionless foundation can carry the
   * assembled loads of @p plate (doc/errors-and-limits.md, "A resultant on
   * the outline"). A soil that cannot pull balances the loads with a
   * pressure q >= 0 on the plate, whose resultant lies inside the convex
   * hull of the plate. Every body that moves on its own (the plate, or a
   * group of slabs joined by joints other than free ones) needs a
   * downward resultant strictly inside its hull: on the outline only a
   * pressure concentrated on a line or a point would balance it, the
   * continuous problem has no solution and the discrete one gives a contact
   * region of one cell whose peak pressure grows without bound under
   * refinement. A body without any load rests where it is on a soil
   * whose nodes do not interact (@p soil_couples_nodes false: the dense
   * liquid) unless the plate curls; on a half-space, or curled, its
   * position is not determined and the scene is refused. The criterion
   * reads only the load vector's resultant and the plate's outline, so it
   * does not depend on the mesh. @p loads names the entries in the
   * message; @p has_weight says whether the plate's own weight is among
   * the loads, so that the advice does not ask for it.
   */
  ResultantVerdict
  check_load_resultant(const MindlinPlate &plate,
                       const LoadList     &loads,
                       const bool          has_weight,
                       const bool          soil_couples_nodes);
} // namespace PlateOnHalfspace

#endif
