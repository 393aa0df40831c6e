/**
 * What the load kinds of source/loads/ share.
 */
#ifndef plate_on_halfspace_loads_load_helpers_h
#define plate_on_halfspace_loads_load_helpers_h

#include <algorithm>
#include <cmath>

namespace PlateOnHalfspace
{
  /** Whether two pressures or forces are equal to 1e-12. */
  inline bool
  same_value(const double a, const double b)
  {
    return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b));
  }
} // namespace PlateOnHalfspace

#endif
