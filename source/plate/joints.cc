#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <plate_on_halfspace/plate/joints.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

namespace PlateOnHalfspace
{
  namespace
  {
    using LoadTransfer = Parameters::Joints::LoadTransfer;

    /** The quadrature points of @p values sorted along a joint that runs
     *  along coordinate @p along: facing faces' points pair up in order. */
    std::vector<unsigned int>
    order_along(const FEFaceValues<2> &values, const unsigned int along)
    {
      std::vector<unsigned int> order(values.n_quadrature_points);
      std::iota(order.begin(), order.end(), 0u);
      std::sort(order.begin(),
                order.end(),
                [&](unsigned int a, unsigned int b) {
                  return values.quadrature_point(a)[along] <
                         values.quadrature_point(b)[along];
                });
      return order;
    }
  } // namespace

  void
  JointCoupling::reinit(const SlabGrid       &slab_grid,
                        const DoFHandler<2>  &dofs,
                        const MirrorSymmetry &mirror_symmetry)
  {
    grid        = &slab_grid;
    dof_handler = &dofs;
    symmetry    = mirror_symmetry;
    pairs.clear();
    dowel_sites.clear();
    if (grid->get_joints().empty())
      return;

    // The joint faces by centre: facing faces have the same centre (the
    // mesh keeps them facing, SlabGrid::match_refinement()).
    std::map<
      std::pair<long long, long long>,
      std::vector<std::pair<DoFHandler<2>::active_cell_iterator, unsigned int>>>
                 by_centre;
    const double tolerance = grid->tolerance();
    for (const auto &cell : dofs.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->at_boundary(f) &&
            (cell->face(f)->boundary_id() == joint_boundary_id ||
             // a tied joint on a mirror plane (SlabGrid::mark_joint_faces())
             ((cell->face(f)->boundary_id() == mirror_plane_x_boundary_id ||
               cell->face(f)->boundary_id() == mirror_plane_y_boundary_id) &&
              grid->joint_at(cell->face(f)->center()) <
                grid->get_joints().size())))
          {
            by_centre[grid->face_key(cell->face(f)->center())].emplace_back(
              cell, f);
          }
    for (const auto &[key, faces] : by_centre)
      {
        (void)key;
        const Point<2> centre = faces[0].first->face(faces[0].second)->center();
        const unsigned int joint = grid->joint_at(centre);
        AssertThrow(joint < grid->get_joints().size() && faces.size() <= 2,
                    ExcInternalError());
        const Joint &j = grid->get_joints()[joint];
        FacePair     pair;
        pair.joint = joint;
        if (faces.size() == 1)
          {
            // a joint on a mirror plane: its other side is the image, which
            // moves alike (SlabGrid::mark_joint_faces())
            pair.cell_low = pair.cell_high = faces[0].first;
            pair.face_low = pair.face_high = faces[0].second;
          }
        else
          {
            const bool  first_low = faces[0].first->material_id() == j.slab_low;
            const auto &low       = faces[first_low ? 0 : 1];
            const auto &high      = faces[first_low ? 1 : 0];
            pair.cell_low         = low.first;
            pair.face_low         = low.second;
            pair.cell_high        = high.first;
            pair.face_high        = high.second;
          }
        pairs.push_back(pair);
      }

    // each dowel bar on the first face pair that holds it
    for (unsigned int joint = 0; joint < grid->get_joints().size(); ++joint)
      for (const Point<2> &bar : grid->get_joints()[joint].dowels)
        for (const FacePair &pair : pairs)
          {
            if (pair.joint != joint || pair.cell_low == pair.cell_high)
              continue;
            const auto         face  = pair.cell_low->face(pair.face_low);
            const unsigned int along = 1 - grid->get_joints()[joint].axis;
            const double       a =
              std::min(face->vertex(0)[along], face->vertex(1)[along]);
            const double b =
              std::max(face->vertex(0)[along], face->vertex(1)[along]);
            if (bar[along] < a - tolerance || bar[along] > b + tolerance)
              continue;
            DowelSite site;
            site.joint     = joint;
            site.location  = bar;
            site.cell_low  = pair.cell_low;
            site.cell_high = pair.cell_high;
            site.reference_low =
              mapping.transform_real_to_unit_cell(pair.cell_low, bar);
            site.reference_high =
              mapping.transform_real_to_unit_cell(pair.cell_high, bar);
            // a bar on a mirror plane is shared with its image
            site.share = 1.;
            for (unsigned int d = 0; d < 2; ++d)
              if ((d == 0 ? symmetry.x : symmetry.y) &&
                  std::abs(bar[d]) <= tolerance)
                site.share *= 0.5;
            site.stiffness = grid->dowel_stiffness();
            dowel_sites.push_back(site);
            break;
          }
  }

