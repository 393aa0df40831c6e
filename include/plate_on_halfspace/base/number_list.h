/**
 * The parameter files' lists of numbers, "a,b,c ; d,e,f" (doc/parameters.md).
 */
#ifndef plate_on_halfspace_base_number_list_h
#define plate_on_halfspace_base_number_list_h

#include <optional>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  /**
   * What a text read as one decimal number gives.
   */
  enum class DecimalReading
  {
    /** a finite number: 0 or of magnitude 2.2e-308 to 1.8e308 */
    number,
    /** a decimal number nearer 0 than 2.2e-308, not 0 itself */
    underflow,
    /** a decimal number beyond 1.8e308 */
    overflow,
    /** inf or nan */
    not_finite,
    /** anything else: empty, trailing characters, hexadecimal */
    not_a_number
  };

  /**
   * Read @p text as one decimal number into @p value (white space before
   * it is skipped, none may follow). strtod() alone would also take the
   * hexadecimal 0x10 as 16 (and 0x1p4); the parameter files, GridIn and
   * deal.II's patterns take decimals only.
   */
  DecimalReading
  read_decimal_number(const std::string &text, double &value);

  /**
   * @p text split at @p separator, each piece trimmed (an empty list for a
   * blank text), or nullopt if a piece is empty: between two separators,
   * before the first or after the last, which Utilities::split_string_list()
   * keeps or drops silently.
   */
  std::optional<std::vector<std::string>>
  split_without_empty(const std::string &text, const char separator);

  /**
   * The items of a list entry "a,b,c ; d,e,f" (split at ';'), each
   * trimmed. An empty item (between two ';', or before the first) is
   * refused naming @p entry_name; a ';' after the last item is allowed.
   */
  std::vector<std::string>
  list_items(const std::string &text, const std::string &entry_name);

  /**
   * The fields of one item "a, b, c" of a list entry (split at ','), each
   * trimmed. An empty field, a trailing ',' included, is refused naming
   * @p entry_name.
   */
  std::vector<std::string>
  item_fields(const std::string &item, const std::string &entry_name);

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

  /**
   * "(x, y)" with 12 significant digits, for messages about a point a
   * scene gave: enough to show the offset that puts it just off the plate.
   */
  std::string
  point_text(const double x, const double y);
} // namespace PlateOnHalfspace

#endif
