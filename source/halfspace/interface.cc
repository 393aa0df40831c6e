#include <deal.II/base/exceptions.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <plate_on_halfspace/halfspace/collocation_operator.h>
#include <plate_on_halfspace/halfspace/compressed_settlement.h>
#include <plate_on_halfspace/halfspace/dense_liquid_operator.h>
#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/halfspace/hierarchical_operator.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/halfspace/split_kernel_operator.h>

#include <algorithm>

namespace PlateOnHalfspace
{
  namespace
  {
    /** The Cholesky factor of a dense SPD flexibility. */
    class DenseCholeskyInverse : public ApproximateInverse
    {
    public:
      explicit DenseCholeskyInverse(LAPACKFullMatrix<double> &&flexibility)
        : factor(std::move(flexibility))
      {
        try
          {
            factor.compute_cholesky_factorization();
          }
        catch (...)
          {
            AssertThrow(false,
                        ExcMessage(
                          "The Galerkin half-space matrix A is not positive "
                          "definite; the singular quadrature is too coarse "
                          "for this mesh (raise Discretization/Singular "
                          "quadrature order)."));
          }
      }

      void
      vmult(Vector<double> &q, const Vector<double> &s) const override
      {
        q = s;
        factor.solve(q);
      }

      std::size_t
      memory_consumption() const override
      {
        return factor.memory_consumption();
      }

    private:
      LAPACKFullMatrix<double> factor;
    };
  } // namespace

  void
  FoundationOperator::plate_settlement(const Vector<double> &w,
                                       Vector<double>       &b) const
  {
    b.reinit(w.size());
    test_coupling().vmult(b, w);
  }

  void
  FoundationOperator::copy_block(const std::vector<unsigned int> &nodes,
                                 LAPACKFullMatrix<double>        &block) const
  {
    const unsigned int m = nodes.size();
    block.reinit(m, m);
    Vector<double> unit(n_nodes()), column;
    for (unsigned int j = 0; j < m; ++j)
      {
        unit[nodes[j]] = 1.;
        apply(unit, column);
        unit[nodes[j]] = 0.;
        for (unsigned int i = 0; i < m; ++i)
          block(i, j) = column[nodes[i]];
      }
  }

  Vector<double>
  FoundationOperator::flexibility_diagonal() const
  {
    Vector<double>            diagonal(n_nodes());
    LAPACKFullMatrix<double>  entry;
    std::vector<unsigned int> node(1);
    for (unsigned int i = 0; i < n_nodes(); ++i)
      {
        node[0] = i;
        copy_block(node, entry);
        diagonal[i] = entry(0, 0);
      }
    return diagonal;
  }

  void
  FoundationOperator::copy_dense_block(const LAPACKFullMatrix<double>  &matrix,
                                       const std::vector<unsigned int> &nodes,
                                       LAPACKFullMatrix<double>        &block)
  {
    const unsigned int m = nodes.size();
    block.reinit(m, m);
    for (unsigned int j = 0; j < m; ++j)
      for (unsigned int i = 0; i < m; ++i)
        block(i, j) = matrix(nodes[i], nodes[j]);
  }

  std::unique_ptr<ApproximateInverse>
  FoundationOperator::make_approximate_inverse()
  {
    std::vector<unsigned int> all(n_nodes());
    for (unsigned int i = 0; i < all.size(); ++i)
      all[i] = i;
    LAPACKFullMatrix<double> flexibility;
    copy_block(all, flexibility);
    return std::make_unique<DenseCholeskyInverse>(std::move(flexibility));
  }

  void
  FoundationOperator::nodal_forces(const Vector<double> &q,
                                   Vector<double>       &forces) const
  {
    forces.reinit(q.size());
    force_coupling().vmult(forces, q);
  }

  void
  FoundationOperator::nodal_pressure(const Vector<double> &q,
                                     Vector<double>       &values) const
  {
    values.reinit(q.size());
    if (positive_basis)
      transform.vmult(values, q);
    else
      values = q;
  }

  void
  FoundationOperator::pressure_coefficients(const Vector<double> &values,
                                            Vector<double>       &q) const
  {
    q.reinit(values.size());
    if (positive_basis)
      coefficients_from_values(values, q);
    else
      q = values;
  }

  void
  FoundationOperator::gap(const Vector<double> &w,
                          const Vector<double> &q,
                          Vector<double>       &g) const
  {
    Vector<double> plate(w.size());
    apply(q, g);
    plate_settlement(w, plate);
    g -= plate;
  }

