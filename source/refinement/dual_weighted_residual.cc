#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_tools.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/manifold.h>

#include <deal.II/lac/sparse_direct.h>

#include <plate_on_halfspace/base/quadrilateral_geometry.h>
#include <plate_on_halfspace/refinement/dual_weighted_residual.h>
#include <plate_on_halfspace/scene/mirror_symmetry.h>
#include <plate_on_halfspace/soil/soil_model.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

namespace PlateOnHalfspace
{
  namespace
  {
    using CellIterator = typename DoFHandler<2>::active_cell_iterator;

    /** The cell of @p dof_handler that is @p cell of the triangulation. */
    CellIterator
    same_cell(const CellIterator &cell, const DoFHandler<2> &dof_handler)
    {
      return CellIterator(&dof_handler.get_triangulation(),
                          cell->level(),
                          cell->index(),
                          &dof_handler);
    }

    /** A field's value and gradient at a point, three components. */
    struct Field
    {
      std::array<double, 3>       value{};
      std::array<Tensor<1, 2>, 3> gradient{};
    };

    /**
     * The plate's generalised strains of @p u, scaled to its stress
     * resultants: bending moments m = D_b kappa (as a vector over kappa's
     * components) and shear forces Q = D_s gamma.
     */
    struct Resultants
    {
      std::array<double, 3> moment{};
      Tensor<1, 2>          shear;
    };

    Resultants
    resultants(const Field &u, const double D, const double nu, const double Ds)
    {
      Tensor<2, 2> grad_beta;
      grad_beta[0]    = u.gradient[1];
      grad_beta[1]    = u.gradient[2];
      const Moments m = bending_moments(D, nu, grad_beta);
      // the energy form pairs D_b kappa = -M with the curvatures
      Resultants r;
      r.moment = {{-m.mx, -m.my, -m.mxy}};
      for (unsigned int d = 0; d < 2; ++d)
        r.shear[d] = Ds * (u.gradient[0][d] - u.value[1 + d]);
      return r;
    }

    /**
     * The test function psi * chi (psi the weight, chi a hat function with
     * value @p chi and gradient @p grad_chi): its curvatures and shear
     * strains.
     */
    void
    product_strains(const Field           &psi,
                    const double           chi,
                    const Tensor<1, 2>    &grad_chi,
                    std::array<double, 3> &kappa,
                    Tensor<1, 2>          &gamma)
    {
      std::array<Tensor<1, 2>, 3> grad;
      for (unsigned int c = 0; c < 3; ++c)
        grad[c] = chi * psi.gradient[c] + psi.value[c] * grad_chi;
      kappa = {{grad[1][0], grad[2][1], grad[1][1] + grad[2][0]}};
      for (unsigned int d = 0; d < 2; ++d)
        gamma[d] = grad[0][d] - chi * psi.value[1 + d];
    }

    void
    get_fields(const FEValues<2>    &values,
               const Vector<double> &vector,
               std::vector<Field>   &fields)
    {
      const unsigned int                     n = values.n_quadrature_points;
      std::vector<Vector<double>>            v(n, Vector<double>(3));
      std::vector<std::vector<Tensor<1, 2>>> g(n, std::vector<Tensor<1, 2>>(3));
      values.get_function_values(vector, v);
      if (values.get_update_flags() & update_gradients)
        values.get_function_gradients(vector, g);
      fields.resize(n);
      for (unsigned int q = 0; q < n; ++q)
        for (unsigned int c = 0; c < 3; ++c)
          {
            fields[q].value[c]    = v[q][c];
            fields[q].gradient[c] = g[q][c];
          }
    }

    /** M_CC^{-1} j_C, zero off C. */
    Vector<double>
    goal_density_pressure(const SparseMatrix<double> &mass,
                          const std::vector<bool>    &contact_set,
                          const Vector<double>       &nodal_goal_load)
    {
      // M_CC x_C = j_C as the whole system with the rows and columns off C
      // replaced by the identity.
      SparseMatrix<double> matrix(mass.get_sparsity_pattern());
      matrix.copy_from(mass);
      Vector<double> x(nodal_goal_load);
      for (unsigned int i = 0; i < matrix.m(); ++i)
        for (auto entry = matrix.begin(i); entry != matrix.end(i); ++entry)
          if (!contact_set[i] || !contact_set[entry->column()])
            entry->value() = (i == entry->column() ? 1. : 0.);
      for (unsigned int i = 0; i < x.size(); ++i)
        if (!contact_set[i])
          x[i] = 0;
      SparseDirectUMFPACK solver;
      solver.initialize(matrix);
      solver.solve(x);
      return x;
    }

  } // namespace

