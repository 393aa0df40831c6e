// The output directory of ResultsOutput (doc/outputs.md, "Safety of the
// output directory"): the lock, the earlier results set aside and brought
// back, the recovery after a killed run, and the atomic writes through
// which every result file goes. The files' contents are written in
// results_output.cc.
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <plate_on_halfspace/base/error_on_every_rank.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/io/results_output.h>
#include <plate_on_halfspace/scene/input_checks.h>

#include <dirent.h>
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <regex>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    /** Where @p name is written before it is renamed into place, so that
     *  a run never leaves a half-written result file. */
    std::string
    temporary_name(const std::string &name)
    {
      return "." + name + ".tmp";
    }

    /** The lock file that keeps a second run out of the directory
     *  (doc/outputs.md, "One run at a time"). */
    const char *const lock_name = ".plate-on-halfspace.lock";

    /** Proof that the directory takes new files, created and removed before
     *  anything is computed. */
    const char *const probe_name = ".plate-on-halfspace.probe.tmp";

    /** The flag a run writes last (doc/outputs.md, "complete"). */
    const char *const complete_name = "complete";

    /**
     * Present in previous-run/ while results move between it and the
     * directory (set aside at the start, brought back by abandon()): the
     * directory then holds nothing but earlier results, so a run killed in
     * between is mended by moving the rest back.
     */
    const char *const moving_name = ".moving";

    [[noreturn]] void
    fail(const std::string &message)
    {
      AssertThrow(false, ExcMessage(message));
      std::abort(); // not reached
    }

    std::string
    error_text(const int error)
    {
      return std::strerror(error);
    }

    /** A file descriptor closed when it goes out of scope. */
    struct Descriptor
    {
      int fd = -1;
      explicit Descriptor(const int fd)
        : fd(fd)
      {}
      Descriptor(const Descriptor &) = delete;
      Descriptor &
      operator=(const Descriptor &) = delete;
      ~Descriptor()
      {
        if (fd >= 0)
          ::close(fd);
      }
    };

    /**
     * The entry @p name of @p parent opened as a directory, never through
     * a symbolic link: a planted link named previous-run must not make the
     * program move or remove files elsewhere. -1 with errno when it is
     * missing (ENOENT) or not a directory (ELOOP, ENOTDIR).
     */
    int
    open_subdirectory(const int parent, const char *name)
    {
      return ::openat(parent,
                      name,
                      O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    }

    /** Whether @p name in @p directory is a regular file (not a link). */
    bool
    is_regular_file_at(const int directory, const std::string &name)
    {
      struct stat status;
      return ::fstatat(directory, name.c_str(), &status, AT_SYMLINK_NOFOLLOW) ==
               0 &&
             S_ISREG(status.st_mode);
    }

    /**
     * Creates (or opens) the marker @p moving_name in @p folder: a regular
     * file, opened without following a link and without waiting (a FIFO
     * planted at the name would block a plain open for a reader). False
     * with errno where the entry is something else or cannot be made.
     */
    bool
    make_moving_marker(const int folder)
    {
      const int fd =
        ::openat(folder,
                 moving_name,
                 O_WRONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC,
                 0644);
      if (fd < 0)
        return false;
      struct stat status;
      const bool regular = ::fstat(fd, &status) == 0 && S_ISREG(status.st_mode);
      ::close(fd);
      if (!regular)
        errno = EEXIST;
      return regular;
    }

    /** The names of the entries of @p directory, sorted. */
    std::vector<std::string>
    entries_of(const int directory)
    {
      std::vector<std::string> names;
      // fdopendir() takes over the descriptor it is given: a copy.
      const int copy =
        ::openat(directory, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (copy < 0)
        return names;
      DIR *stream = ::fdopendir(copy);
      if (stream == nullptr)
        {
          ::close(copy);
          return names;
        }
      while (const dirent *entry = ::readdir(stream))
        {
          const std::string name = entry->d_name;
          if (name != "." && name != "..")
            names.push_back(name);
        }
      ::closedir(stream);
      std::sort(names.begin(), names.end());
      return names;
    }
  } // namespace

  ResultsOutput::ResultsOutput(const std::string &directory,
                               const MPI_Comm     communicator)
    : directory(directory)
    , previous_run((std::filesystem::path(directory) / "previous-run").string())
    , failed_run((std::filesystem::path(directory) / "failed-run").string())
    , communicator(communicator)
  {
    if (n_ranks(communicator) == 1)
      {
        prepare_directory();
        return;
      }
    // Only rank 0 touches the directory, but every rank must learn that it
    // cannot be used (in use, unwritable, a planted link), so that all stop
    // alike with one message instead of waiting for rank 0.
    std::string failure;
    if (writes_files())
      try
        {
          prepare_directory();
        }
      catch (const std::exception &e)
        {
          failure = one_line_message(e);
        }
    failure = Utilities::MPI::broadcast(communicator, failure, 0);
    if (!failure.empty())
      throw ErrorOnEveryRank(failure);
  }

  void
  ResultsOutput::prepare_directory()
  {
    // A NUL inside the name would cut it short for the system calls while
    // std::filesystem keeps it whole: the scene's own check, again here as
    // the last line of defence for callers that bypass the scene.
    const std::string control =
      control_character_in_path("Output directory", directory);
    AssertThrow(control.empty(), ExcMessage(control));
    AssertThrow(!directory.empty(),
                ExcMessage("Output directory must not be empty."));
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    AssertThrow(!error && std::filesystem::is_directory(directory),
                ExcMessage("Output directory: cannot create <" + directory +
                           ">: " + error.message()));
    // The directory is opened once; every later step names its entries
    // relative to it (openat, renameat, unlinkat), so that a path swapped
    // for a link during the run cannot redirect the program.
    directory_fd =
      ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    AssertThrow(directory_fd >= 0,
                ExcMessage("Output directory: cannot open <" + directory +
                           ">: " + error_text(errno)));
    try
      {
        lock_directory();
        check_writable();
        remove_stale_temporaries();
        recover_interrupted_run();
        set_earlier_results_aside();
      }
    catch (...)
      {
        // Put back what was set aside; a run refused by the lock touches
        // nothing.
        if (setting_aside)
          try
            {
              restore_earlier_results();
            }
          catch (...)
            {
              // the next run mends what is left (recover_interrupted_run())
            }
        unlock_directory();
        ::close(directory_fd);
        directory_fd = -1;
        throw;
      }
  }

  ResultsOutput::~ResultsOutput()
  {
    if (!finished)
      try
        {
          abandon();
        }
      catch (...)
        {
          // nothing more can be done while unwinding
        }
    unlock_directory();
    if (directory_fd >= 0)
      ::close(directory_fd);
  }

  bool
  ResultsOutput::is_result_file(const std::string &name)
  {
    // NN is a cycle's number, 00 to 29 (Adaptivity/Cycles is at most 30):
    // a file named with other digits is never this program's.
    static const std::regex pattern(
      R"((summary\.json|convergence\.txt|solution\.pvd|solution-[0-2]\d\.vtu|)"
      R"(sweep\.csv|complete|(gauss-profile|profile|nodes)-[0-2]\d\.csv))");
    return std::regex_match(name, pattern);
  }

  void
  ResultsOutput::lock_directory()
  {
    // flock() on a file of the directory: released by the kernel when the
    // process ends, however it ends, so a killed run never leaves the
    // directory locked. The lock file is removed when the run ends; a run
    // that opened it just before must then lock the file that is there now,
    // hence the comparison of the inodes.
    for (unsigned int attempt = 0; attempt < 100; ++attempt)
      {
        const int fd = ::openat(directory_fd,
                                lock_name,
                                O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC,
                                0644);
        if (fd < 0)
          {
            const int e = errno;
            if (e == ELOOP)
              fail("Output directory: <" + directory + "/" + lock_name +
                   "> is a symbolic link; this program locks the directory "
                   "with a file of that name and does not follow links: "
                   "remove it.");
            fail("Output directory: cannot write in <" + directory +
                 ">: " + error_text(e) + ".");
          }
        Descriptor  lock(fd);
        struct stat opened;
        AssertThrow(::fstat(fd, &opened) == 0 && S_ISREG(opened.st_mode),
                    ExcMessage("Output directory: <" + directory + "/" +
                               lock_name +
                               "> is not a regular file; remove "
                               "it."));
        // A hard link planted at the name would make the pid written below
        // overwrite the linked file: only a file of this user with no
        // other name is the lock file (doc/outputs.md).
        if (opened.st_nlink != 1 || opened.st_uid != ::geteuid())
          fail("Output directory: <" + directory + "/" + lock_name +
               "> has another name (a hard link) or another owner; this "
               "program writes its lock there and never into a file it "
               "did not create: remove it.");
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0)
          {
            const int e = errno;
            AssertThrow(e == EWOULDBLOCK,
                        ExcMessage("Output directory: cannot lock <" +
                                   directory + "/" + lock_name +
                                   ">: " + error_text(e) + "."));
            // The other run writes its pid right after locking.
            std::string pid;
            for (unsigned int wait = 0; wait < 50 && pid.empty(); ++wait)
              {
                char          buffer[32] = {};
                const ssize_t n = ::pread(fd, buffer, sizeof(buffer) - 1, 0);
                for (ssize_t i = 0;
                     i < n &&
                     std::isdigit(static_cast<unsigned char>(buffer[i]));
                     ++i)
                  pid += buffer[i];
                if (pid.empty())
                  ::usleep(10000);
              }
            fail("Output directory: <" + directory +
                 "> is in use by another run (pid " +
                 (pid.empty() ? std::string("unknown") : pid) +
                 "); wait until it ends, or choose another Output "
                 "directory.");
          }
        struct stat present;
        if (::fstatat(directory_fd, lock_name, &present, AT_SYMLINK_NOFOLLOW) !=
              0 ||
            present.st_dev != opened.st_dev || present.st_ino != opened.st_ino)
          continue; // removed by the run that held it: lock the new one
        const std::string pid = std::to_string(::getpid()) + "\n";
        if (::ftruncate(fd, 0) != 0 ||
            ::pwrite(fd, pid.data(), pid.size(), 0) != ssize_t(pid.size()))
          fail("Output directory: cannot write in <" + directory +
               ">: " + error_text(errno) + ".");
        lock_fd = lock.fd;
        lock.fd = -1;
        return;
      }
    fail("Output directory: cannot lock <" + directory + "/" + lock_name +
         ">: it keeps being removed.");
  }

  void
  ResultsOutput::unlock_directory()
  {
    if (lock_fd < 0)
      return;
    // Remove the lock file only if it is still ours (the same inode), while
    // holding the lock; then release it.
    struct stat ours, present;
    if (::fstat(lock_fd, &ours) == 0 &&
        ::fstatat(directory_fd, lock_name, &present, AT_SYMLINK_NOFOLLOW) ==
          0 &&
        ours.st_dev == present.st_dev && ours.st_ino == present.st_ino)
      ::unlinkat(directory_fd, lock_name, 0);
    ::close(lock_fd);
    lock_fd = -1;
  }

  void
  ResultsOutput::check_writable() const
  {
    // Before anything is computed: a directory that takes no new file
    // (read-only file system, no permission, full) is reported now, not
    // after the computation.
    ::unlinkat(directory_fd, probe_name, 0); // left by a killed run
    const int fd =
      ::openat(directory_fd,
               probe_name,
               O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
               0600);
    int e = fd < 0 ? errno : 0;
    if (fd >= 0)
      {
        if (::write(fd, "\n", 1) != 1)
          e = errno;
        if (::close(fd) != 0 && e == 0)
          e = errno;
        // a directory that takes files but lets none be removed or renamed
        // (append-only) cannot take the results either
        if (::unlinkat(directory_fd, probe_name, 0) != 0 && e == 0)
          e = errno;
      }
    AssertThrow(e == 0,
                ExcMessage("Output directory: cannot write in <" + directory +
                           ">: " + error_text(e) + "."));
  }

  void
  ResultsOutput::remove_stale_temporaries() const
  {
    // A run killed while writing leaves its temporary file (".NAME.tmp");
    // the names are this program's. unlinkat() removes a link, never what
    // it points to.
    for (const std::string &name : entries_of(directory_fd))
      if (name.size() > 5 && name[0] == '.' &&
          name.compare(name.size() - 4, 4, ".tmp") == 0 &&
          is_result_file(name.substr(1, name.size() - 5)))
        ::unlinkat(directory_fd, name.c_str(), 0);
  }

  std::vector<std::string>
  ResultsOutput::result_files_in(const int directory)
  {
    std::vector<std::string> files;
    for (const std::string &name : entries_of(directory))
      if (is_result_file(name) && is_regular_file_at(directory, name))
        files.push_back(name);
    return files;
  }

  unsigned int
  ResultsOutput::move_result_files(const int   from,
                                   const int   to,
                                   const bool  flag_first,
                                   std::string where) const
  {
    // `complete` leaves first and comes back last: the directory never
    // shows the flag beside an incomplete set of results.
    std::vector<std::string> files = result_files_in(from);
    const auto flag = std::find(files.begin(), files.end(), complete_name);
    if (flag != files.end())
      {
        files.erase(flag);
        if (flag_first)
          files.insert(files.begin(), complete_name);
        else
          files.push_back(complete_name);
      }
    for (const std::string &name : files)
      if (::renameat(from, name.c_str(), to, name.c_str()) != 0)
        fail("Output directory: cannot move <" + name + "> to <" + where +
             ">: " + error_text(errno) + ".");
    return files.size();
  }

  void
  ResultsOutput::remove_result_files(const int directory)
  {
    // Only the names this program writes, each a regular file: whatever
    // else a user put there stays.
    for (const std::string &name : result_files_in(directory))
      ::unlinkat(directory, name.c_str(), 0);
    if (is_regular_file_at(directory, moving_name))
      ::unlinkat(directory, moving_name, 0);
  }

  int
  ResultsOutput::open_results_folder(const char *name, const bool create) const
  {
    if (create && ::mkdirat(directory_fd, name, 0755) != 0 && errno != EEXIST)
      fail("Output directory: cannot create <" + directory + "/" + name +
           ">: " + error_text(errno) + ".");
    const int fd = open_subdirectory(directory_fd, name);
    if (fd < 0 && errno != ENOENT)
      fail("Output directory: <" + directory + "/" + name +
           "> is not a directory (a symbolic link or a file); this program "
           "keeps results there and neither follows nor removes it: move it "
           "away.");
    return fd;
  }

  void
  ResultsOutput::remove_results_folder(const char *name) const
  {
    const int fd = open_subdirectory(directory_fd, name);
    if (fd < 0)
      return; // missing, or not ours (a link): left alone
    {
      Descriptor folder(fd);
      remove_result_files(folder.fd);
    }
    // Removed only if empty: a file this program did not write keeps it.
    ::unlinkat(directory_fd, name, AT_REMOVEDIR);
  }

  void
  ResultsOutput::restore_earlier_results() const
  {
    const int fd = open_results_folder("previous-run", false);
    if (fd < 0)
      return;
    Descriptor previous(fd);
    if (!result_files_in(previous.fd).empty())
      {
        make_moving_marker(previous.fd);
        move_result_files(previous.fd, directory_fd, false, directory);
      }
    remove_result_files(previous.fd);
    ::unlinkat(directory_fd, "previous-run", AT_REMOVEDIR);
  }

  void
  ResultsOutput::set_failed_run_aside()
  {
    // This run's files go to failed-run/ (emptied of an older failure's).
    if (result_files_in(directory_fd).empty())
      return;
    const int  fd = open_results_folder("failed-run", true);
    Descriptor failed(fd);
    remove_result_files(failed.fd);
    failed_files =
      move_result_files(directory_fd, failed.fd, false, failed_run);
  }

  void
  ResultsOutput::recover_interrupted_run()
  {
    // previous-run/ outlives a run only when that run was killed
    // (doc/outputs.md, "Interrupted and killed runs"). Bring the directory
    // back to the newest complete results before setting them aside.
    const int fd = open_results_folder("previous-run", false);
    if (fd < 0)
      return;
    Descriptor previous(fd);
    if (is_regular_file_at(previous.fd, moving_name))
      {
        // killed while moving the earlier results: the directory holds
        // nothing else, move the rest back
        restore_earlier_results();
        recovery = "A run into <" + directory +
                   "> was killed while it moved the earlier results; they "
                   "are back in place.";
      }
    else if (result_files_in(previous.fd).empty())
      ::unlinkat(directory_fd, "previous-run", AT_REMOVEDIR);
    else if (is_regular_file_at(directory_fd, complete_name))
      {
        // killed after its `complete`: the directory's results are the
        // newest complete ones
        remove_result_files(previous.fd);
        ::unlinkat(directory_fd, "previous-run", AT_REMOVEDIR);
      }
    else
      {
        // killed while computing: its files go to failed-run/
        set_failed_run_aside();
        restore_earlier_results();
        recovery = "A run into <" + directory +
                   "> was killed before it finished; its files are in <" +
                   failed_run + ">, the results before it are kept.";
        failed_files = 0;
      }
  }

  void
  ResultsOutput::set_earlier_results_aside()
  {
    if (result_files_in(directory_fd).empty())
      return;
    setting_aside = true;
    const int  fd = open_results_folder("previous-run", true);
    Descriptor previous(fd);
    AssertThrow(make_moving_marker(previous.fd),
                ExcMessage(
                  "Output directory: cannot create the regular file <" +
                  previous_run + "/" + moving_name +
                  "> that marks results being moved: " + error_text(errno) +
                  "; this program does not remove an entry of that "
                  "name it did not create: remove it."));
    move_result_files(directory_fd, previous.fd, true, previous_run);
    ::unlinkat(previous.fd, moving_name, 0);
  }

  bool
  ResultsOutput::writes_files() const
  {
    return rank_in(communicator) == 0;
  }

  void
  ResultsOutput::commit()
  {
    if (!writes_files())
      {
        finished = true;
        return;
      }
    // summary.json says the run finished, then `complete` is written: the
    // last file, so that its presence means the results are whole
    // (doc/outputs.md). The run counts as finished only then: if a write
    // fails before, the destructor abandons it and the earlier results
    // come back.
    if (!summary_text.empty())
      {
        nlohmann::ordered_json summary =
          nlohmann::ordered_json::parse(summary_text);
        summary["finished"]  = true;
        summary["converged"] = summary_converged;
        write_file("summary.json", summary.dump(2) + "\n");
      }
    std::time_t now = std::time(nullptr);
    char        stamp[32];
    std::strftime(stamp,
                  sizeof(stamp),
                  "%Y-%m-%dT%H:%M:%SZ",
                  std::gmtime(&now));
    nlohmann::ordered_json flag;
    flag["finished"]  = stamp;
    flag["cycles"]    = summary_cycles;
    flag["converged"] = summary_converged;
    write_file(complete_name, flag.dump() + "\n");
    finished = true;
    remove_results_folder("previous-run");
    remove_results_folder("failed-run");
    unlock_directory();
  }

  std::string
  ResultsOutput::abandon()
  {
    finished = true;
    if (!writes_files())
      return "";
    std::string note;
    try
      {
        failed_files = 0;
        set_failed_run_aside();
      }
    catch (const std::exception &e)
      {
        // failed-run/ is unusable: this run's own files go, so that the
        // earlier results can come back
        for (const std::string &name : result_files_in(directory_fd))
          ::unlinkat(directory_fd, name.c_str(), 0);
        note = " (" + one_line_message(e) + " This run's files are removed.)";
      }
    restore_earlier_results();
    unlock_directory();
    if (failed_files == 0 && note.empty())
      return "";
    if (!note.empty())
      return "The earlier results in <" + directory + "> are kept." + note;
    return "The failed run's results are in <" + failed_run +
           ">; the earlier results in <" + directory + "> are kept.";
  }

  void
  ResultsOutput::write_file(const std::string &name,
                            const std::string &text) const
  {
    write_file_in_parts(name, [&text](std::string_view &part) {
      part = text;
      return false;
    });
  }

  void
  ResultsOutput::write_file_in_parts(
    const std::string                             &name,
    const std::function<bool(std::string_view &)> &next_part) const
  {
    if (!writes_files())
      return;
    AssertThrow(directory_fd >= 0,
                ExcMessage("Output directory: <" + directory +
                           "> is not open for writing."));
    // Created afresh (O_EXCL) and never through a link (O_NOFOLLOW): a link
    // planted at the temporary name cannot make the run write elsewhere.
    // An entry already there (left by a killed run, or planted) is removed
    // first; unlinkat() removes a link itself, not its target. rename()
    // then replaces the entry at the final name, a link included, without
    // following it.
    const std::string temporary = temporary_name(name);
    const std::string shown     = directory + "/" + temporary;
    int               fd        = -1;
    for (unsigned int attempt = 0; attempt < 3 && fd < 0; ++attempt)
      {
        fd = ::openat(directory_fd,
                      temporary.c_str(),
                      O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                      0644);
        if (fd < 0 && errno == EEXIST)
          ::unlinkat(directory_fd, temporary.c_str(), 0);
        else if (fd < 0)
          break;
      }
    if (fd < 0)
      fail("Output directory: cannot write <" + shown +
           ">: " + error_text(errno) + ".");
    int              e = 0;
    std::string_view text;
    try
      {
        for (bool more = true; more && e == 0;)
          {
            more                = next_part(text);
            std::size_t written = 0;
            while (written < text.size())
              {
                const ssize_t n =
                  ::write(fd, text.data() + written, text.size() - written);
                if (n < 0 && errno == EINTR)
                  continue;
                if (n <= 0)
                  {
                    e = n < 0 ? errno : EIO;
                    break;
                  }
                written += n;
              }
          }
      }
    catch (...)
      {
        ::close(fd);
        ::unlinkat(directory_fd, temporary.c_str(), 0);
        throw;
      }
    if (::close(fd) != 0 && e == 0)
      e = errno;
    if (e == 0 && ::renameat(directory_fd,
                             temporary.c_str(),
                             directory_fd,
                             name.c_str()) != 0)
      e = errno;
    if (e != 0)
      {
        ::unlinkat(directory_fd, temporary.c_str(), 0);
        fail("Output directory: cannot write <" + directory + "/" + name +
             ">: " + error_text(e) + ".");
      }
  }
} // namespace PlateOnHalfspace
