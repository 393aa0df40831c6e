/**
 * A one-line progress display for the long phases of a run (the dense
 * Galerkin assembly, the hierarchical compression, the H-Cholesky
 * factorisation): the phase, the percentage done and the elapsed time on
 * stderr, redrawn in place with a carriage return, e.g.
 *
 *   Dense Galerkin flexibility:  42 %  12.3 s
 *
 * Process-wide switch: nothing is shown unless ProgressReport::enable(true)
 * was called (the default is off, so library users and the tests see
 * nothing). The program's driver calls it with Output/Verbosity > 0. Even
 * then, a report stays silent when stderr is not a terminal
 * (isatty(STDERR_FILENO)): a redirected stderr gets no carriage-return
 * lines. Nothing is ever written to stdout.
 *
 * Boost's boost::timer::progress_display was not used: it draws a scale and
 * a row of asterisks over three lines, shows neither the phase nor the
 * elapsed time, writes on construction, and its counter is not safe to
 * increment from several threads.
 */
#ifndef plate_on_halfspace_base_progress_h
#define plate_on_halfspace_base_progress_h

#include <atomic>
#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <mutex>
#include <string>

namespace PlateOnHalfspace
{
  /**
   * Progress of one phase of @p n_steps steps.
   *
   * Threads: add() may be called from any number of threads (deal.II tasks)
   * at once. It costs a relaxed atomic increment, plus a clock reading when
   * the report is shown; the line is redrawn by whichever caller finds the
   * redraw interval elapsed (at most a few times per second, the others do
   * not wait for it). Callers should still count coarse steps (cell-pair
   * chunks, blocks), not single entries.
   *
   * Quick phases stay invisible: the line first appears when the phase has
   * run for the initial delay (half a second), so a run of small problems
   * does not fill the terminal with finished lines.
   *
   * End: finish() draws the final line (100 %) and ends it with a newline;
   * the destructor does the same when finish() was not called, and when
   * the phase is left by an exception it ends the line with "interrupted"
   * instead, so that the error message starts on a fresh line.
   */
  class ProgressReport
  {
  public:
    /**
     * Show progress reports from now on (true) or not (false, the
     * default). The application's driver calls this once with
     * Output/Verbosity > 0. Reports already under way keep their state.
     */
    static void
    enable(const bool on);

    /** Whether enable(true) is in force. */
    static bool
    enabled();

    /**
     * A report of the phase @p phase on stderr; silent unless enabled()
     * and stderr is a terminal.
     */
    ProgressReport(const std::string &phase, const std::uint64_t n_steps);

    /**
     * A report rendered into @p out whatever enabled() and the terminal
     * say (for tests and for callers that own a terminal stream), with the
     * given delay before the first line and least interval between two
     * redraws, in seconds (0 and 0 draw at every add()).
     */
    ProgressReport(const std::string  &phase,
                   const std::uint64_t n_steps,
                   std::ostream       &out,
                   const double        initial_delay   = 0.5,
                   const double        redraw_interval = 0.25);

    ~ProgressReport();

    ProgressReport(const ProgressReport &) = delete;
    ProgressReport &
    operator=(const ProgressReport &) = delete;

    /** @p steps more steps are done. Thread-safe. */
    void
    add(const std::uint64_t steps = 1);

    /**
     * Done steps are at least @p done (for a callee that reports its own
     * position, such as hmat-oss's factorisation). Thread-safe.
     */
    void
    advance_to(const std::uint64_t done);

    /** Draw the final line (if anything was shown) and end it. Once. */
    void
    finish();

    /** Steps done so far. */
    std::uint64_t
    n_done() const
    {
      return done.load(std::memory_order_relaxed);
    }

    std::uint64_t
    n_steps() const
    {
      return total;
    }

    /** Whether this report draws at all. */
    bool
    is_shown() const
    {
      return out != nullptr;
    }

    /**
     * The line for @p done of @p n_steps steps after @p seconds, without
     * the carriage return: "phase:  42 %  12.3 s" (from a minute on "2 min
     * 05 s"). The percentage is rounded down and capped at 100 (a callee
     * may count a few more steps than announced); 0 steps count as done.
     */
    static std::string
    format_line(const std::string  &phase,
                const std::uint64_t done,
                const std::uint64_t n_steps,
                const double        seconds);

  private:
    using Clock = std::chrono::steady_clock;

    ProgressReport(const std::string  &phase,
                   const std::uint64_t n_steps,
                   std::ostream       *out,
                   const double        initial_delay,
                   const double        redraw_interval);

    const std::string   phase;
    const std::uint64_t total;
    /** Where the line goes; nullptr when the report is silent. */
    std::ostream *const out;
    /** In clock ticks. */
    const Clock::rep        initial_delay, redraw_interval;
    const Clock::time_point start;
    /** std::uncaught_exceptions() at construction: the destructor runs
     *  during unwinding when there are more. */
    const int uncaught_at_start;

    std::atomic<std::uint64_t> done{0};
    /** Clock ticks since start before which add() does not redraw. */
    std::atomic<Clock::rep> next_draw;
    /** Held by the thread that draws; the others skip the redraw. */
    std::mutex drawing;
    /** Length of the last line drawn (to blank a longer one); 0: none. */
    std::size_t drawn_width = 0;
    bool        finished    = false;

    /** Redraw if the interval has elapsed and nobody else is drawing. */
    void
    maybe_draw();

    /** The final line, ending with @p note, and the newline. Once. */
    void
    end_line(const char *note);

    /** Draw the line at @p now (ticks since start) with @p note. Needs the
     *  lock. */
    void
    draw(const Clock::rep now, const char *note, const bool final_line);
  };
} // namespace PlateOnHalfspace

#endif
