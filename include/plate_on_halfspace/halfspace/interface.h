/**
 * The interface behind which the half-space sits (doc/formulation.md,
 * "Half-space"): build it for a mesh, apply it to pressures, and solve it for
 * the pressures that produce a given plate deflection on the set of nodes in
 * contact. The plate, the contact solver and the output only talk to this
 * interface, so that a compressed (hierarchical) or distributed operator can
 * replace the dense ones without touching them.
 *
 * Both variants share the same algebraic form. With F the flexibility
 * (galerkin: the symmetric A, weak settlements; collocation: the paper's
 * nodal G) and B the matching plate operator (galerkin: M, collocation: I),
 *   settlement of the soil surface       s = F q,
 *   the same for the plate               b = B w,
 *   gap (soil surface minus plate)       g = s - b,
 *   pressures on the contact set C       q_C = F_CC^{-1} b_C,  q = 0 off C,
 *   nodal forces on the plate            Q = M q   (the paper's E q),
 *   foundation stiffness                 S = M_{:,C} F_CC^{-1} B_{C,:}.
 * With serendipity elements the Galerkin variant states the contact
 * conditions in the positive pressure basis of foundation_space.h: q are
 * its coefficients, F = T^T A T, B = T^T M, the forces M T q, and
 * nodal_pressure() gives the nodal values T q.
 * Units: q force/length^2, w and s length (galerkin s: length^3).
 */
