#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/halfspace/dense_liquid_operator.h>

#include <algorithm>

namespace PlateOnHalfspace
{
  namespace
  {
    /** The Cholesky factor of the sparse flexibility: F^{-1} exactly. */
    class SparseCholeskyInverse : public ApproximateInverse
    {
    public:
      explicit SparseCholeskyInverse(const SparseMatrix<double> &flexibility)
        : n(flexibility.m())
      {
        factor.factorize(flexibility);
      }

      void
      vmult(Vector<double> &q, const Vector<double> &s) const override
      {
        std::vector<double> block(s.begin(), s.end());
        factor.solve(block, 1);
        q.reinit(n);
        std::copy(block.begin(), block.end(), q.begin());
      }

      std::size_t
      memory_consumption() const override
      {
        // CHOLMOD keeps its factor to itself; a 2-d mass matrix fills in
        // to about ten times its nonzeros (nested dissection).
        return 0;
      }

    private:
      const unsigned int n;
      SparseCholesky     factor{"the dense liquid's flexibility"};
    };
  } // namespace

  DenseLiquidOperator::DenseLiquidOperator(
    std::shared_ptr<const DenseLiquidSoil> soil,
    const bool                             positive_pressure_basis)
    : subgrade_modulus(soil->subgrade_modulus())
    , positive_pressure_basis(positive_pressure_basis)
  {
    AssertThrow(subgrade_modulus > 0,
                ExcMessage("Foundation/Modulus of subgrade reaction must be "
                           "> 0 for Foundation/Model = dense liquid."));
    soil_model = std::move(soil);
  }

  DenseLiquidOperator::~DenseLiquidOperator() = default;

  void
  DenseLiquidOperator::build(const FoundationSpace   &space,
                             const std::vector<bool> &cell_in_foundation)
  {
    AssertThrow(std::find(cell_in_foundation.begin(),
                          cell_in_foundation.end(),
                          false) == cell_in_foundation.end(),
                ExcMessage("The dense-liquid foundation has no element "
                           "exclusion (Contact/Method = element exclusion "
                           "belongs to the half-space)."));
    build_mass_matrix(space, {});
    set_pressure_basis(space, positive_pressure_basis);
    // F = B T / k = T^T M T / k (M itself without the positive basis): the
    // settlement q_h/k tested with the pressure basis.
    flexibility.clear();
    if (positive_basis)
      {
        flexibility.reinit(flexibility_sparsity);
        test_coupling().mmult(flexibility, transform);
      }
    else
      {
        flexibility_sparsity.copy_from(mass.get_sparsity_pattern());
        flexibility.reinit(flexibility_sparsity);
        flexibility.copy_from(mass);
      }
    flexibility /= subgrade_modulus;
  }

  void
  DenseLiquidOperator::apply(const Vector<double> &q, Vector<double> &s) const
  {
    s.reinit(q.size());
    flexibility.vmult(s, q);
  }

  void
  DenseLiquidOperator::copy_block(const std::vector<unsigned int> &nodes,
                                  LAPACKFullMatrix<double>        &block) const
  {
    const unsigned int m = nodes.size();
    block.reinit(m, m);
    block = 0.;
    std::vector<int> position(n_nodes(), -1);
    for (unsigned int i = 0; i < m; ++i)
      position[nodes[i]] = i;
    for (unsigned int i = 0; i < m; ++i)
      for (auto entry = flexibility.begin(nodes[i]);
           entry != flexibility.end(nodes[i]);
           ++entry)
        if (position[entry->column()] >= 0)
          block(i, position[entry->column()]) = entry->value();
  }

  Vector<double>
  DenseLiquidOperator::flexibility_diagonal() const
  {
    Vector<double> diagonal(n_nodes());
    for (unsigned int i = 0; i < n_nodes(); ++i)
      diagonal[i] = flexibility.diag_element(i);
    return diagonal;
  }

  std::unique_ptr<ApproximateInverse>
  DenseLiquidOperator::make_approximate_inverse()
  {
    try
      {
        return std::make_unique<SparseCholeskyInverse>(flexibility);
      }
    catch (...)
      {
        AssertThrow(false,
                    ExcMessage("The dense-liquid flexibility T^T M T / k is "
                               "not positive definite: the mesh has a "
                               "degenerate cell."));
      }
    return nullptr;
  }

  std::size_t
  DenseLiquidOperator::memory_consumption() const
  {
    return flexibility.memory_consumption() +
           flexibility_sparsity.memory_consumption() +
           coupling_memory_consumption();
  }
} // namespace PlateOnHalfspace
