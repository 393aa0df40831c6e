#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <plate_on_halfspace/base/number_list.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

namespace PlateOnHalfspace
{
  using namespace dealii;

  DecimalReading
  read_decimal_number(const std::string &text, double &value)
  {
    value = 0;
    if (text.empty() || text.find_first_of("xXpP") != std::string::npos)
      return DecimalReading::not_a_number;
    char *end = nullptr;
    errno     = 0;
    value     = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size())
      return DecimalReading::not_a_number;
    if (!std::isfinite(value))
      return errno == ERANGE ? DecimalReading::overflow :
                               DecimalReading::not_finite;
    // strtod signals both an underflow to 0 and a subnormal with ERANGE
    if (errno == ERANGE || std::fpclassify(value) == FP_SUBNORMAL)
      return DecimalReading::underflow;
    return DecimalReading::number;
  }

  std::vector<std::string>
  list_items(const std::string &text, const std::string &entry_name)
  {
    // split_string_list() keeps an empty item between two ';' (or before
    // the first) and drops one after the last: "a ; ; b" is a slip (an
    // item deleted in part?), refused like an empty field; a trailing ';'
    // stays allowed.
    const std::vector<std::string> items =
      Utilities::split_string_list(text, ';');
    for (std::size_t i = 0; i < items.size(); ++i)
      AssertThrow(!items[i].empty(),
                  ExcMessage("Entry <" + entry_name + ">: item " +
                             std::to_string(i + 1) + " of <" + text +
                             "> is empty (nothing between two ';', or "
                             "before the first); remove the extra ';'."));
    return items;
  }

  std::optional<std::vector<std::string>>
  split_without_empty(const std::string &text, const char separator)
  {
    std::vector<std::string> pieces =
      Utilities::split_string_list(text, separator);
    if (pieces.empty())
      return pieces;
    // split_string_list() drops a trailing empty piece: a separator with
    // nothing after it is a slip, not a shorter list.
    if (static_cast<std::size_t>(
          std::count(text.begin(), text.end(), separator)) +
            1 !=
          pieces.size() ||
        std::any_of(pieces.begin(), pieces.end(), [](const std::string &p) {
          return p.empty();
        }))
      return std::nullopt;
    return pieces;
  }

  std::vector<std::string>
  item_fields(const std::string &item, const std::string &entry_name)
  {
    const auto fields = split_without_empty(item, ',');
    AssertThrow(fields && !fields->empty(),
                ExcMessage("Entry <" + entry_name + ">: the item <" + item +
                           "> has an empty field."));
    return *fields;
  }

  std::vector<std::vector<double>>
  parse_number_list(const std::string &text,
                    const unsigned int n_fields,
                    const std::string &entry_name,
                    const std::string &field_names)
  {
    std::vector<std::vector<double>> items;
    for (const std::string &item : list_items(text, entry_name))
      {
        const std::vector<std::string> fields = item_fields(item, entry_name);
        AssertThrow(n_fields == 0 || fields.size() == n_fields,
                    ExcMessage("Entry <" + entry_name + ">: the item <" + item +
                               "> must have " + std::to_string(n_fields) +
                               " fields (" + field_names + ")."));
        std::vector<double> numbers;
        for (const std::string &field : fields)
          {
            double               value   = 0;
            const DecimalReading reading = read_decimal_number(field, value);
            AssertThrow(reading == DecimalReading::number ||
                          reading == DecimalReading::not_finite,
                        ExcMessage("Entry <" + entry_name + ">: <" + field +
                                   "> in <" + item +
                                   "> is not a number (a decimal "
                                   "number of magnitude 1e-307 to "
                                   "1e308, or 0)."));
            AssertThrow(reading == DecimalReading::number,
                        ExcMessage("Entry <" + entry_name + ">: <" + field +
                                   "> is not a finite number."));
            numbers.push_back(value);
          }
        items.push_back(numbers);
      }
    return items;
  }

  std::string
  point_text(const double x, const double y)
  {
    std::ostringstream text;
    text << std::setprecision(12) << "(" << x << ", " << y << ")";
    return text.str();
  }
} // namespace PlateOnHalfspace
