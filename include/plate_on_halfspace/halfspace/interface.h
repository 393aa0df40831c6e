/**
 * The foundation family's interface (doc/architecture.md, "The foundation
 * family"; doc/formulation.md, "Half-space" and "Dense-liquid foundation"):
 * an operator built on the foundation space of the plate that applies the
 * soil's flexibility to pressures and couples it to the plate. Every model
 * (the elastic half-space, the dense liquid), every storage (dense,
 * hierarchical, fft, sparse) and every flexibility (Galerkin, collocation)
 * honours all of it; how a
 * contact solver factorises or preconditions the flexibility is the solver's
 * business, built from what this interface offers.
 *
 * The algebraic form shared by all variants. With F the flexibility
 * (Galerkin: the symmetric A, weak settlements; collocation: the paper's
 * nodal G) and B the matching test coupling (Galerkin: M, collocation: I),
 *   settlement of the soil surface       s = F q,
 *   the same for the plate               b = B w,
 *   gap (soil surface minus plate)       g = s - b,
 *   pressures on the contact set C       q_C = F_CC^{-1} b_C,  q = 0 off C,
 *   nodal forces on the plate            Q = M q   (the paper's E q).
 * With serendipity elements the Galerkin variant states the contact
 * conditions in the positive pressure basis (doc/formulation.md,
 * "Positive pressure basis"): q are its coefficients, F = T^T A T,
 * B = T^T M, the forces M T q, and nodal_pressure() gives the nodal values
 * T q.
 * Units: q force/length^2, w and s length (Galerkin s: length^3).
 */