  void
  FoundationOperator::set_pressure_basis(const FoundationSpace &space,
                                         const bool positive_pressure_basis)
  {
    positive_basis =
      positive_pressure_basis &&
      space.positive_pressure_transform(transform_sparsity, transform);
    if (!positive_basis)
      transform.clear();
    force_mass.clear();
    transform_tests(mass, tests_sparsity, tests);
    if (!positive_basis)
      return;
    force_mass.reinit(force_sparsity);
    mass.mmult(force_mass, transform);
  }

  void
  FoundationOperator::use_identity_test_coupling()
  {
    const unsigned int     n = n_nodes();
    DynamicSparsityPattern pattern(n, n);
    for (unsigned int i = 0; i < n; ++i)
      pattern.add(i, i);
    tests.clear();
    tests_sparsity.copy_from(pattern);
    tests.reinit(tests_sparsity);
    for (unsigned int i = 0; i < n; ++i)
      tests.set(i, i, 1.);
    identity_tests = true;
  }

  void
  FoundationOperator::transform_tests(const SparseMatrix<double> &matrix,
                                      SparsityPattern            &sparsity,
                                      SparseMatrix<double>       &tested) const
  {
    tested.clear();
    if (!positive_basis)
      {
        sparsity.copy_from(matrix.get_sparsity_pattern());
        tested.reinit(sparsity);
        tested.copy_from(matrix);
        return;
      }
    tested.reinit(sparsity);
    transform.Tmmult(tested, matrix);
  }

  void
  FoundationOperator::transform_flexibility(
    LAPACKFullMatrix<double> &flexibility) const
  {
    if (!positive_basis)
      return;
    // T has at most three entries per row, so F T and T^T (F T) cost 3 n^2
    // each and need one row or column of scratch, not a second matrix.
    const unsigned int n = flexibility.m();
    Vector<double>     scratch(n);
    for (unsigned int r = 0; r < n; ++r)
      {
        scratch = 0.;
        for (unsigned int j = 0; j < n; ++j)
          for (auto t = transform.begin(j); t != transform.end(j); ++t)
            scratch[t->column()] += flexibility(r, j) * t->value();
        for (unsigned int i = 0; i < n; ++i)
          flexibility(r, i) = scratch[i];
      }
    for (unsigned int c = 0; c < n; ++c)
      {
        scratch = 0.;
        for (unsigned int j = 0; j < n; ++j)
          for (auto t = transform.begin(j); t != transform.end(j); ++t)
            scratch[t->column()] += t->value() * flexibility(j, c);
        for (unsigned int i = 0; i < n; ++i)
          flexibility(i, c) = scratch[i];
      }
  }

  void
  FoundationOperator::build_mass_matrix(
    const FoundationSpace   &space,
    const std::vector<bool> &cell_in_foundation)
  {
    space.assemble_mass_matrix(cell_in_foundation, mass_sparsity, mass);
    node_supported.assign(space.n_nodes(), false);
    for (unsigned int c = 0; c < space.cells.size(); ++c)
      if (cell_in_foundation.empty() || cell_in_foundation[c])
        for (const auto &terms : space.cells[c].expansion)
          for (const auto &t : terms)
            node_supported[t.first] = true;
  }

  std::size_t
  FoundationOperator::coupling_memory_consumption() const
  {
    return mass.memory_consumption() + mass_sparsity.memory_consumption() +
           tests.memory_consumption() + force_mass.memory_consumption() +
           transform.memory_consumption();
  }

  unsigned int
  FoundationOperator::n_loaded_cells(const FoundationSpace &space,
                                     const Vector<double>  &nodal_pressure)
  {
    unsigned int loaded_cells = 0;
    for (const auto &cell : space.cells)
      for (const auto &shape : cell.expansion)
        if (std::any_of(shape.begin(), shape.end(), [&](const auto &t) {
              return nodal_pressure[t.first] != 0;
            }))
          {
            ++loaded_cells;
            break;
          }
    return loaded_cells;
  }

  std::vector<double>
  FoundationOperator::settlement_at_points(
    const FoundationSpace       &space,
    const Vector<double>        &nodal_pressure,
    const std::vector<Point<2>> &points) const
  {
    const auto *elastic = dynamic_cast<const ElasticSoil *>(soil_model.get());
    if (elastic != nullptr)
      {
        if (double(points.size()) * n_loaded_cells(space, nodal_pressure) >=
            compressed_settlement_threshold)
          return compressed_settlement_at_points(
            space,
            nodal_pressure,
            points,
            elastic->kernel(maximal_distance(space)),
            elastic->singular_quadrature_order(),
            compression_tolerance);
      }
    return soil_model->settlement_at_points(space, nodal_pressure, points);
  }

