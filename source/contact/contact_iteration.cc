#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/base/interruption.h>
#include <plate_on_halfspace/contact/active_set.h>
#include <plate_on_halfspace/contact/contact_iteration.h>
#include <plate_on_halfspace/contact/contact_region.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <algorithm>
#include <cmath>
#include <iomanip>

namespace PlateOnHalfspace
{
  namespace
  {
    double
    max_abs(const Vector<double> &v)
    {
      return v.size() > 0 ? v.linfty_norm() : 0.;
    }

    /**
     * Finish a solve done in the contact basis (q holds the coefficients):
     * store them as pressure_coefficients, make q the nodal values, keep
     * the active set, and report contact where the pressure acts (the
     * active set and every node with q > 0: in the positive basis a
     * mid-side node whose own coefficient is zero still carries
     * q_m = alpha (qt_c0 + qt_c1)).
     */
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
  } // namespace

  ContactIteration::ContactIteration(const Parameters::Contact &contact,
                                     const bool                 tensionless,
                                     const unsigned int         verbosity,
                                     std::ostream              &log)
    : contact(contact)
    , tensionless(tensionless)
    , verbosity(verbosity)
    , log(log)
  {}

  ContactState
  ContactIteration::solve(MindlinPlate         &plate,
                          FoundationOperator   &foundation,
                          const Vector<double> &load,
                          const ContactSeed    &seed)
  {
    this->plate      = &plate;
    this->foundation = &foundation;
    final_contact_set.clear();
    ContactState state;
    state.cell_in_foundation.assign(plate.get_foundation_space().cells.size(),
                                    true);

    // Without any load the answer is w = q = 0 whatever the scene: a user
    // who asks for it has forgotten a load (or put every load off the
    // plate, which the load assembly refuses first).
    AssertThrow(load.linfty_norm() > 0,
                ExcMessage("Loads: the total load is zero (Loads/Uniform "
                           "pressure, Rectangular patches, Circular patches, "
                           "Point loads, Axles, Pressure function, "
                           "Plate/Unit weight and Temperature give no load; a "
                           "Pressure function counts at its quadrature points "
                           "only); set at least one non-zero load."));
    AssertThrow(!tensionless || plate.resultant(load) > 0,
                ExcMessage(
                  std::string("The loads lift the plate off a tensionless "
                              "foundation: their resultant is not downward (") +
                  (plate.get_thermal_load().moment != 0 ?
                     "a temperature difference alone does not hold a plate "
                     "down: give it its Plate/Unit weight)." :
                     "loads are positive downward: turn them down, or give "
                     "the plate its Plate/Unit weight).")));

    prepare(plate, foundation, state);
    prepare_load(load);
    if (!tensionless)
      solve_bonded(state);
    else if (contact.method == Parameters::Contact::Method::element_exclusion)
      solve_by_element_exclusion(state);
    else
      solve_by_active_set(seed, state);
    if (state.converged)
      check_accepted_solution(state);
    express_in_nodal_values(foundation, state);
    measure_contact_region(plate.get_foundation_space(),
                           foundation,
                           tensionless,
                           state);
    return state;
  }

  ContactState
  ContactIteration::solve_linearised(const Vector<double> &load)
  {
    return solve_on_final_set(load, final_tolerance());
  }

  ContactState
  ContactIteration::solve_adjoint(const Vector<double> &load)
  {
    return solve_on_final_set(load, adjoint_tolerance());
  }

  ContactState
  ContactIteration::solve_on_final_set(const Vector<double> &load,
                                       const double          tolerance)
  {
    AssertThrow(plate != nullptr && !final_contact_set.empty(),
                ExcMessage("ContactSolver::solve_linearised() and "
                           "solve_adjoint() need a solve() first."));
    prepare_load(load);
    ContactState state;
    state.cell_in_foundation.assign(plate->get_foundation_space().cells.size(),
                                    true);
    solve_on_set(final_contact_set, tolerance, state);
    state.iterations = 1;
    state.converged  = true;
    express_in_nodal_values(*foundation, state);
    measure_contact_region(plate->get_foundation_space(),
                           *foundation,
                           tensionless,
                           state);
    return state;
  }

  void
  ContactIteration::solve_bonded(ContactState &state)
  {
    final_contact_set = foundation->supported_nodes();
    const Vector<double> plate_settlement =
      solve_on_set(final_contact_set, final_tolerance(), state);
    state.iterations = 1;
    state.converged  = true;
    evaluate_contact_conditions(plate_settlement,
                                foundation->supported_nodes(),
                                state);
  }

