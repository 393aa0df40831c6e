// Adaptivity/Goal = contact area: the area where the soil carries the
// plate, whole plate (doc/outputs.md, "Contact area").

#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/refinement/goal.h>

namespace PlateOnHalfspace
{
  namespace
  {
    class ContactAreaGoal : public GoalFunctional
    {
    public:
      using GoalFunctional::GoalFunctional;

      Estimate
      estimate() const override
      {
        return Estimate::contact_region;
      }

      Evaluation
      evaluate(const MindlinPlate &plate,
               const Vector<double> &,
               const Vector<double> &,
               const ContactState &contact) const override
      {
        Evaluation result;
        result.value = plate.get_foundation_space().symmetry.n_copies() *
                       contact_area(contact);
        return result;
      }
    };

    const bool registered = register_goal_kind(
      {"contact area",
       2,
       [](const std::string &text, const std::vector<std::string> &words)
         -> std::unique_ptr<GoalFunctional> {
         if (words != std::vector<std::string>{"contact", "area"})
           return nullptr;
         return std::make_unique<ContactAreaGoal>(text);
       }});
  } // namespace
} // namespace PlateOnHalfspace
