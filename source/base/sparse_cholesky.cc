#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/base/nested_dissection.h>
#include <plate_on_halfspace/base/sparse_cholesky.h>

#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <mutex>
#include <new>
#include <numeric>
#include <string>

namespace PlateOnHalfspace
{
  struct SparseCholesky::Data
  {
    cholmod_common  common;
    cholmod_factor *factor = nullptr;
    unsigned int    n      = 0;
    /** The analysed pattern (analyze()): column starts and row indices
     *  of the upper triangle, which factorize_as() must meet. */
    std::vector<int> analysed_starts, analysed_rows;

    /** Whether @p a has the analysed pattern. */
    bool
    has_analysed_pattern(const cholmod_sparse *a) const
    {
      const unsigned int n       = a->ncol;
      const int         *starts  = static_cast<const int *>(a->p);
      const int         *indices = static_cast<const int *>(a->i);
      return std::equal(starts,
                        starts + n + 1,
                        analysed_starts.begin(),
                        analysed_starts.end()) &&
             std::equal(indices,
                        indices + starts[n],
                        analysed_rows.begin(),
                        analysed_rows.end());
    }

    /** Keep @p a's pattern as the analysed one. */
    void
    keep_pattern(const cholmod_sparse *a)
    {
      const unsigned int n       = a->ncol;
      const int         *starts  = static_cast<const int *>(a->p);
      const int         *indices = static_cast<const int *>(a->i);
      analysed_starts.assign(starts, starts + n + 1);
      analysed_rows.assign(indices, indices + starts[n]);
    }

    void
    free_factor()
    {
      if (factor != nullptr)
        cholmod_free_factor(&factor, &common);
    }
  };

  namespace
  {
    std::string
    does_not_fit(const std::string &what, const unsigned int n)
    {
      return "The sparse Cholesky factor of " + what + " (" +
             std::to_string(n) +
             " unknowns) needs more memory than this machine has: reduce "
             "the node count (Discretization/Subdivisions x and y, "
             "Discretization/Initial refinements, Adaptivity/Max cells).";
    }

    /**
     * The upper triangle of A(rows, rows) in CHOLMOD's compressed columns
     * (A symmetric: row i of A is column i); with @p keep_zeros every
     * stored entry, so that matrices on one pattern share one analysis.
     */
    cholmod_sparse *
    upper_triangle(const SparseMatrix<double>                 &matrix,
                   const std::vector<types::global_dof_index> &rows,
                   const bool                                  keep_zeros,
                   cholmod_common                             &common,
                   const bool                                  values = true)
    {
      const unsigned int n = rows.size();
      std::vector<int>   position(matrix.m(), -1);
      for (unsigned int i = 0; i < n; ++i)
        position[rows[i]] = i;
      // Counted first and written in place: a copy of the matrix beside
      // CHOLMOD's would raise the peak memory by more than the matrix
      // (doc/performance.md, "Peak memory").
      const auto for_each_kept = [&](const unsigned int j, const auto &use) {
        for (auto entry = matrix.begin(rows[j]); entry != matrix.end(rows[j]);
             ++entry)
          {
            const int i = position[entry->column()];
            if (i >= 0 && i <= static_cast<int>(j) &&
                (keep_zeros || entry->value() != 0.))
              use(i, entry->value());
          }
      };
      std::size_t nnz = 0;
      for (unsigned int j = 0; j < n; ++j)
        for_each_kept(j, [&](int, double) { ++nnz; });
      cholmod_sparse *a =
        cholmod_allocate_sparse(n,
                                n,
                                nnz,
                                /*sorted*/ 1,
                                /*packed*/ 1,
                                /*stype*/ 1,
                                values ? CHOLMOD_REAL : CHOLMOD_PATTERN,
                                &common);
      if (a == nullptr)
        return nullptr;
      int                                *p = static_cast<int *>(a->p);
      int                                *r = static_cast<int *>(a->i);
      double                             *x = static_cast<double *>(a->x);
      std::vector<std::pair<int, double>> column;
      p[0] = 0;
      for (unsigned int j = 0; j < n; ++j)
        {
          column.clear();
          for_each_kept(j, [&](const int i, const double value) {
            column.emplace_back(i, value);
          });
          std::sort(column.begin(), column.end());
          int k = p[j];
          for (const auto &e : column)
            {
              r[k] = e.first;
              if (x != nullptr)
                x[k] = e.second;
              ++k;
            }
          p[j + 1] = k;
        }
      return a;
    }