  void
  ContactIteration::solve_by_element_exclusion(ContactState &state)
  {
    const FoundationSpace &space         = plate->get_foundation_space();
    double                 previous_norm = 0;
    Vector<double>         plate_settlement;
    for (state.iterations = 1; state.iterations <= contact.max_iterations;
         ++state.iterations)
      {
        // a safe point: SIGINT/SIGTERM end the run here
        // (base/interruption.h)
        Interruption::check();
        if (state.iterations > 1)
          foundation->build(space, state.cell_in_foundation);
        AssertThrow(contact_set_supports_plate(space,
                                               foundation->supported_nodes()),
                    ExcMessage(plate_is_mechanism_message()));
        final_contact_set = foundation->supported_nodes();
        plate_settlement =
          solve_on_set(final_contact_set, final_tolerance(), state);
        const double norm = state.w.l2_norm();
        const double change =
          std::abs(norm - previous_norm) / std::max(norm, 1e-300);
        previous_norm = norm;

        // the paper's criterion is on the nodal pressures
        Vector<double> nodal_q;
        foundation->nodal_pressure(state.q, nodal_q);
        unsigned int n_excluded = 0;
        bool         changed    = false;
        for (unsigned int c = 0; c < space.cells.size(); ++c)
          {
            if (!state.cell_in_foundation[c])
              {
                ++n_excluded;
                continue;
              }
            const std::vector<unsigned int> nodes     = space.cells[c].nodes();
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
    evaluate_contact_conditions(plate_settlement,
                                foundation->supported_nodes(),
                                state);
  }

  void
  ContactIteration::solve_by_active_set(const ContactSeed &seed,
                                        ContactState      &state)
  {
    // Inexact solves while the set changes (as inexact Newton methods do):
    // a set that is about to change needs only the signs of q and of the
    // gap away from the contact boundary, which a loose solve gets right.
    // Once a loose solve leaves nothing to change, the same set is solved
    // more accurately and checked again; only a check at the final
    // accuracy converges.
    // A direct solver solves every set exactly (both accuracies 0).
    const FoundationSpace  &space     = plate->get_foundation_space();
    const std::vector<bool> predicted = predict_contact_set(seed, state);
    ActiveSetUpdate         active_set(space,
                               foundation->supported_nodes(),
                               predicted,
                               foundation->test_coupling());
    Vector<double>          plate_settlement;
    double tolerance = std::max(final_tolerance(), changing_set_tolerance());
    for (state.iterations = 1; state.iterations <= contact.max_iterations;
         ++state.iterations)
      {
        // a safe point: SIGINT/SIGTERM end the run here
        // (base/interruption.h)
        Interruption::check();
        AssertThrow(contact_set_supports_plate(space, active_set.contact_set()),
                    ExcMessage(plate_is_mechanism_message()));
        final_contact_set = active_set.contact_set();
        plate_settlement  = solve_on_set(final_contact_set, tolerance, state);
        // A sign below the solve's accuracy is rounding, not a violation.
        const double accuracy  = std::max(1e-12, tolerance);
        const double q_scale   = std::max(max_abs(state.q), 1e-300);
        const double gap_scale = std::max(max_abs(plate_settlement), 1e-300);
        if (active_set.step(state.q,
                            state.gap,
                            accuracy * q_scale,
                            accuracy * gap_scale,
                            state.iterations,
                            verbosity,
                            log))
          {
            if (tolerance <= final_tolerance())
              {
                state.converged = true;
                break;
              }
            // Tighten in stages of 1e-3: the nodes at the contact
            // boundary whose signs a loose solve could not tell are
            // settled by solves of intermediate accuracy, so that the
            // costly solves to the final accuracy meet few changes. A
            // stage within a factor 5 of the final accuracy is that one
            // (1e-4, 1e-7, then 1e-10 or 1e-8: a factor 10 would sit on
            // the rounding of 1e-3 * 1e-4).
            tolerance = 1e-3 * tolerance < 5 * final_tolerance() ?
                          final_tolerance() :
                          1e-3 * tolerance;
            active_set.forget_visited_sets();
          }
      }
    state.iterations = std::min(state.iterations, contact.max_iterations);
    evaluate_contact_conditions(plate_settlement,
                                foundation->supported_nodes(),
                                state);
  }
} // namespace PlateOnHalfspace
