/**
 * A distributed sparse direct solver: MUMPS through Trilinos' Amesos, on a
 * matrix split by rows over the ranks of a communicator (doc/parallel.md,
 * "The plate"). The plate's stiffness of a run on several processes is
 * factorised here; one process keeps CHOLMOD (sparse_cholesky.h).
 *
 * Vectors in and out are whole on every rank, as the contact solvers hold
 * them: each rank hands MUMPS its own rows of the right-hand side, and the
 * solution's rows are summed over the ranks (each row comes from one rank
 * and zeros from the others, so every rank gets the same bits). Where a
 * caller needs a few rows of the solution only (the plate's deflections at
 * the foundation nodes), solve_at() sums only those.
 */
#ifndef plate_on_halfspace_base_distributed_sparse_direct_h
#define plate_on_halfspace_base_distributed_sparse_direct_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** See the file documentation. */
  class DistributedSparseDirect
  {
  public:
    DistributedSparseDirect();
    ~DistributedSparseDirect();
    DistributedSparseDirect(const DistributedSparseDirect &) = delete;
    DistributedSparseDirect &
    operator=(const DistributedSparseDirect &) = delete;

    /**
     * Factorise @p matrix (whole on every rank) with the rows and columns
     * of the indices not in @p solved removed: their rows become identity
     * rows and their right-hand side zero, so their solution is zero. Each
     * rank contributes the rows @p owned_rows (a partition of all rows
     * over @p communicator). Collective; throws ExcMessage if MUMPS fails
     * (a singular matrix).
     */
    void
    factorize(const SparseMatrix<double> &matrix,
              const std::vector<bool>    &solved,
              const IndexSet             &owned_rows,
              const MPI_Comm              communicator);

    /** u = A^{-1} f, zero off the solved indices; collective. */
    void
    solve(const Vector<double> &f, Vector<double> &u) const;

    /** @p values[k] = (A^{-1} f)[@p rows[k]], the same as solve()'s;
     *  collective, and only these entries are summed over the ranks. */
    void
    solve_at(const Vector<double>                       &f,
             const std::vector<types::global_dof_index> &rows,
             Vector<double>                             &values) const;

  private:
    struct Data;
    std::unique_ptr<Data> data;

    /** MUMPS's solution of f, each rank's own rows (zero off the solved
     *  indices); collective. */
    void
    solve_owned_rows(const Vector<double> &f,
                     std::vector<double>  &owned_values) const;
  };
} // namespace PlateOnHalfspace

#endif
