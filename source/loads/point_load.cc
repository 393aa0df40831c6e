#include <deal.II/base/bounding_box.h>

#include <plate_on_halfspace/loads/load.h>
#include <plate_on_halfspace/loads/load_helpers.h>

#include <cmath>

namespace PlateOnHalfspace
{
  namespace
  {
    /** A force at a point (Loads/Point loads). */
    class PointLoadOnPlate : public Load
    {
    public:
      PointLoadOnPlate(const Point<2> &location, const double force)
        : location(location)
        , force(force)
      {}

      std::string
      label() const override
      {
        return "Loads/Point loads";
      }

      CellLoad
      on_cell(const BilinearQuadrilateral &, const unsigned int) const override
      {
        // a point load has no distributed part (concentrated_force())
        return CellLoad();
      }

      std::optional<std::pair<Point<2>, double>>
      concentrated_force() const override
      {
        return std::make_pair(location, force);
      }

      bool
      integrated_exactly() const override
      {
        return true;
      }

      double
      jump_on(const std::array<Point<2>, 4> &vertices,
              const double) const override
      {
        const BoundingBox<2> box(
          std::vector<Point<2>>(vertices.begin(), vertices.end()));
        return box.point_inside(location) ? std::abs(force) : 0.;
      }

      std::shared_ptr<const Load>
      mirror_image(const unsigned int axis) const override
      {
        Point<2> image = location;
        image[axis]    = -image[axis];
        return std::make_shared<PointLoadOnPlate>(image, force);
      }

      bool
      same_as(const Load &other, const double tolerance) const override
      {
        const auto *o = dynamic_cast<const PointLoadOnPlate *>(&other);
        return o && o->location.distance(location) <= tolerance &&
               same_value(o->force, force);
      }

      std::shared_ptr<const Load>
      on_computed_part(const std::array<bool, 2> &planes,
                       const double               tolerance) const override
      {
        Point<2> part       = location;
        double   part_force = force;
        for (const unsigned int axis : {0u, 1u})
          if (planes[axis])
            {
              if (part[axis] < -tolerance)
                return nullptr;
              if (part[axis] <= tolerance)
                {
                  // on the plane: the computed part carries its half
                  part[axis] = 0;
                  part_force /= 2;
                }
            }
        return std::make_shared<PointLoadOnPlate>(part, part_force);
      }

    private:
      Point<2> location;
      double   force;
    };
  } // namespace

  std::shared_ptr<const Load>
  create_point_load(const Point<2> &location, const double force)
  {
    return std::make_shared<PointLoadOnPlate>(location, force);
  }
} // namespace PlateOnHalfspace
