/**
 * The fill-reducing ordering that the plate's sparse factors share: METIS's
 * nested dissection of the quotient graph of the unknowns with equal rows
 * (doc/performance.md, "Orderings of the sparse factors"). CHOLMOD takes it
 * on one process (sparse_cholesky.h), MUMPS on several
 * (distributed_sparse_direct.h).
 */
#ifndef plate_on_halfspace_base_nested_dissection_h
#define plate_on_halfspace_base_nested_dissection_h

#include <deal.II/lac/sparsity_pattern.h>

#include <mutex>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * A nested-dissection ordering of the unknowns @p rows of @p pattern
   * (a symmetric pattern): position k holds the index into @p rows of the
   * unknown eliminated k-th. METIS orders the quotient graph of the
   * unknowns with equal rows, each group's unknowns kept together; the
   * plate's three fields at a node have equal rows, so METIS sees a third
   * of the unknowns and a ninth of the entries. Empty if METIS fails or
   * the pattern is not symmetric; throws std::bad_alloc where the graph
   * does not fit. Hold metis_ordering_lock() while calling it.
   */
  std::vector<int>
  nested_dissection(const SparsityPattern                      &pattern,
                    const std::vector<types::global_dof_index> &rows);

  /**
   * METIS seeds the C library's srand() at each call and draws from
   * rand(): two orderings side by side would interleave their draws and
   * depend on the timing. Every METIS ordering of the process holds this
   * lock, so that each is the ordering it is alone.
   */
  std::mutex &
  metis_ordering_lock();
} // namespace PlateOnHalfspace

#endif