    std::vector<types::global_dof_index>
    all_rows(const unsigned int n)
    {
      std::vector<types::global_dof_index> rows(n);
      std::iota(rows.begin(), rows.end(), types::global_dof_index(0));
      return rows;
    }
    /**
     * cholmod_analyze() of @p a, the upper triangle of @p pattern's
     * unknowns @p rows (nullptr where memory ran out). From 10^4 unknowns
     * on it tries AMD and nested_dissection() and keeps the smaller
     * factor: CHOLMOD's default
     * tries METIS only where AMD fills badly, which the soil inverse's
     * Laplacian at 10^5 nodes does not count as bad, yet METIS's factor
     * is 18 % smaller there (the plate's a fifth). Below, the default:
     * METIS rarely wins there and takes longer (doc/performance.md, "The
     * build's transient blocks").
     */
    cholmod_factor *
    analyze_with_best_ordering(cholmod_sparse        *a,
                               const SparsityPattern &pattern,
                               const std::vector<types::global_dof_index> &rows,
                               cholmod_common &common)
    {
      // the plate's ordering runs beside the soil inverse's
      // (doc/performance.md, "The plate's ordering beside the operator's
      // build"); CHOLMOD's own METIS draws from rand() as well
      const std::lock_guard<std::mutex> lock(metis_ordering_lock());
      if (a->nrow < 10000)
        {
          common.nmethods = 0;
          return cholmod_analyze(a, &common);
        }
      std::vector<int> perm;
      try
        {
          perm = nested_dissection(pattern, rows);
        }
      catch (const std::bad_alloc &)
        {
          return nullptr;
        }
      common.nmethods           = 2;
      common.method[0].ordering = CHOLMOD_AMD;
      if (perm.empty())
        {
          common.method[1].ordering = CHOLMOD_METIS;
          return cholmod_analyze(a, &common);
        }
      common.method[1].ordering = CHOLMOD_GIVEN;
      return cholmod_analyze_p(a, perm.data(), nullptr, 0, &common);
    }
  } // namespace

  SparseCholesky::SparseCholesky(const std::string &what)
    : data(std::make_unique<Data>())
    , what(what)
  {
    cholmod_start(&data->common);
    data->common.supernodal = CHOLMOD_SUPERNODAL;
  }

  SparseCholesky::~SparseCholesky()
  {
    data->free_factor();
    cholmod_finish(&data->common);
  }

  unsigned int
  SparseCholesky::size() const
  {
    return data->n;
  }

  std::size_t
  SparseCholesky::memory_consumption() const
  {
    const cholmod_factor *f = data->factor;
    if (f == nullptr)
      return 0;
    if (f->xtype == CHOLMOD_PATTERN)
      return f->is_super ? f->ssize * sizeof(int) : 0;
    return factor_bytes();
  }

  std::size_t
  SparseCholesky::factor_bytes() const
  {
    const cholmod_factor *f = data->factor;
    if (f == nullptr)
      return 0;
    // supernodal: xsize values and ssize row indices (both set by the
    // analysis); simplicial: nzmax, or the analysis's count lnz
    if (f->is_super)
      return f->xsize * sizeof(double) + f->ssize * sizeof(int);
    const double entries =
      f->xtype == CHOLMOD_PATTERN ? data->common.lnz : double(f->nzmax);
    return static_cast<std::size_t>(entries) * (sizeof(double) + sizeof(int));
  }

  void
  SparseCholesky::factorize(const SparseMatrix<double> &matrix)
  {
    factorize(matrix, all_rows(matrix.m()));
  }

  void
  SparseCholesky::analyze(const SparseMatrix<double>                 &matrix,
                          const std::vector<types::global_dof_index> &rows)
  {
    data->free_factor();
    const unsigned int n = rows.size();
    data->n              = n;
    if (n == 0)
      return;
    // the pattern alone: a third of the matrix's bytes, beside whatever
    // else runs
    cholmod_sparse *a =
      upper_triangle(matrix, rows, false, data->common, /*values*/ false);
    AssertThrow(a != nullptr, ExcMessage(does_not_fit(what, n)));
    data->keep_pattern(a);
    data->factor = analyze_with_best_ordering(a,
                                              matrix.get_sparsity_pattern(),
                                              rows,
                                              data->common);
    // factorize() makes the matrix with its values
    cholmod_free_sparse(&a, &data->common);
    AssertThrow(data->factor != nullptr, ExcMessage(does_not_fit(what, n)));
  }

