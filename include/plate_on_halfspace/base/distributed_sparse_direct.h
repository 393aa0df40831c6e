/**
 * A distributed sparse direct solver: MUMPS's LDL^T factorisation of a
 * symmetric positive definite matrix split by rows over the ranks of a
 * communicator (doc/parallel.md, "The plate"). The plate's stiffness of a
 * run on several processes is factorised here; one process keeps CHOLMOD
 * (sparse_cholesky.h).
 *
 * Vectors in and out are whole on every rank, as the contact solvers hold
 * them: MUMPS takes the right-hand side on rank 0 and gathers the solution
 * there, and rank 0 sends it to the others, so every rank gets the same
 * bits. Where a caller needs a few rows of the solution only (the plate's
 * deflections at the foundation nodes), solve_at() sends only those.
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
     * (a matrix that is not positive definite, or MUMPS out of memory).
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
     *  collective, and only these entries are sent to the other ranks. */
    void
    solve_at(const Vector<double>                       &f,
             const std::vector<types::global_dof_index> &rows,
             Vector<double>                             &values) const;

    /** Bytes of this rank's share of the factor (MUMPS's INFO(9) and
     *  INFO(10)) and of the entries it gave MUMPS; 0 before factorize(). */
    std::size_t
    memory_consumption() const;

  private:
    struct Data;
    std::unique_ptr<Data> data;

    /** MUMPS's solution of f, zero off the solved indices, on rank 0
     *  (Data::rhs); collective. */
    void
    solve_on_first_rank(const Vector<double> &f) const;
  };
} // namespace PlateOnHalfspace

#endif
