#include <deal.II/base/thread_management.h>

#include <plate_on_halfspace/base/tasks.h>

#include <exception>
#include <vector>

namespace PlateOnHalfspace
{
  void
  run_tasks(const unsigned int                       n_tasks,
            const std::function<void(unsigned int)> &work)
  {
    if (n_tasks == 1)
      {
        work(0);
        return;
      }
    std::vector<std::exception_ptr>  failures(n_tasks);
    dealii::Threads::TaskGroup<void> tasks;
    for (unsigned int t = 0; t < n_tasks; ++t)
      tasks += dealii::Threads::new_task([&work, &failures, t]() {
        try
          {
            work(t);
          }
        catch (...)
          {
            failures[t] = std::current_exception();
          }
      });
    tasks.join_all();
    for (const std::exception_ptr &failure : failures)
      if (failure)
        std::rethrow_exception(failure);
  }
} // namespace PlateOnHalfspace
