#include <deal.II/base/bounding_box.h>
#include <deal.II/base/exceptions.h>

#include <deal.II/numerics/rtree.h>

#include <plate_on_halfspace/soil/dense_liquid.h>

#include <cmath>
#include <limits>

namespace PlateOnHalfspace
{
  DenseLiquidSoil::DenseLiquidSoil(const double subgrade_modulus)
    : modulus(subgrade_modulus)
  {}

  std::string
  DenseLiquidSoil::name() const
  {
    return "dense liquid";
  }

  std::vector<double>
  DenseLiquidSoil::settlement_at_points(
    const FoundationSpace       &space,
    const Vector<double>        &nodal_pressure,
    const std::vector<Point<2>> &points) const
  {
    namespace bgi = boost::geometry::index;
    std::vector<std::pair<BoundingBox<2>, unsigned int>> boxes;
    boxes.reserve(space.cells.size());
    for (unsigned int c = 0; c < space.cells.size(); ++c)
      {
        BoundingBox<2> box(space.cells[c].geometry.bounding_box());
        box.extend(1e-10 * space.cells[c].geometry.diameter());
        boxes.emplace_back(box, c);
      }
    const auto tree = pack_rtree(boxes);

    std::vector<double> settlement(points.size());
    std::vector<std::pair<BoundingBox<2>, unsigned int>> candidates;
    for (unsigned int p = 0; p < points.size(); ++p)
      {
        candidates.clear();
        tree.query(bgi::intersects(points[p]), std::back_inserter(candidates));
        bool found = false;
        for (const auto &candidate : candidates)
          {
            const FoundationSpace::Cell &cell = space.cells[candidate.second];
            if (!cell.geometry.contains(points[p]))
              continue;
            const std::array<double, 9> shape =
              q2_shape_values(cell.geometry.inverse_map(points[p]));
            double pressure = 0;
            for (unsigned int i = 0; i < 9; ++i)
              for (const auto &term : cell.expansion[i])
                pressure += shape[i] * term.second * nodal_pressure[term.first];
            settlement[p] = pressure / modulus;
            found         = true;
            break;
          }
        AssertThrow(found,
                    ExcMessage("The point (" + std::to_string(points[p][0]) +
                               ", " + std::to_string(points[p][1]) +
                               ") is not on the plate."));
      }
    return settlement;
  }

  double
  DenseLiquidSoil::typical_settlement(const double force,
                                      const double area) const
  {
    return force / area / modulus;
  }

  double
  DenseLiquidSoil::patch_stiffness(const double) const
  {
    return modulus;
  }

  double
  DenseLiquidSoil::radius_of_relative_stiffness(
    const double flexural_rigidity) const
  {
    return std::sqrt(std::sqrt(flexural_rigidity / modulus));
  }

  double
  DenseLiquidSoil::relative_stiffness(const double flexural_rigidity,
                                      const double length) const
  {
    return flexural_rigidity / modulus / std::pow(length, 4);
  }
} // namespace PlateOnHalfspace
