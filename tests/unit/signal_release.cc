// Interruption::release_signals() (base/interruption.h): while the run
// computes, SIGTERM and SIGINT are recorded for its next safe point; once
// its results are committed or restored the run releases them, and a
// signal then ends the process at once (its teardown has no safe point).
//  - a child process that catches the signals and raises SIGTERM lives on
//    and exits normally;
//  - one that releases them first is ended by SIGTERM, and likewise by
//    SIGINT;
//  - here: a raised SIGTERM is recorded, release_signals() returns it and
//    restores both signals' default action.
// The verdicts only are printed.

#include <plate_on_halfspace/base/interruption.h>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <functional>
#include <string>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  void
  verdict(const std::string &what, const bool holds)
  {
    deallog << what << ": " << (holds ? "ok" : "FAILED") << std::endl;
  }

  /** The wait status of a child process that runs @p body, then exits 0. */
  int
  status_of_child(const std::function<void()> &body)
  {
    const pid_t child = fork();
    if (child == 0)
      {
        body();
        _exit(0);
      }
    int status = 0;
    waitpid(child, &status, 0);
    return status;
  }

  bool
  default_action(const int signal_number)
  {
    struct sigaction current = {};
    sigaction(signal_number, nullptr, &current);
    return current.sa_handler == SIG_DFL;
  }
} // namespace

int
main()
{
  initlog();

  const int recorded = status_of_child([] {
    Interruption::catch_signals();
    std::raise(SIGTERM);
  });
  verdict("caught SIGTERM: the process lives on and exits normally",
          WIFEXITED(recorded) && WEXITSTATUS(recorded) == 0);

  for (const int signal_number : {SIGTERM, SIGINT})
    {
      const int ended = status_of_child([signal_number] {
        Interruption::catch_signals();
        Interruption::release_signals();
        std::raise(signal_number);
      });
      verdict(std::string("released ") +
                (signal_number == SIGTERM ? "SIGTERM" : "SIGINT") +
                ": the signal ends the process",
              WIFSIGNALED(ended) && WTERMSIG(ended) == signal_number);
    }

  Interruption::catch_signals();
  verdict("caught: neither signal has its default action",
          !default_action(SIGTERM) && !default_action(SIGINT));
  std::raise(SIGTERM);
  verdict("a raised SIGTERM is recorded",
          Interruption::pending_signal() == SIGTERM);
  verdict("release_signals() returns it",
          Interruption::release_signals() == SIGTERM);
  verdict("released: both signals have their default action",
          default_action(SIGTERM) && default_action(SIGINT));
}
