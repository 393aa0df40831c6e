#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/soil/boussinesq_kernel.h>
#include <plate_on_halfspace/soil/dense_liquid.h>
#include <plate_on_halfspace/soil/half_space.h>
#include <plate_on_halfspace/soil/layered_soil.h>
#include <plate_on_halfspace/soil/soil_model.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <algorithm>
#include <limits>

namespace PlateOnHalfspace
{
  ElasticSoil::ElasticSoil(const unsigned int singular_order)
    : singular_order(singular_order)
  {}

  std::vector<double>
  ElasticSoil::settlement_at_points(const FoundationSpace       &space,
                                    const Vector<double>        &nodal_pressure,
                                    const std::vector<Point<2>> &points) const
  {
    return PlateOnHalfspace::settlement_at_points(space,
                                                  nodal_pressure,
                                                  points,
                                                  kernel(
                                                    maximal_distance(space)),
                                                  singular_order);
  }

  double
  maximal_distance(const FoundationSpace &space)
  {
    double     lower[2] = {std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::max()};
    double     upper[2] = {-lower[0], -lower[1]};
    const auto extend   = [&](const std::vector<FoundationSpace::Cell> &cells) {
      for (const auto &cell : cells)
        for (const Point<2> &v : cell.geometry.get_vertices())
          for (unsigned int d = 0; d < 2; ++d)
            {
              lower[d] = std::min(lower[d], v[d]);
              upper[d] = std::max(upper[d], v[d]);
            }
    };
    extend(space.cells);
    extend(space.mirror_image_cells());
    if (lower[0] > upper[0])
      return 0.;
    return std::hypot(upper[0] - lower[0], upper[1] - lower[1]);
  }

  std::shared_ptr<const SoilModel>
  create_soil_model(const SceneParameters &parameters)
  {
    using Model             = Parameters::Foundation::Model;
    const auto        &soil = parameters.foundation;
    const unsigned int order =
      parameters.discretization.singular_quadrature_order;
    switch (soil.model)
      {
        case Model::dense_liquid:
          return std::make_shared<DenseLiquidSoil>(soil.subgrade_modulus);
        case Model::layered:
          {
            LayeredProfile profile;
            for (const auto &layer : soil.layers)
              profile.layers.push_back(
                {layer.thickness, layer.youngs_modulus, layer.poissons_ratio});
            profile.base = soil.rigid_base ? LayeredProfile::Base::rigid :
                                             LayeredProfile::Base::half_space;
            profile.base_youngs_modulus = soil.youngs_modulus;
            profile.base_poissons_ratio = soil.poissons_ratio;
            profile.interfaces          = soil.frictionless_interfaces ?
                                            LayeredProfile::Interfaces::frictionless :
                                            LayeredProfile::Interfaces::bonded;
            return std::make_shared<LayeredSoil>(profile, order);
          }
        case Model::half_space:
        default:
          return std::make_shared<HomogeneousHalfSpace>(
            boussinesq_flexibility_constant(soil.youngs_modulus,
                                            soil.poissons_ratio),
            order);
      }
  }
} // namespace PlateOnHalfspace
