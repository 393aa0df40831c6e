#include <plate_on_halfspace/contact/active_set.h>
#include <plate_on_halfspace/contact/direct_solver.h>
#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/contact/iterative_solver.h>

#include <numeric>

namespace PlateOnHalfspace
{
  double
  contact_area(const ContactState &state)
  {
    return std::accumulate(state.cell_contact_area.begin(),
                           state.cell_contact_area.end(),
                           0.);
  }

  std::unique_ptr<ContactSolver>
  create_contact_solver(const SceneParameters            &parameters,
                        const Parameters::Contact::Solver solver,
                        const unsigned int                verbosity,
                        std::ostream                     &log,
                        const bool                        contact_set_only)
  {
    // The mechanism message suggests the weight only to a weightless plate.
    set_plate_weightless(!(parameters.plate.unit_weight > 0));
    if (solver == Parameters::Contact::Solver::iterative)
      {
        ConjugateGradientControl control;
        control.constrained_start = parameters.contact.constrained_start;
        control.preconditioner    = parameters.contact.preconditioner;
        // the last set's solve at the changing sets' accuracy: the active
        // set then stops at the first set that no longer changes
        if (contact_set_only)
          control.tolerance = control.changing_set_tolerance;
        return std::make_unique<IterativeContactSolver>(
          parameters.contact,
          parameters.foundation.tensionless,
          control,
          verbosity,
          log);
      }
    return std::make_unique<DirectContactSolver>(
      parameters.contact, parameters.foundation.tensionless, verbosity, log);
  }
} // namespace PlateOnHalfspace
