#include <plate_on_halfspace/base/progress.h>
#include <plate_on_halfspace/halfspace/cell_pair_summation.h>
#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/soil/half_space.h>

#include <algorithm>
#include <cmath>

namespace PlateOnHalfspace
{
  BoussinesqGalerkinOperator::BoussinesqGalerkinOperator(
    std::shared_ptr<const ElasticSoil> soil,
    const bool                         positive_pressure_basis)
    : elastic(std::move(soil))
    , positive_pressure_basis(positive_pressure_basis)
  {
    soil_model = elastic;
  }

  BoussinesqGalerkinOperator::BoussinesqGalerkinOperator(
    const double       alpha,
    const unsigned int singular_order,
    const bool         positive_pressure_basis)
    : BoussinesqGalerkinOperator(
        std::make_shared<HomogeneousHalfSpace>(alpha, singular_order),
        positive_pressure_basis)
  {}

  void
  BoussinesqGalerkinOperator::build(const FoundationSpace   &space,
                                    const std::vector<bool> &cell_in_foundation)
  {
    build_mass_matrix(space, cell_in_foundation);
    partial_foundation =
      std::find(cell_in_foundation.begin(), cell_in_foundation.end(), false) !=
      cell_in_foundation.end();
    if (partial_foundation)
      // The gap is reported on the whole plate, also under excluded cells:
      // it tests with every w-shape function.
      space.assemble_mass_matrix({}, full_mass_sparsity, full_mass);

    const unsigned int n = space.n_nodes();
    flexibility.reinit(n);
    flexibility = 0.;
    system_flexibility.reinit(partial_foundation ? n : 0);
    if (partial_foundation)
      system_flexibility = 0.;

    // flexibility(i,j): test functions over the whole plate, pressures over
    // the foundation cells (the settlement everywhere); system_flexibility:
    // both over the foundation cells (the paper's exclusion removes a cell's
    // contribution to A). They coincide when every cell is in. The sum over
    // cell pairs and mirror images, its order and the symmetrisation of a
    // cell against its own image are CellPairSummation's
    // (cell_pair_summation.h; doc/formulation.md, "Default variant" and
    // "Symmetry"), shared with the hierarchical operator.
    const std::vector<FoundationSpace::Cell> cells =
      CellPairSummation::cells_with_images(space);
    const CellPairSummation summation(cells,
                                      space.symmetry.n_copies(),
                                      n,
                                      elastic->kernel(maximal_distance(space)),
                                      elastic->singular_quadrature_order(),
                                      cell_in_foundation);
    ProgressReport progress("Dense Galerkin flexibility", summation.n_pairs());
    summation.add_all(
      [&](const unsigned int i,
          const unsigned int j,
          const double       value,
          const bool         in_system) {
        flexibility(i, j) += value;
        if (partial_foundation && in_system)
          system_flexibility(i, j) += value;
      },
      &progress);
    progress.finish();

    // The contact conditions in the positive pressure basis
    // (foundation_space.h): A <- T^T A T, M <- T^T M.
    set_pressure_basis(space, positive_pressure_basis);
    transform_flexibility(flexibility);
    if (partial_foundation)
      {
        transform_flexibility(system_flexibility);
        transform_tests(full_mass, full_tested_sparsity, full_tested_mass);
      }
  }

  void
  BoussinesqGalerkinOperator::copy_block(const std::vector<unsigned int> &nodes,
                                         LAPACKFullMatrix<double> &block) const
  {
    // The paper's exclusion removes a cell's contribution to A of the
    // contact conditions: both test and pressure over the foundation cells.
    copy_dense_block(partial_foundation ? system_flexibility : flexibility,
                     nodes,
                     block);
  }

  void
  BoussinesqGalerkinOperator::apply(const Vector<double> &q,
                                    Vector<double>       &s) const
  {
    s.reinit(q.size());
    flexibility.vmult(s, q);
  }

  void
  BoussinesqGalerkinOperator::plate_settlement(const Vector<double> &w,
                                               Vector<double>       &b) const
  {
    b.reinit(w.size());
    (partial_foundation ? full_tested_mass : test_coupling()).vmult(b, w);
  }

  std::size_t
  BoussinesqGalerkinOperator::memory_consumption() const
  {
    return flexibility.memory_consumption() +
           system_flexibility.memory_consumption() +
           full_mass.memory_consumption() +
           full_tested_mass.memory_consumption() +
           coupling_memory_consumption();
  }
} // namespace PlateOnHalfspace