  void
  JointCoupling::add_tied_constraints(
    AffineConstraints<double> &constraints) const
  {
    if (pairs.empty())
      return;
    const FiniteElement<2> &fe = dof_handler->get_fe();
    std::vector<Point<2>>   support(dof_handler->n_dofs());
    DoFTools::map_dofs_to_support_points(mapping, *dof_handler, support);

    // groups of DoFs joined by tied faces (a corner of four tied slabs
    // joins four), each group's smallest unconstrained DoF its master
    std::map<types::global_dof_index, types::global_dof_index> parent;
    const std::function<types::global_dof_index(types::global_dof_index)> root =
      [&](const types::global_dof_index i) {
        auto it = parent.find(i);
        if (it == parent.end() || it->second == i)
          return i;
        return it->second = root(it->second);
      };
    std::vector<types::global_dof_index> low(fe.n_dofs_per_face()),
      high(fe.n_dofs_per_face());
    for (const FacePair &pair : pairs)
      {
        if (grid->get_joints()[pair.joint].transfer != LoadTransfer::tied ||
            pair.cell_low == pair.cell_high)
          continue;
        pair.cell_low->face(pair.face_low)->get_dof_indices(low);
        pair.cell_high->face(pair.face_high)->get_dof_indices(high);
        for (unsigned int i = 0; i < low.size(); ++i)
          for (unsigned int k = 0; k < high.size(); ++k)
            if (fe.face_system_to_component_index(i).first ==
                  fe.face_system_to_component_index(k).first &&
                support[low[i]].distance(support[high[k]]) <= grid->tolerance())
              {
                const auto a = root(low[i]), b = root(high[k]);
                if (a != b)
                  parent[std::max(a, b)] = std::min(a, b);
                parent.emplace(low[i], low[i]);
                parent.emplace(high[k], high[k]);
              }
      }
    std::map<types::global_dof_index, std::vector<types::global_dof_index>>
      groups;
    for (const auto &[dof, p] : parent)
      {
        (void)p;
        groups[root(dof)].push_back(dof);
      }
    for (auto &[r, members] : groups)
      {
        (void)r;
        // Hanging DoFs of a joint face are constrained on both sides alike
        // (the faces match), so they already agree.
        std::vector<types::global_dof_index> free;
        for (const auto dof : members)
          if (!constraints.is_constrained(dof))
            free.push_back(dof);
        std::sort(free.begin(), free.end());
        for (unsigned int i = 1; i < free.size(); ++i)
          {
            constraints.add_line(free[i]);
            constraints.add_entry(free[i], free[0], 1.);
          }
      }
  }

  void
  JointCoupling::add_sparsity(const AffineConstraints<double> &constraints,
                              DynamicSparsityPattern          &dsp) const
  {
    const unsigned int n = dof_handler->get_fe().n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(2 * n), high(n);
    for (const FacePair &pair : pairs)
      {
        const LoadTransfer t = grid->get_joints()[pair.joint].transfer;
        if (t == LoadTransfer::free || t == LoadTransfer::tied ||
            pair.cell_low == pair.cell_high)
          continue;
        dofs.resize(n);
        pair.cell_low->get_dof_indices(dofs);
        pair.cell_high->get_dof_indices(high);
        dofs.insert(dofs.end(), high.begin(), high.end());
        constraints.add_entries_local_to_global(dofs, dsp, false);
      }
  }

