#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <plate_on_halfspace/plate/field_extrema.h>
#include <plate_on_halfspace/refinement/goal.h>

#include <cmath>

namespace PlateOnHalfspace
{
  namespace
  {
    using Kind     = Parameters::Goal::Kind;
    using Quantity = Parameters::Goal::Quantity;

    PlateQuantity
    plate_quantity_of(const Quantity quantity)
    {
      switch (quantity)
        {
          case Quantity::mx:
            return PlateQuantity::mx;
          case Quantity::my:
            return PlateQuantity::my;
          case Quantity::mxy:
            return PlateQuantity::mxy;
          case Quantity::principal_moment:
            return PlateQuantity::principal_moment;
          case Quantity::stress_bottom:
            return PlateQuantity::principal_stress_bottom;
          case Quantity::stress_top:
            return PlateQuantity::principal_stress_top;
          case Quantity::w:
          case Quantity::q:
            break;
        }
      return PlateQuantity::w;
    }

    /**
     * The derivatives of Mx, My, Mxy (doc/formulation.md, "Conventions")
     * and of w with respect to the cell's shape functions at the reference
     * point @p p.
     */
    struct LocalDerivatives
    {
      Vector<double> w, mx, my, mxy;
    };

    LocalDerivatives
    local_derivatives(const MindlinPlate                                 &plate,
                      const typename DoFHandler<2>::active_cell_iterator &cell,
                      const Point<2>                                     &p)
    {
      const FESystem<2> &fe = plate.get_fe();
      FEValues<2>        values(fe,
                         Quadrature<2>(std::vector<Point<2>>{p}),
                         update_values | update_gradients);
      values.reinit(cell);
      const unsigned int n = fe.n_dofs_per_cell();
      LocalDerivatives   d{Vector<double>(n),
                         Vector<double>(n),
                         Vector<double>(n),
                         Vector<double>(n)};
      const double D = plate.flexural_rigidity(), nu = plate.poissons_ratio();
      for (unsigned int i = 0; i < n; ++i)
        {
          const unsigned int component = fe.system_to_component_index(i).first;
          if (component == 0)
            {
              d.w[i] = values.shape_value_component(i, 0, 0);
              continue;
            }
          // beta_x = component 1, beta_y = component 2
          const Tensor<1, 2> g = values.shape_grad_component(i, 0, component);
          if (component == 1)
            {
              d.mx[i]  = -D * g[0];
              d.my[i]  = -D * nu * g[0];
              d.mxy[i] = -D * 0.5 * (1. - nu) * g[1];
            }
          else
            {
              d.mx[i]  = -D * nu * g[1];
              d.my[i]  = -D * g[1];
              d.mxy[i] = -D * 0.5 * (1. - nu) * g[0];
            }
        }
      return d;
    }

  } // namespace

  GoalFunctional::GoalFunctional(const Parameters::Goal &goal,
                                 const MirrorSymmetry   &symmetry)
    : goal(goal)
    , symmetry(symmetry)
  {}

  bool
  GoalFunctional::measures_contact_area() const
  {
    return goal.kind == Kind::contact_area;
  }

  bool
  GoalFunctional::depends_on_plate_only() const
  {
    return !measures_contact_area() &&
           !(goal.kind == Kind::point_value && goal.quantity == Quantity::q);
  }

  std::vector<std::pair<Point<2>, double>>
  GoalFunctional::deflection_terms() const
  {
    if (goal.kind == Kind::point_value && goal.quantity == Quantity::w)
      return {{symmetry.to_computed_part(goal.first_point), 1.}};
    if (goal.kind == Kind::w_difference)
      return {{symmetry.to_computed_part(goal.first_point), 1.},
              {symmetry.to_computed_part(goal.second_point), -1.}};
    return {};
  }

  GoalFunctional::Evaluation
  GoalFunctional::evaluate(const MindlinPlate   &plate,
                           const Vector<double> &solution,
                           const Vector<double> &pressure_field,
                           const ContactState   &contact) const
  {
    Evaluation result;
    const auto at_point = [&](const Point<2> &x) {
      Evaluation e;
      e.location     = symmetry.to_computed_part(x);
      e.has_location = true;
      try
        {
          std::tie(e.cell, e.reference_point) = plate.locate(e.location);
        }
      catch (...)
        {
          AssertThrow(
            false,
            ExcMessage("Adaptivity/Goal: the point (" + std::to_string(x[0]) +
                       ", " + std::to_string(x[1]) + ") is not on the plate."));
        }
      return e;
    };
    switch (goal.kind)
      {
        case Kind::none:
          break;
        case Kind::point_value:
          result = at_point(goal.first_point);
          result.value =
            plate_quantity(plate,
                           goal.quantity == Quantity::q ? pressure_field :
                                                          solution,
                           plate_quantity_of(goal.quantity),
                           result.cell,
                           result.reference_point);
          break;
        case Kind::w_difference:
          {
            const Evaluation second = at_point(goal.second_point);
            result                  = at_point(goal.first_point);
            result.value            = plate_quantity(plate,
                                          solution,
                                          PlateQuantity::w,
                                          result.cell,
                                          result.reference_point) -
                           plate_quantity(plate,
                                          solution,
                                          PlateQuantity::w,
                                          second.cell,
                                          second.reference_point);
            break;
          }
        case Kind::peak:
          {
            const FieldExtremum peak =
              field_maximum(plate, solution, plate_quantity_of(goal.quantity));
            result.value           = peak.value;
            result.location        = peak.location;
            result.has_location    = true;
            result.cell            = peak.cell;
            result.reference_point = peak.reference_point;
            break;
          }
        case Kind::mean_w:
          // linear: the derivative (the mean of each shape function, with
          // the constraints) times the solution
          result.value = derivative(plate, solution, result) * solution;
          break;
        case Kind::contact_area:
          result.value =
            symmetry.n_copies() * plate.get_foundation_space()
                                    .area_in_contact(contact.in_contact)
                                    .second;
          break;
      }
    AssertThrow(std::isfinite(result.value),
                ExcMessage("Adaptivity/Goal: the value of <" + goal.text +
                           "> is not finite."));
    return result;
  }

