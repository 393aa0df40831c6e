/**
 * The reductions of a run on several processes (doc/parallel.md): a
 * vector whose entries each rank filled for its own rows (zero elsewhere)
 * becomes the whole vector on every rank. Each entry is one rank's value
 * plus zeros, so every rank gets the same bits whatever the order of the
 * sum. Where several ranks add to one entry (sum_shared_entries_over_ranks()),
 * one rank sums and sends the result to all, for the same reason: every
 * rank must take the same contact decisions from the same bits.
 */
#ifndef plate_on_halfspace_base_sum_over_ranks_h
#define plate_on_halfspace_base_sum_over_ranks_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/vector.h>

#include <string>

namespace PlateOnHalfspace
{
  /** The number of ranks of @p communicator; 1 where MPI is not
   *  initialised (the unit tests, the library without mpirun). */
  inline unsigned int
  n_ranks(const MPI_Comm communicator)
  {
    return dealii::Utilities::MPI::job_supports_mpi() ?
             dealii::Utilities::MPI::n_mpi_processes(communicator) :
             1;
  }

  /** This process's rank in @p communicator; 0 without MPI. */
  inline unsigned int
  rank_in(const MPI_Comm communicator)
  {
    return dealii::Utilities::MPI::job_supports_mpi() ?
             dealii::Utilities::MPI::this_mpi_process(communicator) :
             0;
  }

  /** @p v summed over the ranks of @p communicator, in place. */
  inline void
  sum_over_ranks(dealii::Vector<double> &v, const MPI_Comm communicator)
  {
    if (n_ranks(communicator) == 1)
      return;
    const dealii::ArrayView<double> view = dealii::make_array_view(v);
    dealii::Utilities::MPI::sum(dealii::ArrayView<const double>(view.data(),
                                                                view.size()),
                                communicator,
                                view);
  }

  /** The entries of @p v as the count of one MPI message; throws, naming
   *  @p caller, where an int cannot count them. */
  inline int
  message_count(const dealii::ArrayView<double> &v, const char *caller)
  {
    const int count = static_cast<int>(v.size());
    AssertThrow(static_cast<std::size_t>(count) == v.size(),
                dealii::ExcMessage(std::string(caller) +
                                   ": more entries than one MPI message "
                                   "holds"));
    return count;
  }

  /** Rank 0's @p v on every rank of @p communicator, in place. */
  inline void
  broadcast_from_first_rank(const dealii::ArrayView<double> &v,
                            const MPI_Comm                   communicator)
  {
    if (n_ranks(communicator) == 1 || v.size() == 0)
      return;
    const int count = message_count(v, "broadcast_from_first_rank");
    const int error = MPI_Bcast(v.data(), count, MPI_DOUBLE, 0, communicator);
    AssertThrowMPI(error);
  }

  /**
   * @p v summed over the ranks of @p communicator, in place, where
   * several ranks hold parts of one entry: summed on rank 0 and broadcast,
   * so that every rank holds the same bits (an all-reduce promises that
   * only for the sum_over_ranks() case).
   */
  inline void
  sum_shared_entries_over_ranks(const dealii::ArrayView<double> &v,
                                const MPI_Comm                   communicator)
  {
    if (n_ranks(communicator) == 1 || v.size() == 0)
      return;
    const int  count = message_count(v, "sum_shared_entries_over_ranks");
    const bool root  = rank_in(communicator) == 0;
    int        error = MPI_Reduce(root ? MPI_IN_PLACE : v.data(),
                           v.data(),
                           count,
                           MPI_DOUBLE,
                           MPI_SUM,
                           0,
                           communicator);
    AssertThrowMPI(error);
    broadcast_from_first_rank(v, communicator);
  }
} // namespace PlateOnHalfspace

#endif