#ifndef plate_on_halfspace_halfspace_interface_h
#define plate_on_halfspace_halfspace_interface_h

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/scene/parameters.h>
#include <plate_on_halfspace/soil/soil_model.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * An approximation of F^{-1} on all foundation nodes, symmetric positive
   * definite for a symmetric F: what an iterative contact solver
   * preconditions with. Each storage makes the one it can afford
   * (FoundationOperator::make_approximate_inverse()).
   */
  class ApproximateInverse
  {
  public:
    virtual ~ApproximateInverse() = default;

    /** q = F̃^{-1} s. Must not change between calls. */
    virtual void
    vmult(Vector<double> &q, const Vector<double> &s) const = 0;

    /** Bytes held by the approximation. */
    virtual std::size_t
    memory_consumption() const = 0;
  };

  /** Abstract half-space operator (see the file documentation). */
  class FoundationOperator
  {
  public:
    virtual ~FoundationOperator() = default;

    /**
     * Build the operator on @p space. @p cell_in_foundation (one flag per
     * cell of the space; empty = all) lists the cells whose area carries
     * pressure: the paper's element exclusion removes cells here.
     */
    virtual void
    build(const FoundationSpace   &space,
          const std::vector<bool> &cell_in_foundation) = 0;

    /** s = F q on all nodes (the settlement, tested over the plate). */
    virtual void
    apply(const Vector<double> &q, Vector<double> &s) const = 0;

    /**
     * b = B w on all nodes: the plate deflection in the sense of apply()
     * (tested over the whole plate, also under excluded cells).
     */
    virtual void
    plate_settlement(const Vector<double> &w, Vector<double> &b) const;

    /**
     * The block F_NN of the flexibility of the foundation cells on the
     * nodes @p nodes (in that order): what the contact conditions invert on
     * a contact set N. With every cell in the foundation these are entries
     * of apply()'s matrix. The default applies the operator to unit vectors
     * (any storage can do it; the dense ones copy).
     */
    virtual void
    copy_block(const std::vector<unsigned int> &nodes,
               LAPACKFullMatrix<double>        &block) const;

    /**
     * The diagonal F_ii of apply()'s F: the flexibility of each pressure
     * coefficient on its own, the soil's part of the contact
     * preconditioner that models the soil as independent springs
     * (contact/pressure_preconditioner.h). The default applies the
     * operator to unit vectors (n products); each storage that can gives
     * it directly.
     */
    virtual Vector<double>
    flexibility_diagonal() const;

    /**
     * An approximate inverse of apply()'s F on all nodes (built with every
     * cell in the foundation). The default is the Cholesky factor of the
     * dense F (n^2 memory, n^3/3 operations); a compressed storage gives
     * its own factorisation. The operator must outlive the result. Throws
     * ExcMessage naming the entry to change if F is not positive definite.
     */
    virtual std::unique_ptr<ApproximateInverse>
    make_approximate_inverse();

    /**
     * The settlement u(x) of the soil surface under the pressure with the
     * nodal values @p nodal_pressure at each of @p points of the computed
     * part, which a goal's error estimate needs between the nodes: the
     * soil model's own law (SoilModel::settlement_at_points()), or, for a
     * continuum soil where points × loaded cells exceed
     * compressed_settlement_threshold, the same integrals through a
     * compressed influence matrix at Foundation operator/Tolerance
     * (halfspace/compressed_settlement.h). A storage with a faster
     * evaluation of the same integrals overrides it.
     */
    virtual std::vector<double>
    settlement_at_points(const FoundationSpace       &space,
                         const Vector<double>        &nodal_pressure,
                         const std::vector<Point<2>> &points) const;

    /**
     * Points × loaded cells from which settlement_at_points() compresses:
     * about where the compressed evaluation becomes the faster
     * (doc/performance.md, "Goal error estimate").
     */
    static constexpr double compressed_settlement_threshold = 2e8;

    /** The cells of @p space on which @p nodal_pressure is not zero: the
     *  cost of a direct settlement_at_points() is points times these. */
    static unsigned int
    n_loaded_cells(const FoundationSpace &space,
                   const Vector<double>  &nodal_pressure);

    /** The accuracy of compressed evaluations (Foundation
     *  operator/Tolerance); create_foundation_operator() sets it. */
    void
    set_compression_tolerance(const double tolerance)
    {
      compression_tolerance = tolerance;
    }

    /** The soil model whose flexibility this operator stores. */
    const SoilModel &
    soil() const
    {
      return *soil_model;
    }

    /** Whether F is symmetric (then the coupled problem is SPD). */
    virtual bool
    is_symmetric() const = 0;

    /**
     * What build() chose that a user should see in the log, such as a
     * split or a grid (empty: nothing beyond the storage's name).
     */
    virtual std::string
    build_report() const
    {
      return "";
    }

    /** "dense", "sparse" (the dense liquid) or a compressed storage. */
    virtual std::string
    storage_name() const = 0;

    /**
     * Whether apply() is BLAS work that OpenBLAS's threads speed up (a
     * matrix-vector product over a whole dense matrix). The iterative
     * contact solver keeps the threads for such a product and applies
     * the soil's and the plate's halves in order; for any other it runs
     * OpenBLAS on one thread, whose triangular solves a second thread
     * slows down, and the halves side by side (doc/performance.md, "BLAS
     * threads in the contact solve").
     */
    virtual bool
    product_uses_blas_threads() const
    {
      return false;
    }

    /**
     * Relative accuracy of apply() against the exact Galerkin flexibility
     * of its soil: 0 where the product is exact to rounding, Foundation
     * operator/Tolerance for a compressed storage. The iterative contact
     * solver's last solve resolves the pressures to a hundredth of it, not
     * below (doc/performance.md, "The last solve's accuracy").
     */
    virtual double
    relative_accuracy() const
    {
      return 0;
    }

    /** Bytes held by the operator's matrices. */
    virtual std::size_t
    memory_consumption() const = 0;

    /** Number of foundation nodes. */
    unsigned int
    n_nodes() const
    {
      return node_supported.size();
    }

    /** Nodal forces Q = M q (M T q in the positive basis) on the plate. */
    void
    nodal_forces(const Vector<double> &q, Vector<double> &forces) const;

    /**
     * Nodal pressures (the values at the foundation nodes) of the pressure
     * with coefficients @p q: T q in the positive basis, else q itself.
     */
    void
    nodal_pressure(const Vector<double> &q, Vector<double> &values) const;

    /** The coefficients @p q of the pressure with the nodal values
     *  @p values: the inverse of nodal_pressure(). */
    void
    pressure_coefficients(const Vector<double> &values,
                          Vector<double>       &q) const;

    /** Gap g = F q - B w (>= 0 where the plate is above the soil). */
    void
    gap(const Vector<double> &w,
        const Vector<double> &q,
        Vector<double>       &g) const;

    /** Nodes that some foundation cell touches. */
    const std::vector<bool> &
    supported_nodes() const
    {
      return node_supported;
    }

    /** The mass matrix M (the paper's E) of the nodal values. */
    const SparseMatrix<double> &
    mass_matrix() const
    {
      return mass;
    }

    /**
     * B over the foundation cells, the test coupling of the contact
     * conditions: T^T M in the positive basis, M for the other Galerkin
     * variants, the identity for collocation.
     */
    const SparseMatrix<double> &
    test_coupling() const
    {
      return tests;
    }

    /**
     * Whether the gap is tested with the pressure basis (Galerkin: a node's
     * gap is an integral over its basis function's support) rather than
     * taken at the node (collocation).
     */
    bool
    gap_is_tested() const
    {
      return !identity_tests;
    }

    /**
     * The forces' matrix: M T (M without the positive basis), the nodal
     * forces M T q of pressure coefficients q (nodal_forces()).
     */
    const SparseMatrix<double> &
    force_coupling() const
    {
      return positive_basis ? force_mass : mass;
    }

    /**
     * Wall times (seconds) of the parts of build() that are not
     * integration: compressing the flexibility (compressed storage). The
     * rest of build() integrates.
     */
    struct BuildTimes
    {
      double compression = 0;
    };

    const BuildTimes &
    build_times() const
    {
      return times;
    }

  protected:
    /** Assemble M over the foundation cells and mark supported nodes. */
    void
    build_mass_matrix(const FoundationSpace   &space,
                      const std::vector<bool> &cell_in_foundation);

    /**
     * State the pressure in the positive basis of @p space where it has
     * one (foundation_space.h), or keep nodal values if
     * @p positive_pressure_basis is false: sets T and the couplings B and
     * M T. Call after build_mass_matrix().
     */
    void
    set_pressure_basis(const FoundationSpace &space,
                       const bool             positive_pressure_basis);

    /**
     * y = T^{-1} x (nodal values to coefficients of the positive basis):
     * a vertex row of T is the identity row, a mid-side row holds
     * 1 - 2 alpha and alpha for its two ends. Call only with the positive
     * basis.
     */
    void
    coefficients_from_values(const Vector<double> &x, Vector<double> &y) const;

    /**
     * @p s = T^T A T @p q for an A given on nodal values by
     * @p apply_to_values(values, settlement) (settlement sized already):
     * a storage of the plain A in the contact basis.
     */
    void
    apply_in_pressure_basis(
      const Vector<double> &q,
      Vector<double>       &s,
      const std::function<void(const Vector<double> &, Vector<double> &)>
        &apply_to_values) const;

    /** y = T^{-T} x (with the positive basis only). */
    void
    apply_inverse_transpose_transform(const Vector<double> &x,
                                      Vector<double>       &y) const;

    /** Make the test coupling B the identity (collocation). */
    void
    use_identity_test_coupling();

    /** F <- T^T F T in place (nothing without the positive basis). */
    void
    transform_flexibility(LAPACKFullMatrix<double> &flexibility) const;

    /** @p tested = T^T @p matrix (a copy without the positive basis). */
    void
    transform_tests(const SparseMatrix<double> &matrix,
                    SparsityPattern            &sparsity,
                    SparseMatrix<double>       &tested) const;

    /** @p block = @p matrix on the nodes @p nodes (copy_block of a dense
     *  storage). */
    static void
    copy_dense_block(const LAPACKFullMatrix<double>  &matrix,
                     const std::vector<unsigned int> &nodes,
                     LAPACKFullMatrix<double>        &block);

    /** Bytes of the members of this class. */
    std::size_t
    coupling_memory_consumption() const;

    /** Set by each variant's constructor. */
    std::shared_ptr<const SoilModel> soil_model;
    double                           compression_tolerance = 1e-6;

    SparsityPattern      mass_sparsity;
    SparseMatrix<double> mass;
    std::vector<bool>    node_supported;
    BuildTimes           times;

    bool                 positive_basis = false;
    SparsityPattern      transform_sparsity, tests_sparsity, force_sparsity;
    SparseMatrix<double> transform; ///< T: nodal values from coefficients
    SparseMatrix<double> tests;     ///< B
    bool                 identity_tests = false;
    SparseMatrix<double> force_mass; ///< M T
  };

  /**
   * Make the operator that stores @p soil with @p storage, dense,
   * hierarchical or sparse (SceneParameters::foundation_storage(), auto
   * resolved; sparse is the dense liquid's), as Discretization/Flexibility
   * and Foundation operator/Tolerance ask. For a continuum soil the space's
   * plate diameter @p max_distance bounds the kernel's range.
   */
  std::unique_ptr<FoundationOperator>
  create_foundation_operator(
    const SceneParameters                        &parameters,
    const std::shared_ptr<const SoilModel>       &soil,
    const Parameters::FoundationOperator::Storage storage);
} // namespace PlateOnHalfspace

#endif
