#include <deal.II/base/exceptions.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <plate_on_halfspace/base/distributed_sparse_direct.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>

namespace PlateOnHalfspace
{
  struct DistributedSparseDirect::Data
  {
    TrilinosWrappers::SparseMatrix matrix;
    SolverControl                  control;
    TrilinosWrappers::SolverDirect solver;
    IndexSet                       owned_rows;
    MPI_Comm                       communicator = MPI_COMM_SELF;
    std::vector<bool>              solved;

    // the control neither logs its history nor its result: a direct
    // solve's "convergence" would only fill deallog
    Data()
      : control(100, 1e-10, false, false)
      , solver(control,
               TrilinosWrappers::SolverDirect::AdditionalData(false,
                                                              "Amesos_Mumps"))
    {}
  };

  DistributedSparseDirect::DistributedSparseDirect() = default;

  DistributedSparseDirect::~DistributedSparseDirect() = default;

  void
  DistributedSparseDirect::factorize(const SparseMatrix<double> &matrix,
                                     const std::vector<bool>    &solved,
                                     const IndexSet             &owned_rows,
                                     const MPI_Comm              communicator)
  {
    AssertDimension(solved.size(), matrix.m());
    AssertDimension(owned_rows.size(), matrix.m());
    data               = std::make_unique<Data>();
    data->owned_rows   = owned_rows;
    data->communicator = communicator;
    data->solved       = solved;
    // Every stored entry is kept (no drop tolerance): the same matrix as
    // the one process's factorisation.
    data->matrix.reinit(owned_rows, owned_rows, matrix, communicator, 0.);
    std::vector<TrilinosWrappers::SparseMatrix::size_type> removed;
    for (const auto i : owned_rows)
      if (!solved[i])
        removed.push_back(i);
    data->matrix.clear_rows(removed, 1.);
    try
      {
        data->solver.initialize(data->matrix);
      }
    catch (const std::exception &e)
      {
        AssertThrow(false,
                    ExcMessage(std::string("MUMPS (Trilinos Amesos) could "
                                           "not factorise the plate: ") +
                               e.what()));
      }
  }

  void
  DistributedSparseDirect::solve_owned_rows(
    const Vector<double> &f,
    std::vector<double>  &owned_values) const
  {
    Assert(data != nullptr, ExcMessage("solve() before factorize()."));
    AssertDimension(f.size(), data->solved.size());
    TrilinosWrappers::MPI::Vector rhs(data->owned_rows, data->communicator),
      solution(data->owned_rows, data->communicator);
    for (const auto i : data->owned_rows)
      rhs[i] = data->solved[i] ? f[i] : 0.;
    rhs.compress(VectorOperation::insert);
    data->solver.solve(solution, rhs);
    owned_values.resize(data->owned_rows.n_elements());
    unsigned int k = 0;
    for (const auto i : data->owned_rows)
      owned_values[k++] = data->solved[i] ? double(solution[i]) : 0.;
  }

  void
  DistributedSparseDirect::solve(const Vector<double> &f,
                                 Vector<double>       &u) const
  {
    std::vector<double> owned_values;
    solve_owned_rows(f, owned_values);
    u.reinit(f.size());
    unsigned int k = 0;
    for (const auto i : data->owned_rows)
      u[i] = owned_values[k++];
    sum_over_ranks(u, data->communicator);
  }

  void
  DistributedSparseDirect::solve_at(
    const Vector<double>                       &f,
    const std::vector<types::global_dof_index> &rows,
    Vector<double>                             &values) const
  {
    std::vector<double> owned_values;
    solve_owned_rows(f, owned_values);
    values.reinit(rows.size());
    for (unsigned int k = 0; k < rows.size(); ++k)
      if (data->owned_rows.is_element(rows[k]))
        values[k] = owned_values[data->owned_rows.index_within_set(rows[k])];
    // each entry from its row's one owner and zeros: the same bits on
    // every rank
    sum_over_ranks(values, data->communicator);
  }
} // namespace PlateOnHalfspace
