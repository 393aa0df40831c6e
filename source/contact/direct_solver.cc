#include <deal.II/base/exceptions.h>

#include <deal.II/lac/full_matrix.h>

#include <plate_on_halfspace/base/condition_estimate.h>
#include <plate_on_halfspace/contact/direct_solver.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <set>

namespace PlateOnHalfspace
{
  namespace
  {
    double
    max_abs(const Vector<double> &v)
    {
      return v.size() > 0 ? v.linfty_norm() : 0.;
    }

  } // namespace

  bool
  contact_set_supports_plate(const FoundationSpace   &space,
                             const std::vector<bool> &in_contact)
  {
    // The nodes in contact on the whole plate: those of the computed
    // part and, for a symmetric scene, their mirror images.
    std::vector<Point<2>> points;
    for (unsigned int i = 0; i < in_contact.size(); ++i)
      if (in_contact[i])
        for (const Point<2> &x : space.symmetry.images(space.node_locations[i]))
          points.push_back(x);
    const unsigned int n = points.size();
    if (n < 3)
      return false;
    Point<2> centre;
    for (const Point<2> &p : points)
      centre += p / n;
    double xx = 0, xy = 0, yy = 0, extent = 0;
    for (const Point<2> &p : points)
      {
        const Tensor<1, 2> d = p - centre;
        xx += d[0] * d[0];
        xy += d[0] * d[1];
        yy += d[1] * d[1];
        extent = std::max(extent, d.norm_square());
      }
    // smallest eigenvalue of the 2x2 second-moment matrix
    const double mean = 0.5 * (xx + yy);
    const double smallest =
      mean - std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
    return smallest > 1e-10 * n * extent;
  }

  void
  evaluate_contact_conditions(const Vector<double>    &plate_settlement,
                              const std::vector<bool> &supported,
                              ContactState            &state)
  {
    const double q_scale   = std::max(max_abs(state.q), 1e-300);
    const double gap_scale = std::max(max_abs(plate_settlement), 1e-300);
    double       tension = 0, penetration = 0, product = 0;
    state.tensile_nodes = 0;
    for (unsigned int i = 0; i < state.q.size(); ++i)
      {
        tension = std::max(tension, -state.q[i] / q_scale);
        if (state.q[i] < 0)
          ++state.tensile_nodes;
        // Only the soil under the plate's foundation area is constrained.
        if (supported[i])
          {
            penetration = std::max(penetration, -state.gap[i] / gap_scale);
            product     = std::max(product,
                               std::abs(state.q[i] * state.gap[i]) /
                                 (q_scale * gap_scale));
          }
      }
    state.complementarity_violation =
      std::max({tension, penetration, product, 0.});
    state.max_penetration = std::max(penetration, 0.);
  }

  ActiveSetUpdate::ActiveSetUpdate(const FoundationSpace   &space,
                                   const std::vector<bool> &supported,
                                   const std::vector<bool> &initial_contact)
    : space(space)
    , supported(supported)
    , active(supported)
  {
    if (initial_contact.size() == active.size() &&
        contact_set_supports_plate(space, initial_contact))
      for (unsigned int i = 0; i < active.size(); ++i)
        active[i] = active[i] && initial_contact[i];
  }

  unsigned int
  ActiveSetUpdate::n_contact_nodes() const
  {
    return std::count(active.begin(), active.end(), true);
  }

  unsigned int
  ActiveSetUpdate::find_violations(const Vector<double> &q,
                                   const Vector<double> &gap,
                                   const double          q_tolerance,
                                   const double          g_tolerance)
  {
    next = active;
    changes.clear();
    for (unsigned int i = 0; i < active.size(); ++i)
      {
        if (!supported[i])
          continue;
        const bool violated =
          active[i] ? (q[i] < -q_tolerance) : (gap[i] < -g_tolerance);
        if (violated)
          {
            next[i] = !active[i];
            changes.push_back(i);
          }
      }
    return changes.size();
  }

  bool
  ActiveSetUpdate::step(const Vector<double> &q,
                        const Vector<double> &gap,
                        const double          q_tolerance,
                        const double          g_tolerance,
                        const unsigned int    iteration,
                        const unsigned int    verbosity,
                        std::ostream         &log)
  {
    const unsigned int n_changes =
      find_violations(q, gap, q_tolerance, g_tolerance);
    if (verbosity > 0)
      log << "   contact iteration " << iteration << ": nodes in contact "
          << n_contact_nodes() << ", changes " << n_changes
          << (single_pivot_mode ? " (single pivots)" : "") << std::endl;
    if (n_changes == 0)
      return true;
    if (detect_cycle() && verbosity > 0)
      log << "   contact iteration " << iteration
          << ": cycle detected, switching to single pivots" << std::endl;
    advance();
    return false;
  }

