/**
 * Axle groups and aircraft main gears (doc/parameters.md, "Axles"): each
 * type is a layout of tyres around the group's centre, and each tyre a
 * circular pressure patch whose area is its share of the group's load
 * over the tyre pressure.
 */
#ifndef plate_on_halfspace_scene_axles_h
#define plate_on_halfspace_scene_axles_h

#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  namespace Parameters
  {
    struct CircularPatch;

    /** One entry of Loads/Axles: a group of tyres that travel together. */
    struct AxleGroup
    {
      enum class Type
      {
        single,                 ///< single axle, single tyres
        single_dual,            ///< single axle, dual tyres
        tandem,                 ///< tandem axle, dual tyres
        tridem,                 ///< tridem axle, dual tyres
        dual_gear,              ///< aircraft main gear, two wheels
        dual_tandem_gear,       ///< aircraft main gear, four wheels
        triple_dual_tandem_gear ///< aircraft main gear, six wheels
      };
      Type     type;
      Point<2> centre;
      double   angle; ///< degrees, counterclockwise from x to the travel
      double   load;  ///< the group's total load [force], > 0
      double   tyre_pressure; ///< [force/length^2], > 0

      /** The entry's names of the types, in the order of Type. */
      static const std::vector<std::string> &
      type_names();

      /**
       * The tyre centres in the group's own frame (x along the travel, y
       * across it) around its centre [m].
       */
      static std::vector<Point<2>>
      tyre_layout(const Type type);

      /**
       * The group's tyres as circular patches: centres rotated by angle
       * and moved to the centre, radius sqrt(load/(n pi p)), pressure p;
       * each labelled "Loads/Axles: group @p number (type), tyre k".
       */
      std::vector<CircularPatch>
      tyre_patches(const unsigned int number) const;
    };
  } // namespace Parameters
} // namespace PlateOnHalfspace

#endif
