// Adaptivity/Goal = mean w: the mean deflection over the plate
// (doc/formulation.md, "Goal-oriented refinement").

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/refinement/goal.h>

namespace PlateOnHalfspace
{
  namespace
  {
    class MeanDeflectionGoal : public GoalFunctional
    {
    public:
      using GoalFunctional::GoalFunctional;

      Evaluation
      evaluate(const MindlinPlate   &plate,
               const Vector<double> &solution,
               const Vector<double> &,
               const ContactState &) const override
      {
        // linear: the derivative (the mean of each shape function, with the
        // constraints) times the solution
        Evaluation result;
        result.value = derivative(plate, solution, result) * solution;
        return result;
      }

      Vector<double>
      derivative(const MindlinPlate &plate,
                 const Vector<double> &,
                 const Evaluation &) const override
      {
        const unsigned int n = plate.get_fe().n_dofs_per_cell();
        const QGauss<2>    rule(3);
        FEValues<2>        values(plate.get_fe(),
                           rule,
                           update_values | update_JxW_values);
        Vector<double>     load(plate.get_dof_handler().n_dofs());
        double             area = 0;
        for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
          {
            values.reinit(cell);
            Vector<double> local(n);
            for (unsigned int q = 0; q < rule.size(); ++q)
              {
                area += values.JxW(q);
                for (unsigned int i = 0; i < n; ++i)
                  local[i] +=
                    values.shape_value_component(i, q, 0) * values.JxW(q);
              }
            add_cell_vector(plate, cell, local, load);
          }
        load /= area;
        return load;
      }
    };

    const bool registered = register_goal_kind(
      {"mean w",
       3,
       [](const std::string &text, const std::vector<std::string> &words)
         -> std::unique_ptr<GoalFunctional> {
         if (words != std::vector<std::string>{"mean", "w"})
           return nullptr;
         return std::make_unique<MeanDeflectionGoal>(text);
       }});
  } // namespace
} // namespace PlateOnHalfspace
