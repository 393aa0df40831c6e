/**
 * Sparse Cholesky factorisation (CHOLMOD, from SuiteSparse, which deal.II's
 * UMFPACK support already brings) with blocked dense right-hand sides.
 *
 * Why not SparseDirectUMFPACK: condensing the plate onto the foundation
 * nodes (the paper's (P18)-(P19)) needs K_rr^{-1} applied to one column per
 * foundation node; UMFPACK solves one vector at a time, while CHOLMOD's
 * supernodal solve treats a block of columns with level-3 BLAS (OpenBLAS),
 * which is over an order of magnitude faster here.
 *
 * Several matrices on one pattern (the shifted Laplacians of the fractional
 * soil inverse) share one symbolic analysis: analyze() once, then
 * factorize_as() for each; the analysis also tells the factor's bytes
 * before its values are allocated.
 */
#ifndef plate_on_halfspace_base_sparse_cholesky_h
#define plate_on_halfspace_base_sparse_cholesky_h

#include <deal.II/lac/sparse_matrix.h>

#include <memory>
#include <string>
#include <vector>

struct cholmod_sparse_struct;

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** Cholesky factor of the principal submatrix A(rows, rows) of an SPD matrix.
   */
  class SparseCholesky
  {
  public:
    /** @p what names the matrix in the messages of a failure, e.g. "the
     *  plate's rotation block". */
    explicit SparseCholesky(const std::string &what);
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky &) = delete;
    SparseCholesky &
    operator=(const SparseCholesky &) = delete;

    /**
     * Factorise A(rows, rows). @p rows lists global indices of @p matrix
     * (symmetric storage, both triangles present). Reuses a symbolic
     * analysis of the same pattern (analyze()) if one is waiting. Throws
     * if the submatrix is not positive definite, or naming the node-count
     * entries if it does not fit the memory.
     */
    void
    factorize(const SparseMatrix<double>                 &matrix,
              const std::vector<types::global_dof_index> &rows);

    /**
     * The symbolic stage of factorize(@p matrix, @p rows) alone: the
     * ordering and the factor's structure of A(rows, rows), its stored
     * zeros dropped. It reads the pattern only and runs on one core (the
     * ordering), so it may go beside other work; a later factorize() of a
     * matrix with the same pattern then computes only the values, and
     * gives the factor that factorize() alone gives. Throws naming the
     * node-count entries if the analysis does not fit the memory.
     */
    void
    analyze(const SparseMatrix<double>                 &matrix,
            const std::vector<types::global_dof_index> &rows);

    /** factorize() of all rows. */
    void
    factorize(const SparseMatrix<double> &matrix);

    /**
     * The symbolic analysis of all rows of @p matrix's sparsity pattern
     * (every stored entry, zero or not): the ordering and the factor's
     * structure, without values. factor_bytes() then tells the factor's
     * size; factorize_as() of another object reuses it.
     */
    void
    analyze(const SparseMatrix<double> &matrix);

    /**
     * Factorise all rows of @p matrix with the symbolic analysis of
     * @p analysed (analyze()), which must have been made on a matrix with
     * the same sparsity pattern: throws if the stored entries differ.
     */
    void
    factorize_as(const SparseCholesky       &analysed,
                 const SparseMatrix<double> &matrix);

    /** Size of the factorised submatrix. */
    unsigned int
    size() const;

    /** Bytes of the factor's values and indices (0 before factorize()). */
    std::size_t
    memory_consumption() const;

    /** Bytes of the factor's values and indices, known after analyze() or
     *  any factorisation. */
    std::size_t
    factor_bytes() const;

    /**
     * Solve in place for @p n_columns right-hand sides stored column by
     * column in @p block (size() * n_columns values). Solves with
     * different factors may run concurrently; with one factor they may
     * not (each factor has one CHOLMOD workspace).
     */
    void
    solve(std::vector<double> &block, const unsigned int n_columns) const;

  private:
    /** cholmod_factorize(@p a) into the factor (analysed, or nullptr if
     *  the analysis ran out of memory); frees @p a; throws on failure. */
    void
    factorize_numerically(cholmod_sparse_struct *a);

    struct Data;
    std::unique_ptr<Data> data;
    const std::string     what;
  };
} // namespace PlateOnHalfspace

#endif
