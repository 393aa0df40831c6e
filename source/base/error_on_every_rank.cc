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
  every_rank_fails_alike(const FailureSite site, const double seconds)
  {
    const MPI_Comm communicator = agreement_communicator();
    if (communicator == MPI_COMM_NULL)
      return true;
    // An agreement that timed out stays open (MPI cannot cancel a
    // collective request): a later one on this rank would meet the
    // others' earlier one.
    static bool timed_out = false;
    if (timed_out)
      return false;
    // The smallest and the largest site over the ranks, which completes
    // only once every rank has failed; polled, so that a rank that failed
    // alone gives up after the time allowed.
    // (both kept: MPI reads and writes them until the request completes,
    // which for one that timed out is after this call)
    static int mine[2], sites[2];
    const int  code = static_cast<int>(site);
    mine[0]         = code;
    mine[1]         = -code;
    MPI_Request request;
    if (MPI_Iallreduce(
          mine, sites, 2, MPI_INT, MPI_MIN, communicator, &request) !=
        MPI_SUCCESS)
      return false;
    const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;)
      {
        int done = 0;
        if (MPI_Test(&request, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS)
          return false;
        if (done)
          return sites[0] == code && -sites[1] == code;
        if (std::chrono::steady_clock::now() > deadline)
          {
            timed_out = true;
            return false;
          }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
  }

  bool
  every_rank_fails_alike(const std::exception &error, const FailureSite site)
  {
    return agreement_communicator() == MPI_COMM_NULL ||
           dynamic_cast<const ErrorOnEveryRank *>(&error) != nullptr ||
           every_rank_fails_alike(site, failure_agreement_seconds);
  }
} // namespace PlateOnHalfspace
