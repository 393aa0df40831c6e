#include <plate_on_halfspace/base/quadrilateral_geometry.h>
#include <plate_on_halfspace/loads/load.h>

#include <cmath>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * A pressure on the whole plate: Loads/Uniform pressure, or the plate's
     * own weight (unit weight times thickness). Both stay while the axles
     * move.
     */
    class UniformPressure : public Load
    {
    public:
      UniformPressure(const double pressure, const std::string &label)
        : pressure(pressure)
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
        // 5 x 5 Gauss points: exact for the goal estimate's weights (degree
        // 9 on parallelograms), and so for the plate's shape functions.
        Quadrature<2>      rule = quadrature_on_cell(cell, 5 + extra_points);
        const unsigned int n    = rule.size();
        return {std::move(rule), std::vector<double>(n, pressure)};
      }

      bool
      integrated_exactly() const override
      {
        return true;
      }

      double
      jump_on(const std::array<Point<2>, 4> &, const double) const override
      {
        return 0;
      }

      bool
      standing() const override
      {
        return true;
      }

      std::shared_ptr<const Load>
      mirror_image(const unsigned int) const override
      {
        return std::make_shared<UniformPressure>(*this);
      }

      bool
      same_as(const Load &other, const double) const override
      {
        const auto *o = dynamic_cast<const UniformPressure *>(&other);
        return o && o->pressure == pressure;
      }

      std::shared_ptr<const Load>
      on_computed_part(const std::array<bool, 2> &, const double) const override
      {
        return std::make_shared<UniformPressure>(*this);
      }

    private:
      double      pressure;
      std::string name;
    };
  } // namespace

  std::shared_ptr<const Load>
  create_uniform_pressure(const double pressure, const std::string &label)
  {
    return std::make_shared<UniformPressure>(pressure, label);
  }
} // namespace PlateOnHalfspace
