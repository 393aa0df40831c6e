/**
 * An error that every rank of a distributed run meets alike, because it is
 * decided from what all ranks hold the same (the mesh and its partition,
 * doc/parallel.md). Unlike a failure that one rank meets during the solve,
 * it needs no MPI_Abort: main.cc reports it once, in one "Error:" line like
 * a bad scene, and every rank ends with exit status 1.
 */
#ifndef plate_on_halfspace_base_error_on_every_rank_h
#define plate_on_halfspace_base_error_on_every_rank_h

#include <exception>
#include <stdexcept>
#include <string>

namespace PlateOnHalfspace
{
  class ErrorOnEveryRank : public std::runtime_error
  {
  public:
    explicit ErrorOnEveryRank(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /** How long a failing rank waits for the others to fail alike: those
   *  fail at the same point of the same computation, within moments. */
  constexpr double failure_agreement_seconds = 5.;

  /**
   * Collective, once, right after MPI_Init: a communicator of its own for
   * every_rank_fails_alike(), so that its agreement never meets the
   * collective steps the other ranks may be waiting in.
   */
  void
  begin_failure_agreement();

  /** Where a rank failed, for every_rank_fails_alike(). */
  enum class FailureSite
  {
    /** anywhere in the run: the run ends (main.cc) */
    run = 1,
    /** the nested start's solve on a coarser mesh, after which the run
     *  goes on without it (PlateOnHalfspaceProblem) */
    coarse_solve = 2
  };

  /**
   * Whether every rank of the run reaches this call within @p seconds,
   * each from the same @p site; each rank that fails calls it on its way
   * out. Errors that are
   * not thrown as ErrorOnEveryRank may still be met by every rank alike
   * where they are decided from what all ranks hold the same (a load off
   * the plate, a soil matrix that is not positive definite): then all
   * ranks arrive at about the same moment, and the run reports the error
   * once, like a bad scene. A rank that fails alone is not answered and
   * stops the others through MPI_Abort (doc/parallel.md, "Choices and
   * their reasons"). True on one process. Each call is one agreement of
   * all ranks: a rank that calls it a second time meets the others'
   * second call. Ranks that fail at different sites all get false, and
   * a rank whose agreement timed out gets false from then on at once.
   */
  bool
  every_rank_fails_alike(FailureSite site, double seconds);

  /**
   * Whether @p error, met at @p site, is met by every rank alike: on one
   * process and for an ErrorOnEveryRank at once, otherwise through
   * every_rank_fails_alike() with failure_agreement_seconds.
   */
  bool
  every_rank_fails_alike(const std::exception &error, FailureSite site);
} // namespace PlateOnHalfspace

#endif
