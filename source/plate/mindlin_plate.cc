#include <deal.II/base/bounding_box.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <deal.II/numerics/rtree.h>

#include <boost/accumulators/accumulators.hpp>
#include <boost/accumulators/statistics/stats.hpp>
#include <boost/accumulators/statistics/sum_kahan.hpp>

#include <plate_on_halfspace/base/number_list.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/plate/generalized_inverse.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>

namespace PlateOnHalfspace
{
  namespace
  {
    BilinearQuadrilateral
    cell_geometry(const typename DoFHandler<2>::active_cell_iterator &cell)
    {
      return BilinearQuadrilateral(std::array<Point<2>, 4>{
        {cell->vertex(0), cell->vertex(1), cell->vertex(2), cell->vertex(3)}});
    }
  } // namespace

  struct MindlinPlate::CellBoxes
  {
    /** Each active cell's bounding box with its active_cell_index(). */
    RTree<std::pair<BoundingBox<2>, unsigned int>> tree;
    /** The active cells by active_cell_index(). */
    std::vector<typename DoFHandler<2>::active_cell_iterator> cells;
  };

  MindlinPlate::MindlinPlate(const Parameters::Plate          &plate,
                             const Parameters::Discretization &discretization)
    : plate(plate)
    , discretization(discretization)
    , fe(FE_Q<2>(2), 3)
  {}

  void
  MindlinPlate::setup(
    const Triangulation<2>                                 &triangulation,
    const std::function<void(const DoFHandler<2> &,
                             AffineConstraints<double> &)> &extra_constraints)
  {
    setup_dofs(triangulation, extra_constraints);
    complete_setup();
  }

