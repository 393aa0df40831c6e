#include <deal.II/base/multithread_info.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/timer.h>

#include <plate_on_halfspace/halfspace/collocation_operator.h>
#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/halfspace/boussinesq_kernel.h>
#include <plate_on_halfspace/base/condition_estimate.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/halfspace/hierarchical_operator.h>

namespace PlateOnHalfspace
{
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
  FoundationOperator::use_positive_pressure_basis(const FoundationSpace &space)
  {
    positive_basis =
      space.positive_pressure_transform(transform_sparsity, transform);
    tested_mass.clear();
    force_mass.clear();
    if (!positive_basis)
      return;
    transform_tests(mass, tested_sparsity, tested_mass);
    force_mass.reinit(force_sparsity);
    mass.mmult(force_mass, transform);
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
    in_contact = node_supported;
  }

  void
  FoundationOperator::factorise_contact_block(
    const std::vector<bool>        &requested,
    const LAPACKFullMatrix<double> &flexibility,
    const bool                      symmetric,
    const std::string              &failure)
  {
    const Timer timer;
    AssertDimension(requested.size(), node_supported.size());
    contact_index.clear();
    for (unsigned int i = 0; i < requested.size(); ++i)
      {
        in_contact[i] = requested[i] && node_supported[i];
        if (in_contact[i])
          contact_index.push_back(i);
      }
    const unsigned int m = contact_index.size();
    contact_factor.reinit(m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        contact_factor(i, j) = flexibility(contact_index[i], contact_index[j]);
    contact_block_rcond = 1.;
    if (m == 0)
      return;
    const double l1_norm = contact_factor.l1_norm();
    try
      {
        if (symmetric)
          contact_factor.compute_cholesky_factorization();
        else
          contact_factor.compute_lu_factorization();
      }
    catch (...)
      {
        AssertThrow(false, ExcMessage(failure));
      }
    contact_block_rcond =
      reciprocal_condition_number(contact_factor, l1_norm, symmetric);
    times.factorization = timer.wall_time();
  }

  void
  FoundationOperator::solve_contact_block(const Vector<double> &b,
                                          Vector<double>       &q) const
  {
    Vector<double> b_contact(contact_index.size());
    for (unsigned int i = 0; i < contact_index.size(); ++i)
      b_contact[i] = b[contact_index[i]];
    if (!contact_index.empty())
      contact_factor.solve(b_contact);
    q.reinit(b.size());
    for (unsigned int i = 0; i < contact_index.size(); ++i)
      q[contact_index[i]] = b_contact[i];
  }

  void
  FoundationOperator::add_mass_times_contact_inverse(
    LAPACKFullMatrix<double> &rows,
    LAPACKFullMatrix<double> &matrix) const
  {
    const unsigned int n = force_coupling().m();
    if (contact_index.empty())
      return;
    contact_factor.solve(rows);
    // M_{:,C} restricted to the contact columns, row by row.
    std::vector<int> position(n, -1);
    for (unsigned int i = 0; i < contact_index.size(); ++i)
      position[contact_index[i]] = i;
    std::vector<std::vector<std::pair<unsigned int, double>>> mass_rows(n);
    for (unsigned int r = 0; r < n; ++r)
      for (auto entry = force_coupling().begin(r);
           entry != force_coupling().end(r);
           ++entry)
        if (position[entry->column()] >= 0)
          mass_rows[r].emplace_back(position[entry->column()], entry->value());
    // matrix(:, c) += M_{:,C} rows(:, c): both columns are contiguous in
    // LAPACK's column-major storage; the columns are independent, so they
    // are split over the threads.
    const auto add_columns = [&](const unsigned int begin,
                                 const unsigned int end) {
      for (unsigned int c = begin; c < end; ++c)
        for (unsigned int r = 0; r < n; ++r)
          {
            double sum = 0;
            for (const auto &kv : mass_rows[r])
              sum += kv.second * rows(kv.first, c);
            matrix(r, c) += sum;
          }
    };
    Threads::TaskGroup<void> tasks;
    const unsigned int       n_chunks = MultithreadInfo::n_threads();
    for (unsigned int t = 0; t < n_chunks; ++t)
      tasks += Threads::new_task(
        [&, t]() { add_columns(n * t / n_chunks, n * (t + 1) / n_chunks); });
    tasks.join_all();
  }

  std::unique_ptr<FoundationOperator>
  create_foundation_operator(const SceneParameters &parameters,
                             const std::string     &storage)
  {
    const double alpha =
      boussinesq_flexibility_constant(parameters.foundation.youngs_modulus,
                                      parameters.foundation.poissons_ratio);
    // SceneParameters allows hierarchical only with the Galerkin operator
    // and the iterative contact solver.
    if (storage == "hierarchical")
      return std::make_unique<HierarchicalGalerkinOperator>(
        alpha,
        parameters.discretization.singular_quadrature_order,
        parameters.foundation_operator.tolerance);
    if (parameters.discretization.flexibility ==
        Parameters::Discretization::Flexibility::galerkin)
      return std::make_unique<BoussinesqGalerkinOperator>(
        alpha, parameters.discretization.singular_quadrature_order);
    return std::make_unique<BoussinesqCollocationOperator>(alpha);
  }
} // namespace PlateOnHalfspace
