// The distributed sparse direct solver (base/distributed_sparse_direct.h:
// MUMPS's LDL^T) on 3 processes, on a symmetric positive
// definite band matrix of 300 rows split in three unequal blocks of rows,
// with every 37th row not solved (its row removed, as the plate's pinned
// DoFs are):
//  - solve(): the residual of the solved rows within 1e-12 of the
//    right-hand side (an independent check of the solution), zero at the
//    rows not solved, and the same bits on every rank;
//  - solve_at() on rows of every rank, a row asked for twice, rows not
//    solved and the first and last rows: the same bits as solve() at
//    those rows, on every rank; and on no rows at all, an empty result;
//  - memory_consumption() over the ranks between the upper triangle's
//    values and a dense factor's;
//  - all rows on the last rank and none on the others: the same solution;
//  - a diagonal entry made negative: every rank refuses the matrix as not
//    positive definite.
// The verdicts only are printed.

#include <deal.II/base/mpi.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <plate_on_halfspace/base/distributed_sparse_direct.h>

#include <cmath>
#include <string>

#include "../tests.h"

using namespace PlateOnHalfspace;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   world = MPI_COMM_WORLD;
  const unsigned int rank    = Utilities::MPI::this_mpi_process(world);
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(world);
  initlog_on_first_rank(rank == 0);

  // A pentadiagonal matrix: 4 on the diagonal, -1 on the first and -0.5
  // on the second off-diagonals, diagonally dominant, so positive definite.
  const unsigned int     n = 300;
  DynamicSparsityPattern dsp(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = (i < 2 ? 0 : i - 2); j < std::min(n, i + 3); ++j)
      dsp.add(i, j);
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  SparseMatrix<double> matrix(pattern);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = (i < 2 ? 0 : i - 2); j < std::min(n, i + 3); ++j)
      matrix.set(i, j, i == j ? 4. : (i + 1 == j || j + 1 == i) ? -1. : -0.5);

  std::vector<bool> solved(n, true);
  for (unsigned int i = 5; i < n; i += 37)
    solved[i] = false;
  // unequal blocks: the first rank's is the smallest
  std::vector<unsigned int> starts(n_ranks + 1, 0);
  for (unsigned int r = 1; r < n_ranks; ++r)
    starts[r] = n * r / n_ranks + 7 * r;
  starts[n_ranks] = n;
  IndexSet owned(n);
  owned.add_range(starts[rank], starts[rank + 1]);

  DistributedSparseDirect solver;
  solver.factorize(matrix, solved, owned, world);

  Vector<double> f(n);
  for (unsigned int i = 0; i < n; ++i)
    f[i] = std::sin(0.1 * i) + 0.3 * std::cos(1.3 * i) + 1.;
  Vector<double> u;
  solver.solve(f, u);

  // the residual on the solved rows, with u zero at the others
  double residual = 0, off = 0;
  for (unsigned int i = 0; i < n; ++i)
    if (solved[i])
      {
        double row = -f[i];
        for (auto e = matrix.begin(i); e != matrix.end(i); ++e)
          row += e->value() * u[e->column()];
        residual = std::max(residual, std::abs(row));
      }
    else
      off = std::max(off, std::abs(u[i]));
  require("solve: the solved rows' residual within 1e-12 of |f|",
          Utilities::MPI::max(residual, world) <= 1e-12 * f.linfty_norm());
  require("solve: zero at the rows not solved",
          Utilities::MPI::max(off, world) == 0.);
  Vector<double> first_rank(u);
  Utilities::MPI::broadcast(first_rank.data(), n, 0, world);
  first_rank -= u;
  require("solve: the same bits on every rank",
          Utilities::MPI::max(first_rank.linfty_norm(), world) == 0.);

  std::vector<types::global_dof_index> rows = {0, 5, 42, 42, 150, n - 1};
  for (unsigned int r = 0; r < n_ranks; ++r)
    rows.push_back(starts[r]);
  Vector<double> values;
  solver.solve_at(f, rows, values);
  bool same = values.size() == rows.size();
  for (unsigned int k = 0; same && k < rows.size(); ++k)
    same = values[k] == u[rows[k]];
  require("solve_at: the same bits as solve() at the rows asked for "
          "(repeated, not solved, on every rank)",
          Utilities::MPI::min(same ? 1u : 0u, world) == 1u);
  Vector<double> first_values(values);
  Utilities::MPI::broadcast(first_values.data(), rows.size(), 0, world);
  first_values -= values;
  require("solve_at: the same bits on every rank",
          Utilities::MPI::max(first_values.linfty_norm(), world) == 0.);

  Vector<double> none;
  solver.solve_at(f, {}, none);
  require("solve_at: no rows, no values",
          Utilities::MPI::max(none.size(), world) == 0u);

  // The factor holds at least the solved rows' upper triangle (no
  // cancellation fills a band matrix's factor with zeros), and not more
  // than a dense one with its indices.
  std::size_t upper = 0;
  for (unsigned int i = 0; i < n; ++i)
    if (solved[i])
      for (auto e = matrix.begin(i); e != matrix.end(i); ++e)
        upper += e->column() >= i && solved[e->column()];
  const std::size_t held =
    Utilities::MPI::sum(solver.memory_consumption(), world);
  require("memory_consumption: over the ranks, at least the upper triangle's "
          "values and at most a dense factor's",
          held >= upper * sizeof(double) && held <= 3 * n * n * sizeof(double));

  // every row on the last rank, none on the others: the same solution
  IndexSet all_on_last(n);
  if (rank + 1 == n_ranks)
    all_on_last.add_range(0, n);
  DistributedSparseDirect on_last;
  on_last.factorize(matrix, solved, all_on_last, world);
  Vector<double> u_on_last;
  on_last.solve(f, u_on_last);
  u_on_last -= u;
  require("ranks without rows: the solution within 1e-14 of |u| of the split "
          "rows'",
          Utilities::MPI::max(u_on_last.linfty_norm(), world) <=
            1e-14 * u.linfty_norm());

  // one diagonal entry made negative: an indefinite matrix, which every
  // rank refuses
  SparseMatrix<double> indefinite(pattern);
  indefinite.copy_from(matrix);
  indefinite.set(150, 150, -4.);
  bool refused = false;
  try
    {
      DistributedSparseDirect rejecting;
      rejecting.factorize(indefinite, solved, owned, world);
    }
  catch (const ExceptionBase &e)
    {
      refused = std::string(e.what()).find("not positive definite") !=
                std::string::npos;
    }
  require("an indefinite matrix: refused on every rank, saying so",
          Utilities::MPI::min(refused ? 1u : 0u, world) == 1u);
}
