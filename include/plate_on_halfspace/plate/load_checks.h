/**
 * Checks of the loads against the plate they act on, on the mesh that
 * carries them (doc/errors-and-limits.md, "What you wrote and what you
 * get"): which share of each patch and tyre lies off the plate, and
 * whether a tensionless scene has a determinate answer at all. Both read
 * the mesh, so they hold for every Plate/Shape, a Gmsh mesh included.
 */
#ifndef plate_on_halfspace_plate_load_checks_h
#define plate_on_halfspace_plate_load_checks_h

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
    /** pressure x area of the whole patch */
    double load = 0;
    /** pressure x the area of the patch on the plate */
    double applied = 0;
  };

  /**
   * Every rectangular and circular patch of @p loads (the tyres of the
   * axles among them): its load and the part on the plate, integrated over
   * the cells of @p space and their mirror images, i.e. the whole plate.
   */
  std::vector<LoadOnPlate>
  loads_on_plate(const FoundationSpace &space, const Parameters::Loads &loads);

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
   * refinement. A body without any load rests where it is. The
   * criterion reads only the load vector's resultant and the plate's
   * outline, so it does not depend on the mesh. @p loads names the
   * entries in the message; @p has_weight says whether the plate's own
   * weight is among the loads, so that the advice does not ask for it.
   */
  ResultantVerdict
  check_load_resultant(const MindlinPlate      &plate,
                       const Parameters::Loads &loads,
                       const bool               has_weight);
} // namespace PlateOnHalfspace

#endif
