#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/scene/parameters.h>

#include <cmath>

namespace PlateOnHalfspace
{
  namespace Parameters
  {
    namespace
    {
      // The layouts (doc/parameters.md, "Axles", with the sources), in
      // metres: x along the travel, y across it.
      constexpr double truck_track  = 1.83;  // 72 in between wheel centres
      constexpr double truck_dual   = 0.343; // 13.5 in between dual tyres
      constexpr double tandem_axles = 1.311; // 51.6 in
      constexpr double tridem_axles = 1.250; // 49.2 in
      constexpr double b737_dual    = 0.864; // 34 in
      constexpr double b767_dual    = 1.143; // 45 in
      constexpr double b767_tandem  = 1.422; // 56 in
      constexpr double b777_dual    = 1.397; // 55 in
      constexpr double b777_tandem  = 1.448; // 57 in

      /** A truck axle at x: dual sets (or single tyres) at +-track/2. */
      void
      add_truck_axle(const double           x,
                     const bool             dual,
                     std::vector<Point<2>> &tyres)
      {
        for (const double side : {-0.5 * truck_track, 0.5 * truck_track})
          if (dual)
            for (const double offset : {-0.5 * truck_dual, 0.5 * truck_dual})
              tyres.emplace_back(x, side + offset);
          else
            tyres.emplace_back(x, side);
      }
    } // namespace

    const std::vector<std::string> &
    AxleGroup::type_names()
    {
      static const std::vector<std::string> names = {"single",
                                                     "single dual",
                                                     "tandem",
                                                     "tridem",
                                                     "dual gear",
                                                     "dual tandem gear",
                                                     "triple dual tandem gear"};
      return names;
    }

    std::vector<Point<2>>
    AxleGroup::tyre_layout(const Type type)
    {
      std::vector<Point<2>> tyres;
      switch (type)
        {
          case Type::single:
            add_truck_axle(0, false, tyres);
            break;
          case Type::single_dual:
            add_truck_axle(0, true, tyres);
            break;
          case Type::tandem:
            for (const double x : {-0.5 * tandem_axles, 0.5 * tandem_axles})
              add_truck_axle(x, true, tyres);
            break;
          case Type::tridem:
            for (const double x : {-tridem_axles, 0., tridem_axles})
              add_truck_axle(x, true, tyres);
            break;
          case Type::dual_gear:
            tyres = {Point<2>(0, -0.5 * b737_dual),
                     Point<2>(0, 0.5 * b737_dual)};
            break;
          case Type::dual_tandem_gear:
            for (const double x : {-0.5 * b767_tandem, 0.5 * b767_tandem})
              for (const double y : {-0.5 * b767_dual, 0.5 * b767_dual})
                tyres.emplace_back(x, y);
            break;
          case Type::triple_dual_tandem_gear:
            for (const double x : {-b777_tandem, 0., b777_tandem})
              for (const double y : {-0.5 * b777_dual, 0.5 * b777_dual})
                tyres.emplace_back(x, y);
            break;
        }
      return tyres;
    }

    std::vector<CircularPatch>
    AxleGroup::tyre_patches(const unsigned int number) const
    {
      const std::vector<Point<2>> layout = tyre_layout(type);
      const double                radius =
        std::sqrt(load / (layout.size() * M_PI * tyre_pressure));
      const double c = std::cos(angle * M_PI / 180.),
                   s = std::sin(angle * M_PI / 180.);
      std::vector<CircularPatch> tyres;
      for (unsigned int k = 0; k < layout.size(); ++k)
        {
          const Point<2> &p = layout[k];
          tyres.push_back(
            {centre + Point<2>(c * p[0] - s * p[1], s * p[0] + c * p[1]),
             radius,
             tyre_pressure,
             "Loads/Axles: group " + std::to_string(number) + " (" +
               type_names()[static_cast<unsigned int>(type)] + "), tyre " +
               std::to_string(k + 1)});
        }
      return tyres;
    }
  } // namespace Parameters
} // namespace PlateOnHalfspace
