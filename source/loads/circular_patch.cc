#include <deal.II/base/bounding_box.h>
#include <deal.II/base/numbers.h>

#include <plate_on_halfspace/base/quadrilateral_geometry.h>
#include <plate_on_halfspace/loads/load.h>
#include <plate_on_halfspace/loads/load_helpers.h>

#include <algorithm>
#include <cmath>

namespace PlateOnHalfspace
{
  namespace
  {
    /** A uniform pressure on a disk (Loads/Circular patches, and each tyre
     *  of Loads/Axles). */
    class CircularPatchLoad : public Load
    {
    public:
      CircularPatchLoad(const Point<2>    &centre,
                        const double       radius,
                        const double       pressure,
                        const std::string &label)
        : patch{centre, radius, pressure, label}
      {}

      std::string
      label() const override
      {
        return patch.label;
      }

      CellLoad
      on_cell(const BilinearQuadrilateral &cell,
              const unsigned int           extra_points) const override
      {
        // 8 points per piece: the rim's segments converge exponentially
        // (quadrature_on_disk_part()).
        Quadrature<2>      rule = quadrature_on_disk_part(cell,
                                                     patch.centre,
                                                     patch.radius,
                                                     8 + extra_points);
        const unsigned int n    = rule.size();
        return {std::move(rule), std::vector<double>(n, patch.pressure)};
      }

      bool
      integrated_exactly() const override
      {
        return true;
      }

      double
      jump_on(const std::array<Point<2>, 4> &vertices,
              const double                   area) const override
      {
        const BoundingBox<2> box(
          std::vector<Point<2>>(vertices.begin(), vertices.end()));
        const auto inside =
          std::count_if(vertices.begin(),
                        vertices.end(),
                        [&](const Point<2> &v) {
                          return v.distance(patch.centre) <= patch.radius;
                        });
        // the rim crosses the cell: some vertices inside, or none while the
        // circle reaches into the cell's box
        const Point<2> nearest(
          std::clamp(patch.centre[0], box.lower_bound(0), box.upper_bound(0)),
          std::clamp(patch.centre[1], box.lower_bound(1), box.upper_bound(1)));
        return (inside < 4 && nearest.distance(patch.centre) < patch.radius) ?
                 std::abs(patch.pressure) * area :
                 0.;
      }

      std::optional<double>
      region_area() const override
      {
        return numbers::PI * patch.radius * patch.radius;
      }

      std::optional<double>
      region_width() const override
      {
        return 2 * patch.radius;
      }

      std::optional<double>
      nominal_force() const override
      {
        return patch.pressure * *region_area();
      }

      std::shared_ptr<const Load>
      mirror_image(const unsigned int axis) const override
      {
        Point<2> centre = patch.centre;
        centre[axis]    = -centre[axis];
        return std::make_shared<CircularPatchLoad>(centre,
                                                   patch.radius,
                                                   patch.pressure,
                                                   patch.label);
      }

      bool
      same_as(const Load &other, const double tolerance) const override
      {
        const auto *o = dynamic_cast<const CircularPatchLoad *>(&other);
        return o && o->patch.centre.distance(patch.centre) <= tolerance &&
               std::abs(o->patch.radius - patch.radius) <= tolerance &&
               same_value(o->patch.pressure, patch.pressure);
      }

      std::shared_ptr<const Load>
      on_computed_part(const std::array<bool, 2> &planes,
                       const double) const override
      {
        // Any part on the computed side stays (the cells clip the patch):
        // a thin patch across a plane carries its share there, however
        // thin, where a tolerance would drop it.
        if ((planes[0] && patch.centre[0] + patch.radius <= 0) ||
            (planes[1] && patch.centre[1] + patch.radius <= 0))
          return nullptr;
        return std::make_shared<CircularPatchLoad>(*this);
      }

    private:
      struct Patch
      {
        Point<2>    centre;
        double      radius, pressure;
        std::string label;
      } patch;
    };
  } // namespace

  std::shared_ptr<const Load>
  create_circular_patch(const Point<2>    &centre,
                        const double       radius,
                        const double       pressure,
                        const std::string &label)
  {
    return std::make_shared<CircularPatchLoad>(centre, radius, pressure, label);
  }
} // namespace PlateOnHalfspace