  void
  MindlinPlate::setup_dofs(
    const Triangulation<2>                                 &triangulation,
    const std::function<void(const DoFHandler<2> &,
                             AffineConstraints<double> &)> &extra_constraints)
  {
    // the previous mesh's matrix goes at once: nothing may read it
    setup_complete = false;
    discard_stiffness();
    static std::atomic<unsigned long long> setups{0};
    current_setup = ++setups;
    // Keep the DoFHandler attached across refinement cycles, so that a
    // SolutionTransfer prepared before refinement can interpolate.
    if (attached_triangulation != &triangulation)
      dof_handler.reinit(triangulation);
    attached_triangulation = &triangulation;
    dof_handler.distribute_dofs(fe);
    if (n_ranks(communicator) > 1)
      {
        // Each rank's DoFs contiguous, in the order of its cells' subdomain
        // ids; a DoF on the border of two ranks' cells goes to the first.
        DoFRenumbering::subdomain_wise(dof_handler);
        owned_dofs = DoFTools::locally_owned_dofs_per_subdomain(
          dof_handler)[rank_in(communicator)];
      }
    else
      owned_dofs = complete_index_set(dof_handler.n_dofs());

    if (slab_grid)
      joint_coupling.reinit(*slab_grid, dof_handler, symmetry);

    constraints.clear();
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    add_centre_constraints();
    add_mirror_plane_constraints(dof_handler, symmetry, constraints);
    if (extra_constraints)
      extra_constraints(dof_handler, constraints);
    if (slab_grid)
      joint_coupling.add_tied_constraints(constraints);
    constraints.close();

    build_foundation_space();
    {
      auto boxes = std::make_shared<CellBoxes>();
      std::vector<std::pair<BoundingBox<2>, unsigned int>> leaves;
      boxes->cells.resize(triangulation.n_active_cells());
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          boxes->cells[cell->active_cell_index()] = cell;
          leaves.emplace_back(cell->bounding_box(), cell->active_cell_index());
        }
      boxes->tree = pack_rtree(leaves);
      cell_boxes  = std::move(boxes);
    }
    load.reinit(dof_handler.n_dofs());
    total_load = 0;
    foundation_space.rigid_motions.clear();
  }

  void
  MindlinPlate::complete_setup()
  {
    if (setup_complete)
      return;
    make_stiffness();
    // what the contact iteration's mechanism check needs of the plate
    // (orthonormal over the nodes: Gram-Schmidt, twice)
    auto &motions = foundation_space.rigid_motions;
    motions.clear();
    // rigid_body_motions() reads the stiffness
    setup_complete = true;
    std::vector<Vector<double>> plate_motions;
    try
      {
        plate_motions = rigid_body_motions(*this);
      }
    catch (...)
      {
        setup_complete = false;
        throw;
      }
    for (const Vector<double> &motion : plate_motions)
      {
        Vector<double> r = restrict_to_foundation(motion);
        for (unsigned int pass = 0; pass < 2; ++pass)
          for (const Vector<double> &e : motions)
            r.add(-(r * e), e);
        if (r.l2_norm() > 0)
          {
            r /= r.l2_norm();
            motions.push_back(r);
          }
      }
  }

  std::vector<JointResponse>
  MindlinPlate::joint_responses(const Vector<double> &solution,
                                const Vector<double> &standing) const
  {
    if (!slab_grid)
      return {};
    return joint_coupling.responses(solution, shear_rigidity(), standing);
  }

  void
  add_mirror_plane_constraints(const DoFHandler<2>       &dof_handler,
                               const MirrorSymmetry      &symmetry,
                               AffineConstraints<double> &constraints)
  {
    // The solution of a symmetric scene is even across a mirror plane
    // (mirror_symmetry.h): w is free there, the slope across the plane
    // vanishes: beta_x = 0 on x = 0, beta_y = 0 on y = 0. Hanging nodes on
    // the plane are already constrained to nodes on the plane, which are
    // zero here too.
    const FiniteElement<2> &fe = dof_handler.get_fe();
    for (const unsigned int axis : {0u, 1u})
      {
        if (!(axis == 0 ? symmetry.x : symmetry.y))
          continue;
        const IndexSet plane_dofs = DoFTools::extract_boundary_dofs(
          dof_handler,
          fe.component_mask(FEValuesExtractors::Scalar(1 + axis)),
          {axis == 0 ? mirror_plane_x_boundary_id :
                       mirror_plane_y_boundary_id});
        for (const auto dof : plane_dofs)
          if (!constraints.is_constrained(dof))
            constraints.add_line(dof);
      }
  }

  void
  MindlinPlate::add_centre_constraints()
  {
    // serendipity: every field; heterosis: w only; lagrange: none
    // (doc/formulation.md, "Plate"). u_centre = 1/2 sum(mid-sides) -
    // 1/4 sum(corners) removes exactly the xi^2 eta^2 mode of Q2.
    unsigned int n_constrained_components = 0;
    switch (discretization.element)
      {
        case Parameters::Discretization::Element::serendipity:
          n_constrained_components = 3;
          break;
        case Parameters::Discretization::Element::heterosis:
          n_constrained_components = 1;
          break;
        case Parameters::Discretization::Element::lagrange:
          n_constrained_components = 0;
          break;
      }
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int c = 0; c < n_constrained_components; ++c)
          {
            const auto centre = dofs[fe.component_to_system_index(c, 8)];
            constraints.add_line(centre);
            for (unsigned int v = 0; v < 4; ++v)
              constraints.add_entry(centre,
                                    dofs[fe.component_to_system_index(c, v)],
                                    -0.25);
            for (unsigned int m = 4; m < 8; ++m)
              constraints.add_entry(centre,
                                    dofs[fe.component_to_system_index(c, m)],
                                    0.5);
          }
      }
  }

  void
  MindlinPlate::build_foundation_space()
  {
    std::vector<Point<2>> support_points(dof_handler.n_dofs());
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support_points);
    const IndexSet w_dofs =
      DoFTools::extract_dofs(dof_handler,
                             fe.component_mask(FEValuesExtractors::Scalar(0)));

    foundation_dofs.clear();
    foundation_index.assign(dof_handler.n_dofs(), -1);
    foundation_space              = FoundationSpace();
    foundation_space.symmetry     = symmetry;
    foundation_space.communicator = communicator;
    // A node belongs to the rank that owns its w-DoF (doc/parallel.md).
    std::vector<types::global_dof_index> owned_nodes;
    for (const auto dof : w_dofs)
      if (!constraints.is_constrained(dof))
        {
          if (owned_dofs.is_element(dof))
            owned_nodes.push_back(foundation_dofs.size());
          foundation_index[dof] = foundation_dofs.size();
          foundation_dofs.push_back(dof);
          foundation_space.node_locations.push_back(support_points[dof]);
        }
    // A joint that is not tied keeps its faces' joint id on a mirror plane
    // (SlabGrid::mark_joint_faces()): its nodes there stand for the other
    // slab's nodes too.
    if (symmetry.n_copies() > 1)
      {
        foundation_space.joint_planes.assign(foundation_dofs.size(), 0);
        std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
        const auto in_plane = [&](const Point<2> &x, const unsigned int axis) {
          return (axis == 0 ? symmetry.x : symmetry.y) &&
                 std::abs(x[axis]) <= symmetry.tolerance;
        };
        for (const auto &cell : dof_handler.active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            if (cell->at_boundary(f) &&
                cell->face(f)->boundary_id() == joint_boundary_id)
              {
                // a face in the plane, not one of a joint across it that
                // ends there
                const Point<2>     centre = cell->face(f)->center();
                const unsigned int planes =
                  (in_plane(centre, 0) ? 1 : 0) | (in_plane(centre, 1) ? 2 : 0);
                if (planes == 0)
                  continue;
                cell->face(f)->get_dof_indices(face_dofs);
                for (unsigned int k = 0; k < face_dofs.size(); ++k)
                  {
                    const auto node = foundation_index[face_dofs[k]];
                    if (fe.face_system_to_component_index(k).first == 0 &&
                        node >= 0)
                      foundation_space.joint_planes[node] |= planes;
                  }
              }
      }
    foundation_space.owned_nodes.set_size(foundation_dofs.size());
    foundation_space.owned_nodes.add_indices(owned_nodes.begin(),
                                             owned_nodes.end());

    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        FoundationSpace::Cell data{cell_geometry(cell), {}};
        for (unsigned int i = 0; i < 9; ++i)
          {
            const auto dof = dofs[fe.component_to_system_index(0, i)];
            if (foundation_index[dof] >= 0)
              data.expansion[i].emplace_back(foundation_index[dof], 1.);
            else
              {
                // After close(), a constrained DoF depends on unconstrained
                // ones only; those of a w-DoF are w-DoFs. A support (w = 0)
                // has no entries.
                const auto *entries = constraints.get_constraint_entries(dof);
                if (entries != nullptr)
                  for (const auto &entry : *entries)
                    {
                      Assert(foundation_index[entry.first] >= 0,
                             ExcInternalError());
                      data.expansion[i].emplace_back(
                        foundation_index[entry.first], entry.second);
                    }
              }
          }
        foundation_space.cells.push_back(data);
      }
  }

  void
  MindlinPlate::make_stiffness() const
  {
    DynamicSparsityPattern dsp(dof_handler.n_dofs());
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
    if (slab_grid)
      joint_coupling.add_sparsity(constraints, dsp);
    sparsity.copy_from(dsp);
    stiffness.reinit(sparsity);
    assemble_stiffness();
    if (slab_grid)
      joint_coupling.assemble(constraints, stiffness);
  }

  const SparseMatrix<double> &
  MindlinPlate::get_stiffness_matrix() const
  {
    return assembled_stiffness();
  }

  const SparseMatrix<double> &
  MindlinPlate::assembled_stiffness() const
  {
    AssertThrow(setup_complete,
                ExcInternalError("MindlinPlate: complete_setup() first."));
    const std::lock_guard<std::mutex> lock(stiffness_mutex);
    // empty once complete: released
    if (stiffness.empty())
      {
        // a failed assembly (out of memory) leaves nothing half made
        try
          {
            make_stiffness();
          }
        catch (...)
          {
            discard_stiffness();
            throw;
          }
      }
    return stiffness;
  }

  void
  MindlinPlate::release_stiffness()
  {
    const std::lock_guard<std::mutex> lock(stiffness_mutex);
    if (setup_complete)
      discard_stiffness();
  }

  void
  MindlinPlate::discard_stiffness() const
  {
    // the matrix first: it refers to the pattern
    stiffness.clear();
    sparsity.reinit(0, 0, 0);
  }

  bool
  MindlinPlate::holds_stiffness() const
  {
    const std::lock_guard<std::mutex> lock(stiffness_mutex);
    return setup_complete && !stiffness.empty();
  }

  void
  MindlinPlate::assemble_stiffness() const
  {
    using SI = Parameters::Discretization::ShearIntegration;
    const SI                         shear = discretization.shear_integration;
    const QGauss<2>                  bending_rule(shear == SI::reduced ? 2 : 3);
    const QGauss<2>                  shear_rule(shear_quadrature_points());
    FEValues<2>                      bending_values(mapping,
                               fe,
                               bending_rule,
                               update_gradients | update_JxW_values);
    FEValues<2>                      shear_values(mapping,
                             fe,
                             shear_rule,
                             update_values | update_gradients |
                               update_JxW_values);
    const FEValuesExtractors::Scalar w(0);
    const FEValuesExtractors::Vector beta(1);

    // (P1): D_b = D [[1,nu,0],[nu,1,0],[0,0,(1-nu)/2]], D_s = k G t.
    const double D  = plate.flexural_rigidity();
    const double nu = plate.poissons_ratio;
    const double Ds = shear_rigidity();

    const unsigned int                   n = fe.n_dofs_per_cell();
    FullMatrix<double>                   local(n, n);
    std::vector<types::global_dof_index> dofs(n);
    std::vector<Tensor<2, 2>>            grad_beta(n);
    std::vector<Moments>                 moments(n);
    std::vector<Tensor<1, 2>>            gamma(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        local = 0;
        bending_values.reinit(cell);
        for (unsigned int q = 0; q < bending_rule.size(); ++q)
          {
            for (unsigned int i = 0; i < n; ++i)
              {
                grad_beta[i] = bending_values[beta].gradient(i, q);
                moments[i] =
                  PlateOnHalfspace::bending_moments(D, nu, grad_beta[i]);
              }
            // the bending energy -M(beta_j) : grad beta_i
            const double JxW = bending_values.JxW(q);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                local(i, j) -=
                  (moments[j].mx * grad_beta[i][0][0] +
                   moments[j].my * grad_beta[i][1][1] +
                   moments[j].mxy * (grad_beta[i][0][1] + grad_beta[i][1][0])) *
                  JxW;
          }
        shear_values.reinit(cell);
        for (unsigned int q = 0; q < shear_rule.size(); ++q)
          {
            // gamma = grad w - beta
            for (unsigned int i = 0; i < n; ++i)
              gamma[i] =
                shear_values[w].gradient(i, q) - shear_values[beta].value(i, q);
            const double JxW = shear_values.JxW(q);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                local(i, j) += Ds * (gamma[i] * gamma[j]) * JxW;
          }
        cell->get_dof_indices(dofs);
        constraints.distribute_local_to_global(local, dofs, stiffness);
      }
  }

  double
  MindlinPlate::resultant(const Vector<double> &load) const
  {
    // Compensated: a plain sum drifted by 6e-12 of example 2's load at
    // 10^6 nodes, past the 1e-12 to which its Verification/Checks compares
    // applied_load (parameters/example2.prm).
    namespace acc = boost::accumulators;
    acc::accumulator_set<double, acc::stats<acc::tag::sum_kahan>> sum;
    for (const auto dof : foundation_dofs)
      sum(load[dof]);
    return acc::sum_kahan(sum);
  }

  void
  MindlinPlate::assemble_loads(const LoadList &loads)
  {
    load       = load_vector(loads);
    total_load = resultant(load);
  }

  Vector<double>
  MindlinPlate::load_vector(const LoadList &loads) const
  {
    Vector<double>                       load(dof_handler.n_dofs());
    const unsigned int                   n = fe.n_dofs_per_cell();
    Vector<double>                       local(n);
    std::vector<types::global_dof_index> dofs(n);
    const QGauss<2>                      cell_rule(3);
    std::vector<bool>                    used(loads.size(), false);
    FEValues<2>                          thermal_values(mapping,
                               fe,
                               cell_rule,
                               update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector     beta(1);

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        local                                = 0;
        const BilinearQuadrilateral geometry = cell_geometry(cell);
        for (unsigned int k = 0; k < loads.size(); ++k)
          {
            const CellLoad on_cell = loads[k]->on_cell(geometry);
            if (on_cell.empty())
              continue;
            used[k] = true;
            for (unsigned int q = 0; q < on_cell.rule.size(); ++q)
              {
                const auto   phi = q2_shape_values(on_cell.rule.point(q));
                const double pq  = on_cell.pressure[q] * on_cell.rule.weight(q);
                for (unsigned int i = 0; i < 9; ++i)
                  local[fe.component_to_system_index(0, i)] += pq * phi[i];
              }
          }
        if (thermal.moment != 0)
          {
            // M_T ∫ div(beta_v): the work of the thermal curvature
            // (doc/formulation.md, "Temperature").
            thermal_values.reinit(cell);
            for (unsigned int q = 0; q < cell_rule.size(); ++q)
              for (unsigned int i = 0; i < n; ++i)
                local[i] += thermal.moment *
                            thermal_values[beta].divergence(i, q) *
                            thermal_values.JxW(q);
          }
        cell->get_dof_indices(dofs);
        constraints.distribute_local_to_global(local, dofs, load);
      }

    for (unsigned int k = 0; k < loads.size(); ++k)
      {
        const auto force = loads[k]->concentrated_force();
        if (!force)
          {
            AssertThrow(used[k],
                        ExcMessage(loads[k]->label() +
                                   " does not overlap the plate."));
            continue;
          }
        const auto &[location, value] = *force;
        std::vector<
          std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>>
          located;
        try
          {
            located = locate_on_each_slab(location);
          }
        catch (...)
          {
            AssertThrow(false,
                        ExcMessage(loads[k]->label() + ": the point " +
                                   point_text(location[0], location[1]) +
                                   " is not on the plate."));
          }
        // on a joint, each slab's face carries its share
        const double share = value / located.size();
        for (const auto &[cell, reference_point] : located)
          {
            local          = 0;
            const auto phi = q2_shape_values(reference_point);
            for (unsigned int i = 0; i < 9; ++i)
              local[fe.component_to_system_index(0, i)] = share * phi[i];
            cell->get_dof_indices(dofs);
            constraints.distribute_local_to_global(local, dofs, load);
          }
      }
    return load;
  }

  double
  MindlinPlate::shear_rigidity() const
  {
    return 5. / 6. * plate.youngs_modulus / (2. * (1. + plate.poissons_ratio)) *
           plate.thickness;
  }

  unsigned int
  MindlinPlate::shear_quadrature_points() const
  {
    return discretization.shear_integration ==
               Parameters::Discretization::ShearIntegration::full ?
             3 :
             2;
  }

  unsigned int
  MindlinPlate::n_unconstrained_dofs() const
  {
    return dof_handler.n_dofs() - constraints.n_constraints();
  }

  void
  MindlinPlate::solve_unsupported(Vector<double> &solution) const
  {
    SparseDirectUMFPACK solver;
    solver.initialize(assembled_stiffness());
    solution = load;
    solver.solve(solution);
    constraints.distribute(solution);
  }

  void
  MindlinPlate::condense(LAPACKFullMatrix<double> &condensed)
  {
    // r: every unconstrained DoF that is not a foundation node (rotations,
    // and w-DoFs a test may have supported).
    rest_dofs.clear();
    for (types::global_dof_index i = 0; i < dof_handler.n_dofs(); ++i)
      if (foundation_index[i] < 0 && !constraints.is_constrained(i))
        rest_dofs.push_back(i);
    std::vector<int> rest_position(dof_handler.n_dofs(), -1);
    for (unsigned int c = 0; c < rest_dofs.size(); ++c)
      rest_position[rest_dofs[c]] = c;
    const SparseMatrix<double> &stiffness = assembled_stiffness();
    rest_factor.factorize(stiffness, rest_dofs);

    const unsigned int nf = foundation_dofs.size(), nr = rest_dofs.size();
    condensed.reinit(nf);
    condensed = 0.;
    // K_ff
    for (unsigned int i = 0; i < nf; ++i)
      for (auto entry = stiffness.begin(foundation_dofs[i]);
           entry != stiffness.end(foundation_dofs[i]);
           ++entry)
        if (foundation_index[entry->column()] >= 0)
          condensed(i, foundation_index[entry->column()]) = entry->value();

    // K_fr row by row, columns numbered within r
    std::vector<std::vector<std::pair<unsigned int, double>>> coupling_rows(nf);
    for (unsigned int i = 0; i < nf; ++i)
      for (auto entry = stiffness.begin(foundation_dofs[i]);
           entry != stiffness.end(foundation_dofs[i]);
           ++entry)
        if (rest_position[entry->column()] >= 0)
          coupling_rows[i].emplace_back(rest_position[entry->column()],
                                        entry->value());

    // - K_fr K_rr^{-1} K_rf, a block of columns at a time (K symmetric: row
    // f_j of K holds column j of K_rf).
    const unsigned int  block_size = 256;
    std::vector<double> block;
    for (unsigned int first = 0; first < nf; first += block_size)
      {
        const unsigned int k = std::min(block_size, nf - first);
        block.assign(std::size_t(nr) * k, 0.);
        for (unsigned int jj = 0; jj < k; ++jj)
          {
            const auto dof = foundation_dofs[first + jj];
            for (auto entry = stiffness.begin(dof); entry != stiffness.end(dof);
                 ++entry)
              if (rest_position[entry->column()] >= 0)
                block[rest_position[entry->column()] + std::size_t(jj) * nr] =
                  entry->value();
          }
        rest_factor.solve(block, k);
        // column by column: both the block's and K̄'s columns are contiguous
        for (unsigned int jj = 0; jj < k; ++jj)
          {
            const double *x = block.data() + std::size_t(jj) * nr;
            for (unsigned int i = 0; i < nf; ++i)
              {
                double sum = 0;
                for (const auto &entry : coupling_rows[i])
                  sum += entry.second * x[entry.first];
                condensed(i, first + jj) -= sum;
              }
          }
      }
  }

  Vector<double>
  MindlinPlate::condensed_load(const Vector<double> &load) const
  {
    AssertThrow(load.size() == dof_handler.n_dofs(), ExcInternalError());
    // P̄ = P_f - K_fr K_rr^{-1} P_r
    const unsigned int  nf = foundation_dofs.size(), nr = rest_dofs.size();
    std::vector<double> rest_load(nr);
    for (unsigned int c = 0; c < nr; ++c)
      rest_load[c] = load[rest_dofs[c]];
    rest_factor.solve(rest_load, 1);
    Vector<double> rest_solution(dof_handler.n_dofs()),
      product(dof_handler.n_dofs());
    for (unsigned int c = 0; c < nr; ++c)
      rest_solution[rest_dofs[c]] = rest_load[c];
    assembled_stiffness().vmult(product, rest_solution);
    Vector<double> condensed(nf);
    for (unsigned int i = 0; i < nf; ++i)
      condensed[i] = load[foundation_dofs[i]] - product[foundation_dofs[i]];
    return condensed;
  }

  void
  MindlinPlate::expand(const Vector<double> &foundation_w,
                       const Vector<double> &load,
                       Vector<double>       &solution) const
  {
    AssertThrow(load.size() == dof_handler.n_dofs(), ExcInternalError());
    const unsigned int n = dof_handler.n_dofs();
    Vector<double>     known(n), rhs(n);
    for (unsigned int i = 0; i < foundation_dofs.size(); ++i)
      known[foundation_dofs[i]] = foundation_w[i];
    // r = K_rr^{-1} (P_r - K_rf w_f)
    assembled_stiffness().vmult(rhs, known);
    rhs.sadd(-1., 1., load);
    std::vector<double> rest(rest_dofs.size());
    for (unsigned int c = 0; c < rest_dofs.size(); ++c)
      rest[c] = rhs[rest_dofs[c]];
    rest_factor.solve(rest, 1);
    solution = known;
    for (unsigned int c = 0; c < rest_dofs.size(); ++c)
      solution[rest_dofs[c]] = rest[c];
    constraints.distribute(solution);
  }

  Vector<double>
  MindlinPlate::restrict_to_foundation(const Vector<double> &solution) const
  {
    Vector<double> values(foundation_dofs.size());
    for (unsigned int i = 0; i < foundation_dofs.size(); ++i)
      values[i] = solution[foundation_dofs[i]];
    return values;
  }

  Vector<double>
  MindlinPlate::foundation_field_to_solution(const Vector<double> &field) const
  {
    Vector<double> values(dof_handler.n_dofs());
    for (unsigned int i = 0; i < foundation_dofs.size(); ++i)
      values[foundation_dofs[i]] = field[i];
    constraints.distribute(values);
    // distribute() also set the rotations from their own constraints (all
    // zero); only component 0 carries the field.
    return values;
  }

  struct MindlinPlate::NearCell
  {
    typename DoFHandler<2>::active_cell_iterator cell;
    Point<2>                                     point;
    double       distance = std::numeric_limits<double>::max();
    unsigned int index    = 0; ///< among the active cells

    /** Whether @p a is nearer than @p b, or as near and first in the
     *  order of the cells: the order locate() takes cells in. */
    static bool
    nearer(const NearCell &a, const NearCell &b)
    {
      return std::make_pair(a.distance, a.index) <
             std::make_pair(b.distance, b.index);
    }
  };

  std::vector<MindlinPlate::NearCell>
  MindlinPlate::cells_near(const Point<2> &x, const double tolerance) const
  {
    // The cells whose bounding boxes come within the tolerance of x, in
    // the order of the active cells.
    AssertThrow(cell_boxes, ExcMessage("MindlinPlate::locate before setup()."));
    std::vector<std::pair<BoundingBox<2>, unsigned int>> near;
    if (std::isfinite(tolerance))
      {
        const Tensor<1, 2> margin({tolerance, tolerance});
        cell_boxes->tree.query(boost::geometry::index::intersects(
                                 BoundingBox<2>({x - margin, x + margin})),
                               std::back_inserter(near));
      }
    std::sort(near.begin(), near.end(), [](const auto &a, const auto &b) {
      return a.second < b.second;
    });
    std::vector<NearCell> cells;
    for (const auto &[box, index] : near)
      {
        const auto                 &cell     = cell_boxes->cells[index];
        const BilinearQuadrilateral geometry = cell_geometry(cell);
        Point<2>                    p        = geometry.inverse_map(x);
        for (unsigned int d = 0; d < 2; ++d)
          p[d] = std::min(1., std::max(0., p[d]));
        cells.push_back({cell, p, geometry.map(p).distance(x), index});
      }
    return cells;
  }

  namespace
  {
    /** How far from a cell a point may lie and count as in it. */
    double
    point_tolerance(const Point<2> &x)
    {
      return 1e-10 * (1. + x.norm());
    }
  } // namespace

  std::vector<MindlinPlate::NearCell>
  MindlinPlate::cells_holding(const Point<2> &x) const
  {
    const double          tolerance = point_tolerance(x);
    std::vector<NearCell> holding;
    for (const NearCell &near : cells_near(x, tolerance))
      if (near.distance <= tolerance)
        holding.push_back(near);
    // a point so far away that its distances overflow is off the plate
    // too (no cell was near)
    AssertThrow(!holding.empty(), ExcMessage("The point is not on the plate."));
    const auto first =
      std::min_element(holding.begin(), holding.end(), NearCell::nearer);
    std::rotate(holding.begin(), first, first + 1);
    return holding;
  }

  std::vector<std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>>
  MindlinPlate::locate_on_each_slab(const Point<2> &x) const
  {
    // On each slab the nearest cell wins, the first in the order of the
    // cells among equals, as on a search through all of them.
    std::map<types::material_id, NearCell> on_slab;
    for (const NearCell &near : cells_holding(x))
      {
        const auto [best, added] =
          on_slab.emplace(near.cell->material_id(), near);
        if (!added && NearCell::nearer(near, best->second))
          best->second = near;
      }
    // the nearest first: locate()'s one
    std::vector<NearCell> holding;
    for (const auto &[slab, best] : on_slab)
      holding.push_back(best);
    std::sort(holding.begin(), holding.end(), NearCell::nearer);
    std::vector<
      std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>>
      located;
    for (const NearCell &n : holding)
      located.emplace_back(n.cell, n.point);
    return located;
  }

  std::vector<std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>>
  MindlinPlate::cells_at(const Point<2> &x) const
  {
    std::vector<
      std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>>
      cells;
    for (const NearCell &n : cells_holding(x))
      cells.emplace_back(n.cell, n.point);
    return cells;
  }

  bool
  MindlinPlate::on_mirror_plane(const Point<2> &x) const
  {
    const MirrorSymmetry &symmetry = foundation_space.symmetry;
    return (symmetry.x && std::abs(x[0]) <= point_tolerance(x)) ||
           (symmetry.y && std::abs(x[1]) <= point_tolerance(x));
  }

  std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>
  MindlinPlate::locate(const Point<2> &x) const
  {
    return locate_on_each_slab(x).front();
  }

  double
  MindlinPlate::point_value(const Vector<double> &solution,
                            const Point<2>       &x,
                            const unsigned int    component) const
  {
    const auto  located = locate(x);
    FEValues<2> values(mapping,
                       fe,
                       Quadrature<2>(std::vector<Point<2>>{located.second}),
                       update_values);
    values.reinit(located.first);
    std::vector<Vector<double>> all(1, Vector<double>(3));
    values.get_function_values(solution, all);
    return all[0][component];
  }

  Moments
  MindlinPlate::moments(
    const typename DoFHandler<2>::active_cell_iterator &cell,
    const Point<2>                                     &p,
    const Vector<double>                               &solution) const
  {
    FEValues<2> values(mapping,
                       fe,
                       Quadrature<2>(std::vector<Point<2>>{p}),
                       update_gradients);
    values.reinit(cell);
    std::vector<Tensor<2, 2>> grad(1);
    values[FEValuesExtractors::Vector(1)].get_function_gradients(solution,
                                                                 grad);
    return moments_of_rotation_gradient(grad[0]);
  }

  Moments
  MindlinPlate::mean_moments(
    const std::vector<
      std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>> &cells,
    const Vector<double> &solution) const
  {
    Moments mean;
    for (const auto &[cell, reference] : cells)
      {
        const Moments in_cell = moments(cell, reference, solution);
        mean.mx += in_cell.mx / cells.size();
        mean.my += in_cell.my / cells.size();
        mean.mxy += in_cell.mxy / cells.size();
      }
    return mean;
  }

  FibreStresses
  MindlinPlate::fibre_stresses(const Moments &m) const
  {
    const double  scale = 6. / (plate.thickness * plate.thickness);
    FibreStresses s;
    s.bottom             = {{scale * m.mx + thermal.nonlinear_stress_bottom,
                             scale * m.my + thermal.nonlinear_stress_bottom,
                             scale * m.mxy}};
    s.top                = {{-scale * m.mx + thermal.nonlinear_stress_top,
                             -scale * m.my + thermal.nonlinear_stress_top,
                             -scale * m.mxy}};
    const auto principal = [](const std::array<double, 3> &t) {
      return 0.5 * (t[0] + t[1]) + std::hypot(0.5 * (t[0] - t[1]), t[2]);
    };
    s.principal_bottom = principal(s.bottom);
    s.principal_top    = principal(s.top);
    return s;
  }
} // namespace PlateOnHalfspace
