/**
 * SIGINT and SIGTERM end a run at a safe point (doc/outputs.md, "Interrupted
 * and killed runs"): the signal handler only records the signal, and the
 * computation asks at its safe points (between cycles and phases, per
 * contact iteration, per conjugate gradient step, per batch of cell pairs)
 * whether one arrived; if so it throws Interrupted, the driver restores the
 * earlier results and main() exits with 128 + the signal's number.
 *
 * Why not act in the handler: restoring the results means listing and
 * renaming files, which is not async-signal-safe, and the computation may be
 * inside a library (LAPACK, MUMPS, deal.II's tasks) that must not be left
 * half way. A second signal while the first is pending stops the process at
 * once (the default action), for a computation that does not reach a safe
 * point soon enough; the next run into the directory then recovers as after
 * a kill. Once the results are committed or the earlier ones restored,
 * release_signals() gives both signals their default action back.
 *
 * Under MPI every rank gets the signal, but not at the same instant: check()
 * is collective (the largest signal number over the ranks), so that all
 * ranks leave at the same safe point and none waits forever in a collective
 * step for one that left (doc/parallel.md).
 */
#ifndef plate_on_halfspace_base_interruption_h
#define plate_on_halfspace_base_interruption_h

#include <mpi.h>

#include <exception>
#include <string>

namespace PlateOnHalfspace
{
  /** A run stopped by SIGINT or SIGTERM at a safe point. */
  class Interrupted : public std::exception
  {
  public:
    /** @p committed: the signal came after the results were written whole
     *  (ResultsOutput::commit()), which then stay. */
    explicit Interrupted(const int signal_number, const bool committed = false);

    /** "interrupted by SIGINT" (or SIGTERM). */
    const char *
    what() const noexcept override;

    /** The signal's number: the program exits with 128 + it. */
    int
    signal_number() const
    {
      return number;
    }

    /** Whether the results were already written whole when it came. */
    bool
    results_committed() const
    {
      return committed;
    }

  private:
    int         number;
    bool        committed;
    std::string message;
  };

  namespace Interruption
  {
    /**
     * Record SIGINT and SIGTERM from now on instead of dying at once (the
     * program's main() calls it; library users and the unit tests keep the
     * default action).
     */
    void
    catch_signals();

    /**
     * The ranks that check() agrees over: the driver's communicator while
     * it runs. MPI_COMM_NULL (the default): this process alone.
     */
    void
    set_communicator(const MPI_Comm communicator);

    /** The signal recorded so far on this process (0: none). */
    int
    pending_signal();

    /**
     * Throws Interrupted if a signal arrived on any rank of the registered
     * communicator. Collective: every rank calls it at the same point.
     */
    void
    check();

    /**
     * Throws Interrupted if a signal arrived and this process runs alone;
     * on several processes it leaves the decision to the next check(), so
     * it may be called where the ranks do not go in step.
     */
    void
    check_if_alone();

    /**
     * From now on SIGINT and SIGTERM take their default action again, and
     * the signal recorded so far (0: none) is returned. The run calls it
     * once its results are committed or its earlier results restored:
     * what follows (freeing the run's memory, the libraries' threads,
     * MPI_Finalize) has no safe point, so a signal must end the process at
     * once instead of being recorded for a check that never comes.
     */
    int
    release_signals();
  } // namespace Interruption
} // namespace PlateOnHalfspace

#endif
