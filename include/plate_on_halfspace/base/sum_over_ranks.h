/**
 * The one reduction of a run on several processes (doc/parallel.md): a
 * vector whose entries each rank filled for its own rows (zero elsewhere)
 * becomes the whole vector on every rank. Each entry is one rank's value
 * plus zeros, so every rank gets the same bits whatever the order of the
 * sum.
 */
#ifndef plate_on_halfspace_base_sum_over_ranks_h
#define plate_on_halfspace_base_sum_over_ranks_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/vector.h>

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
} // namespace PlateOnHalfspace

#endif