  void
  JointCoupling::assemble(const AffineConstraints<double> &constraints,
                          SparseMatrix<double>            &stiffness) const
  {
    if (pairs.empty())
      return;
    const FiniteElement<2> &fe = dof_handler->get_fe();
    const unsigned int      n  = fe.n_dofs_per_cell();
    // (w_low - w_high)^2 is a quartic along a face: 3 Gauss points
    const QGauss<1>                      rule(3);
    FEFaceValues<2>                      low_values(mapping,
                               fe,
                               rule,
                               update_values | update_quadrature_points |
                                 update_JxW_values);
    FEFaceValues<2>                      high_values(mapping,
                                fe,
                                rule,
                                update_values | update_quadrature_points);
    FullMatrix<double>                   local(2 * n, 2 * n);
    std::vector<types::global_dof_index> dofs(2 * n), high(n);
    std::vector<double>                  jump(2 * n);
    const double k_s = grid->get_joint_parameters().shear_stiffness;

    const auto add_spring = [&](const double stiffness) {
      for (unsigned int i = 0; i < 2 * n; ++i)
        if (jump[i] != 0)
          for (unsigned int j = 0; j < 2 * n; ++j)
            local(i, j) += stiffness * jump[i] * jump[j];
    };
    const auto distribute = [&](const DoFHandler<2>::active_cell_iterator &a,
                                const DoFHandler<2>::active_cell_iterator &b) {
      dofs.resize(n);
      a->get_dof_indices(dofs);
      b->get_dof_indices(high);
      dofs.insert(dofs.end(), high.begin(), high.end());
      constraints.distribute_local_to_global(local, dofs, stiffness);
    };

    // aggregate interlock: k_s ∫ (w_low - w_high)(v_low - v_high) ds
    for (const FacePair &pair : pairs)
      {
        const Joint &joint = grid->get_joints()[pair.joint];
        if (joint.transfer != LoadTransfer::aggregate_interlock ||
            pair.cell_low == pair.cell_high)
          continue;
        low_values.reinit(pair.cell_low, pair.face_low);
        high_values.reinit(pair.cell_high, pair.face_high);
        const auto low_order  = order_along(low_values, 1 - joint.axis);
        const auto high_order = order_along(high_values, 1 - joint.axis);
        local                 = 0;
        for (unsigned int q = 0; q < rule.size(); ++q)
          {
            const unsigned int ql = low_order[q], qh = high_order[q];
            for (unsigned int i = 0; i < n; ++i)
              {
                jump[i]     = low_values.shape_value_component(i, ql, 0);
                jump[n + i] = -high_values.shape_value_component(i, qh, 0);
              }
            add_spring(k_s * low_values.JxW(ql));
          }
        distribute(pair.cell_low, pair.cell_high);
      }
    // dowels: k (w_low - w_high)(v_low - v_high) at each bar
    for (const DowelSite &site : dowel_sites)
      {
        local = 0;
        for (unsigned int i = 0; i < n; ++i)
          {
            jump[i]     = fe.shape_value_component(i, site.reference_low, 0);
            jump[n + i] = -fe.shape_value_component(i, site.reference_high, 0);
          }
        add_spring(site.share * site.stiffness);
        distribute(site.cell_low, site.cell_high);
      }
  }