  bool
  ActiveSetUpdate::detect_cycle()
  {
    visited.insert(active);
    if (visited.count(next) > 0 && !single_pivot_mode)
      {
        // The full step returns to a set seen before: a cycle. Fall back
        // to Murty's least-index rule, one status change per iteration,
        // which terminates for the SPD Galerkin problem.
        single_pivot_mode = true;
        return true;
      }
    return false;
  }

  void
  ActiveSetUpdate::advance()
  {
    if (single_pivot_mode)
      {
        // the least index whose change leaves a set that carries the plate
        next = active;
        for (const unsigned int i : changes)
          {
            next[i] = !active[i];
            if (contact_set_supports_plate(space, next))
              break;
            next[i] = active[i];
          }
      }
    else if (!contact_set_supports_plate(space, next))
      {
        // A plate that lifts off almost entirely (a load at an edge or a
        // corner) can make the full step drop too many nodes at once. Take
        // every entry, then the exits in order for as long as the rest
        // still carries the plate.
        next = active;
        for (const unsigned int i : changes)
          if (!active[i])
            next[i] = true;
        for (const unsigned int i : changes)
          if (active[i])
            {
              next[i] = false;
              if (!contact_set_supports_plate(space, next))
                next[i] = true;
            }
      }
    AssertThrow(next != active,
                ExcMessage(
                  "The plate is a mechanism: the nodes left in contact "
                  "cannot carry it (fewer than three non-collinear "
                  "supporting nodes). A load on or very near the edge "
                  "of a weightless plate tilts it about that edge: move "
                  "the load inward, refine the mesh there or give the "
                  "plate its weight (Plate/Unit weight)."));
    active = next;
  }

  ContactSolver::ContactSolver(const Parameters::Contact &contact,
                               const bool                 tensionless,
                               const unsigned int         verbosity,
                               std::ostream              &log)
    : contact(contact)
    , tensionless(tensionless)
    , verbosity(verbosity)
    , log(log)
  {}

  void
  ContactSolver::solve_coupled(const LAPACKFullMatrix<double> &plate_stiffness,
                               const Vector<double>           &plate_load,
                               const FoundationOperator       &foundation,
                               const FoundationSpace          &space,
                               ContactState                   &state) const
  {
    // (K̄ + S) w = P̄ (P21), S the foundation stiffness on the contact set.
    LAPACKFullMatrix<double> coupled(plate_stiffness);
    foundation.add_stiffness(coupled);
    const double      l1_norm = coupled.l1_norm();
    const std::string mechanism =
      "The plate is a mechanism: the contact set cannot carry it (fewer than "
      "three non-collinear supporting nodes, or loads that lift it off).";
    try
      {
        if (foundation.is_symmetric())
          coupled.compute_cholesky_factorization();
        else
          coupled.compute_lu_factorization();
      }
    catch (...)
      {
        AssertThrow(false, ExcMessage(mechanism));
      }
    state.coupled_rcond =
      reciprocal_condition_number(coupled, l1_norm, foundation.is_symmetric());
    state.w = plate_load;
    coupled.solve(state.w);
    for (const double v : state.w)
      AssertThrow(std::isfinite(v), ExcMessage(mechanism));
    foundation.solve(state.w, state.q);
    correct_rigid_body_equilibrium(
      plate_stiffness, plate_load, foundation, space, state);
    state.in_contact = foundation.contact_nodes();
  }

