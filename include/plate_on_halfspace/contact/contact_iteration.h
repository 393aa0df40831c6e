/**
 * The contact iteration both contact solvers run (doc/formulation.md,
 * "Tensionless contact"): the scene checks, bonded contact as one solve,
 * the paper's element exclusion, and the primal-dual active set with
 * inexact solves while the set changes. A solver supplies only what
 * differs: how it prepares a cycle and how it solves the coupled problem on
 * one contact set.
 */
#ifndef plate_on_halfspace_contact_contact_iteration_h
#define plate_on_halfspace_contact_contact_iteration_h

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/interface.h>

#include <ostream>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** The shared part of every contact solver (see the file documentation). */
  class ContactIteration : public ContactSolver
  {
  public:
    ContactIteration(const Parameters::Contact &contact,
                     const bool                 tensionless,
                     const unsigned int         verbosity,
                     std::ostream              &log);

    ContactState
    solve(MindlinPlate         &plate,
          FoundationOperator   &foundation,
          const Vector<double> &load,
          const ContactSeed    &seed) final;

    ContactState
    solve_linearised(const Vector<double> &load) final;

    ContactState
    solve_adjoint(const Vector<double> &load) final;

  protected:
    /**
     * Once per solve(), before any contact set: set up what every set
     * shares, and record in @p state the time and memory of the solver's
     * factorisation of the flexibility.
     */
    virtual void
    prepare(MindlinPlate       &plate,
            FoundationOperator &foundation,
            ContactState       &state) = 0;

    /**
     * Before the contact sets of a solve() or solve_linearised(), after
     * prepare(): derive what the solves need from the load vector @p load,
     * which solve_on_set() then solves for.
     */
    virtual void
    prepare_load(const Vector<double> &load) = 0;

    /**
     * The coupled problem with the gap closed on @p contact_set (a subset
     * of the supported nodes that carries the plate) and no pressure off
     * it, solved to the relative accuracy @p tolerance (0: a direct solve),
     * warm started from state.q if it has the right size. Fills w, q (the
     * coefficients of the contact basis), gap, plate_solution and
     * in_contact of @p state and returns B w.
     */
    virtual Vector<double>
    solve_on_set(const std::vector<bool> &contact_set,
                 const double             tolerance,
                 ContactState            &state) = 0;

    /**
     * A first contact set for the active set, from @p seed (the previous
     * cycle's set and pressure, or empty): a solver that can move the
     * contact boundary more cheaply than a solve per set returns its
     * estimate, and may leave its pressures in state.q as the warm start.
     * The active set then checks and corrects it, so the estimate decides
     * only how many steps follow, never the answer. By default the seed's
     * set itself.
     */
    virtual std::vector<bool>
    predict_contact_set(const ContactSeed &seed, ContactState &state)
    {
      (void)state;
      return seed.contact_set;
    }

    /**
     * After the iteration has accepted @p state: a solver that can tell
     * how many digits of its pressures rounding left refuses an answer
     * less accurate than accepted_rounding_floor. By default nothing.
     */
    virtual void
    check_accepted_solution(const ContactState &state) const
    {
      (void)state;
    }

    /** Relative accuracy of the solves while the active set changes. */
    virtual double
    changing_set_tolerance() const
    {
      return 0;
    }

    /** Relative accuracy of the solve that confirms the last set. */
    virtual double
    final_tolerance() const
    {
      return 0;
    }

    /** Relative accuracy of solve_adjoint(). */
    virtual double
    adjoint_tolerance() const
    {
      return final_tolerance();
    }

    const Parameters::Contact contact;
    const bool                tensionless;
    const unsigned int        verbosity;
    std::ostream             &log;
    /** The problem of the last solve(). */
    MindlinPlate       *plate      = nullptr;
    FoundationOperator *foundation = nullptr;

  private:
    /** solve_linearised() to the relative accuracy @p tolerance. */
    ContactState
    solve_on_final_set(const Vector<double> &load, const double tolerance);

    /** The contact set of the last solve_on_set() of solve(). */
    std::vector<bool> final_contact_set;

    void
    solve_bonded(ContactState &state);

    /**
     * The paper's iteration: drop every cell with more than half of its
     * nodal pressures tensile, rebuild the operator, repeat until the
     * displacements stop changing.
     */
    void
    solve_by_element_exclusion(ContactState &state);

    /** The primal-dual active set from @p seed (ActiveSetUpdate). */
    void
    solve_by_active_set(const ContactSeed &seed, ContactState &state);
  };
} // namespace PlateOnHalfspace

#endif
