// ProgressReport (base/progress.h), the progress line of long phases:
//  - the line's format (phase, percentage rounded down and capped at 100,
//    seconds, from a minute on minutes and seconds);
//  - silence: nothing on std::cerr while reports are disabled (the
//    default), nor when they are enabled but stderr is not a terminal
//    (file descriptor 2 is pointed at /dev/null here, so the check does not
//    depend on how the test is run);
//  - counting: add() from several deal.II tasks at once loses no step,
//    advance_to() only moves forward, also while every add() redraws into
//    a stream;
//  - rendering into a given stream: carriage-return lines, the final line
//    at 100 % ended by a newline, a line ended with "interrupted" when an
//    exception leaves the phase, none for a phase shorter than the delay.
// Elapsed times are masked in the output ("T"), they depend on the machine.

#include <deal.II/base/thread_management.h>

#include <plate_on_halfspace/base/progress.h>

#include <fcntl.h>
#include <unistd.h>

#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  /** The lines drawn into a stream (split at '\r'), with the elapsed time
   *  after "%  " replaced by T, and '\n' shown as "<newline>". */
  std::vector<std::string>
  masked_lines(const std::string &drawn)
  {
    std::vector<std::string> lines;
    std::size_t              begin = 0;
    while (begin < drawn.size())
      {
        AssertThrow(drawn[begin] == '\r',
                    ExcMessage("a line does not start with '\\r'"));
        std::size_t end = drawn.find('\r', begin + 1);
        if (end == std::string::npos)
          end = drawn.size();
        std::string       line = drawn.substr(begin + 1, end - begin - 1);
        const std::size_t time = line.find("%  ");
        if (time != std::string::npos)
          {
            const std::size_t seconds = line.find(" s", time);
            line.replace(time + 3, seconds + 2 - (time + 3), "T");
          }
        const std::size_t newline = line.find('\n');
        if (newline != std::string::npos)
          line.replace(newline, 1, "<newline>");
        // trailing blanks that clear a longer previous line
        while (!line.empty() && line.back() == ' ')
          line.pop_back();
        lines.push_back(line);
        begin = end;
      }
    return lines;
  }

  /** What @p action writes to std::cerr. */
  template <typename Action>
  std::string
  written_to_cerr(const Action &action)
  {
    std::ostringstream captured;
    std::streambuf    *saved = std::cerr.rdbuf(captured.rdbuf());
    action();
    std::cerr.rdbuf(saved);
    return captured.str();
  }

  void
  run_phase()
  {
    ProgressReport report("silent phase", 10);
    for (unsigned int i = 0; i < 10; ++i)
      report.add();
    report.finish();
    AssertThrow(!report.is_shown(), ExcMessage("the report is shown"));
  }
} // namespace

int
main()
{
  initlog();

  // Format.
  deallog << ProgressReport::format_line("Phase", 0, 10, 0.04) << std::endl;
  deallog << ProgressReport::format_line("Phase", 5, 10, 1.26) << std::endl;
  deallog << ProgressReport::format_line("Phase", 2, 3, 59.9) << std::endl;
  deallog << ProgressReport::format_line("Phase", 10, 10, 75.4) << std::endl;
  deallog << ProgressReport::format_line("Phase", 12, 10, 3725.) << std::endl;
  deallog << ProgressReport::format_line("Phase", 0, 0, 0.) << std::endl;

  // Silent while disabled (the default).
  require("disabled by default", !ProgressReport::enabled());
  require("disabled: nothing on stderr", written_to_cerr(run_phase).empty());

  // Enabled, but stderr is not a terminal.
  {
    const int saved_stderr = dup(STDERR_FILENO);
    const int null         = open("/dev/null", O_WRONLY);
    AssertThrow(saved_stderr >= 0 && null >= 0, ExcMessage("dup/open"));
    dup2(null, STDERR_FILENO);
    close(null);
    ProgressReport::enable(true);
    const std::string written = written_to_cerr(run_phase);
    ProgressReport::enable(false);
    dup2(saved_stderr, STDERR_FILENO);
    close(saved_stderr);
    require("enabled, stderr not a terminal: nothing on stderr",
            written.empty());
  }

  // Counting from several tasks, with a redraw at every add().
  {
    const unsigned int n_tasks = 8, n_adds = 2000;
    std::ostringstream out;
    {
      ProgressReport report("counting", n_tasks * n_adds, out, 0., 0.);
      Threads::TaskGroup<void> tasks;
      for (unsigned int t = 0; t < n_tasks; ++t)
        tasks += Threads::new_task([&report]() {
          for (unsigned int i = 0; i < n_adds; ++i)
            report.add();
        });
      tasks.join_all();
      require("8 tasks x 2000 steps counted",
              report.n_done() == n_tasks * n_adds);
      report.advance_to(5);
      require("advance_to() does not go back",
              report.n_done() == n_tasks * n_adds);
      report.finish();
    }
    const std::vector<std::string> lines       = masked_lines(out.str());
    bool                           well_formed = !lines.empty();
    for (unsigned int l = 0; l + 1 < lines.size(); ++l)
      well_formed = well_formed && lines[l].rfind("counting: ", 0) == 0 &&
                    lines[l].find("<newline>") == std::string::npos;
    require("concurrent redraws give whole lines", well_formed);
    deallog << "last line: " << lines.back() << std::endl;
  }

  // advance_to() from a position reported by a callee.
  {
    std::ostringstream out;
    ProgressReport     report("factorisation", 200, out, 0., 0.);
    report.advance_to(50);
    report.advance_to(20);
    report.advance_to(150);
    report.finish();
    for (const std::string &line : masked_lines(out.str()))
      deallog << "drawn: " << line << std::endl;
  }

  // Rendering: every add() draws, then the final line.
  {
    std::ostringstream out;
    {
      ProgressReport report("Dense Galerkin flexibility", 7, out, 0., 0.);
      report.add(3);
      report.add(4);
      // the destructor finishes the line
    }
    for (const std::string &line : masked_lines(out.str()))
      deallog << "drawn: " << line << std::endl;
  }

  // An exception leaves the phase.
  {
    std::ostringstream out;
    try
      {
        ProgressReport report("integration", 10, out, 0., 0.);
        report.add(4);
        throw std::runtime_error("integration failed");
      }
    catch (const std::exception &e)
      {
        deallog << "caught: " << e.what() << std::endl;
      }
    for (const std::string &line : masked_lines(out.str()))
      deallog << "drawn: " << line << std::endl;
  }

  // A phase shorter than the delay before the first line leaves none.
  {
    std::ostringstream out;
    {
      ProgressReport report("quick", 10, out, 3600., 0.25);
      report.add(10);
      report.finish();
    }
    require("a quick phase leaves no line", out.str().empty());
  }
}
