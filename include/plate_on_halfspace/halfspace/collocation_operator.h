/**
 * The paper's collocation half-space operator (doc/formulation.md, "Paper
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
   * Dense collocation operator: F = G (LU), B = I, S = E G^{-1} = K_G (P17).
   * Needs axis-aligned rectangular cells (the closed-form integral (P5)).
   */
  class BoussinesqCollocationOperator : public FoundationOperator
  {
  public:
    /** @param alpha (1 - nu0^2)/(pi E0). */
    explicit BoussinesqCollocationOperator(const double alpha);

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
      return false;
    }
    std::string
    storage_name() const override
    {
      return "dense";
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
    const double             alpha;
    LAPACKFullMatrix<double> flexibility;
  };
} // namespace PlateOnHalfspace

#endif