  Vector<double>
  remove_carried_goal_density(const MindlinPlate         &plate,
                              const SparseMatrix<double> &mass,
                              const std::vector<bool>    &contact_set,
                              const Vector<double>       &adjoint_pressure,
                              std::vector<std::pair<Point<2>, double>> &terms)
  {
    Vector<double>       reaction(adjoint_pressure);
    const Vector<double> adjoint_field =
      plate.foundation_field_to_solution(adjoint_pressure);
    const unsigned int                   n = plate.get_fe().n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(n);
    for (auto &term : terms)
      {
        // c_k phi(x_k): the term's load on the plate's w-functions
        const auto  located = plate.locate(term.first);
        FEValues<2> values(plate.get_fe(),
                           Quadrature<2>(std::vector<Point<2>>{located.second}),
                           update_values);
        values.reinit(located.first);
        located.first->get_dof_indices(dofs);
        Vector<double> local(n), point_load(plate.get_dof_handler().n_dofs());
        for (unsigned int i = 0; i < n; ++i)
          local[i] = term.second * values.shape_value_component(i, 0, 0);
        plate.get_constraints().distribute_local_to_global(local,
                                                           dofs,
                                                           point_load);
        const Vector<double> density =
          goal_density_pressure(mass,
                                contact_set,
                                plate.restrict_to_foundation(point_load));
        const double at_point =
          plate.point_value(plate.foundation_field_to_solution(density),
                            term.first,
                            0);
        const double theta =
          at_point != 0 ?
            std::clamp(plate.point_value(adjoint_field, term.first, 0) /
                         at_point,
                       0.,
                       1.) :
            0.;
        reaction.add(-theta, density);
        term.second *= theta;
      }
    return reaction;
  }

  GoalErrorEstimate
  estimate_goal_error(const MindlinPlate           &plate,
                      const Vector<double>         &solution,
                      const Vector<double>         &pressure_field,
                      const Vector<double>         &adjoint_solution,
                      const FoundationResidualData &foundation,
                      const LoadList               &loads)
  {
    const DoFHandler<2>    &dof_handler   = plate.get_dof_handler();
    const Triangulation<2> &triangulation = dof_handler.get_triangulation();
    const MirrorSymmetry   &symmetry = plate.get_foundation_space().symmetry;

    // The weight I z_h - z_h in the biquartic space: I interpolates z_h on
    // each patch of 2 x 2 cells by the biquartic function of the patch
    // (FETools::extrapolate), the plain interpolation of z_h is z_h itself.
    // Rotations across a mirror plane vanish as the plate's do.
    const FESystem<2>         weight_fe(FE_Q<2>(4), 3);
    DoFHandler<2>             weight_dofs(triangulation);
    AffineConstraints<double> weight_constraints;
    weight_dofs.distribute_dofs(weight_fe);
    DoFTools::make_hanging_node_constraints(weight_dofs, weight_constraints);
    add_mirror_plane_constraints(weight_dofs, symmetry, weight_constraints);
    weight_constraints.close();
    Vector<double> weight(weight_dofs.n_dofs()),
      interpolant(weight_dofs.n_dofs());
    FETools::extrapolate(
      dof_handler, adjoint_solution, weight_dofs, weight_constraints, weight);
    FETools::interpolate(dof_handler,
                         adjoint_solution,
                         weight_dofs,
                         weight_constraints,
                         interpolant);
    weight -= interpolant;
    // The partition of unity: bilinear hat functions of the vertices (the
    // hanging ones expressed by their neighbours).
    const FE_Q<2>             hat_fe(1);
    DoFHandler<2>             hat_dofs(triangulation);
    AffineConstraints<double> hat_constraints;
    hat_dofs.distribute_dofs(hat_fe);
    DoFTools::make_hanging_node_constraints(hat_dofs, hat_constraints);
    hat_constraints.close();

    // the same for the adjoint pressure (component 0)
    Vector<double> pressure_weight(weight_dofs.n_dofs());
    FETools::extrapolate(dof_handler,
                         foundation.adjoint_pressure_field,
                         weight_dofs,
                         weight_constraints,
                         pressure_weight);
    FETools::interpolate(dof_handler,
                         foundation.adjoint_pressure_field,
                         weight_dofs,
                         weight_constraints,
                         interpolant);
    pressure_weight -= interpolant;

    // The settlement of q_h at the points of the half-space term: 4 x 4
    // Gauss points of each cell whose nodes are all in contact, followed
    // by the goal's points (one evaluation for both).
    const QGauss<2>        soil_rule(4);
    const FoundationSpace &space = plate.get_foundation_space();
    std::vector<bool>      soil_cell(space.cells.size(), true);
    std::vector<Point<2>>  soil_points;
    {
      FEValues<2>  points(plate.get_fe(), soil_rule, update_quadrature_points);
      unsigned int c = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          for (const unsigned int i : space.cells[c].nodes())
            soil_cell[c] = soil_cell[c] && foundation.contact_set[i];
          if (soil_cell[c])
            {
              points.reinit(cell);
              for (const Point<2> &x : points.get_quadrature_points())
                soil_points.push_back(x);
            }
          ++c;
        }
    }
    const std::size_t n_cell_points = soil_points.size();
    for (const auto &term : foundation.goal_point_terms)
      soil_points.push_back(term.first);
    const std::vector<double> settlement =
      foundation.foundation.settlement_at_points(space,
                                                 foundation.nodal_pressure,
                                                 soil_points);
    FEValues<2>         plate_soil(plate.get_fe(),
                           soil_rule,
                           update_values | update_JxW_values);
    FEValues<2>         weight_soil(weight_fe, soil_rule, update_values);
    FEValues<2>         hat_soil(hat_fe, soil_rule, update_values);
    std::vector<double> w_soil(soil_rule.size()), mu(soil_rule.size());
    unsigned int        next_soil_point = 0;

