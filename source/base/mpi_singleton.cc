#include <plate_on_halfspace/base/mpi_singleton.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  bool
  MpiSingletonEnvironment::started_by_launcher()
  {
    // Open MPI's mpirun, PMIx launchers (srun --mpi=pmix, prterun), and
    // PMI-1/2 launchers (MPICH's hydra, srun --mpi=pmi2) each set one.
    for (const char *variable :
         {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_FD"})
      if (std::getenv(variable) != nullptr)
        return true;
    return false;
  }

  namespace
  {
    const std::string prefix = "plate-on-halfspace-mpi.";

    /**
     * Removes the private session directories that runs of this user
     * killed by SIGKILL left in @p base: named prefix + PID + ".XXXXXX",
     * a real directory owned by this user, whose process is gone. A
     * directory of a living process, or of another user, is never touched.
     */
    void
    remove_stale_session_directories(const std::string &base)
    {
      std::error_code error;
      for (const auto &entry : std::filesystem::directory_iterator(base, error))
        {
          const std::string name = entry.path().filename().string();
          if (name.compare(0, prefix.size(), prefix) != 0)
            continue;
          const std::size_t dot = name.find('.', prefix.size());
          if (dot == std::string::npos || dot == prefix.size())
            continue;
          const std::string digits =
            name.substr(prefix.size(), dot - prefix.size());
          if (digits.find_first_not_of("0123456789") != std::string::npos ||
              digits.size() > 9)
            continue;
          struct stat status;
          if (lstat(entry.path().c_str(), &status) != 0 ||
              !S_ISDIR(status.st_mode) || status.st_uid != geteuid())
            continue;
          const pid_t pid = static_cast<pid_t>(std::stol(digits));
          if (kill(pid, 0) == 0 || errno != ESRCH)
            continue;
          std::filesystem::remove_all(entry.path(), error);
        }
    }
  } // namespace

  MpiSingletonEnvironment::MpiSingletonEnvironment()
  {
    if (started_by_launcher())
      return;
    // A singleton never spawns processes, so it needs no daemon
    // (doc/parallel.md, "Serial runs"). setenv(..., 0) keeps a value the
    // user set.
    setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
    if (std::getenv("OMPI_MCA_orte_tmpdir_base") != nullptr)
      return;
    const char *tmpdir = std::getenv("TMPDIR");
    std::string base = (tmpdir != nullptr && *tmpdir != '\0') ? tmpdir : "/tmp";
    remove_stale_session_directories(base);
    std::string pattern =
      base + "/" + prefix + std::to_string(getpid()) + ".XXXXXX";
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    // mkdtemp makes a new directory, mode 0700, that no other run shares;
    // if it cannot, Open MPI falls back to its default and says so itself.
    if (mkdtemp(name.data()) == nullptr)
      return;
    private_directory = name.data();
    setenv("OMPI_MCA_orte_tmpdir_base", private_directory.c_str(), 1);
  }

  MpiSingletonEnvironment::~MpiSingletonEnvironment()
  {
    if (private_directory.empty())
      return;
    // Open MPI removes its session tree at MPI_Finalize; what a failed
    // finalisation left is ours too, as the directory is.
    std::error_code error;
    std::filesystem::remove_all(private_directory, error);
  }

  const std::string &
  MpiSingletonEnvironment::session_directory() const
  {
    return private_directory;
  }
} // namespace PlateOnHalfspace
