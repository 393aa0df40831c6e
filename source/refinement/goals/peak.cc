// Adaptivity/Goal = peak <field>: the largest value of a plate field over
// the plate (doc/formulation.md, "Goal-oriented refinement").

#include <plate_on_halfspace/plate/mindlin_plate.h>

#include "plate_field_goal.h"

namespace PlateOnHalfspace
{
  namespace
  {
    class PeakGoal : public PlateFieldGoal
    {
    public:
      using PlateFieldGoal::PlateFieldGoal;

      Evaluation
      evaluate(const MindlinPlate   &plate,
               const Vector<double> &solution,
               const Vector<double> &,
               const ContactState &) const override
      {
        // linearised where the field peaks (field_extrema.h)
        const FieldExtremum peak =
          field_maximum(plate, solution, field_quantity());
        Evaluation result;
        result.value        = peak.value;
        result.location     = peak.location;
        result.has_location = true;
        result.cells        = {{peak.cell, peak.reference_point}};
        return result;
      }
    };

    const bool registered = register_goal_kind(
      {"peak Mx|My|M1|stress_bottom|stress_top",
       1,
       [](const std::string &text, const std::vector<std::string> &words)
         -> std::unique_ptr<GoalFunctional> {
         if (words.size() != 2 || words[0] != "peak")
           return nullptr;
         const auto field = PlateFieldGoal::parse_field(words[1], true);
         if (!field)
           return nullptr;
         return std::make_unique<PeakGoal>(text, *field);
       }});
  } // namespace
} // namespace PlateOnHalfspace