  void
  SparseCholesky::factorize(const SparseMatrix<double>                 &matrix,
                            const std::vector<types::global_dof_index> &rows)
  {
    const unsigned int n = rows.size();
    // a numerical factor goes before the new matrix is made; a symbolic
    // analysis waiting for its values stays
    if (n == 0 ||
        (data->factor != nullptr && data->factor->xtype != CHOLMOD_PATTERN))
      data->free_factor();
    if (n == 0)
      {
        data->n = 0;
        return;
      }
    cholmod_sparse *a = upper_triangle(matrix, rows, false, data->common);
    AssertThrow(a != nullptr, ExcMessage(does_not_fit(what, n)));
    // A symbolic analysis of this pattern (analyze()) is the one the
    // ordering below would make: the symbolic stage depends on the
    // pattern alone.
    const bool analysed =
      data->factor != nullptr && data->n == n && data->has_analysed_pattern(a);
    if (!analysed)
      {
        data->free_factor();
        data->n      = n;
        data->factor = analyze_with_best_ordering(a,
                                                  matrix.get_sparsity_pattern(),
                                                  rows,
                                                  data->common);
      }
    // a numerical factor serves no factorize_as()
    std::vector<int>().swap(data->analysed_starts);
    std::vector<int>().swap(data->analysed_rows);
    factorize_numerically(a);
  }

  void
  SparseCholesky::analyze(const SparseMatrix<double> &matrix)
  {
    data->free_factor();
    const unsigned int n = matrix.m();
    data->n              = n;
    if (n == 0)
      return;
    cholmod_sparse *a = upper_triangle(matrix, all_rows(n), true, data->common);
    AssertThrow(a != nullptr, ExcMessage(does_not_fit(what, n)));
    data->keep_pattern(a);
    data->factor = analyze_with_best_ordering(a,
                                              matrix.get_sparsity_pattern(),
                                              all_rows(n),
                                              data->common);
    cholmod_free_sparse(&a, &data->common);
    AssertThrow(data->factor != nullptr, ExcMessage(does_not_fit(what, n)));
  }

  void
  SparseCholesky::factorize_as(const SparseCholesky       &analysed,
                               const SparseMatrix<double> &matrix)
  {
    AssertThrow(analysed.data->factor != nullptr &&
                  analysed.data->n == matrix.m(),
                ExcMessage("SparseCholesky::factorize_as: the analysis is "
                           "of another matrix size."));
    data->free_factor();
    const unsigned int n = matrix.m();
    data->n              = n;
    cholmod_sparse *a = upper_triangle(matrix, all_rows(n), true, data->common);
    AssertThrow(a != nullptr, ExcMessage(does_not_fit(what, n)));
    // An entry outside the analysed pattern would be dropped silently.
    const bool same_pattern = analysed.data->has_analysed_pattern(a);
    if (!same_pattern)
      cholmod_free_sparse(&a, &data->common);
    AssertThrow(same_pattern,
                ExcMessage("SparseCholesky::factorize_as: the matrix of " +
                           what +
                           " has another sparsity pattern than the "
                           "analysed one."));
    // The copy of a symbolic factor is its structure only; the values
    // are allocated by cholmod_factorize.
    data->factor = cholmod_copy_factor(analysed.data->factor, &data->common);
    factorize_numerically(a);
  }

  void
  SparseCholesky::factorize_numerically(cholmod_sparse_struct *a)
  {
    const unsigned int n = data->n;
    if (data->factor != nullptr)
      cholmod_factorize(a, data->factor, &data->common);
    const bool out_of_memory = data->factor == nullptr ||
                               data->common.status == CHOLMOD_OUT_OF_MEMORY ||
                               data->common.status == CHOLMOD_TOO_LARGE;
    const bool positive_definite = !out_of_memory &&
                                   data->common.status == CHOLMOD_OK &&
                                   data->factor->minor == n;
    cholmod_free_sparse(&a, &data->common);
    AssertThrow(!out_of_memory, ExcMessage(does_not_fit(what, n)));
    AssertThrow(positive_definite,
                ExcMessage("The sparse Cholesky factorisation of " + what +
                           " found it not positive definite."));
  }

  void
  SparseCholesky::solve(std::vector<double> &block,
                        const unsigned int   n_columns) const
  {
    const unsigned int n = data->n;
    AssertDimension(block.size(), std::size_t(n) * n_columns);
    if (n == 0 || n_columns == 0)
      return;
    AssertThrow(data->factor != nullptr &&
                  data->factor->xtype != CHOLMOD_PATTERN,
                ExcMessage("SparseCholesky::solve before a factorisation."));
    cholmod_dense b;
    b.nrow  = n;
    b.ncol  = n_columns;
    b.nzmax = std::size_t(n) * n_columns;
    b.d     = n;
    b.x     = block.data();
    b.z     = nullptr;
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    cholmod_dense *solution =
      cholmod_solve(CHOLMOD_A, data->factor, &b, &data->common);
    AssertThrow(solution != nullptr,
                ExcMessage("CHOLMOD could not solve with the factor of " +
                           what + "."));
    std::memcpy(block.data(),
                solution->x,
                sizeof(double) * std::size_t(n) * n_columns);
    cholmod_free_dense(&solution, &data->common);
  }
} // namespace PlateOnHalfspace