    const double D = plate.flexural_rigidity(), nu = plate.poissons_ratio(),
                 Ds             = plate.shear_rigidity();
    const double thermal_moment = plate.get_thermal_load().moment;

    // Bending, pressure and load terms: 5 x 5 Gauss points (exact for the
    // products on parallelograms up to degree 9); the shear term with the
    // element's rule, so that the residual is that of the discrete form.
    const QGauss<2>   rule(5);
    const QGauss<2>   shear_rule(plate.shear_quadrature_points());
    const UpdateFlags flags = update_values | update_gradients;
    FEValues<2> plate_values(plate.get_fe(), rule, flags | update_JxW_values);
    FEValues<2> weight_values(weight_fe, rule, flags);
    FEValues<2> hat_values(hat_fe, rule, flags);
    FEValues<2> plate_shear(plate.get_fe(),
                            shear_rule,
                            flags | update_JxW_values);
    FEValues<2> weight_shear(weight_fe, shear_rule, flags);
    FEValues<2> hat_shear(hat_fe, shear_rule, flags);
    std::vector<Field>                   u, psi, u_shear, psi_shear;
    std::vector<double>                  q(rule.size());
    std::vector<types::global_dof_index> hat_indices(4);
    Vector<double>                       local(4);
    Vector<double>                       node_estimates(hat_dofs.n_dofs());

    // psi_w * chi_v at the points of a load quadrature (reference points,
    // physical weights) times the pressure there.
    const auto add_load = [&](const CellIterator &cell, const CellLoad &load) {
      const Quadrature<2> &load_rule = load.rule;
      if (load_rule.size() == 0)
        return;
      FEValues<2> w_values(weight_fe, load_rule, update_values);
      FEValues<2> v_values(hat_fe, load_rule, update_values);
      w_values.reinit(same_cell(cell, weight_dofs));
      v_values.reinit(same_cell(cell, hat_dofs));
      std::vector<Vector<double>> values(load_rule.size(), Vector<double>(3));
      w_values.get_function_values(weight, values);
      for (unsigned int p = 0; p < load_rule.size(); ++p)
        for (unsigned int v = 0; v < 4; ++v)
          local[v] += load.pressure[p] * values[p][0] *
                      v_values.shape_value(v, p) * load_rule.weight(p);
    };

