/**
 * Contact between the condensed plate and the half-space (doc/formulation.md,
 * "Tensionless contact"): bonded contact (one coupled solve) and the
 * algorithms for tensionless contact, the paper's element exclusion and the
 * primal-dual active set method (deal.II step-41 is the model).
 */
#ifndef plate_on_halfspace_contact_direct_solver_h
#define plate_on_halfspace_contact_direct_solver_h

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <ostream>
#include <set>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** The state of the foundation after a contact solve (foundation nodes). */
  struct ContactState
  {
    Vector<double> w; ///< plate deflection at the foundation nodes
    Vector<double> q; ///< nodal contact pressure, compression positive
    /**
     * The pressure's coefficients in the basis of the contact conditions
     * (foundation_operator.h; equal to q unless the positive serendipity
     * basis is used): what complementarity, tensile_nodes and the
     * foundation operator's nodal_forces() refer to.
     */
    Vector<double> pressure_coefficients;
    Vector<double> gap; ///< F q - B w: soil surface minus plate
    /** Where the pressure acts: the active set and every node with q > 0. */
    std::vector<bool> in_contact;
    /**
     * The solver's active set (coefficients free to carry pressure): what
     * the next cycle's iteration starts from.
     */
    std::vector<bool> active_set;
    std::vector<bool> cell_in_foundation; ///< element exclusion's cell set
    unsigned int      iterations = 0;
    bool              converged  = false;
    /**
     * max of (-min q)+, (-min gap)+, max |q gap|, each relative to the
     * problem's scale (max |q|, max |B w|) (doc/parameters.md).
     */
    double complementarity_violation = 0;
    /** Nodes in contact with a tensile pressure (q < 0). */
    unsigned int tensile_nodes = 0;
    /** Largest penetration -gap, relative to max |B w| (0 if none). */
    double max_penetration = 0;
    /**
     * LAPACK's estimate of 1/κ₁ of the coupled matrix K̄ + S of the last
     * solve (condition_estimate.h).
     */
    double coupled_rcond = 1;

    /**
     * One linear solve of an iterative contact solver
     * (iterative_contact_solver.h); empty for the direct ContactSolver.
     */
    struct LinearSolve
    {
      unsigned int contact_iteration = 0; ///< 1, 2, ... of the active set
      unsigned int contact_nodes     = 0; ///< size of the contact set
      unsigned int iterations        = 0; ///< conjugate gradient iterations
      /** Achieved |residual| / |settlement| on the contact set
       *  (recomputed, not the recursive estimate). */
      double relative_residual = 0;
    };
    /** One entry per contact iteration (iterative solvers only). */
    std::vector<LinearSolve> linear_solves;
  };

  /**
   * Whether the nodes flagged in @p in_contact can carry a plate: at least
   * three of them (with their mirror images), not on one line
   * (doc/formulation.md: fewer than three non-collinear supporting points make
   * the plate a mechanism).
   */
  bool
  contact_set_supports_plate(const FoundationSpace   &space,
                             const std::vector<bool> &in_contact);

  /**
   * Fill complementarity_violation, tensile_nodes and max_penetration of
   * @p state from its q and gap (which must be set), with @p plate_settlement
   * = B w giving the gap's scale and @p supported the nodes under the
   * foundation (the only ones whose gap is constrained).
   */
  void
  evaluate_contact_conditions(const Vector<double>    &plate_settlement,
                              const std::vector<bool> &supported,
                              ContactState            &state);

  /**
   * Finish a solve done in the contact basis (q holds the coefficients):
   * store them as pressure_coefficients, make q the nodal values, keep the
   * active set, and report contact where the pressure acts (the active set
   * and every node with q > 0: in the positive basis a mid-side node whose
   * own coefficient is zero still carries q_m = alpha (qt_c0 + qt_c1)).
   */
  void
  express_in_nodal_values(const FoundationOperator &foundation,
                          ContactState             &state);

  /**
   * The set update of the primal-dual active set method (doc/formulation.md,
   * "Tensionless contact"; deal.II step-41): C = {i : q_i + c g_i > 0}.
   * On C the gap is zero and off C the pressure is, so the test reads
   * q_i < 0 on C and g_i < 0 (penetration) off C; c only balances the units.
   * If a full step returns to a set seen before (a cycle), it falls back to
   * Murty's least-index rule, one status change per step, which terminates
   * for the SPD Galerkin problem. Every step keeps a set that carries the
   * plate (contact_set_supports_plate()): a full step that would leave a
   * mechanism takes every entry, then the exits in order while the rest
   * still carries the plate; a single pivot is the least index whose change
   * keeps the set carrying. Shared by the direct and the iterative contact
   * solvers so that both walk the same sequence of sets.
   */
  class ActiveSetUpdate
  {
  public:
    /**
     * Start from the @p supported nodes, restricted to @p initial_contact
     * (e.g. the previous cycle's set) if that has the right size and can
     * carry the plate.
     */
    ActiveSetUpdate(const FoundationSpace   &space,
                    const std::vector<bool> &supported,
                    const std::vector<bool> &initial_contact);

    /** The current contact set. */
    const std::vector<bool> &
    contact_set() const
    {
      return active;
    }

    /**
     * One step after a solve on the current set with solution (@p q,
     * @p gap): count the violated conditions (signs below @p q_tolerance
     * and @p g_tolerance are rounding), log iteration @p iteration at
     * @p verbosity > 0, and return true if none is violated (converged).
     * Otherwise move to the next set: the full step, or one status change
     * once a cycle has switched on single pivots, kept to a set that
     * carries the plate (see the class documentation). Throws ExcMessage
     * if no change keeps the plate carried (a load at the edge of a
     * weightless plate).
     */
    bool
    step(const Vector<double> &q,
         const Vector<double> &gap,
         const double          q_tolerance,
         const double          g_tolerance,
         const unsigned int    iteration,
         const unsigned int    verbosity,
         std::ostream         &log);

  private:
    /** Size of the current contact set. */
    unsigned int
    n_contact_nodes() const;

    /**
     * Count the violated conditions of (@p q, @p gap) on the current set
     * and prepare the full step. Returns the number of changes.
     */
    unsigned int
    find_violations(const Vector<double> &q,
                    const Vector<double> &gap,
                    const double          q_tolerance,
                    const double          g_tolerance);

    /**
     * Record the current set; if the full step find_violations() prepared
     * returns to a set seen before (a cycle), switch to single pivots and
     * return true.
     */
    bool
    detect_cycle();

    /** Move to the next set (see step()). */
    void
    advance();

    const FoundationSpace      &space;
    std::vector<bool>           supported;
    std::vector<bool>           active;
    std::vector<bool>           next;
    std::vector<unsigned int>   changes; ///< violated entries, least first
    std::set<std::vector<bool>> visited;
    bool                        single_pivot_mode = false;
  };

  /**
   * Solves  K̄ w + M q = P̄  with the foundation's contact conditions. The
   * coupled matrix K̄ + S is dense and of the size of the foundation block;
   * it is factorised by LAPACK (Cholesky when S is symmetric, else LU).
   */
  class ContactSolver
  {
  public:
    ContactSolver(const Parameters::Contact &contact,
                  const bool                 tensionless,
                  const unsigned int         verbosity,
                  std::ostream              &log);

    /**
     * Solve for the plate condensed to @p plate_stiffness and @p plate_load
     * on @p foundation, which must have been built on @p space with every
     * cell in the foundation. @p initial_contact (may be empty) seeds the
     * contact set, e.g. transferred from the previous cycle.
     */
    ContactState
    solve(const LAPACKFullMatrix<double> &plate_stiffness,
          const Vector<double>           &plate_load,
          FoundationOperator             &foundation,
          const FoundationSpace          &space,
          const std::vector<bool>        &initial_contact) const;

  private:
    /** solve() in the contact basis: q holds the coefficients. */
    ContactState
    solve_in_contact_basis(const LAPACKFullMatrix<double> &plate_stiffness,
                           const Vector<double>           &plate_load,
                           FoundationOperator             &foundation,
                           const FoundationSpace          &space,
                           const std::vector<bool> &initial_contact) const;

    /** One coupled solve on the foundation's current contact set. */
    void
    solve_coupled(const LAPACKFullMatrix<double> &plate_stiffness,
                  const Vector<double>           &plate_load,
                  const FoundationOperator       &foundation,
                  const FoundationSpace          &space,
                  ContactState                   &state) const;

    /**
     * Restore vertical force and moment equilibrium within the rigid-body
     * kernel of the free plate (see the implementation for why).
     */
    void
    correct_rigid_body_equilibrium(
      const LAPACKFullMatrix<double> &plate_stiffness,
      const Vector<double>           &plate_load,
      const FoundationOperator       &foundation,
      const FoundationSpace          &space,
      ContactState                   &state) const;

    /** Fill gap and complementarity_violation of @p state. */
    void
    evaluate_conditions(const FoundationOperator &foundation,
                        ContactState             &state) const;

    const Parameters::Contact contact;
    const bool                tensionless;
    const unsigned int        verbosity;
    std::ostream             &log;
  };
} // namespace PlateOnHalfspace

#endif
