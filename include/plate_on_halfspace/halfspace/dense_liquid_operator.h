/**
 * The dense-liquid (Winkler) foundation (doc/formulation.md, "Dense-liquid
 * foundation"): the soil surface settles by s = q/k where the pressure q
 * acts, with no spreading to its neighbours. In the Galerkin sense of the
 * half-space operators the settlement tested with the pressure basis is
 *   F = T^T M T / k,   B = T^T M,
 * so the whole foundation is a scaled mass matrix: sparse, never densified.
 * Bonded on every node it reduces to the classical K + k M of the plate on
 * springs; tensionless, the contact conditions and the active set are those
 * of the half-space (doc/formulation.md, "Tensionless contact").
 */
#ifndef plate_on_halfspace_halfspace_dense_liquid_operator_h
#define plate_on_halfspace_halfspace_dense_liquid_operator_h

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/soil/dense_liquid.h>

#include <memory>

namespace PlateOnHalfspace
{
  /** See the file documentation. */
  class DenseLiquidOperator : public FoundationOperator
  {
  public:
    /**
     * @param soil the dense liquid, k > 0 [force/length^3].
     * @param positive_pressure_basis as for the half-space operators
     *   (galerkin_operator.h).
     */
    explicit DenseLiquidOperator(std::shared_ptr<const DenseLiquidSoil> soil,
                                 const bool positive_pressure_basis = true);
    ~DenseLiquidOperator() override;

    /** Throws ExcMessage unless every cell is in the foundation: the
     *  paper's element exclusion belongs to the half-space. */
    void
    build(const FoundationSpace   &space,
          const std::vector<bool> &cell_in_foundation) override;
    void
    apply(const Vector<double> &q, Vector<double> &s) const override;
    /** Copies from the sparse flexibility (a small block only). */
    void
    copy_block(const std::vector<unsigned int> &nodes,
               LAPACKFullMatrix<double>        &block) const override;
    /** The diagonal of the sparse flexibility. */
    Vector<double>
    flexibility_diagonal() const override;
    /** The sparse Cholesky factor of F (CHOLMOD): exact. */
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
      return "sparse";
    }
    std::size_t
    memory_consumption() const override;

    /** F = T^T M T / k on all nodes: what apply() multiplies by. */
    const SparseMatrix<double> &
    flexibility_matrix() const
    {
      return flexibility;
    }

  private:
    const double         subgrade_modulus;
    const bool           positive_pressure_basis;
    SparsityPattern      flexibility_sparsity;
    SparseMatrix<double> flexibility;
  };
} // namespace PlateOnHalfspace

#endif
