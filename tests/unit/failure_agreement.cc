// every_rank_fails_alike() (base/error_on_every_rank.h) on 2 processes,
// the agreement by which a failure that every rank meets alike is
// reported once and a failure of one rank stops the run (main.cc):
//  - both ranks call it from the same site: true on both, well within the
//    time allowed;
//  - both from different sites (one in the nested start's coarse solve,
//    one elsewhere): false on both, well within the time;
//  - rank 1 alone, allowed 0.3 s, while rank 0 waits in a collective
//    step of MPI_COMM_WORLD, as the other ranks of a run wait for the one
//    that failed: false on rank 1, and not before 0.3 s;
//  - rank 1 again after that: false at once.
// The verdicts only are printed.

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <plate_on_halfspace/base/error_on_every_rank.h>

#include <string>

#include "../tests.h"

using namespace PlateOnHalfspace;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   world = MPI_COMM_WORLD;
  const unsigned int rank = Utilities::MPI::this_mpi_process(world);
  initlog_on_first_rank(rank == 0);
  begin_failure_agreement();

  // "ok" where @p holds_here holds on every rank
  const auto verdict = [world](const std::string &what, const bool holds_here) {
    deallog << what << ": "
            << (Utilities::MPI::min(holds_here ? 1 : 0, world) == 1 ? "ok" :
                                                                      "FAILED")
            << std::endl;
  };

  // every rank fails at the same point
  Timer      timer;
  const bool alike = every_rank_fails_alike(FailureSite::run, 30.);
  verdict("every rank failing alike: agreed on every rank", alike);
  verdict("every rank failing alike: agreed well within the time",
          timer.wall_time() < 10.);

  // the ranks fail at different sites
  timer.restart();
  const bool apart = every_rank_fails_alike(
    rank == 0 ? FailureSite::run : FailureSite::coarse_solve, 30.);
  verdict("failing at different sites: refused on every rank", !apart);
  verdict("failing at different sites: refused well within the time",
          timer.wall_time() < 10.);

  // rank 1 fails alone while rank 0 waits in a collective step
  bool   alone_refused = true;
  double waited        = 0.;
  if (rank == 1)
    {
      timer.restart();
      alone_refused = !every_rank_fails_alike(FailureSite::run, 0.3);
      waited        = timer.wall_time();
    }
  MPI_Barrier(world);
  verdict("one rank failing alone: not agreed", alone_refused);
  verdict("one rank failing alone: waited the time allowed",
          rank != 1 || waited >= 0.3);
  // once timed out, rank 1 refuses at once
  bool refused_at_once = true;
  if (rank == 1)
    {
      timer.restart();
      refused_at_once = !every_rank_fails_alike(FailureSite::run, 30.) &&
                        timer.wall_time() < 10.;
    }
  verdict("after its time ran out: refused at once", refused_at_once);
  // Rank 1's agreement is still open, as in a run that then stops through
  // MPI_Abort; rank 0 answers it here so that both end cleanly.
  if (rank == 0)
    every_rank_fails_alike(FailureSite::run, 30.);
  MPI_Barrier(world);
}