  Vector<double>
  GoalFunctional::derivative(const MindlinPlate   &plate,
                             const Vector<double> &solution,
                             const Evaluation     &evaluation) const
  {
    AssertThrow(depends_on_plate_only(), ExcInternalError());
    const DoFHandler<2>                 &dof_handler = plate.get_dof_handler();
    const AffineConstraints<double>     &constraints = plate.get_constraints();
    const unsigned int                   n = plate.get_fe().n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(n);
    Vector<double>                       load(dof_handler.n_dofs());

    const auto add_at =
      [&](const typename DoFHandler<2>::active_cell_iterator &cell,
          const Vector<double>                               &local) {
        cell->get_dof_indices(dofs);
        constraints.distribute_local_to_global(local, dofs, load);
      };

    switch (goal.kind)
      {
        case Kind::none:
        case Kind::contact_area:
          break;
        case Kind::point_value:
        case Kind::peak:
          {
            const LocalDerivatives d =
              local_derivatives(plate,
                                evaluation.cell,
                                evaluation.reference_point);
            Vector<double> local(n);
            switch (goal.quantity)
              {
                case Quantity::w:
                case Quantity::q:
                  local = d.w;
                  break;
                case Quantity::mx:
                  local = d.mx;
                  break;
                case Quantity::my:
                  local = d.my;
                  break;
                case Quantity::mxy:
                  local = d.mxy;
                  break;
                case Quantity::principal_moment:
                case Quantity::stress_bottom:
                case Quantity::stress_top:
                  {
                    // M1,2 = (Mx + My)/2 +- R, R = sqrt(((Mx - My)/2)^2 +
                    // Mxy^2): dM1,2 = (dMx + dMy)/2 +- ((Mx - My)/2 (dMx -
                    // dMy)/2 + Mxy dMxy) / R. The bottom's largest
                    // principal stress is 6/t^2 M1 (plus a constant), the
                    // top's -6/t^2 M2 (MindlinPlate::fibre_stresses()).
                    const Moments m = plate.moments(evaluation.cell,
                                                    evaluation.reference_point,
                                                    solution);
                    const double  half_difference = 0.5 * (m.mx - m.my);
                    const double  radius = std::hypot(half_difference, m.mxy);
                    const double  t      = plate.thickness();
                    const double  sign =
                      goal.quantity == Quantity::stress_top ? -1. : 1.;
                    const double scale =
                      goal.quantity == Quantity::principal_moment ?
                        1. :
                        6. / (t * t);
                    for (unsigned int i = 0; i < n; ++i)
                      {
                        local[i] = 0.5 * (d.mx[i] + d.my[i]);
                        if (radius > 0)
                          local[i] +=
                            sign *
                            (half_difference * 0.5 * (d.mx[i] - d.my[i]) +
                             m.mxy * d.mxy[i]) /
                            radius;
                        local[i] *= sign * scale;
                      }
                    break;
                  }
              }
            add_at(evaluation.cell, local);
            break;
          }
        case Kind::w_difference:
          {
            for (const auto &[x, sign] :
                 {std::make_pair(goal.first_point, 1.),
                  std::make_pair(goal.second_point, -1.)})
              {
                const auto located = plate.locate(symmetry.to_computed_part(x));
                Vector<double> local =
                  local_derivatives(plate, located.first, located.second).w;
                local *= sign;
                add_at(located.first, local);
              }
            break;
          }
        case Kind::mean_w:
          {
            const QGauss<2> rule(3);
            FEValues<2>     values(plate.get_fe(),
                               rule,
                               update_values | update_JxW_values);
            double          area = 0;
            for (const auto &cell : dof_handler.active_cell_iterators())
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
                add_at(cell, local);
              }
            load /= area;
            break;
          }
      }
    return load;
  }
} // namespace PlateOnHalfspace
