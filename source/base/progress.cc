#include <plate_on_halfspace/base/progress.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>

namespace PlateOnHalfspace
{
  namespace
  {
    std::atomic<bool> reports_enabled{false};

    /** std::cerr if reports are enabled and stderr is a terminal. */
    std::ostream *
    terminal_or_nothing()
    {
      if (!reports_enabled.load(std::memory_order_relaxed))
        return nullptr;
      return isatty(STDERR_FILENO) ? &std::cerr : nullptr;
    }

    /** Seconds as clock ticks. */
    std::chrono::steady_clock::rep
    ticks(const double seconds)
    {
      return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
               std::chrono::duration<double>(seconds))
        .count();
    }
  } // namespace

  void
  ProgressReport::enable(const bool on)
  {
    reports_enabled.store(on, std::memory_order_relaxed);
  }

  bool
  ProgressReport::enabled()
  {
    return reports_enabled.load(std::memory_order_relaxed);
  }

  ProgressReport::ProgressReport(const std::string  &phase,
                                 const std::uint64_t n_steps)
    : ProgressReport(phase, n_steps, terminal_or_nothing(), 0.5, 0.25)
  {}

  ProgressReport::ProgressReport(const std::string  &phase,
                                 const std::uint64_t n_steps,
                                 std::ostream       &out,
                                 const double        initial_delay,
                                 const double        redraw_interval)
    : ProgressReport(phase, n_steps, &out, initial_delay, redraw_interval)
  {}

  ProgressReport::ProgressReport(const std::string  &phase,
                                 const std::uint64_t n_steps,
                                 std::ostream       *out,
                                 const double        initial_delay,
                                 const double        redraw_interval)
    : phase(phase)
    , total(n_steps)
    , out(out)
    , initial_delay(ticks(initial_delay))
    , redraw_interval(ticks(redraw_interval))
    , start(Clock::now())
    , uncaught_at_start(std::uncaught_exceptions())
    , next_draw(ticks(initial_delay))
  {}

  ProgressReport::~ProgressReport()
  {
    try
      {
        if (std::uncaught_exceptions() > uncaught_at_start)
          end_line(" interrupted");
        else
          end_line("");
      }
    catch (...)
      {
        // a destructor must not throw; the line stays as it is
      }
  }

  void
  ProgressReport::add(const std::uint64_t steps)
  {
    done.fetch_add(steps, std::memory_order_relaxed);
    if (out != nullptr)
      maybe_draw();
  }

  void
  ProgressReport::advance_to(const std::uint64_t position)
  {
    std::uint64_t current = done.load(std::memory_order_relaxed);
    while (
      current < position &&
      !done.compare_exchange_weak(current, position, std::memory_order_relaxed))
      {}
    if (out != nullptr)
      maybe_draw();
  }

  void
  ProgressReport::finish()
  {
    end_line("");
  }

  void
  ProgressReport::maybe_draw()
  {
    const Clock::rep now = (Clock::now() - start).count();
    if (now < next_draw.load(std::memory_order_relaxed))
      return;
    // Whoever holds the lock draws; the others carry on counting.
    const std::unique_lock<std::mutex> lock(drawing, std::try_to_lock);
    if (!lock.owns_lock() || finished ||
        now < next_draw.load(std::memory_order_relaxed))
      return;
    next_draw.store(now + redraw_interval, std::memory_order_relaxed);
    draw(now, "", false);
  }

  void
  ProgressReport::end_line(const char *note)
  {
    const std::lock_guard<std::mutex> lock(drawing);
    if (finished)
      return;
    finished = true;
    if (out == nullptr)
      return;
    const Clock::rep now = (Clock::now() - start).count();
    // A phase that ended before its first line was due leaves none.
    if (drawn_width == 0 && now < initial_delay)
      return;
    if (*note == '\0')
      // Done: whatever the count, the phase is complete.
      done.store(std::max<std::uint64_t>(total, n_done()),
                 std::memory_order_relaxed);
    draw(now, note, true);
  }

  void
  ProgressReport::draw(const Clock::rep now,
                       const char      *note,
                       const bool       final_line)
  {
    const double seconds =
      std::chrono::duration<double>(Clock::duration(now)).count();
    std::string line = format_line(phase, n_done(), total, seconds) + note;
    const std::size_t width = line.size();
    // Blank what is left of a longer previous line.
    if (width < drawn_width)
      line.append(drawn_width - width, ' ');
    drawn_width = width;
    *out << '\r' << line;
    if (final_line)
      *out << '\n';
    out->flush();
  }

  std::string
  ProgressReport::format_line(const std::string  &phase,
                              const std::uint64_t done,
                              const std::uint64_t n_steps,
                              const double        seconds)
  {
    const unsigned int percent =
      (n_steps == 0 || done >= n_steps) ?
        100 :
        static_cast<unsigned int>(done * 100 / n_steps);
    char time[32];
    if (seconds < 60)
      std::snprintf(time, sizeof(time), "%.1f s", seconds);
    else
      {
        const long whole = static_cast<long>(seconds);
        std::snprintf(
          time, sizeof(time), "%ld min %02ld s", whole / 60, whole % 60);
      }
    char numbers[64];
    std::snprintf(numbers, sizeof(numbers), ": %3u %%  %s", percent, time);
    return phase + numbers;
  }
} // namespace PlateOnHalfspace