    unsigned int cell_index = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        local                          = 0;
        const CellIterator weight_cell = same_cell(cell, weight_dofs);
        const CellIterator hat_cell    = same_cell(cell, hat_dofs);
        // (u(q_h) - w_h) mu chi on the cells in contact
        if (soil_cell[cell_index++])
          {
            plate_soil.reinit(cell);
            weight_soil.reinit(weight_cell);
            hat_soil.reinit(hat_cell);
            plate_soil[FEValuesExtractors::Scalar(0)].get_function_values(
              solution, w_soil);
            weight_soil[FEValuesExtractors::Scalar(0)].get_function_values(
              pressure_weight, mu);
            for (unsigned int p = 0; p < soil_rule.size(); ++p)
              {
                const double residual =
                  (settlement[next_soil_point++] - w_soil[p]) * mu[p] *
                  plate_soil.JxW(p);
                for (unsigned int v = 0; v < 4; ++v)
                  local[v] += residual * hat_soil.shape_value(v, p);
              }
          }
        plate_values.reinit(cell);
        weight_values.reinit(weight_cell);
        hat_values.reinit(hat_cell);
        get_fields(plate_values, solution, u);
        get_fields(weight_values, weight, psi);
        plate_values[FEValuesExtractors::Scalar(0)].get_function_values(
          pressure_field, q);

        // - q_h psi chi - (m(u_h) - M_T I) : kappa(psi chi), the
        // thermal moment M_T's work as in MindlinPlate::assemble_loads()
        for (unsigned int p = 0; p < rule.size(); ++p)
          {
            const Resultants r   = resultants(u[p], D, nu, Ds);
            const double     JxW = plate_values.JxW(p);
            for (unsigned int v = 0; v < 4; ++v)
              {
                std::array<double, 3> kappa;
                Tensor<1, 2>          gamma;
                const double          chi = hat_values.shape_value(v, p);
                product_strains(
                  psi[p], chi, hat_values.shape_grad(v, p), kappa, gamma);
                local[v] += (-q[p] * psi[p].value[0] * chi -
                             ((r.moment[0] - thermal_moment) * kappa[0] +
                              (r.moment[1] - thermal_moment) * kappa[1] +
                              r.moment[2] * kappa[2])) *
                            JxW;
              }
          }
        // - Q(u_h) . gamma(psi chi)
        plate_shear.reinit(cell);
        weight_shear.reinit(weight_cell);
        hat_shear.reinit(hat_cell);
        get_fields(plate_shear, solution, u_shear);
        get_fields(weight_shear, weight, psi_shear);
        for (unsigned int p = 0; p < shear_rule.size(); ++p)
          {
            const Resultants r = resultants(u_shear[p], D, nu, Ds);
            for (unsigned int v = 0; v < 4; ++v)
              {
                std::array<double, 3> kappa;
                Tensor<1, 2>          gamma;
                product_strains(psi_shear[p],
                                hat_shear.shape_value(v, p),
                                hat_shear.shape_grad(v, p),
                                kappa,
                                gamma);
                local[v] -= (r.shear * gamma) * plate_shear.JxW(p);
              }
          }

        // the loads, by the rules with which the plate's load vector
        // integrates them (Load::on_cell())
        const BilinearQuadrilateral geometry(
          std::array<Point<2>, 4>{{cell->vertex(0),
                                   cell->vertex(1),
                                   cell->vertex(2),
                                   cell->vertex(3)}});
        for (const auto &load : loads)
          add_load(cell, load->on_cell(geometry));

