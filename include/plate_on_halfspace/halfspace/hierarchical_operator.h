/**
 * The Galerkin half-space operator (doc/formulation.md, "Default variant") with
 * the flexibility A stored as a hierarchical matrix (hierarchical_flexibility
 * .h, hmat-oss) instead of a dense block: Foundation operator/Storage =
 * hierarchical. Products and the preconditioner of the contact solver cost
 * about n log n instead of n^2 and n^3, and memory grows about like n^1.3.
 *
 * The contact conditions are stated in the positive pressure basis like the
 * dense operator's (foundation_space.h): F = T^T A T, applied as T^T (A (T
 * q)); the preconditioner inverts it with the H-Cholesky factor of A and
 * the explicit inverse of T (a mid-side row of T holds 1 - 2 alpha and
 * alpha for its two ends, a vertex row is the identity row).
 *
 * It serves the iterative contact solver only (Contact/Solver = iterative,
 * iterative_contact_solver.h): the dense solver's F_CC factorisation and
 * foundation stiffness S would densify it again, so solve(), add_stiffness()
 * and set_contact_nodes() with a partial set refuse with a message. The
 * paper's element exclusion (a partial foundation) is not supported either.
 */
#ifndef plate_on_halfspace_halfspace_hierarchical_operator_h
#define plate_on_halfspace_halfspace_hierarchical_operator_h

#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/halfspace/hierarchical_flexibility.h>
#include <plate_on_halfspace/contact/iterative_solver.h>

namespace PlateOnHalfspace
{
  /** See the file documentation. */
  class HierarchicalGalerkinOperator : public FoundationOperator,
                                       public PreconditionedFlexibility
  {
  public:
    /**
     * @param alpha (1 - nu0^2)/(pi E0).
     * @param singular_order Gauss points of the singular cell pairs.
     * @param tolerance Foundation operator/Tolerance: the relative accuracy
     *   of the compressed blocks and of the H-Cholesky factor.
     */
    HierarchicalGalerkinOperator(const double       alpha,
                                 const unsigned int singular_order,
                                 const double       tolerance);

    void
    build(const FoundationSpace   &space,
          const std::vector<bool> &cell_in_foundation) override;
    void
    set_contact_nodes(const std::vector<bool> &in_contact) override;
    void
    apply(const Vector<double> &q, Vector<double> &s) const override;
    void
    plate_settlement(const Vector<double> &w, Vector<double> &b) const override;
    void
    solve(const Vector<double> &w, Vector<double> &q) const override;
    void
    add_stiffness(LAPACKFullMatrix<double> &matrix) const override;
    bool
    is_symmetric() const override
    {
      return true;
    }
    std::string
    storage_name() const override
    {
      return "hierarchical";
    }
    std::size_t
    memory_consumption() const override;

    unsigned int
    size() const override;
    void
    vmult(Vector<double> &s, const Vector<double> &q) const override;
    void
    precondition(Vector<double> &q, const Vector<double> &s) const override;

    /** The compressed A (for tests and the benchmark). */
    const HierarchicalFlexibility &
    hierarchical_matrix() const
    {
      return flexibility;
    }

  private:
    /** y = T^{-1} x (nodal values to coefficients). */
    void
    coefficients_from_values(const Vector<double> &x, Vector<double> &y) const;

    /** y = T^{-T} x. */
    void
    apply_inverse_transpose_transform(const Vector<double> &x,
                                      Vector<double>       &y) const;

    const double            alpha;
    const unsigned int      singular_order;
    HierarchicalFlexibility flexibility;
  };
} // namespace PlateOnHalfspace

#endif
