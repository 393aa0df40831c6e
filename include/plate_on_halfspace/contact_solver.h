/**
 * Contact between the condensed plate and the half-space (formulation.md,
 * "Tensionless contact"): bonded contact (one coupled solve) and the
 * algorithms for tensionless contact, the paper's element exclusion and the
 * primal-dual active set method (deal.II step-41 is the model).
 */
#ifndef plate_on_halfspace_contact_solver_h
#define plate_on_halfspace_contact_solver_h

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/foundation_operator.h>
#include <plate_on_halfspace/parameters.h>

#include <ostream>
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
     * problem's scale (max |q|, max |B w|) (interfaces.md).
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
