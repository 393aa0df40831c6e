#include <plate_on_halfspace/base/error_on_every_rank.h>

#include <mpi.h>

#include <chrono>
#include <thread>

namespace PlateOnHalfspace
{
  namespace
  {
    MPI_Comm &
    agreement_communicator()
    {
      static MPI_Comm communicator = MPI_COMM_NULL;
      return communicator;
    }
  } // namespace

  void
  begin_failure_agreement()
  {
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (size > 1)
      MPI_Comm_dup(MPI_COMM_WORLD, &agreement_communicator());
  }

  bool
  every_rank_fails_alike(const double seconds)
  {
    const MPI_Comm communicator = agreement_communicator();
    if (communicator == MPI_COMM_NULL)
      return true;
    // A barrier that completes only once every rank has failed; polled,
    // so that a rank that failed alone gives up after the time allowed.
    MPI_Request request;
    if (MPI_Ibarrier(communicator, &request) != MPI_SUCCESS)
      return false;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration<double>(seconds);
    for (;;)
      {
        int done = 0;
        if (MPI_Test(&request, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS)
          return false;
        if (done)
          return true;
        if (std::chrono::steady_clock::now() > deadline)
          return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
  }
} // namespace PlateOnHalfspace
