#include <deal.II/base/bounding_box.h>

#include <plate_on_halfspace/base/quadrilateral_geometry.h>
#include <plate_on_halfspace/loads/load.h>
#include <plate_on_halfspace/loads/load_helpers.h>

#include <algorithm>
#include <cmath>

namespace PlateOnHalfspace
{
  namespace
  {
    /** A uniform pressure on a rectangle [x1, x2] x [y1, y2]
     *  (Loads/Rectangular patches), exactly over each cell's part. */
    class RectangularPatchLoad : public Load
    {
    public:
      RectangularPatchLoad(const Point<2>    &lower,
                           const Point<2>    &upper,
                           const double       pressure,
                           const std::string &label)
        : patch{lower, upper, pressure}
        , name(label)
      {}

      std::string
      label() const override
      {
        return name;
      }

      CellLoad
      on_cell(const BilinearQuadrilateral &cell,
              const unsigned int           extra_points) const override
      {
        // 5 points per direction on each piece: exact for the goal
        // estimate's weights, as the uniform pressure.
        Quadrature<2>      rule = quadrature_on_rectangle_part(cell,
                                                          patch.lower,
                                                          patch.upper,
                                                          5 + extra_points);
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
        const double overlap_x = std::min(box.upper_bound(0), patch.upper[0]) -
                                 std::max(box.lower_bound(0), patch.lower[0]),
                     overlap_y = std::min(box.upper_bound(1), patch.upper[1]) -
                                 std::max(box.lower_bound(1), patch.lower[1]);
        if (overlap_x <= 0 || overlap_y <= 0)
          return 0; // apart, or touching along an edge
        const BoundingBox<2> patch_box({patch.lower, patch.upper});
        const bool           all_inside =
          std::all_of(vertices.begin(), vertices.end(), [&](const Point<2> &v) {
            return patch_box.point_inside(v);
          });
        return all_inside ? 0 : std::abs(patch.pressure) * area;
      }

      std::optional<double>
      region_area() const override
      {
        return (patch.upper[0] - patch.lower[0]) *
               (patch.upper[1] - patch.lower[1]);
      }

      std::optional<double>
      region_width() const override
      {
        return std::min(patch.upper[0] - patch.lower[0],
                        patch.upper[1] - patch.lower[1]);
      }

      std::optional<double>
      nominal_force() const override
      {
        return patch.pressure * *region_area();
      }

      std::shared_ptr<const Load>
      mirror_image(const unsigned int axis) const override
      {
        Patch image       = patch;
        image.lower[axis] = -patch.upper[axis];
        image.upper[axis] = -patch.lower[axis];
        return std::make_shared<RectangularPatchLoad>(image.lower,
                                                      image.upper,
                                                      image.pressure,
                                                      name);
      }

      bool
      same_as(const Load &other, const double tolerance) const override
      {
        const auto *o = dynamic_cast<const RectangularPatchLoad *>(&other);
        return o && o->patch.lower.distance(patch.lower) <= tolerance &&
               o->patch.upper.distance(patch.upper) <= tolerance &&
               same_value(o->patch.pressure, patch.pressure);
      }

      std::shared_ptr<const Load>
      on_computed_part(const std::array<bool, 2> &planes,
                       const double) const override
      {
        // Any part on the computed side stays (the cells clip the patch):
        // a thin patch across a plane carries its share there, however
        // thin, where a tolerance would drop it.
        if ((planes[0] && patch.upper[0] <= 0) ||
            (planes[1] && patch.upper[1] <= 0))
          return nullptr;
        return std::make_shared<RectangularPatchLoad>(*this);
      }

    private:
      struct Patch
      {
        Point<2> lower, upper;
        double   pressure;
      } patch;
      std::string name;
    };
  } // namespace

  std::shared_ptr<const Load>
  create_rectangular_patch(const Point<2>    &lower,
                           const Point<2>    &upper,
                           const double       pressure,
                           const std::string &label)
  {
    return std::make_shared<RectangularPatchLoad>(lower,
                                                  upper,
                                                  pressure,
                                                  label);
  }
} // namespace PlateOnHalfspace
