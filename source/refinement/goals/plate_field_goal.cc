#include "plate_field_goal.h"

#include <deal.II/base/quadrature.h>

#include <deal.II/fe/fe_values.h>

#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <cmath>

namespace PlateOnHalfspace
{
  std::optional<PlateFieldGoal::Field>
  PlateFieldGoal::parse_field(const std::string &name, const bool peak)
  {
    if (name == "w" && !peak)
      return Field::w;
    if (name == "q" && !peak)
      return Field::q;
    if (name == "Mx")
      return Field::mx;
    if (name == "My")
      return Field::my;
    if (name == "Mxy" && !peak)
      return Field::mxy;
    if (name == "M1" && peak)
      return Field::principal_moment;
    if (name == "stress_bottom")
      return Field::stress_bottom;
    if (name == "stress_top")
      return Field::stress_top;
    return std::nullopt;
  }

  PlateFieldGoal::PlateFieldGoal(const std::string &text, const Field field)
    : GoalFunctional(text)
    , field(field)
  {}

  PlateQuantity
  PlateFieldGoal::field_quantity() const
  {
    switch (field)
      {
        case Field::mx:
          return PlateQuantity::mx;
        case Field::my:
          return PlateQuantity::my;
        case Field::mxy:
          return PlateQuantity::mxy;
        case Field::principal_moment:
          return PlateQuantity::principal_moment;
        case Field::stress_bottom:
          return PlateQuantity::principal_stress_bottom;
        case Field::stress_top:
          return PlateQuantity::principal_stress_top;
        case Field::w:
        case Field::q:
          break;
      }
    return PlateQuantity::w;
  }

  namespace
  {
    /** The mean of the moments of @p solution in @p evaluation's cells,
     *  Mxy 0 on a mirror plane. */
    Moments
    mean_moments(const MindlinPlate               &plate,
                 const Vector<double>             &solution,
                 const GoalFunctional::Evaluation &evaluation)
    {
      Moments mean = plate.mean_moments(evaluation.cells, solution);
      if (evaluation.on_mirror_plane)
        mean.mxy = 0;
      return mean;
    }
  } // namespace

  double
  PlateFieldGoal::value_at(const MindlinPlate   &plate,
                           const Vector<double> &solution,
                           const Vector<double> &pressure_field,
                           const Evaluation     &evaluation) const
  {
    const auto &[cell, reference] = evaluation.cells.front();
    if (field == Field::w)
      return plate_quantity(plate, solution, PlateQuantity::w, cell, reference);
    if (field == Field::q)
      return plate_quantity(
        plate, pressure_field, PlateQuantity::w, cell, reference);
    const double value =
      moment_quantity(plate,
                      mean_moments(plate, solution, evaluation),
                      field_quantity());
    // a zero stays +0, as a probe's
    return field == Field::mxy && value != 0 ?
             evaluation.odd_field_sign * value :
             value;
  }

  Vector<double>
  PlateFieldGoal::derivative(const MindlinPlate   &plate,
                             const Vector<double> &solution,
                             const Evaluation     &evaluation) const
  {
    AssertThrow(estimate() == Estimate::dual_weighted_residual,
                ExcInternalError());
    Vector<double> load(plate.get_dof_handler().n_dofs());
    // the whole plate's Mxy on a mirror plane is 0 whatever the solution
    if (field == Field::mxy && evaluation.on_mirror_plane)
      return load;
    const bool moment_field = field != Field::w && field != Field::q;
    // where a principal value is linearised
    const Moments m =
      moment_field ? mean_moments(plate, solution, evaluation) : Moments();
    const unsigned int n_cells = moment_field ? evaluation.cells.size() : 1;
    const FESystem<2> &fe      = plate.get_fe();
    const unsigned int n       = fe.n_dofs_per_cell();
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const auto &[cell, reference] = evaluation.cells[c];
        FEValues<2> values(fe,
                           Quadrature<2>(std::vector<Point<2>>{reference}),
                           update_values | update_gradients);
        values.reinit(cell);
        // The derivatives of w and of the moments (the plate's one moment
        // law, MindlinPlate::bending_moments()) with respect to each shape
        // function.
        Vector<double>       dw(n);
        std::vector<Moments> dm(n);
        for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int component =
              fe.system_to_component_index(i).first;
            if (component == 0)
              {
                dw[i] = values.shape_value_component(i, 0, 0);
                continue;
              }
            // grad beta of the shape function: row component - 1 of the
            // tensor
            Tensor<2, 2> grad_beta;
            grad_beta[component - 1] =
              values.shape_grad_component(i, 0, component);
            dm[i] = plate.bending_moments(grad_beta);
          }

        Vector<double> local(n);
        switch (field)
          {
            case Field::w:
            case Field::q:
              local = dw;
              break;
            case Field::mx:
            case Field::my:
            case Field::mxy:
              for (unsigned int i = 0; i < n; ++i)
                local[i] = field == Field::mx ? dm[i].mx :
                           field == Field::my ? dm[i].my :
                                                dm[i].mxy;
              if (field == Field::mxy)
                local *= evaluation.odd_field_sign;
              break;
            case Field::principal_moment:
            case Field::stress_bottom:
            case Field::stress_top:
              {
                // M1,2 = (Mx + My)/2 +- R, R = sqrt(((Mx - My)/2)^2 +
                // Mxy^2): dM1,2 = (dMx + dMy)/2 +- ((Mx - My)/2 (dMx -
                // dMy)/2 + Mxy dMxy) / R. The bottom's largest principal
                // stress is 6/t^2 M1 (plus a constant), the top's -6/t^2 M2
                // (MindlinPlate::fibre_stresses()).
                const double half_difference = 0.5 * (m.mx - m.my);
                const double radius = std::hypot(half_difference, m.mxy);
                const double t      = plate.thickness();
                const double sign   = field == Field::stress_top ? -1. : 1.;
                const double scale =
                  field == Field::principal_moment ? 1. : 6. / (t * t);
                for (unsigned int i = 0; i < n; ++i)
                  {
                    local[i] = 0.5 * (dm[i].mx + dm[i].my);
                    if (radius > 0)
                      local[i] +=
                        sign *
                        (half_difference * 0.5 * (dm[i].mx - dm[i].my) +
                         m.mxy * dm[i].mxy) /
                        radius;
                    local[i] *= sign * scale;
                  }
                break;
              }
          }
        // the mean of the cells' values
        local /= n_cells;
        add_cell_vector(plate, cell, local, load);
      }
    return load;
  }
} // namespace PlateOnHalfspace
