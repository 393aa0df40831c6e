/**
 * Independent pieces of work as deal.II tasks, with their failures
 * carried back: deal.II's Task<void>::join() does not rethrow a task's
 * exception, so each task keeps its own, and the first (by the pieces'
 * order) is rethrown on the calling thread once every task has ended, so
 * that none still uses the caller's frame while an error unwinds it.
 */
#ifndef plate_on_halfspace_base_tasks_h
#define plate_on_halfspace_base_tasks_h

#include <functional>

namespace PlateOnHalfspace
{
  /**
   * Run @p work(t) for t < @p n_tasks, each as a task (one alone on the
   * calling thread), and wait for all; then rethrow the first failure.
   */
  void
  run_tasks(const unsigned int                       n_tasks,
            const std::function<void(unsigned int)> &work);
} // namespace PlateOnHalfspace

#endif