        hat_cell->get_dof_indices(hat_indices);
        hat_constraints.distribute_local_to_global(local,
                                                   hat_indices,
                                                   node_estimates);
      }

    // point loads: F psi_w(x) chi(x)
    for (const auto &load : loads)
      {
        const auto force = load->concentrated_force();
        if (!force)
          continue;
        // on a joint, each slab's face carries its share (as assembled)
        const auto   located = plate.locate_on_each_slab(force->first);
        const double share   = force->second / located.size();
        for (const auto &[cell, reference_point] : located)
          {
            local = 0;
            add_load(
              cell,
              CellLoad{Quadrature<2>(std::vector<Point<2>>{reference_point},
                                     std::vector<double>{1.}),
                       {share}});
            same_cell(cell, hat_dofs)->get_dof_indices(hat_indices);
            hat_constraints.distribute_local_to_global(local,
                                                       hat_indices,
                                                       node_estimates);
          }
      }

    // The curved edge's strips (doc/formulation.md, "Goal-oriented
    // refinement", the plate's outline): between a boundary face's chord
    // and its arc the plate lacks the loads f that act there. Their work
    // on the adjoint deflection, int_strip f z_w, is the error that the
    // missing strip makes in J; the soil's reaction q there cancels on a
    // continuum (its settlement of the adjoint pressure is z_w on the
    // contact set) and stays on a dense liquid: int_strip (f - q_h) z_w.
    // The strip is taken as the rectangle on the chord of the segment's
    // area (2/3 L H, H the arc's height over the chord's midpoint), z_w and
    // q_h at the chord beneath each of its points.
    std::vector<double> strip_terms(triangulation.n_active_cells(), 0.);
    {
      const bool local_soil = dynamic_cast<const ElasticSoil *>(
                                &foundation.foundation.soil()) == nullptr;
      const auto on_mirror_plane = [&](const Point<2> &a, const Point<2> &b) {
        return (symmetry.x && std::abs(a[0]) <= symmetry.tolerance &&
                std::abs(b[0]) <= symmetry.tolerance) ||
               (symmetry.y && std::abs(a[1]) <= symmetry.tolerance &&
                std::abs(b[1]) <= symmetry.tolerance);
      };
      for (const auto &cell : dof_handler.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          {
            const auto face = cell->face(f);
            if (!face->at_boundary() ||
                face->manifold_id() == numbers::flat_manifold_id)
              continue;
            const Point<2> a = face->vertex(0), b = face->vertex(1);
            if (on_mirror_plane(a, b))
              continue;
            const double   length = a.distance(b);
            const Point<2> chord_middle((a[0] + b[0]) / 2, (a[1] + b[1]) / 2);
            const std::vector<Point<2>> ends{a, b};
            const std::vector<double>   halves{0.5, 0.5};
            const Point<2>              arc_middle =
              face->get_manifold().get_new_point(make_array_view(ends),
                                                 make_array_view(halves));
            // outward: away from the cell's centre
            Tensor<1, 2> normal({b[1] - a[1], a[0] - b[0]});
            normal /= normal.norm();
            if (normal * (chord_middle - cell->center()) < 0)
              normal *= -1.;
            const double height = normal * (arc_middle - chord_middle);
            if (!(std::abs(height) > 1e-12 * length))
              continue;
            // the rectangle on the chord; a concave arc (height < 0) takes
            // area away, its loads count negative
            const double       depth = 2. / 3. * std::abs(height);
            const Tensor<1, 2> lift  = (height > 0 ? depth : -depth) * normal;
            // counter-clockwise, as a cell (the loads' weights are areas)
            const bool forward =
              (b - a)[0] * lift[1] - (b - a)[1] * lift[0] > 0;
            const Point<2> first = forward ? a : b, second = forward ? b : a;
            const BilinearQuadrilateral strip(std::array<Point<2>, 4>{
              {first, second, first + lift, second + lift}});
            const BilinearQuadrilateral cell_geometry(
              std::array<Point<2>, 4>{{cell->vertex(0),
                                       cell->vertex(1),
                                       cell->vertex(2),
                                       cell->vertex(3)}});
            // the pressure on the strip at its points, by each load's own
            // rule, and (dense liquid) the reaction at 3 x 3 Gauss points
            std::vector<Point<2>> chord_points;
            std::vector<double>   densities;
            for (const auto &load : loads)
              {
                const CellLoad part = load->on_cell(strip);
                for (unsigned int p = 0; p < part.rule.size(); ++p)
                  {
                    chord_points.push_back(first + part.rule.point(p)[0] *
                                                     (second - first));
                    densities.push_back(part.pressure[p] * part.rule.weight(p));
                  }
              }
            const std::size_t n_load_points = chord_points.size();
            const QGauss<1>   along(3);
            if (local_soil)
              for (unsigned int p = 0; p < along.size(); ++p)
                chord_points.push_back(a + along.point(p)[0] * (b - a));
            if (chord_points.empty())
              continue;
            std::vector<Point<2>> unit_points;
            for (const Point<2> &x : chord_points)
              unit_points.push_back(cell_geometry.inverse_map(x));
            FEValues<2> at_chord(plate.get_fe(),
                                 Quadrature<2>(unit_points),
                                 update_values);
            at_chord.reinit(cell);
            std::vector<double> z(unit_points.size()), q(unit_points.size());
            at_chord[FEValuesExtractors::Scalar(0)].get_function_values(
              adjoint_solution, z);
            at_chord[FEValuesExtractors::Scalar(0)].get_function_values(
              pressure_field, q);
            const double sign = height > 0 ? 1. : -1.;
            double       term = 0;
            for (std::size_t p = 0; p < n_load_points; ++p)
              term += sign * densities[p] * z[p];
            for (std::size_t p = n_load_points; p < chord_points.size(); ++p)
              term -= sign * q[p] * z[p] * along.weight(p - n_load_points) *
                      length * depth;
            strip_terms[cell->active_cell_index()] += term;
          }
    }

    // The goal density's part of rho_F: (u(q_h) - w_h) at the goal's
    // points in contact, given to the cell that holds the point.
    std::vector<double> point_terms(triangulation.n_active_cells(), 0.);
    for (unsigned int k = 0; k < foundation.goal_point_terms.size(); ++k)
      {
        const auto &[x, coefficient] = foundation.goal_point_terms[k];
        const auto located           = plate.locate(x);
        const auto index             = located.first->active_cell_index();
        if (!soil_cell[index])
          continue; // lifted off: no pressure acts at the point
        point_terms[index] += coefficient * (settlement[n_cell_points + k] -
                                             plate.point_value(solution, x, 0));
      }

    GoalErrorEstimate estimate;
    estimate.has_dwr = true;
    for (const double term : point_terms)
      {
        estimate.dwr += term;
        estimate.estimated_error += std::abs(term);
      }
    for (const double term : strip_terms)
      {
        estimate.dwr += term;
        estimate.estimated_error += std::abs(term);
      }
    for (unsigned int i = 0; i < node_estimates.size(); ++i)
      if (!hat_constraints.is_constrained(i))
        {
          estimate.dwr += node_estimates[i];
          estimate.estimated_error += std::abs(node_estimates[i]);
        }

    // Each cell gets its share of the |eta_i| of its vertices.
    std::vector<unsigned int> valence(hat_dofs.n_dofs(), 0);
    for (const auto &cell : hat_dofs.active_cell_iterators())
      {
        cell->get_dof_indices(hat_indices);
        for (const auto i : hat_indices)
          ++valence[i];
      }
    estimate.cell_indicators.reinit(triangulation.n_active_cells());
    unsigned int c = 0;
    for (const auto &cell : hat_dofs.active_cell_iterators())
      {
        cell->get_dof_indices(hat_indices);
        double indicator = 0;
        for (const auto i : hat_indices)
          if (!hat_constraints.is_constrained(i))
            indicator += std::abs(node_estimates[i]) / valence[i];
        estimate.cell_indicators[c] =
          indicator + std::abs(point_terms[c]) + std::abs(strip_terms[c]);
        ++c;
      }
    return estimate;
  }

  GoalErrorEstimate
  estimate_contact_area_error(const ContactState &contact,
                              const unsigned int  copies)
  {
    GoalErrorEstimate estimate;
    estimate.cell_indicators.reinit(
      contact.cell_contact_area_uncertainty.size());
    for (unsigned int c = 0; c < estimate.cell_indicators.size(); ++c)
      {
        estimate.cell_indicators[c] = contact.cell_contact_area_uncertainty[c];
        estimate.estimated_error +=
          copies * contact.cell_contact_area_uncertainty[c];
      }
    return estimate;
  }

  GoalErrorEstimate
  estimate_goal_error(const GoalFunctional             &goal,
                      const GoalFunctional::Evaluation &value,
                      const MindlinPlate               &plate,
                      const ContactState               &contact,
                      const Vector<double>             &pressure_field,
                      ContactSolver                    &contact_solver,
                      const GoalEstimateScene          &scene)
  {
    if (goal.estimate() == GoalFunctional::Estimate::contact_region)
      return estimate_contact_area_error(
        contact, plate.get_foundation_space().symmetry.n_copies());
    if (goal.estimate() != GoalFunctional::Estimate::dual_weighted_residual)
      return GoalErrorEstimate();
    const ContactState adjoint = contact_solver.solve_adjoint(
      goal.derivative(plate, contact.plate_solution, value));
    // the goal's points on the computed part, where the solution is
    std::vector<std::pair<Point<2>, double>> terms = goal.deflection_terms();
    for (auto &term : terms)
      term.first =
        plate.get_foundation_space().symmetry.to_computed_part(term.first);
    const Vector<double> reaction =
      remove_carried_goal_density(plate,
                                  scene.foundation.mass_matrix(),
                                  contact.active_set,
                                  adjoint.q,
                                  terms);
    const Vector<double> adjoint_pressure =
      plate.foundation_field_to_solution(reaction);
    const FoundationResidualData soil{
      contact.q, contact.active_set, adjoint_pressure, scene.foundation, terms};
    GoalErrorEstimate estimate = estimate_goal_error(plate,
                                                     contact.plate_solution,
                                                     pressure_field,
                                                     adjoint.plate_solution,
                                                     soil,
                                                     scene.loads);
    estimate.adjoint_rounding_limited_residual =
      adjoint.rounding_limited_residual;
    return estimate;
  }
} // namespace PlateOnHalfspace
