/**
 * The Galerkin half-space operator (doc/formulation.md, "Default variant")
 * with the flexibility A stored as a hierarchical matrix
 * (hierarchical_flexibility.h, hmat-oss; doc/formulation.md, "Hierarchical
 * storage") instead of a dense block: Foundation operator/Storage =
 * hierarchical. Products cost about n log n instead of n^2, and memory
 * grows about like n^1.3.
 *
 * The contact conditions are stated in the positive pressure basis like the
 * dense operator's (foundation_space.h): F = T^T A T, applied as T^T (A (T
 * q)). Its approximate inverse is the H-Cholesky factor of A with the
 * explicit inverse of T (a mid-side row of T holds 1 - 2 alpha and alpha
 * for its two ends, a vertex row is the identity row).
 *
 * On several processes (doc/parallel.md, "The half-space") each rank holds
 * the rows of A of the nodes it owns (FoundationSpace::owned_nodes): the
 * block on its own nodes, symmetric, and the block against all other
 * nodes, each compressed by hmat-oss on its own. A product computes each
 * rank's rows from the whole input and sums the rows over the ranks; the
 * approximate inverse is block-Jacobi, the H-Cholesky factor of each
 * rank's diagonal block. One process holds the whole A as before.
 *
 * copy_block() is the interface's (products with unit vectors): a contact
 * solver that needs dense blocks should use the dense storage, and the
 * scene checks (SceneParameters) keep the direct solver off this storage.
 * The paper's element exclusion (a partial foundation) is not supported.
 */
#ifndef plate_on_halfspace_halfspace_hierarchical_operator_h
#define plate_on_halfspace_halfspace_hierarchical_operator_h

#include <plate_on_halfspace/halfspace/hierarchical_flexibility.h>
#include <plate_on_halfspace/halfspace/interface.h>

#include <memory>
#include <vector>

namespace PlateOnHalfspace
{
  /** See the file documentation. */
  class HierarchicalGalerkinOperator : public FoundationOperator
  {
  public:
    /**
     * @param soil the continuum whose kernel A integrates (with its
     *   singular order).
     * @param tolerance Foundation operator/Tolerance: the relative accuracy
     *   of the compressed blocks (the H-Cholesky factor is coarser:
     *   HierarchicalFlexibility::Settings::factor_tolerance).
     */
    HierarchicalGalerkinOperator(std::shared_ptr<const ElasticSoil> soil,
                                 const double                       tolerance);

    void
    build(const FoundationSpace   &space,
          const std::vector<bool> &cell_in_foundation) override;
    void
    apply(const Vector<double> &q, Vector<double> &s) const override;
    /**
     * The diagonal of F = T^T A T from the diagonal of the H-matrix:
     * sum_j T_ji^2 A_jj, without the cross terms of a mid-side and its
     * vertex: 1 to 2.7 times the exact diagonal on example 2 (the springs
     * of the contact preconditioner need the local flexibility to a
     * factor of a few, not every digit of it).
     */
    Vector<double>
    flexibility_diagonal() const override;
    /** The H-Cholesky factor of A (computed here, kept in the operator). */
    std::unique_ptr<ApproximateInverse>
    make_approximate_inverse() override;
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
    /** Foundation operator/Tolerance. */
    double
    relative_accuracy() const override
    {
      return tolerance;
    }

    std::size_t
    memory_consumption() const override;

    /** (T^T A T)^{-1} s = T^{-1} A^{-1} T^{-T} s by the H-Cholesky factor
     *  (make_approximate_inverse() must have been called). */
    void
    solve(Vector<double> &q, const Vector<double> &s) const;

    /** The compressed A (for tests and the benchmark). */
    const HierarchicalFlexibility &
    hierarchical_matrix() const
    {
      return flexibility;
    }

  private:
    const std::shared_ptr<const ElasticSoil> elastic;
    const double                             tolerance;
    /** The whole A on one process, else this rank's diagonal block. */
    HierarchicalFlexibility flexibility;
    /**
     * This rank's rows against each other rank's nodes, one block per
     * rank (several processes only): a METIS part is compact, the union of
     * several is not, and ACA+ samples a compact cluster reliably.
     */
    std::vector<std::unique_ptr<HierarchicalFlexibility>> off_diagonal;
    /** The ranks the rows are split over (MPI_COMM_SELF: not split). */
    MPI_Comm communicator = MPI_COMM_SELF;

    /** Whether the rows are split over several processes. */
    bool
    rows_are_split() const;
  };
} // namespace PlateOnHalfspace

#endif