  void
  FoundationOperator::apply_in_pressure_basis(
    const Vector<double> &q,
    Vector<double>       &s,
    const std::function<void(const Vector<double> &, Vector<double> &)>
      &apply_to_values) const
  {
    // s = T^T A T q (doc/formulation.md's weak settlement in the contact
    // basis)
    Vector<double> values, settlement(q.size());
    nodal_pressure(q, values);
    apply_to_values(values, settlement);
    s.reinit(q.size());
    if (positive_basis)
      transform.Tvmult(s, settlement);
    else
      s = settlement;
  }

  void
  FoundationOperator::coefficients_from_values(const Vector<double> &x,
                                               Vector<double>       &y) const
  {
    // T y = x: vertex rows are identity rows, so y_c = x_c first, then
    // each mid-side row y_m = (x_m - sum_c T_mc y_c) / T_mm.
    y = x;
    for (unsigned int i = 0; i < transform.m(); ++i)
      if (transform.diag_element(i) != 1.)
        {
          double rest = x[i];
          for (auto t = transform.begin(i); t != transform.end(i); ++t)
            if (t->column() != i)
              rest -= t->value() * x[t->column()];
          y[i] = rest / transform.diag_element(i);
        }
  }

  void
  FoundationOperator::apply_inverse_transpose_transform(const Vector<double> &x,
                                                        Vector<double> &y) const
  {
    // T^T y = x: a mid-side column of T holds only its diagonal, so
    // y_m = x_m / T_mm first; then y_c = x_c - sum_m T_mc y_m.
    y = x;
    for (unsigned int i = 0; i < transform.m(); ++i)
      if (transform.diag_element(i) != 1.)
        y[i] = x[i] / transform.diag_element(i);
    for (unsigned int i = 0; i < transform.m(); ++i)
      if (transform.diag_element(i) != 1.)
        for (auto t = transform.begin(i); t != transform.end(i); ++t)
          if (t->column() != i)
            y[t->column()] -= t->value() * y[i];
  }

  std::unique_ptr<FoundationOperator>
  create_foundation_operator(
    const SceneParameters                        &parameters,
    const std::shared_ptr<const SoilModel>       &soil,
    const Parameters::FoundationOperator::Storage storage)
  {
    // SceneParameters pairs the sparse storage with the dense liquid, and
    // allows hierarchical storage only with the Galerkin operator.
    if (storage == Parameters::FoundationOperator::Storage::sparse)
      {
        auto dense_liquid =
          std::dynamic_pointer_cast<const DenseLiquidSoil>(soil);
        AssertThrow(dense_liquid,
                    ExcMessage("The sparse storage holds the dense liquid "
                               "only; Foundation/Model = " +
                               soil->name() + " needs dense or hierarchical."));
        return std::make_unique<DenseLiquidOperator>(dense_liquid);
      }
    auto elastic = std::dynamic_pointer_cast<const ElasticSoil>(soil);
    AssertThrow(elastic,
                ExcMessage("Foundation/Model = " + soil->name() +
                           " is stored sparse; leave Foundation "
                           "operator/Storage auto."));
    std::unique_ptr<FoundationOperator> foundation;
    if (storage == Parameters::FoundationOperator::Storage::hierarchical)
      foundation = std::make_unique<HierarchicalGalerkinOperator>(
        elastic, parameters.foundation_operator.tolerance);
    else if (storage == Parameters::FoundationOperator::Storage::fft)
      foundation = std::make_unique<SplitKernelFftOperator>(
        elastic,
        parameters.foundation_operator.tolerance,
        parameters.contact.preconditioner !=
          Parameters::Contact::Preconditioner::plate_on_springs);
    else if (parameters.discretization.flexibility ==
             Parameters::Discretization::Flexibility::galerkin)
      foundation = std::make_unique<BoussinesqGalerkinOperator>(elastic);
    else
      foundation = std::make_unique<BoussinesqCollocationOperator>(elastic);
    foundation->set_compression_tolerance(
      parameters.foundation_operator.tolerance);
    return foundation;
  }
} // namespace PlateOnHalfspace