  void
  ContactSolver::correct_rigid_body_equilibrium(
    const LAPACKFullMatrix<double> &plate_stiffness,
    const Vector<double>           &plate_load,
    const FoundationOperator       &foundation,
    const FoundationSpace          &space,
    ContactState                   &state) const
  {
    // The rigid-body motions w = 1, x, y of the free plate are exactly in
    // the kernel of K̄, so the three equations r^T (K̄ + S) w = r^T P̄ read
    // r^T S w = r^T P̄: vertical force and moment equilibrium. In floating
    // point K̄ r is only zero to rounding times |K̄|, which for a plate much
    // stiffer than the soil (E/E0 >= 1e8) spoils equilibrium. A correction
    // w += R da within that kernel restores the three equations at the
    // soil's scale without touching the others.
    const unsigned int n = state.w.size();
    if (n < 3)
      return;
    Point<2> centre;
    double   extent = 0;
    for (const Point<2> &x : space.node_locations)
      centre += x / n;
    for (const Point<2> &x : space.node_locations)
      extent = std::max(extent, x.distance(centre));
    // Of w = 1, x, y, a symmetric scene's computed part (mirror_symmetry.h)
    // only has the motions that are even across its mirror planes.
    std::vector<Vector<double>> modes(1, Vector<double>(n));
    modes[0]               = 1.;
    const bool mirrored[2] = {space.symmetry.x, space.symmetry.y};
    for (unsigned int axis = 0; axis < 2; ++axis)
      if (!mirrored[axis])
        {
          Vector<double> mode(n);
          for (unsigned int i = 0; i < n; ++i)
            mode[i] = (space.node_locations[i][axis] - centre[axis]) / extent;
          modes.push_back(mode);
        }
    // Only a free plate has these motions in its kernel (a plate with
    // supports, or any other stiffness, is left as solved).
    const double plate_scale = plate_stiffness.linfty_norm();
    for (const auto &mode : modes)
      {
        Vector<double> image(n);
        plate_stiffness.vmult(image, mode);
        if (image.linfty_norm() > 1e-8 * plate_scale * mode.linfty_norm())
          return;
      }
    const unsigned int n_modes = modes.size();
    FullMatrix<double> rigid_stiffness(n_modes, n_modes); // R^T S R
    Vector<double>     residual(n_modes), correction(n_modes), forces, q;
    foundation.nodal_forces(state.q, forces);
    for (unsigned int j = 0; j < n_modes; ++j)
      {
        residual[j] = modes[j] * plate_load - modes[j] * forces;
        Vector<double> s_mode;
        foundation.solve(modes[j], q);
        foundation.nodal_forces(q, s_mode);
        for (unsigned int i = 0; i < n_modes; ++i)
          rigid_stiffness(i, j) = modes[i] * s_mode;
      }
    rigid_stiffness.gauss_jordan();
    rigid_stiffness.vmult(correction, residual);
    for (unsigned int j = 0; j < n_modes; ++j)
      state.w.add(correction[j], modes[j]);
    foundation.solve(state.w, state.q);
  }

  void
  ContactSolver::evaluate_conditions(const FoundationOperator &foundation,
                                     ContactState             &state) const
  {
    foundation.gap(state.w, state.q, state.gap);
    Vector<double> plate;
    foundation.plate_settlement(state.w, plate);
    evaluate_contact_conditions(plate, foundation.supported_nodes(), state);
  }

  ContactState
  ContactSolver::solve(const LAPACKFullMatrix<double> &plate_stiffness,
                       const Vector<double>           &plate_load,
                       FoundationOperator             &foundation,
                       const FoundationSpace          &space,
                       const std::vector<bool>        &initial_contact) const
  {
    ContactState state = solve_in_contact_basis(
      plate_stiffness, plate_load, foundation, space, initial_contact);
    express_in_nodal_values(foundation, state);
    return state;
  }

  void
  express_in_nodal_values(const FoundationOperator &foundation,
                          ContactState             &state)
  {
    state.pressure_coefficients = state.q;
    foundation.nodal_pressure(state.pressure_coefficients, state.q);
    state.active_set                = state.in_contact;
    const double pressure_tolerance = 1e-12 * max_abs(state.q);
    for (unsigned int i = 0; i < state.q.size(); ++i)
      if (state.q[i] > pressure_tolerance)
        state.in_contact[i] = true;
  }

