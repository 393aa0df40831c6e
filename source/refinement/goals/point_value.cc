// Adaptivity/Goal = <field> at x,y: a plate field at a point
// (doc/formulation.md, "Goal-oriented refinement").

#include <plate_on_halfspace/plate/mindlin_plate.h>

#include "plate_field_goal.h"

namespace PlateOnHalfspace
{
  namespace
  {
    class PointValueGoal : public PlateFieldGoal
    {
    public:
      PointValueGoal(const std::string &text,
                     const Field        field,
                     const Point<2>    &point)
        : PlateFieldGoal(text, field)
        , point(point)
      {}

      Estimate
      estimate() const override
      {
        return field == Field::q ? Estimate::change_only :
                                   Estimate::dual_weighted_residual;
      }

      std::string
      no_estimate_reason() const override
      {
        return "the pressure's adjoint problem is not solved (it would need "
               "a load in the gap equation), so its error is bounded by the "
               "change between cycles";
      }

      std::vector<std::pair<Point<2>, double>>
      deflection_terms() const override
      {
        if (field == Field::w)
          return {{point, 1.}};
        return {};
      }

      Evaluation
      evaluate(const MindlinPlate   &plate,
               const Vector<double> &solution,
               const Vector<double> &pressure_field,
               const ContactState &) const override
      {
        Evaluation result = at_point(plate, point);
        result.value      = value_at(plate, solution, pressure_field, result);
        return result;
      }

    private:
      const Point<2> point;
    };

    const bool registered = register_goal_kind(
      {"w|Mx|My|Mxy|q|stress_bottom|stress_top at x,y",
       0,
       [](const std::string &text, const std::vector<std::string> &words)
         -> std::unique_ptr<GoalFunctional> {
         if (words.size() != 3 || words[1] != "at")
           return nullptr;
         const auto field = PlateFieldGoal::parse_field(words[0], false);
         if (!field)
           return nullptr;
         const auto point = parse_goal_point(words[2]);
         if (!point)
           return nullptr;
         return std::make_unique<PointValueGoal>(text, *field, *point);
       }});
  } // namespace
} // namespace PlateOnHalfspace
