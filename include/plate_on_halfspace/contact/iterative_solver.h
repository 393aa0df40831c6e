/**
 * The iterative contact solver: bonded and tensionless (primal-dual active
 * set) contact of the symmetric Galerkin variant (doc/formulation.md,
 * "Default variant" and "Tensionless contact") without a dense matrix of
 * the size of the foundation block, from
 *  - the sparse plate stiffness K of MindlinPlate, factorised once per
 *    solve by CHOLMOD with the rigid-body motions pinned
 *    (plate/generalized_inverse.h),
 *  - the couplings of the foundation operator: B = T^T M testing
 *    deflections and M T giving forces (FoundationOperator::
 *    test_coupling(), force_coupling()),
 *  - products s = F q of the half-space operator on all nodes, and its
 *    approximate inverse (FoundationOperator::make_approximate_inverse())
 *    as the preconditioner; any storage provides both.
 *
 * Formulation (FETI-style, on the pressures of the contact set C). With u
 * the plate's unconstrained DoFs, N u its deflections w at the foundation
 * nodes, P the load and R the rigid-body motions in the kernel of K, the
 * coupled problem of doc/formulation.md (K w + M q = P, gap A q - M w = 0 on C,
 * q = 0 off C) reads
 *   K u = P - N^T M q,                    (plate)
 *   (F q)_C = (M N u)_C.                  (no gap on C)
 * The plate equation has a solution iff R^T (P - N^T M q) = 0 (vertical
 * force and moment equilibrium), and then u = K^+ (P - N^T M q) + R alpha
 * with K^+ a generalised inverse (CHOLMOD of K with one deflection per
 * rigid motion pinned). Eliminating u gives, with G = (M N R)_C,
 *   H q_C - G alpha = d,   G^T q_C = R^T P,
 *   H = F_CC + (M N K^+ N^T M)_CC,   d = (M N K^+ P)_C,
 * H symmetric positive definite on ker G^T (F is SPD, K^+ positive
 * semidefinite there). Conjugate gradients on the affine space
 * {G^T q = R^T P} with the projector Pi = I - G (G^T G)^{-1} G^T solve it;
 * the preconditioner is (F^{-1})_CC, the approximate inverse of the FULL F
 * restricted to C, so it is built once per cycle and serves every contact
 * set (no factorisation of F_CC per active-set iteration). Equilibrium
 * holds exactly (to rounding) at every iterate, however stiff the plate
 * (the direct solver needs a separate correction for that). Then
 *   alpha = (G^T G)^{-1} G^T (H q_C - d),  u = K^+ (P - N^T M q) + R alpha.
 *
 * H adds the flexibilities of plate and soil in series; (F^{-1})_CC
 * inverts the soil's. The preconditioned spectrum is 1 + (k l)^{-3} in
 * terms of the wave number k of a pressure mode and the characteristic
 * length l^3 = 2 D (1 - nu0^2)/E0: a plate stiffer than the soil over the
 * plate's size (rafts, slabs with L of a few l) needs few iterations
 * whatever the mesh, a very flexible one (L >> l) needs more as the mesh is
 * refined.
 *
 * In the positive pressure basis the unknowns are the coefficients qt and
 * the same reads with F = T^T A T (what FoundationOperator::apply()
 * multiplies by), M q -> M T qt in the plate equation and M -> B = T^T M
 * in the gap: H = F_CC + (B N K^+ N^T B^T)_CC, d = (B N K^+ P)_C,
 * G = (B N R)_C. This is the discrete problem of DirectContactSolver, so
 * both give the same w, coefficients, nodal q = T qt and contact sets.
 *
 * Not covered here (they stay on the direct solver): the paper's
 * collocation operator (F unsymmetric; the projected CG needs an SPD H) and
 * the paper's element exclusion (it rebuilds the operator on fewer cells).
 */
#ifndef plate_on_halfspace_contact_iterative_solver_h
#define plate_on_halfspace_contact_iterative_solver_h

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/contact_iteration.h>

