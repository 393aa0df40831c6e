/**
 * A run started without mpirun is an MPI singleton. By default Open MPI
 * starts its runtime daemon for it and creates its session directory under
 * the shared /tmp/ompi.HOST.UID, which serial runs started at the same
 * moment race to create (doc/parallel.md, "Serial runs").
 */
#ifndef plate_on_halfspace_base_mpi_singleton_h
#define plate_on_halfspace_base_mpi_singleton_h

#include <string>

namespace PlateOnHalfspace
{
  /**
   * Constructed before MPI_Init: if no MPI launcher started this process,
   * tells Open MPI to run the singleton without its daemon and to keep its
   * session directory in a new private directory, which the destructor
   * removes (after MPI_Finalize); it also removes the directories that
   * killed runs of this user left. Under a launcher, and for settings the
   * user made in the environment, it changes nothing.
   */
  class MpiSingletonEnvironment
  {
  public:
    MpiSingletonEnvironment();
    ~MpiSingletonEnvironment();

    MpiSingletonEnvironment(const MpiSingletonEnvironment &) = delete;
    MpiSingletonEnvironment &
    operator=(const MpiSingletonEnvironment &) = delete;

    /** Whether an MPI launcher (mpirun, mpiexec, srun) started us. */
    static bool
    started_by_launcher();

    /** The private session directory (empty if none was made). */
    const std::string &
    session_directory() const;

  private:
    std::string private_directory;
  };
} // namespace PlateOnHalfspace

#endif
