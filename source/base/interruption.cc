#include <plate_on_halfspace/base/interruption.h>

#include <csignal>

namespace PlateOnHalfspace
{
  namespace
  {
    /** The first signal received (0: none); written by the handler only. */
    volatile std::sig_atomic_t received = 0;

    MPI_Comm registered = MPI_COMM_NULL;

    extern "C" void
    record_signal(const int signal_number)
    {
      // Only async-signal-safe actions here: set the flag; on a second
      // signal restore the default action and raise it again.
      if (received != 0)
        {
          std::signal(signal_number, SIG_DFL);
          std::raise(signal_number);
          return;
        }
      received = signal_number;
    }

    /** @p handler with @p flags for both SIGINT and SIGTERM. */
    void
    set_action(void (*handler)(int), const int flags)
    {
      struct sigaction action = {};
      action.sa_handler       = handler;
      sigemptyset(&action.sa_mask);
      action.sa_flags = flags;
      sigaction(SIGINT, &action, nullptr);
      sigaction(SIGTERM, &action, nullptr);
    }

    bool
    mpi_is_running()
    {
      int initialized = 0, finalized = 0;
      MPI_Initialized(&initialized);
      MPI_Finalized(&finalized);
      return initialized != 0 && finalized == 0;
    }
  } // namespace

  Interrupted::Interrupted(const int signal_number, const bool committed)
    : number(signal_number)
    , committed(committed)
    , message(
        std::string("interrupted by ") +
        (signal_number == SIGINT  ? "SIGINT" :
         signal_number == SIGTERM ? "SIGTERM" :
                                    "signal " + std::to_string(signal_number)))
  {}

  const char *
  Interrupted::what() const noexcept
  {
    return message.c_str();
  }

  namespace Interruption
  {
    void
    catch_signals()
    {
      // Restart interrupted system calls: file and MPI I/O go on, and the
      // computation notices the flag at its next safe point.
      set_action(record_signal, SA_RESTART);
    }

    void
    set_communicator(const MPI_Comm communicator)
    {
      registered = communicator;
    }

    int
    pending_signal()
    {
      return received;
    }

    void
    check()
    {
      int signal_number = received;
      if (registered != MPI_COMM_NULL && mpi_is_running())
        {
          int size = 1;
          MPI_Comm_size(registered, &size);
          if (size > 1)
            {
              int largest = 0;
              MPI_Allreduce(
                &signal_number, &largest, 1, MPI_INT, MPI_MAX, registered);
              signal_number = largest;
            }
        }
      if (signal_number != 0)
        throw Interrupted(signal_number);
    }

    void
    check_if_alone()
    {
      if (received == 0)
        return;
      if (registered != MPI_COMM_NULL && mpi_is_running())
        {
          int size = 1;
          MPI_Comm_size(registered, &size);
          if (size > 1)
            return;
        }
      throw Interrupted(received);
    }

    int
    release_signals()
    {
      // Default action first: a signal after it ends the process, one
      // before it is in the flag.
      set_action(SIG_DFL, 0);
      return received;
    }
  } // namespace Interruption
} // namespace PlateOnHalfspace