#include <memory>
#include <ostream>
#include <stdexcept>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  class PlateGeneralizedInverse;
  class PressurePreconditioner;

  /** Settings of the conjugate gradient iteration of each contact set. */
  struct ConjugateGradientControl
  {
    /** Iterations per contact set before the solve fails with an error. */
    unsigned int max_iterations = 1000;
    /**
     * Target of |Pi (d - H q)| / |(F q)_C|: the residual is minus the
     * (projected) gap on the contact set, measured against the soil's
     * settlement there (the scale of the contact conditions).
     */
    double tolerance = 1e-10;
    /**
     * The same target while the active set is still changing (the solves
     * before the last); the last set is always solved to
     * last_solve_tolerance().
     */
    double changing_set_tolerance = 1e-4;
    /**
     * Start the active set from the constrained conjugate gradients'
     * estimate of the contact set (predict_contact_set()); false: from the
     * seed, one solve per set.
     */
    bool constrained_start = true;
    /** Contact/Preconditioner (pressure_preconditioner.h). */
    Parameters::Contact::Preconditioner preconditioner =
      Parameters::Contact::Preconditioner::automatic;
  };

  /**
   * The accuracy of the iterative solver's last solve on a contact set
   * with @p foundation: @p tolerance (ConjugateGradientControl::tolerance),
   * or a hundredth of the operator's relative_accuracy() where that is
   * larger. Residuals far below the product's own error change the
   * pressures by less than that error (doc/performance.md, "The last
   * solve's accuracy").
   */
  double
  last_solve_tolerance(const double              tolerance,
                       const FoundationOperator &foundation);

  /**
   * The conjugate gradients of a contact set did not reach their tolerance
   * or met a direction of non-positive curvature
   * (IterativeContactSolver::solve_on_set()); what() says why and what to
   * change. Contact/Solver = auto answers it by taking the direct solver
   * (doc/errors-and-limits.md, "Stiffness ratio").
   */
  class ConjugateGradientsFailed : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /** See the file documentation. */
  class IterativeContactSolver : public ContactIteration
  {
  public:
    /**
     * @p contact: Method must be active set on a tensionless foundation
     * (element exclusion stays on the direct solver; throws otherwise);
     * Max iterations bounds the active-set steps.
     */
    IterativeContactSolver(const Parameters::Contact      &contact,
                           const bool                      tensionless,
                           const ConjugateGradientControl &control,
                           const unsigned int              verbosity,
                           std::ostream                   &log);

    ~IterativeContactSolver() override;

    /**
     * K^+ of the plate that the next solve() is given, made beforehand
     * on the plate as it is set up then (its symbolic stage, beside the
     * foundation operator's build: doc/performance.md, "The plate's
     * ordering beside the operator's build"); that solve() completes it
     * instead of making its own.
     */
    void
    use_plate_inverse(std::unique_ptr<PlateGeneralizedInverse> analysed);

  protected:
    /** Throws ExcMessage unless the operator is symmetric. */
    void
    prepare(MindlinPlate       &plate,
            FoundationOperator &foundation,
            ContactState       &state) override;

    void
    prepare_load(const Vector<double> &load) override;

    /**
     * Projected conjugate gradients on the pressures of @p contact_set;
     * throws ConjugateGradientsFailed if they do not reach
     * @p tolerance within ConjugateGradientControl::max_iterations or meet
     * a direction of non-positive curvature (never a silently inaccurate
     * answer).
     */
    Vector<double>
    solve_on_set(const std::vector<bool> &contact_set,
                 const double             tolerance,
                 ContactState            &state) override;

    /**
     * Constrained conjugate gradients in the spirit of Polonsky and Keer
     * (doc/formulation.md, "Tensionless contact"): the projected
     * conjugate gradients of solve_on_set(), but the contact set changes
     * inside the one loop: a pressure that turns negative drops its node,
     * a node off the set whose gap closes joins it, and either restarts
     * the directions. Ends when a set is solved to the changing-set
     * tolerance and nothing more changes; leaves its pressures in
     * state.q. Starts from the seed's pressure where it has one (its
     * tension dropped, then equilibrated), else from the equilibrated
     * zero pressure.
     */
    std::vector<bool>
    predict_contact_set(const ContactSeed &seed, ContactState &state) override;

    double
    changing_set_tolerance() const override;

    double
    final_tolerance() const override;

    /** 1e-6, or final_tolerance() where that is coarser. */
    double
    adjoint_tolerance() const override;

  private:
    const ConjugateGradientControl           control;
    std::unique_ptr<PressurePreconditioner>  preconditioner;
    std::unique_ptr<PlateGeneralizedInverse> inverse;
    /** use_plate_inverse()'s, until prepare() takes it. */
    std::unique_ptr<PlateGeneralizedInverse> given_inverse;
    /** The plate's response K^+ P to the load P of the current solve,
     *  B N K^+ P, the columns B N R, and R^T P (see the file doc). */
    Vector<double>              plate_load_response;
    Vector<double>              tested_plate_load;
    std::vector<Vector<double>> tested_motions;
    Vector<double>              motion_loads;
    /** Conjugate directions of the solves on the last contact set, which
     *  the next solve on the same set recycles (doc/formulation.md,
     *  "Recycled directions"); cleared by prepare(). */
    struct RecordedDirections;
    std::unique_ptr<RecordedDirections> recorded;
  };
} // namespace PlateOnHalfspace

#endif
