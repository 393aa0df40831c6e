#include <plate_on_halfspace/scene/parameters.h>

namespace PlateOnHalfspace
{
  LoadList
  make_loads(const Parameters::Loads &loads, const double self_weight_pressure)
  {
    LoadList list;
    if (loads.uniform_pressure != 0)
      list.push_back(create_uniform_pressure(loads.uniform_pressure,
                                             "Loads/Uniform pressure"));
    if (self_weight_pressure != 0)
      list.push_back(
        create_uniform_pressure(self_weight_pressure, "Plate/Unit weight"));
    for (unsigned int k = 0; k < loads.rectangular_patches.size(); ++k)
      {
        const auto &patch = loads.rectangular_patches[k];
        list.push_back(
          create_rectangular_patch(patch.lower,
                                   patch.upper,
                                   patch.pressure,
                                   "Loads/Rectangular patches: patch " +
                                     std::to_string(k + 1)));
      }
    for (const auto &patch : loads.circular_patches)
      list.push_back(create_circular_patch(
        patch.centre, patch.radius, patch.pressure, patch.label));
    for (const auto &point : loads.point_loads)
      list.push_back(create_point_load(point.location, point.force));
    list.insert(list.end(),
                loads.registered_kinds.begin(),
                loads.registered_kinds.end());
    return list;
  }
} // namespace PlateOnHalfspace
