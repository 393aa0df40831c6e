/**
 * The parameter files' lists of numbers, "a,b,c ; d,e,f" (doc/parameters.md).
 */
#ifndef plate_on_halfspace_base_number_list_h
#define plate_on_halfspace_base_number_list_h

#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  /**
   * Split a list entry "a,b,c ; d,e,f" into items of exactly @p n_fields
   * decimal numbers each (any number if @p n_fields is 0). Errors name the
   * entry @p entry_name and its @p field_names.
   */
  std::vector<std::vector<double>>
  parse_number_list(const std::string &text,
                    const unsigned int n_fields,
                    const std::string &entry_name,
                    const std::string &field_names);
} // namespace PlateOnHalfspace

#endif