  ContactState
  ContactSolver::solve_in_contact_basis(
    const LAPACKFullMatrix<double> &plate_stiffness,
    const Vector<double>           &plate_load,
    FoundationOperator             &foundation,
    const FoundationSpace          &space,
    const std::vector<bool>        &initial_contact) const
  {
    ContactState state;
    state.cell_in_foundation.assign(space.cells.size(), true);

    // Without any load the answer is w = q = 0 whatever the scene: a user
    // who asks for it has forgotten a load (or put every load off the
    // plate, which the load assembly refuses first).
    AssertThrow(plate_load.linfty_norm() > 0,
                ExcMessage("Loads: the total load is zero (Loads/Uniform "
                           "pressure, Rectangular patches, Circular patches, "
                           "Point loads and Plate/Unit weight give no load); "
                           "set at least one non-zero load."));

    if (!tensionless)
      {
        solve_coupled(plate_stiffness, plate_load, foundation, space, state);
        state.iterations = 1;
        state.converged  = true;
        evaluate_conditions(foundation, state);
        return state;
      }

    // The condensed load keeps the resultant (no moments are applied).
    AssertThrow(std::accumulate(plate_load.begin(), plate_load.end(), 0.) > 0,
                ExcMessage("The loads lift the plate off a tensionless "
                           "foundation: their resultant is not downward."));

    if (contact.method == Parameters::Contact::Method::element_exclusion)
      {
        // The paper's iteration: drop every cell with more than half of its
        // nodal pressures tensile, rebuild, repeat until the displacements
        // stop changing.
        double previous_norm = 0;
        for (state.iterations = 1; state.iterations <= contact.max_iterations;
             ++state.iterations)
          {
            if (state.iterations > 1)
              foundation.build(space, state.cell_in_foundation);
            AssertThrow(contact_set_supports_plate(space,
                                                   foundation.contact_nodes()),
                        ExcMessage("The plate is a mechanism: after element "
                                   "exclusion the remaining foundation "
                                   "cannot carry it."));
            solve_coupled(
              plate_stiffness, plate_load, foundation, space, state);
            const double norm = state.w.l2_norm();
            const double change =
              std::abs(norm - previous_norm) / std::max(norm, 1e-300);
            previous_norm = norm;

            // the paper's criterion is on the nodal pressures
            Vector<double> nodal_q;
            foundation.nodal_pressure(state.q, nodal_q);
            unsigned int n_excluded = 0;
            bool         changed    = false;
            for (unsigned int c = 0; c < space.cells.size(); ++c)
              {
                if (!state.cell_in_foundation[c])
                  {
                    ++n_excluded;
                    continue;
                  }
                const std::vector<unsigned int> nodes = space.cells[c].nodes();
                unsigned int                    n_tensile = 0;
                for (const unsigned int i : nodes)
                  if (nodal_q[i] < 0)
                    ++n_tensile;
                if (2 * n_tensile > nodes.size())
                  {
                    state.cell_in_foundation[c] = false;
                    changed                     = true;
                    ++n_excluded;
                  }
              }
            if (verbosity > 0)
              log << "   contact iteration " << state.iterations
                  << ": excluded cells " << n_excluded
                  << ", relative change of |w| " << std::scientific
                  << std::setprecision(2) << change << std::defaultfloat
                  << std::endl;
            if (!changed || change < contact.tolerance)
              {
                state.converged = true;
                break;
              }
          }
        state.iterations = std::min(state.iterations, contact.max_iterations);
        evaluate_conditions(foundation, state);
        return state;
      }

    // Primal-dual active set (step-41, ActiveSetUpdate): solve the bonded
    // problem on C; repeat until C does not change.
    ActiveSetUpdate active_set(space,
                               foundation.supported_nodes(),
                               initial_contact);
    for (state.iterations = 1; state.iterations <= contact.max_iterations;
         ++state.iterations)
      {
        AssertThrow(contact_set_supports_plate(space, active_set.contact_set()),
                    ExcMessage("The plate is a mechanism: the nodes left in "
                               "contact cannot carry it (fewer than three "
                               "non-collinear supporting nodes)."));
        foundation.set_contact_nodes(active_set.contact_set());
        solve_coupled(plate_stiffness, plate_load, foundation, space, state);
        foundation.gap(state.w, state.q, state.gap);

        Vector<double> plate;
        foundation.plate_settlement(state.w, plate);
        const double q_scale   = std::max(max_abs(state.q), 1e-300);
        const double gap_scale = std::max(max_abs(plate), 1e-300);
        // Tolerances below which a sign is rounding, not a violation.
        if (active_set.step(state.q,
                            state.gap,
                            1e-12 * q_scale,
                            1e-12 * gap_scale,
                            state.iterations,
                            verbosity,
                            log))
          {
            state.converged = true;
            break;
          }
      }
    state.iterations = std::min(state.iterations, contact.max_iterations);
    evaluate_conditions(foundation, state);
    return state;
  }
} // namespace PlateOnHalfspace
