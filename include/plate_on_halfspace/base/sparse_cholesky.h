/**
 * Sparse Cholesky factorisation (CHOLMOD, from SuiteSparse, which deal.II's
 * UMFPACK support already brings) with blocked dense right-hand sides.
 *
 * Why not SparseDirectUMFPACK: condensing the plate onto the foundation
 * nodes (the paper's (P18)-(P19)) needs K_rr^{-1} applied to one column per
 * foundation node; UMFPACK solves one vector at a time, while CHOLMOD's
 * supernodal solve treats a block of columns with level-3 BLAS (OpenBLAS),
 * which is over an order of magnitude faster here.
 */
#ifndef plate_on_halfspace_base_sparse_cholesky_h
#define plate_on_halfspace_base_sparse_cholesky_h

#include <deal.II/lac/sparse_matrix.h>

#include <memory>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** Cholesky factor of the principal submatrix A(rows, rows) of an SPD matrix.
   */
  class SparseCholesky
  {
  public:
    SparseCholesky();
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky &) = delete;
    SparseCholesky &
    operator=(const SparseCholesky &) = delete;

    /**
     * Factorise A(rows, rows). @p rows lists global indices of @p matrix
     * (symmetric storage, both triangles present). Throws if the submatrix
     * is not positive definite.
     */
    void
    factorize(const SparseMatrix<double>                 &matrix,
              const std::vector<types::global_dof_index> &rows);

    /** Size of the factorised submatrix. */
    unsigned int
    size() const;

    /** Bytes of the factor's values and indices (0 before factorize()). */
    std::size_t
    memory_consumption() const;

    /**
     * Solve in place for @p n_columns right-hand sides stored column by
     * column in @p block (size() * n_columns values).
     */
    void
    solve(std::vector<double> &block, const unsigned int n_columns) const;

  private:
    struct Data;
    std::unique_ptr<Data> data;
  };
} // namespace PlateOnHalfspace

#endif
