/**
 * A contact solver that never forms a dense matrix of the size of the
 * foundation block (issue 6, part 2): bonded and tensionless (primal-dual
 * active set) contact of the Galerkin variant (doc/formulation.md, "Default
 * variant" and "Tensionless contact") from
 *  - the sparse plate stiffness K of MindlinPlate, factorised once per
 *    refinement cycle by CHOLMOD with the rigid-body motions pinned,
 *  - the sparse couplings of the foundation: M, or with serendipity
 *    elements the positive pressure basis q = T qt (foundation_operator.h)
 *    with B = T^T M testing deflections and M T giving forces
 *    (FoundationOperator::test_coupling(), force_coupling()),
 *  - products s = F q with the half-space flexibility on all nodes and an
 *    approximate inverse of F used as a preconditioner, both behind the
 *    small interface PreconditionedFlexibility (dense today, a
 *    hierarchical matrix later).
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
 * (ContactSolver needs a separate correction for that). Then
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
 * G = (B N R)_C. This is the discrete problem of ContactSolver, so both
 * give the same w, coefficients, nodal q = T qt and contact sets; solve()
 * finishes like ContactSolver::solve().
 *
 * Not covered here (they stay on the dense ContactSolver path): the paper's
 * collocation operator (F unsymmetric; the projected CG needs an SPD H) and
 * the paper's element exclusion (it rebuilds the operator on fewer cells).
 */
#ifndef plate_on_halfspace_contact_iterative_solver_h
#define plate_on_halfspace_contact_iterative_solver_h

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/direct_solver.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <ostream>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * The half-space flexibility F on all foundation nodes in the contact
   * basis (the Galerkin A of doc/formulation.md, T^T A T in the positive
   * pressure basis: exactly what FoundationOperator::apply() multiplies by;
   * SPD) with an approximate inverse, all the IterativeContactSolver needs of
   * the half-space. A dense operator and a hierarchical matrix (H-Cholesky of
   * the full F) both provide it. The application (Contact/Solver =
   * iterative) uses a FoundationOperator that also derives from this class
   * as it is, and wraps any other in DenseGalerkinFlexibility.
   */
  class PreconditionedFlexibility
  {
  public:
    virtual ~PreconditionedFlexibility() = default;

    /** Number of foundation nodes. */
    virtual unsigned int
    size() const = 0;

    /** s = F q over all nodes (q zero off the contact set is allowed). */
    virtual void
    vmult(Vector<double> &s, const Vector<double> &q) const = 0;

    /**
     * q = F̃^{-1} s with F̃^{-1} symmetric positive definite and close to
     * F^{-1} (the solver restricts it to the contact set). Must not change
     * between calls of one solve.
     */
    virtual void
    precondition(Vector<double> &q, const Vector<double> &s) const = 0;
  };

  /**
   * The dense Galerkin operator as a PreconditionedFlexibility: products by
   * FoundationOperator::apply, the preconditioner by a LAPACK Cholesky
   * factor of the full flexibility_matrix() (A, or T^T A T in the positive
   * pressure basis: the matrix apply() uses) (n^3/3 once per cycle, n^2 memory:
   * a stand-in until the hierarchical matrix provides the same with near-linear
   * cost).
   */
  class DenseGalerkinFlexibility : public PreconditionedFlexibility
  {
  public:
    /**
     * @p foundation must be a BoussinesqGalerkinOperator built with every
     * cell in the foundation (throws otherwise). It is referenced, not
     * copied.
     */
    explicit DenseGalerkinFlexibility(const FoundationOperator &foundation);

    unsigned int
    size() const override;
    void
    vmult(Vector<double> &s, const Vector<double> &q) const override;
    void
    precondition(Vector<double> &q, const Vector<double> &s) const override;

  private:
    const FoundationOperator &foundation;
    LAPACKFullMatrix<double>  cholesky_factor;
  };

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
     * before the last); the last set is always solved to tolerance.
     */
    double changing_set_tolerance = 1e-4;
  };

  /**
   * Bonded and tensionless contact (active set) of a Galerkin scene without
   * dense matrices (see the file documentation). Returns the same
   * ContactState as ContactSolver, plus one ContactState::LinearSolve per
   * contact iteration.
   */
  class IterativeContactSolver
  {
  public:
    /**
     * @p contact: Method must be active set (element exclusion stays on the
     * dense path); Max iterations bounds the active-set steps.
     */
    IterativeContactSolver(const Parameters::Contact      &contact,
                           const bool                      tensionless,
                           const ConjugateGradientControl &control,
                           const unsigned int              verbosity,
                           std::ostream                   &log);

    /**
     * Solve for @p plate (set up, loads assembled) on @p foundation (built
     * on the plate's foundation space with every cell in the foundation;
     * only its couplings test_coupling() = B and force_coupling() = B^T,
     * supported nodes, nodal_pressure() and plate settlement B w are used,
     * never its dense blocks) with the half-space @p flexibility.
     * @p initial_contact (may be empty) seeds the contact set. If
     * @p plate_solution is given, it receives the plate's full solution
     * vector (w, beta_x, beta_y at every DoF, constraints distributed), as
     * MindlinPlate::expand() would give it from the returned w.
     *
     * Throws ExcMessage if the contact set cannot carry the plate, or if
     * the conjugate gradients do not reach the tolerance within
     * max_iterations (never a silently inaccurate answer).
     */
    ContactState
    solve(const MindlinPlate              &plate,
          const FoundationOperator        &foundation,
          const PreconditionedFlexibility &flexibility,
          const std::vector<bool>         &initial_contact,
          Vector<double>                  *plate_solution = nullptr) const;

  private:
    /** solve() in the contact basis: q holds the coefficients. */
    ContactState
    solve_in_contact_basis(const MindlinPlate              &plate,
                           const FoundationOperator        &foundation,
                           const PreconditionedFlexibility &flexibility,
                           const std::vector<bool>         &initial_contact,
                           Vector<double> *plate_solution) const;

    const Parameters::Contact      contact;
    const bool                     tensionless;
    const ConjugateGradientControl control;
    const unsigned int             verbosity;
    std::ostream                  &log;
  };
} // namespace PlateOnHalfspace

#endif
