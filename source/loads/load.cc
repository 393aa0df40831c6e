#include <plate_on_halfspace/loads/load.h>

#include <algorithm>

namespace PlateOnHalfspace
{
  namespace
  {
    std::vector<LoadKind> &
    kinds()
    {
      // a function's static: made on first use, whatever the order in
      // which the kinds' files register
      static std::vector<LoadKind> registered;
      return registered;
    }
  } // namespace

  bool
  register_load_kind(const LoadKind &kind)
  {
    auto &list = kinds();
    list.push_back(kind);
    // the order of the entries does not depend on the link order
    std::sort(list.begin(), list.end(), [](const auto &a, const auto &b) {
      return a.name < b.name;
    });
    return true;
  }

  const std::vector<LoadKind> &
  registered_load_kinds()
  {
    return kinds();
  }

  LoadList
  loads_on_computed_part(const LoadList            &loads,
                         const std::array<bool, 2> &planes,
                         const double               tolerance)
  {
    if (!planes[0] && !planes[1])
      return loads;
    LoadList part;
    for (const auto &load : loads)
      if (auto kept = load->on_computed_part(planes, tolerance))
        part.push_back(std::move(kept));
    return part;
  }

  std::string
  reason_loads_not_symmetric(const LoadList    &loads,
                             const unsigned int axis,
                             const double       tolerance)
  {
    const auto count_same = [&](const Load &load) {
      return std::count_if(loads.begin(),
                           loads.end(),
                           [&](const std::shared_ptr<const Load> &l) {
                             return l->same_as(load, tolerance);
                           });
    };
    for (const auto &load : loads)
      {
        const auto image = load->mirror_image(axis);
        if (!image)
          return load->label() + " is not checked for mirror symmetry";
        if (count_same(*load) != count_same(*image))
          return std::string("the loads are not mirror symmetric about ") +
                 (axis == 0 ? "x = 0" : "y = 0");
      }
    return "";
  }

  LoadList
  standing_loads(const LoadList &loads)
  {
    LoadList standing;
    for (const auto &load : loads)
      if (load->standing())
        standing.push_back(load);
    return standing;
  }
} // namespace PlateOnHalfspace
