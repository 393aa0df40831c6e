#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <plate_on_halfspace/base/number_list.h>

#include <algorithm>
#include <cmath>

namespace PlateOnHalfspace
{
  using namespace dealii;

  std::vector<std::vector<double>>
  parse_number_list(const std::string &text,
                    const unsigned int n_fields,
                    const std::string &entry_name,
                    const std::string &field_names)
  {
    std::vector<std::vector<double>> items;
    for (const std::string &item : Utilities::split_string_list(text, ';'))
      {
        if (item.empty())
          continue;
        const std::vector<std::string> fields =
          Utilities::split_string_list(item, ',');
        // split_string_list() drops a trailing empty field: a comma
        // with nothing after it is a malformed item, not a shorter one.
        AssertThrow(static_cast<std::size_t>(
                      std::count(item.begin(), item.end(), ',')) +
                        1 ==
                      fields.size(),
                    ExcMessage("Entry <" + entry_name + ">: the item <" + item +
                               "> has an empty field."));
        AssertThrow(n_fields == 0 || fields.size() == n_fields,
                    ExcMessage("Entry <" + entry_name + ">: the item <" + item +
                               "> must have " + std::to_string(n_fields) +
                               " fields (" + field_names + ")."));
        std::vector<double> numbers;
        for (const std::string &field : fields)
          {
            // A decimal number: strtod alone would also take the
            // hexadecimal 0x10 as 16 (and 0x1p4).
            double value = 0;
            try
              {
                AssertThrow(field.find_first_of("xXpP") == std::string::npos,
                            ExcInternalError());
                value = Utilities::string_to_double(field);
              }
            catch (...)
              {
                AssertThrow(false,
                            ExcMessage("Entry <" + entry_name + ">: <" + field +
                                       "> in <" + item +
                                       "> is not a number (a decimal "
                                       "number of magnitude 1e-307 to "
                                       "1e308, or 0)."));
              }
            AssertThrow(std::isfinite(value),
                        ExcMessage("Entry <" + entry_name + ">: <" + field +
                                   "> is not a finite number."));
            numbers.push_back(value);
          }
        items.push_back(numbers);
      }
    return items;
  }
} // namespace PlateOnHalfspace
