#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/halfspace/cell_pair_summation.h>
#include <plate_on_halfspace/halfspace/hierarchical_operator.h>

#include <algorithm>

namespace PlateOnHalfspace
{
  namespace
  {
    HierarchicalFlexibility::Settings
    settings_with(const double       tolerance,
                  const std::string &definiteness_advice = {})
    {
      HierarchicalFlexibility::Settings settings;
      settings.tolerance           = tolerance;
      settings.definiteness_advice = definiteness_advice;
      return settings;
    }


    /** The operator's H-Cholesky solve as an ApproximateInverse. */
    class HierarchicalCholeskyInverse : public ApproximateInverse
    {
    public:
      explicit HierarchicalCholeskyInverse(
        const HierarchicalGalerkinOperator &foundation)
        : foundation(foundation)
      {}

      void
      vmult(Vector<double> &q, const Vector<double> &s) const override
      {
        foundation.solve(q, s);
      }

      std::size_t
      memory_consumption() const override
      {
        // The factor is held (and counted) by the operator.
        return 0;
      }

    private:
      const HierarchicalGalerkinOperator &foundation;
    };
  } // namespace

  HierarchicalGalerkinOperator::HierarchicalGalerkinOperator(
    std::shared_ptr<const ElasticSoil> soil,
    const double                       tolerance)
    : elastic(std::move(soil))
    , tolerance(tolerance)
    , flexibility(settings_with(tolerance, elastic->definiteness_advice()))
  {
    soil_model = elastic;
  }

  bool
  HierarchicalGalerkinOperator::rows_are_split() const
  {
    return n_ranks(communicator) > 1;
  }

  void
  HierarchicalGalerkinOperator::build(
    const FoundationSpace   &space,
    const std::vector<bool> &cell_in_foundation)
  {
    AssertThrow(std::find(cell_in_foundation.begin(),
                          cell_in_foundation.end(),
                          false) == cell_in_foundation.end(),
                ExcMessage("Foundation operator/Storage = hierarchical does "
                           "not support Contact/Method = element exclusion "
                           "(use active set)."));
    build_mass_matrix(space, cell_in_foundation);
    set_pressure_basis(space, true);
    communicator = space.communicator;
    off_diagonal.clear();
    const SurfaceKernel kernel = elastic->kernel(maximal_distance(space));
    const unsigned int  singular_order = elastic->singular_quadrature_order();
    if (!rows_are_split())
      {
        flexibility.build(space, kernel, singular_order);
        times.compression = flexibility.build_times().compression;
        return;
      }
    // This rank's rows: the block on its own nodes and one block against
    // each other rank's nodes, from one summation (its singular pairs
    // integrated once).
    std::vector<unsigned int> own;
    for (unsigned int i = 0; i < space.n_nodes(); ++i)
      if (space.owned_nodes.is_element(i))
        own.push_back(i);
    const std::vector<std::vector<unsigned int>> nodes_of_rank =
      Utilities::MPI::all_gather(communicator, own);
    // Decided by all ranks together, so that all stop or none.
    AssertThrow(std::none_of(nodes_of_rank.begin(),
                             nodes_of_rank.end(),
                             [](const auto &nodes) { return nodes.empty(); }),
                ExcMessage("More MPI processes than the mesh can share: a "
                           "rank owns no foundation node. Run on fewer "
                           "processes or refine the mesh (Discretization/"
                           "Subdivisions x and y)."));
    const std::vector<FoundationSpace::Cell> cells =
      CellPairSummation::cells_with_images(space);
    const CellPairSummation summation(cells,
                                      space.symmetry.n_copies(),
                                      space.n_nodes(),
                                      kernel,
                                      singular_order);
    flexibility.build(cells, summation, space.node_locations, own, own);
    times.compression = flexibility.build_times().compression;
    for (unsigned int rank = 0; rank < nodes_of_rank.size(); ++rank)
      if (rank != rank_in(communicator))
        {
          off_diagonal.push_back(std::make_unique<HierarchicalFlexibility>(
            settings_with(tolerance)));
          off_diagonal.back()->build(
            cells, summation, space.node_locations, own, nodes_of_rank[rank]);
          times.compression += off_diagonal.back()->build_times().compression;
        }
  }

  std::unique_ptr<ApproximateInverse>
  HierarchicalGalerkinOperator::make_approximate_inverse()
  {
    flexibility.factorize();
    return std::make_unique<HierarchicalCholeskyInverse>(*this);
  }

  void
  HierarchicalGalerkinOperator::apply(const Vector<double> &q,
                                      Vector<double>       &s) const
  {
    apply_in_pressure_basis(
      q, s, [this](const Vector<double> &values, Vector<double> &settlement) {
        flexibility.vmult(settlement, values);
        if (rows_are_split())
          {
            Vector<double> rest;
            for (const auto &block : off_diagonal)
              {
                block->vmult(rest, values);
                settlement += rest;
              }
            sum_over_ranks(settlement, communicator);
          }
      });
  }

  Vector<double>
  HierarchicalGalerkinOperator::flexibility_diagonal() const
  {
    // Each rank's diagonal block holds its own nodes' entries.
    Vector<double> values_diagonal;
    flexibility.diagonal(values_diagonal);
    if (rows_are_split())
      sum_over_ranks(values_diagonal, communicator);
    if (!positive_basis)
      return values_diagonal;
    Vector<double> diagonal(values_diagonal.size());
    for (unsigned int j = 0; j < transform.m(); ++j)
      for (auto t = transform.begin(j); t != transform.end(j); ++t)
        diagonal[t->column()] += t->value() * t->value() * values_diagonal[j];
    return diagonal;
  }

  void
  HierarchicalGalerkinOperator::solve(Vector<double>       &q,
                                      const Vector<double> &s) const
  {
    // (T^T A T)^{-1} s = T^{-1} A^{-1} T^{-T} s, A^{-1} by the H-Cholesky
    // factor.
    Vector<double> tested(s.size()), values(s.size());
    if (positive_basis)
      apply_inverse_transpose_transform(s, tested);
    else
      tested = s;
    flexibility.solve(values, tested);
    sum_over_ranks(values, communicator);
    q.reinit(s.size());
    if (positive_basis)
      coefficients_from_values(values, q);
    else
      q = values;
  }

  std::size_t
  HierarchicalGalerkinOperator::memory_consumption() const
  {
    std::size_t bytes =
      flexibility.memory_consumption() + coupling_memory_consumption();
    for (const auto &block : off_diagonal)
      bytes += block->memory_consumption();
    return bytes;
  }
} // namespace PlateOnHalfspace
