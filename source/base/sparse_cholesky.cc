#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/base/sparse_cholesky.h>

#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <string>

namespace PlateOnHalfspace
{
  struct SparseCholesky::Data
  {
    cholmod_common  common;
    cholmod_factor *factor = nullptr;
    unsigned int    n      = 0;
  };

  SparseCholesky::SparseCholesky()
    : data(std::make_unique<Data>())
  {
    cholmod_start(&data->common);
    data->common.supernodal = CHOLMOD_SUPERNODAL;
  }

  SparseCholesky::~SparseCholesky()
  {
    if (data->factor != nullptr)
      cholmod_free_factor(&data->factor, &data->common);
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
    // supernodal: xsize values and ssize row indices; simplicial: nzmax
    return f->is_super ? f->xsize * sizeof(double) + f->ssize * sizeof(int) :
                         f->nzmax * (sizeof(double) + sizeof(int));
  }

  void
  SparseCholesky::factorize(const SparseMatrix<double>                 &matrix,
                            const std::vector<types::global_dof_index> &rows)
  {
    if (data->factor != nullptr)
      cholmod_free_factor(&data->factor, &data->common);
    const unsigned int n = rows.size();
    data->n              = n;
    if (n == 0)
      return;

    std::vector<int> position(matrix.m(), -1);
    for (unsigned int i = 0; i < n; ++i)
      position[rows[i]] = i;

    // Upper triangle of A(rows, rows) in compressed columns (A symmetric:
    // row i of A is column i).
    std::vector<std::vector<std::pair<int, double>>> columns(n);
    std::size_t                                      nnz = 0;
    for (unsigned int j = 0; j < n; ++j)
      {
        for (auto entry = matrix.begin(rows[j]); entry != matrix.end(rows[j]);
             ++entry)
          {
            const int i = position[entry->column()];
            if (i >= 0 && i <= static_cast<int>(j) && entry->value() != 0.)
              columns[j].emplace_back(i, entry->value());
          }
        std::sort(columns[j].begin(), columns[j].end());
        nnz += columns[j].size();
      }
    cholmod_sparse *a = cholmod_allocate_sparse(n,
                                                n,
                                                nnz,
                                                /*sorted*/ 1,
                                                /*packed*/ 1,
                                                /*stype*/ 1,
                                                CHOLMOD_REAL,
                                                &data->common);
    AssertThrow(a != nullptr,
                ExcMessage("A sparse matrix of " + std::to_string(n) +
                           " unknowns needs more memory than this machine "
                           "has: reduce the node count (Discretization/"
                           "Subdivisions x and y, Discretization/Initial "
                           "refinements, Adaptivity/Max cells)."));
    int    *p = static_cast<int *>(a->p);
    int    *r = static_cast<int *>(a->i);
    double *x = static_cast<double *>(a->x);
    p[0]      = 0;
    for (unsigned int j = 0; j < n; ++j)
      {
        int k = p[j];
        for (const auto &e : columns[j])
          {
            r[k] = e.first;
            x[k] = e.second;
            ++k;
          }
        p[j + 1] = k;
      }

    data->factor = cholmod_analyze(a, &data->common);
    if (data->factor != nullptr)
      cholmod_factorize(a, data->factor, &data->common);
    const bool out_of_memory = data->factor == nullptr ||
                               data->common.status == CHOLMOD_OUT_OF_MEMORY ||
                               data->common.status == CHOLMOD_TOO_LARGE;
    const bool positive_definite = !out_of_memory &&
                                   data->common.status == CHOLMOD_OK &&
                                   data->factor->minor == n;
    cholmod_free_sparse(&a, &data->common);
    AssertThrow(!out_of_memory,
                ExcMessage("A sparse Cholesky factorisation of " +
                           std::to_string(n) +
                           " unknowns needs more memory than this machine "
                           "has: reduce the node count (Discretization/"
                           "Subdivisions x and y, Discretization/Initial "
                           "refinements, Adaptivity/Max cells)."));
    AssertThrow(positive_definite,
                ExcMessage("The plate's rotation block is not positive "
                           "definite (a mechanism inside the plate)."));
  }

  void
  SparseCholesky::solve(std::vector<double> &block,
                        const unsigned int   n_columns) const
  {
    const unsigned int n = data->n;
    AssertDimension(block.size(), std::size_t(n) * n_columns);
    if (n == 0 || n_columns == 0)
      return;
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
                ExcMessage("CHOLMOD could not solve with the plate's "
                           "rotation block."));
    std::memcpy(block.data(),
                solution->x,
                sizeof(double) * std::size_t(n) * n_columns);
    cholmod_free_dense(&solution, &data->common);
  }
} // namespace PlateOnHalfspace
