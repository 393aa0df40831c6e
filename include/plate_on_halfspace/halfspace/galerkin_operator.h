/**
 * The symmetric Galerkin half-space operator (doc/formulation.md, "Default
 * variant"):  A_ij = alpha ∫∫ φ_i(x) φ_j(y) / |x - y| dy dx,  stored dense.
 */
#ifndef plate_on_halfspace_halfspace_galerkin_operator_h
#define plate_on_halfspace_halfspace_galerkin_operator_h

#include <plate_on_halfspace/halfspace/interface.h>

namespace PlateOnHalfspace
{
  /**
   * Dense Galerkin Boussinesq operator. Far cell pairs use tensor Gauss rules
   * whose order grows as the pair gets closer; coincident and touching pairs
   * integrate the inner integral with deal.II's QSplit(QDuffy) rule split at
   * the (projected) outer point, which removes the 1/r singularity, so
   * general straight-sided quadrilaterals work (disks, Gmsh meshes).
   * F = A (SPD), B = M (T^T A T and T^T M in the positive pressure basis).
   */
  class BoussinesqGalerkinOperator : public FoundationOperator
  {
  public:
    /**
     * @param soil the continuum whose kernel A integrates; its singular
     *   order is the Gauss points per direction for the outer rule and the
     *   Duffy rule of coincident and touching pairs.
     * @param positive_pressure_basis state the contact conditions in the
     *   positive basis of foundation_space.h (the program always does;
     *   false keeps the plain A, e.g. to compare with another assembly
     *   of A).
     */
    explicit BoussinesqGalerkinOperator(
      std::shared_ptr<const ElasticSoil> soil,
      const bool                         positive_pressure_basis = true);

    /** On the homogeneous half-space alpha = (1 - nu0^2)/(pi E0). */
    BoussinesqGalerkinOperator(const double       alpha,
                               const unsigned int singular_order,
                               const bool positive_pressure_basis = true);

    void
    build(const FoundationSpace   &space,
          const std::vector<bool> &cell_in_foundation) override;
    void
    apply(const Vector<double> &q, Vector<double> &s) const override;
    void
    plate_settlement(const Vector<double> &w, Vector<double> &b) const override;
    /** Copies from the dense flexibility of the foundation cells. */
    void
    copy_block(const std::vector<unsigned int> &nodes,
               LAPACKFullMatrix<double>        &block) const override;
    bool
    is_symmetric() const override
    {
      return true;
    }
    std::string
    storage_name() const override
    {
      return "dense";
    }
    /** The product is the BLAS dgemv over the whole matrix. */
    bool
    product_uses_blas_threads() const override
    {
      return true;
    }
    std::size_t
    memory_consumption() const override;

    /**
     * The flexibility on all nodes in the contact basis: the assembled A,
     * T^T A T in the positive pressure basis (foundation_operator.h); what
     * apply() multiplies by.
     */
    const LAPACKFullMatrix<double> &
    flexibility_matrix() const
    {
      return flexibility;
    }

  private:
    const std::shared_ptr<const ElasticSoil> elastic;
    const bool                               positive_pressure_basis;
    /** Settlement of the whole plate from pressures on the foundation cells. */
    LAPACKFullMatrix<double> flexibility;
    /** A over foundation cells only; used when some cells are excluded. */
    LAPACKFullMatrix<double> system_flexibility;
    /** M over all cells (the plate's weak settlement when cells are out). */
    SparsityPattern      full_mass_sparsity;
    SparseMatrix<double> full_mass;
    /** T^T of full_mass (foundation_space.h, positive pressure basis). */
    SparsityPattern      full_tested_sparsity;
    SparseMatrix<double> full_tested_mass;
    bool                 partial_foundation = false;
  };
} // namespace PlateOnHalfspace

#endif
