// Adaptivity/Goal = w at x1,y1 minus x2,y2: a differential settlement
// (doc/formulation.md, "Goal-oriented refinement").

#include <plate_on_halfspace/plate/field_extrema.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/refinement/goal.h>

namespace PlateOnHalfspace
{
  namespace
  {
    class DeflectionDifferenceGoal : public GoalFunctional
    {
    public:
      DeflectionDifferenceGoal(const std::string &text,
                               const Point<2>    &first,
                               const Point<2>    &second)
        : GoalFunctional(text)
        , first(first)
        , second(second)
      {}

      std::vector<std::pair<Point<2>, double>>
      deflection_terms() const override
      {
        return {{first, 1.}, {second, -1.}};
      }

      Evaluation
      evaluate(const MindlinPlate   &plate,
               const Vector<double> &solution,
               const Vector<double> &,
               const ContactState &) const override
      {
        const Evaluation other  = at_point(plate, second);
        Evaluation       result = at_point(plate, first);
        // w is read in the first cell, as a probe reads it
        result.value =
          PlateOnHalfspace::plate_quantity(plate,
                                           solution,
                                           PlateQuantity::w,
                                           result.cells.front().first,
                                           result.cells.front().second) -
          PlateOnHalfspace::plate_quantity(plate,
                                           solution,
                                           PlateQuantity::w,
                                           other.cells.front().first,
                                           other.cells.front().second);
        return result;
      }

      Vector<double>
      derivative(const MindlinPlate &plate,
                 const Vector<double> &,
                 const Evaluation &) const override
      {
        Vector<double> load(plate.get_dof_handler().n_dofs());
        for (const auto &[x, sign] : deflection_terms())
          {
            const Evaluation   e  = at_point(plate, x);
            const FESystem<2> &fe = plate.get_fe();
            Vector<double>     local(fe.n_dofs_per_cell());
            const auto         phi = q2_shape_values(e.cells.front().second);
            for (unsigned int i = 0; i < 9; ++i)
              local[fe.component_to_system_index(0, i)] = sign * phi[i];
            add_cell_vector(plate, e.cells.front().first, local, load);
          }
        return load;
      }

    private:
      const Point<2> first, second;
    };

    const bool registered = register_goal_kind(
      {"w at x1,y1 minus x2,y2",
       4,
       [](const std::string &text, const std::vector<std::string> &words)
         -> std::unique_ptr<GoalFunctional> {
         if (words.size() != 5 || words[0] != "w" || words[1] != "at" ||
             words[3] != "minus")
           return nullptr;
         const auto first  = parse_goal_point(words[2]),
                    second = parse_goal_point(words[4]);
         if (!first || !second)
           return nullptr;
         // the same point twice: J = 0 on every mesh, with no relative
         // error and no target it could meet
         AssertThrow(first->distance(*second) > 0,
                     ExcMessage("Adaptivity/Goal: <" + text +
                                "> names the same point twice; the "
                                "difference is 0 on every mesh and has no "
                                "relative error. Name two different "
                                "points."));
         return std::make_unique<DeflectionDifferenceGoal>(text,
                                                           *first,
                                                           *second);
       }});
  } // namespace
} // namespace PlateOnHalfspace
