/**
 * The paper's collocation half-space operator (doc/formulation.md, "Paper's
 * variant"; (P4)-(P17)): each cell split into 3x3 sub-rectangles around its
 * Gauss points, the pressure constant on each and equal to its Gauss-point
 * value, the settlement collocated at the nodes with the closed-form
 * rectangle integral. G is full and unsymmetric.
 */
#ifndef plate_on_halfspace_halfspace_collocation_operator_h
#define plate_on_halfspace_halfspace_collocation_operator_h

#include <plate_on_halfspace/halfspace/interface.h>

namespace PlateOnHalfspace
{
  /**
   * Dense collocation operator: F = G, B = I; the foundation stiffness of a
   * direct solver is then E G^{-1} = K_G (P17).
   * Needs axis-aligned rectangular cells (the closed-form integral (P5)).
   */
  class BoussinesqCollocationOperator : public FoundationOperator
  {
  public:
    /**
     * @param soil a homogeneous half-space: the paper's closed-form
     *   integral (P5) has no remainder (build() refuses another kernel).
     */
    explicit BoussinesqCollocationOperator(
      std::shared_ptr<const ElasticSoil> soil);

    /**
     * @param alpha (1 - nu0^2)/(pi E0).
     * @param singular_order Duffy points of settlement_at_points().
     */
    explicit BoussinesqCollocationOperator(
      const double       alpha,
      const unsigned int singular_order = 8);

    void
    build(const FoundationSpace   &space,
          const std::vector<bool> &cell_in_foundation) override;
    void
    apply(const Vector<double> &q, Vector<double> &s) const override;
    /** Copies from the dense G. */
    void
    copy_block(const std::vector<unsigned int> &nodes,
               LAPACKFullMatrix<double>        &block) const override;
    bool
    is_symmetric() const override
    {
      return false;
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

    /** The assembled G on all nodes (for tests). */
    const LAPACKFullMatrix<double> &
    flexibility_matrix() const
    {
      return flexibility;
    }

  private:
    const std::shared_ptr<const ElasticSoil> elastic;
    LAPACKFullMatrix<double>                 flexibility;
  };
} // namespace PlateOnHalfspace

#endif