#ifndef plate_on_halfspace_halfspace_interface_h
#define plate_on_halfspace_halfspace_interface_h

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <memory>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** Abstract half-space operator (see the file documentation). */
  class FoundationOperator
  {
  public:
    virtual ~FoundationOperator() = default;

    /**
     * Build the operator on @p space. @p cell_in_foundation (one flag per
     * cell of the space; empty = all) lists the cells whose area carries
     * pressure: the paper's element exclusion removes cells here. All nodes
     * start in contact.
     */
    virtual void
    build(const FoundationSpace   &space,
          const std::vector<bool> &cell_in_foundation) = 0;

    /**
     * Restrict to the nodes in contact (one flag per node) and factorise
     * F_CC. Nodes that no foundation cell touches are never in contact.
     * Throws if F_CC cannot be factorised.
     */
    virtual void
    set_contact_nodes(const std::vector<bool> &in_contact) = 0;

    /** s = F q (settlement of the soil surface, in the operator's sense). */
    virtual void
    apply(const Vector<double> &q, Vector<double> &s) const = 0;

    /** b = B w (the plate deflection, in the same sense as apply()). */
    virtual void
    plate_settlement(const Vector<double> &w, Vector<double> &b) const = 0;

    /** q with q_C = F_CC^{-1} (B w)_C and q = 0 off the contact set. */
    virtual void
    solve(const Vector<double> &w, Vector<double> &q) const = 0;

    /**
     * Add the foundation stiffness S (see file doc) to the dense matrix
     * @p matrix of size n_nodes x n_nodes.
     */
    virtual void
    add_stiffness(LAPACKFullMatrix<double> &matrix) const = 0;

    /** Whether S is symmetric (then the coupled matrix is SPD). */
    virtual bool
    is_symmetric() const = 0;

    /** Nodal forces Q = M q (M T q in the positive basis) on the plate. */
    void
    nodal_forces(const Vector<double> &q, Vector<double> &forces) const;

    /**
     * Nodal pressures (the values at the foundation nodes) of the pressure
     * with coefficients @p q: T q in the positive basis, else q itself.
     */
    void
    nodal_pressure(const Vector<double> &q, Vector<double> &values) const;

    /** Gap g = F q - B w (>= 0 where the plate is above the soil). */
    void
    gap(const Vector<double> &w,
        const Vector<double> &q,
        Vector<double>       &g) const;

    /** Contact flags of the nodes. */
    const std::vector<bool> &
    contact_nodes() const
    {
      return in_contact;
    }

    /** Nodes that some foundation cell touches. */
    const std::vector<bool> &
    supported_nodes() const
    {
      return node_supported;
    }

    /**
     * The mass matrix M (the paper's E) of the nodal values; the contact
     * conditions use test_coupling() and force_coupling().
     */
    const SparseMatrix<double> &
    mass_matrix() const
    {
      return mass;
    }

    /**
     * B of the Galerkin variant over the foundation cells: T^T M (M without
     * the positive basis). It tests the plate's deflection with the
     * pressure basis: plate_settlement() when every cell is in the
     * foundation.
     */
    const SparseMatrix<double> &
    test_coupling() const
    {
      return positive_basis ? tested_mass : mass;
    }

    /**
     * The forces' matrix: M T (M without the positive basis), the nodal
     * forces M T q of pressure coefficients q (nodal_forces()); the
     * transpose of test_coupling().
     */
    const SparseMatrix<double> &
    force_coupling() const
    {
      return positive_basis ? force_mass : mass;
    }

    /**
     * LAPACK's estimate of 1/κ₁ of the flexibility block F_CC of the
     * current contact set (condition_estimate.h).
     */
    double
    contact_block_reciprocal_condition_number() const
    {
      return contact_block_rcond;
    }

    /**
     * Wall times (seconds) of the parts of build() that are not
     * integration: compressing the flexibility (hierarchical storage) and
     * factorising it (the H-Cholesky factor of A, or the dense F_CC of all
     * nodes in contact; for the dense operators the latest factorisation,
     * so read it right after build(), before set_contact_nodes()). The
     * rest of build() integrates.
     */
    struct BuildTimes
    {
      double compression   = 0;
      double factorization = 0;
    };

    const BuildTimes &
    build_times() const
    {
      return times;
    }

    /** "dense" or the name of a compressed storage. */
    virtual std::string
    storage_name() const = 0;

    /** Bytes held by the operator's matrices and factorisations. */
    virtual std::size_t
    memory_consumption() const = 0;

  protected:
    /** Assemble M over the foundation cells and mark supported nodes. */
    void
    build_mass_matrix(const FoundationSpace   &space,
                      const std::vector<bool> &cell_in_foundation);

    /**
     * State the pressure in the positive basis of @p space where it has
     * one (foundation_space.h): sets T and the couplings T^T M and M T.
     * Call after build_mass_matrix().
     */
    void
    use_positive_pressure_basis(const FoundationSpace &space);

    /** F <- T^T F T in place (nothing without the positive basis). */
    void
    transform_flexibility(LAPACKFullMatrix<double> &flexibility) const;

    /** @p tested = T^T @p matrix (a copy without the positive basis). */
    void
    transform_tests(const SparseMatrix<double> &matrix,
                    SparsityPattern            &sparsity,
                    SparseMatrix<double>       &tested) const;

    /**
     * Store the contact set (restricted to supported nodes) and factorise
     * F_CC of the dense @p flexibility: Cholesky if @p symmetric, else LU.
     * Throws ExcMessage(@p failure) if the factorisation fails.
     */
    void
    factorise_contact_block(const std::vector<bool>        &requested,
                            const LAPACKFullMatrix<double> &flexibility,
                            const bool                      symmetric,
                            const std::string              &failure);

    /** q_C = F_CC^{-1} b_C and q = 0 off the contact set. */
    void
    solve_contact_block(const Vector<double> &b, Vector<double> &q) const;

    /**
     * matrix += M_{:,C} F_CC^{-1} @p rows, where @p rows (|C| x n, the
     * contact rows of B) is overwritten.
     */
    void
    add_mass_times_contact_inverse(LAPACKFullMatrix<double> &rows,
                                   LAPACKFullMatrix<double> &matrix) const;

    SparsityPattern           mass_sparsity;
    SparseMatrix<double>      mass;
    std::vector<bool>         node_supported;
    std::vector<bool>         in_contact;
    std::vector<unsigned int> contact_index;  ///< the nodes of C
    LAPACKFullMatrix<double>  contact_factor; ///< factor of F_CC
    double                    contact_block_rcond = 1.;
    BuildTimes                times;

    bool                 positive_basis = false;
    SparsityPattern      transform_sparsity, tested_sparsity, force_sparsity;
    SparseMatrix<double> transform;   ///< T: nodal values from coefficients
    SparseMatrix<double> tested_mass; ///< T^T M
    SparseMatrix<double> force_mass;  ///< M T
  };

  /**
   * Make the operator the scene asks for (Discretization/Flexibility and
   * Foundation operator/Tolerance) with @p storage, "dense" or
   * "hierarchical" (SceneParameters::foundation_storage()).
   */
  std::unique_ptr<FoundationOperator>
  create_foundation_operator(const SceneParameters &parameters,
                             const std::string     &storage);
} // namespace PlateOnHalfspace

#endif