  std::vector<JointResponse>
  JointCoupling::responses(const Vector<double> &solution,
                           const double          shear_rigidity,
                           const Vector<double> &standing) const
  {
    const auto                &joints = grid->get_joints();
    std::vector<JointResponse> result(joints.size());
    if (joints.empty())
      return result;
    const FiniteElement<2> &fe = dof_handler->get_fe();
    const QGaussLobatto<1>  rule(5);
    const UpdateFlags       flags = update_values | update_gradients |
                              update_quadrature_points | update_normal_vectors;
    FEFaceValues<2>             low_values(mapping, fe, rule, flags);
    FEFaceValues<2>             high_values(mapping, fe, rule, flags);
    std::vector<Vector<double>> low_u(rule.size(), Vector<double>(3)),
      high_u(rule.size(), Vector<double>(3));
    std::vector<std::vector<Tensor<1, 2>>> low_grad(
      rule.size(), std::vector<Tensor<1, 2>>(3)),
      high_grad(rule.size(), std::vector<Tensor<1, 2>>(3));
    // zero: the deflections themselves
    std::vector<Vector<double>> low_standing(rule.size(), Vector<double>(3)),
      high_standing(rule.size(), Vector<double>(3));
    const double        k_s = grid->get_joint_parameters().shear_stiffness;
    std::vector<double> highest(joints.size(),
                                -std::numeric_limits<double>::infinity());

    for (const FacePair &pair : pairs)
      {
        const Joint   &joint    = joints[pair.joint];
        JointResponse &response = result[pair.joint];
        response.computed       = true;
        low_values.reinit(pair.cell_low, pair.face_low);
        high_values.reinit(pair.cell_high, pair.face_high);
        low_values.get_function_values(solution, low_u);
        high_values.get_function_values(solution, high_u);
        low_values.get_function_gradients(solution, low_grad);
        high_values.get_function_gradients(solution, high_grad);
        if (standing.size() == solution.size())
          {
            low_values.get_function_values(standing, low_standing);
            high_values.get_function_values(standing, high_standing);
          }
        const auto low_order  = order_along(low_values, 1 - joint.axis);
        const auto high_order = order_along(high_values, 1 - joint.axis);
        for (unsigned int q = 0; q < rule.size(); ++q)
          {
            const unsigned int ql = low_order[q], qh = high_order[q];
            const double       wl = low_u[ql][0] - low_standing[ql][0],
                         wh       = high_u[qh][0] - high_standing[qh][0];
            if (std::max(wl, wh) > highest[pair.joint])
              {
                highest[pair.joint] = std::max(wl, wh);
                response.lte_at     = low_values.quadrature_point(ql);
                response.w_loaded   = std::max(wl, wh);
                response.w_unloaded = std::min(wl, wh);
              }
            double shear = 0;
            if (joint.transfer == LoadTransfer::aggregate_interlock)
              shear = k_s * std::abs(low_u[ql][0] - high_u[qh][0]);
            else if (joint.transfer == LoadTransfer::tied &&
                     pair.cell_low != pair.cell_high)
              {
                // the plates' shear resultant Q.n = D_s (dw/dn - beta_n),
                // the mean of the two sides
                const auto Qn = [&](const std::vector<Tensor<1, 2>> &grad,
                                    const Vector<double>            &u,
                                    const Tensor<1, 2>              &normal) {
                  Tensor<1, 2> beta;
                  beta[0] = u[1];
                  beta[1] = u[2];
                  return shear_rigidity * ((grad[0] - beta) * normal);
                };
                shear = 0.5 * std::abs(Qn(low_grad[ql],
                                          low_u[ql],
                                          low_values.normal_vector(ql)) -
                                       Qn(high_grad[qh],
                                          high_u[qh],
                                          high_values.normal_vector(qh)));
              }
            response.max_shear_force =
              std::max(response.max_shear_force, shear);
          }
      }
    // the bars' forces; a bar of the mirrored part reads its image
    std::vector<double> site_force(dowel_sites.size());
    for (unsigned int k = 0; k < dowel_sites.size(); ++k)
      {
        const DowelSite                     &site = dowel_sites[k];
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        double                               wl = 0, wh = 0;
        site.cell_low->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          wl += solution[dofs[i]] *
                fe.shape_value_component(i, site.reference_low, 0);
        site.cell_high->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          wh += solution[dofs[i]] *
                fe.shape_value_component(i, site.reference_high, 0);
        site_force[k] = site.stiffness * (wl - wh);
      }
    for (unsigned int j = 0; j < joints.size(); ++j)
      for (const Point<2> &bar : joints[j].dowels)
        {
          const Point<2>     image       = symmetry.to_computed_part(bar);
          const unsigned int image_joint = grid->joint_at(image);
          // a joint on a mirror plane carries nothing
          const unsigned int axis = joints[j].axis;
          if ((axis == 0 ? symmetry.x : symmetry.y) &&
              std::abs(joints[j].start[axis]) <= grid->tolerance())
            {
              DowelForce dowel;
              dowel.location = bar;
              result[j].dowels.push_back(dowel);
              continue;
            }
          for (unsigned int k = 0; k < dowel_sites.size(); ++k)
            if (dowel_sites[k].joint == image_joint &&
                dowel_sites[k].location.distance(image) <= grid->tolerance())
              {
                DowelForce dowel;
                dowel.location = bar;
                // a reflection across the joint swaps its sides
                dowel.force =
                  (image[axis] != bar[axis] ? -1. : 1.) * site_force[k];
                dowel.bearing_stress =
                  grid->dowel_bearing_stress(std::abs(dowel.force));
                result[j].dowels.push_back(dowel);
                result[j].max_shear_force =
                  std::max(result[j].max_shear_force,
                           std::abs(dowel.force) /
                             grid->get_joint_parameters().dowel_spacing);
              }
        }
    for (unsigned int j = 0; j < joints.size(); ++j)
      if (result[j].computed)
        result[j].lte =
          (result[j].w_loaded > 0 ? result[j].w_unloaded / result[j].w_loaded :
                                    std::numeric_limits<double>::quiet_NaN());

    // a joint in the mirrored part: its image's response, mirrored
    for (unsigned int j = 0; j < joints.size(); ++j)
      if (!result[j].computed)
        {
          const Point<2> middle =
            joints[j].start + 0.5 * (joints[j].end - joints[j].start);
          const unsigned int image =
            grid->joint_at(symmetry.to_computed_part(middle));
          if (image == joints.size() || !result[image].computed)
            continue;
          const std::vector<DowelForce> dowels = result[j].dowels;
          result[j]                            = result[image];
          result[j].lte_at =
            symmetry.from_computed_part(result[j].lte_at, middle);
          result[j].dowels = dowels;
        }
    return result;
  }
} // namespace PlateOnHalfspace
