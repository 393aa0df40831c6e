#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <plate_on_halfspace/base/error_on_every_rank.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/io/results_output.h>
#include <plate_on_halfspace/plate/field_extrema.h>
#include <plate_on_halfspace/scene/input_checks.h>

#include <dirent.h>
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <regex>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * Mx, My, Mxy from the rotation gradients and the thermal moment
     * (doc/formulation.md, "Conventions" and "Temperature"), and the
     * fibre stresses (MindlinPlate::fibre_stresses()).
     */
    class MomentsPostprocessor : public DataPostprocessor<2>
    {
    public:
      explicit MomentsPostprocessor(const MindlinPlate &plate)
        : plate(plate)
      {}

      void
      evaluate_vector_field(
        const DataPostprocessorInputs::Vector<2> &inputs,
        std::vector<Vector<double>> &computed_quantities) const override
      {
        for (unsigned int p = 0; p < inputs.solution_gradients.size(); ++p)
          {
            const auto &g = inputs.solution_gradients[p];
            // g[c][d] = d u_c / d x_d; components 1, 2 are beta_x, beta_y
            Tensor<2, 2> grad_beta;
            for (unsigned int c = 0; c < 2; ++c)
              grad_beta[c] = g[1 + c];
            const Moments   m   = plate.moments_of_rotation_gradient(grad_beta);
            Vector<double> &out = computed_quantities[p];
            out[0]              = m.mx;
            out[1]              = m.my;
            out[2]              = m.mxy;
            const auto stresses = plate.fibre_stresses(m).values();
            std::copy(stresses.begin(), stresses.end(), out.begin() + 3);
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names = {"Mx", "My", "Mxy"};
        names.insert(names.end(),
                     Parameters::fibre_stress_names().begin(),
                     Parameters::fibre_stress_names().end());
        return names;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_gradients;
      }

    private:
      const MindlinPlate &plate;
    };

    /**
     * DataOut that writes the <Piece> of its own patches alone, as each rank
     * contributes to DataOut::write_vtu_in_parallel() (the default VtkFlags,
     * as there): empty without patches unless @p even_if_empty.
     */
    class PieceDataOut : public DataOut<2>
    {
    public:
      std::string
      piece(const bool even_if_empty = false) const
      {
        std::ostringstream out;
        if (!get_patches().empty() || even_if_empty)
          DataOutBase::write_vtu_main(get_patches(),
                                      get_dataset_names(),
                                      get_nonscalar_data_ranges(),
                                      DataOutBase::VtkFlags(),
                                      out);
        return out.str();
      }
    };

    std::string
    two_digits(const unsigned int cycle)
    {
      std::ostringstream s;
      s << std::setw(2) << std::setfill('0') << cycle;
      return s.str();
    }

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
    static const std::regex pattern(
      R"((summary\.json|convergence\.txt|solution\.pvd|solution-\d+\.vtu|)"
      R"(sweep\.csv|complete|(gauss-profile|profile|nodes)-\d+\.csv))");
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
        ::unlinkat(directory_fd, probe_name, 0);
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
        const int marker = ::openat(previous.fd,
                                    moving_name,
                                    O_WRONLY | O_CREAT | O_NOFOLLOW | O_CLOEXEC,
                                    0644);
        if (marker >= 0)
          ::close(marker);
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
    const int  marker = ::openat(previous.fd,
                                moving_name,
                                O_WRONLY | O_CREAT | O_NOFOLLOW | O_CLOEXEC,
                                0644);
    AssertThrow(marker >= 0,
                ExcMessage("Output directory: cannot write in <" +
                           previous_run + ">: " + error_text(errno) + "."));
    ::close(marker);
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
    std::size_t written = 0;
    int         e       = 0;
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

  void
  ResultsOutput::evaluate(const MindlinPlate   &plate,
                          const Vector<double> &solution,
                          const Vector<double> &pressure_field,
                          const ContactState   &contact,
                          CycleSummary         &summary,
                          const Vector<double> &standing) const
  {
    // Peaks of the finite element fields over the plate, each with its
    // location: the extremes of the fields, not of samples, so a probe's
    // value does not lie beyond them. q is the nodal pressure field in the
    // w-space, so its peaks bound the nodal values.
    const auto set =
      [](const FieldExtremum &peak, double &value, Point<2> &location) {
        value    = peak.value;
        location = peak.location;
      };
    const FieldExtrema w = field_extrema(plate, solution, PlateQuantity::w);
    set(w.maximum, summary.max_w, summary.max_w_at);
    set(w.minimum, summary.min_w, summary.min_w_at);
    const FieldExtrema q =
      field_extrema(plate, pressure_field, PlateQuantity::w);
    set(q.maximum, summary.max_q, summary.max_q_at);
    set(q.minimum, summary.min_q, summary.min_q_at);
    const FieldExtrema mx = field_extrema(plate, solution, PlateQuantity::mx);
    set(mx.maximum, summary.max_mx, summary.max_mx_at);
    set(mx.minimum, summary.min_mx, summary.min_mx_at);
    const FieldExtrema my = field_extrema(plate, solution, PlateQuantity::my);
    set(my.maximum, summary.max_my, summary.max_my_at);
    set(my.minimum, summary.min_my, summary.min_my_at);
    set(field_maximum(plate, solution, PlateQuantity::principal_moment),
        summary.max_principal_moment,
        summary.max_principal_moment_at);
    set(field_maximum(plate, solution, PlateQuantity::principal_stress_bottom),
        summary.max_principal_stress_bottom,
        summary.max_principal_stress_bottom_at);
    set(field_maximum(plate, solution, PlateQuantity::principal_stress_top),
        summary.max_principal_stress_top,
        summary.max_principal_stress_top_at);

    // per slab and per joint of a grid of slabs; a slab of the mirrored
    // part reads its image
    summary.slabs.clear();
    summary.joints = plate.joint_responses(solution, standing);
    if (const SlabGrid *grid = plate.get_slab_grid();
        grid != nullptr && grid->n_slabs() > 1)
      {
        const MirrorSymmetry &symmetry = plate.get_foundation_space().symmetry;
        for (const Slab &slab : grid->get_slabs())
          {
            const Point<2>     centre   = 0.5 * (slab.lower + slab.upper);
            const Point<2>     image    = symmetry.to_computed_part(centre);
            types::material_id computed = 0;
            for (unsigned int s = 0; s < grid->n_slabs(); ++s)
              {
                const Slab &other = grid->get_slabs()[s];
                if (image[0] > other.lower[0] && image[0] < other.upper[0] &&
                    image[1] > other.lower[1] && image[1] < other.upper[1])
                  computed = s;
              }
            CycleSummary::SlabPeaks peaks;
            const FieldExtremum     bottom =
              field_maximum(plate,
                            solution,
                            PlateQuantity::principal_stress_bottom,
                            computed);
            const FieldExtremum top = field_maximum(
              plate, solution, PlateQuantity::principal_stress_top, computed);
            peaks.max_principal_stress_bottom = bottom.value;
            peaks.max_principal_stress_bottom_at =
              symmetry.from_computed_part(bottom.location, centre);
            peaks.max_principal_stress_top = top.value;
            peaks.max_principal_stress_top_at =
              symmetry.from_computed_part(top.location, centre);
            summary.slabs.push_back(peaks);
          }
      }

    const FoundationSpace &space  = plate.get_foundation_space();
    summary.contact_area_fraction = contact_area(contact) / space.area();
    // Nodes in contact on the whole plate: a node of the computed part
    // stands for its distinct mirror images.
    // The same for the nodes whose pressure coefficient is tensile.
    summary.contact_nodes = 0;
    summary.tensile_nodes = 0;
    for (unsigned int i = 0; i < space.n_nodes(); ++i)
      {
        const unsigned int images =
          space.symmetry.images(space.node_locations[i]).size();
        if (contact.in_contact[i])
          summary.contact_nodes += images;
        if (contact.pressure_coefficients[i] < 0)
          summary.tensile_nodes += images;
      }
    summary.complementarity_violation = contact.complementarity_violation;
    summary.max_penetration           = contact.max_penetration;
    summary.contact_iterations        = contact.iterations;
    summary.converged                 = contact.converged;
  }

  PointValues
  ResultsOutput::point_values(const MindlinPlate   &plate,
                              const Vector<double> &solution,
                              const Vector<double> &pressure_field,
                              const Point<2>       &x) const
  {
    // w, q, Mx and My are even across a mirror plane: a point of the
    // mirrored-away part reads its image in the computed part.
    const Point<2> y =
      plate.get_foundation_space().symmetry.to_computed_part(x);
    PointValues values;
    values.location    = x;
    values.w           = plate.point_value(solution, y, 0);
    values.q           = plate.point_value(pressure_field, y, 0);
    const auto located = plate.locate(y);
    Moments    m       = plate.moments(located.first, located.second, solution);
    values.mx          = m.mx;
    values.my          = m.my;
    // Mxy, and with it sxy, is odd across each mirror plane the point was
    // reflected in.
    for (unsigned int d = 0; d < 2; ++d)
      if (x[d] != y[d])
        m.mxy = -m.mxy;
    values.stresses = plate.fibre_stresses(m);
    return values;
  }

  void
  ResultsOutput::write_summary(const std::vector<CycleSummary> &cycles,
                               const std::string               &symmetry,
                               const bool                       converged,
                               const SlabGrid                  &slab_grid,
                               const std::vector<SweepRow>     &sweep)
  {
    // Until commit() the run has not finished: an interrupted or killed
    // run's summary.json must not claim convergence (doc/outputs.md).
    nlohmann::ordered_json summary;
    summary["finished"]            = false;
    summary["converged"]           = false;
    summary["symmetry"]            = symmetry;
    const unsigned int n_processes = n_ranks(communicator);
    summary["mpi_processes"]       = n_processes;
    // The mesh's cells are split among the ranks by METIS
    // (partition_plate_mesh()); one rank holds them all.
    summary["partitioner"] = n_processes > 1 ? "metis" : "none";
    summary["cycles"]      = nlohmann::ordered_json::array();
    for (const CycleSummary &c : cycles)
      {
        nlohmann::ordered_json j;
        j["cycle"]                     = c.cycle;
        j["n_cells"]                   = c.n_cells;
        j["n_dofs"]                    = c.n_dofs;
        j["n_foundation_dofs"]         = c.n_foundation_dofs;
        j["contact_iterations"]        = c.contact_iterations;
        j["contact_nodes"]             = c.contact_nodes;
        j["contact_area_fraction"]     = c.contact_area_fraction;
        j["applied_load"]              = c.applied_load;
        j["load_integration_error"]    = c.load_integration_error;
        j["contact_force"]             = c.contact_force;
        j["complementarity_violation"] = c.complementarity_violation;
        j["tensile_nodes"]             = c.tensile_nodes;
        j["max_penetration"]           = c.max_penetration;
        // each peak and where it is
        const auto peak = [&j](const std::string &name,
                               const double       value,
                               const Point<2>    &location) {
          j[name]         = value;
          j[name + "_at"] = {location[0], location[1]};
        };
        peak("max_w", c.max_w, c.max_w_at);
        peak("min_w", c.min_w, c.min_w_at);
        peak("max_q", c.max_q, c.max_q_at);
        peak("min_q", c.min_q, c.min_q_at);
        peak("max_Mx", c.max_mx, c.max_mx_at);
        peak("min_Mx", c.min_mx, c.min_mx_at);
        peak("max_My", c.max_my, c.max_my_at);
        peak("min_My", c.min_my, c.min_my_at);
        peak("max_principal_moment",
             c.max_principal_moment,
             c.max_principal_moment_at);
        peak("max_principal_stress_bottom",
             c.max_principal_stress_bottom,
             c.max_principal_stress_bottom_at);
        peak("max_principal_stress_top",
             c.max_principal_stress_top,
             c.max_principal_stress_top_at);
        j["wall_time_s"]                   = c.wall_time_s;
        j["assembly_time_s"]               = c.assembly_time_s;
        j["foundation_time_s"]             = c.foundation_time_s;
        j["foundation_integration_time_s"] = c.foundation_integration_time_s;
        j["foundation_compression_time_s"] = c.foundation_compression_time_s;
        j["foundation_factorization_time_s"] =
          c.foundation_factorization_time_s;
        j["solve_time_s"]              = c.solve_time_s;
        j["output_time_s"]             = c.output_time_s;
        j["foundation_storage"]        = c.foundation_storage;
        j["foundation_memory_bytes"]   = c.foundation_memory_bytes;
        j["foundation_nodes_per_rank"] = c.foundation_nodes_per_rank;
        j["converged"]                 = c.converged;
        j["coupled_matrix_rcond"]      = c.coupled_matrix_rcond;
        j["foundation_block_rcond"]    = c.foundation_block_rcond;
        j["probes"]                    = nlohmann::ordered_json::array();
        for (const PointValues &p : c.probes)
          j["probes"].push_back({{"x", p.location[0]},
                                 {"y", p.location[1]},
                                 {"w", p.w},
                                 {"q", p.q},
                                 {"Mx", p.mx},
                                 {"My", p.my},
                                 {"stress_bottom", p.stresses.bottom},
                                 {"stress_top", p.stresses.top}});
        const auto number = [](const double value) {
          return std::isfinite(value) ? nlohmann::ordered_json(value) :
                                        nlohmann::ordered_json(nullptr);
        };
        const SlabGrid *grid = &slab_grid;
        if (grid != nullptr && !c.slabs.empty())
          {
            j["slabs"] = nlohmann::ordered_json::array();
            for (unsigned int s = 0; s < c.slabs.size(); ++s)
              {
                const Slab &slab = grid->get_slabs()[s];
                const auto &p    = c.slabs[s];
                j["slabs"].push_back({{"x1", slab.lower[0]},
                                      {"y1", slab.lower[1]},
                                      {"x2", slab.upper[0]},
                                      {"y2", slab.upper[1]},
                                      {"max_principal_stress_bottom",
                                       number(p.max_principal_stress_bottom)},
                                      {"max_principal_stress_bottom_at",
                                       {p.max_principal_stress_bottom_at[0],
                                        p.max_principal_stress_bottom_at[1]}},
                                      {"max_principal_stress_top",
                                       number(p.max_principal_stress_top)},
                                      {"max_principal_stress_top_at",
                                       {p.max_principal_stress_top_at[0],
                                        p.max_principal_stress_top_at[1]}}});
              }
          }
        if (grid != nullptr && !c.joints.empty())
          {
            j["joints"] = nlohmann::ordered_json::array();
            for (unsigned int k = 0; k < c.joints.size(); ++k)
              {
                const Joint           &joint = grid->get_joints()[k];
                const JointResponse   &r     = c.joints[k];
                nlohmann::ordered_json entry;
                entry["x1"]   = joint.start[0];
                entry["y1"]   = joint.start[1];
                entry["x2"]   = joint.end[0];
                entry["y2"]   = joint.end[1];
                entry["kind"] = joint.axis == 0 ? "transverse" : "longitudinal";
                entry["load_transfer"] =
                  Parameters::Joints::name(joint.transfer);
                entry["lte"]             = number(r.lte);
                entry["lte_at"]          = {r.lte_at[0], r.lte_at[1]};
                entry["w_loaded"]        = r.w_loaded;
                entry["w_unloaded"]      = r.w_unloaded;
                entry["max_shear_force"] = r.max_shear_force;
                if (joint.transfer == Parameters::Joints::LoadTransfer::dowels)
                  {
                    double largest = 0, bearing = 0;
                    entry["dowels"] = nlohmann::ordered_json::array();
                    for (const DowelForce &d : r.dowels)
                      {
                        entry["dowels"].push_back(
                          {{"x", d.location[0]},
                           {"y", d.location[1]},
                           {"force", d.force},
                           {"bearing_stress", d.bearing_stress}});
                        largest = std::max(largest, std::abs(d.force));
                        bearing = std::max(bearing, d.bearing_stress);
                      }
                    entry["max_dowel_force"]          = largest;
                    entry["max_dowel_bearing_stress"] = bearing;
                  }
                j["joints"].push_back(entry);
              }
          }
        if (c.has_goal)
          {
            nlohmann::ordered_json goal;
            goal["quantity"] = c.goal.quantity;
            goal["value"]    = c.goal.value;
            if (c.goal.has_location)
              goal["at"] = {c.goal.location[0], c.goal.location[1]};
            goal["estimated_error"] = c.goal.estimated_error;
            if (c.goal.has_dwr)
              goal["dwr"] = c.goal.dwr;
            else
              goal["dwr"] = nullptr;
            if (c.goal.has_change)
              goal["change"] = c.goal.change;
            else
              goal["change"] = nullptr;
            goal["relative_error"] = c.goal.relative_error;
            goal["time_s"]         = c.goal.time_s;
            j["goal"]              = goal;
          }
        summary["cycles"].push_back(j);
      }
    // Whether the last cycle met Adaptivity/Target error.
    if (!cycles.empty() && cycles.back().has_goal &&
        cycles.back().goal.target_error > 0)
      {
        const CycleSummary::Goal &goal = cycles.back().goal;
        summary["goal_target"]         = {{"quantity", goal.quantity},
                                          {"target_error", goal.target_error},
                                          {"relative_error", goal.relative_error},
                                          {"met", goal.target_met}};
      }
    if (!sweep.empty())
      {
        // the envelope: each extreme with the position where it occurs
        const auto extreme = [&](const auto &value, const bool largest) {
          unsigned int best = sweep.size();
          for (unsigned int k = 0; k < sweep.size(); ++k)
            if (std::isfinite(value(sweep[k])) &&
                (best == sweep.size() ||
                 (largest ? value(sweep[k]) > value(sweep[best]) :
                            value(sweep[k]) < value(sweep[best]))))
              best = k;
          return best;
        };
        nlohmann::ordered_json envelope;
        const auto             entry = [&](const std::string &name,
                               const unsigned int k,
                               const double       value,
                               const Point<2>    &at) {
          if (k == sweep.size())
            {
              envelope[name] = nullptr;
              return;
            }
          envelope[name] = {{"value", value},
                            {"step", k},
                            {"position",
                             {sweep[k].position[0], sweep[k].position[1]}},
                            {"at", {at[0], at[1]}}};
        };
        unsigned int k =
          extreme([](const SweepRow &r) { return r.max_w; }, true);
        entry("max_w", k, sweep[k].max_w, sweep[k].max_w_at);
        k =
          extreme([](const SweepRow &r) { return r.max_stress_bottom; }, true);
        entry("max_principal_stress_bottom",
              k,
              sweep[k].max_stress_bottom,
              sweep[k].max_stress_bottom_at);
        k = extreme([](const SweepRow &r) { return r.max_stress_top; }, true);
        entry("max_principal_stress_top",
              k,
              sweep[k].max_stress_top,
              sweep[k].max_stress_top_at);
        k = extreme([](const SweepRow &r) { return r.min_lte; }, false);
        if (k < sweep.size())
          {
            const Joint &joint = slab_grid.get_joints()[sweep[k].min_lte_joint];
            entry("min_lte",
                  k,
                  sweep[k].min_lte,
                  joint.start + 0.5 * (joint.end - joint.start));
            envelope["min_lte"]["joint"] = sweep[k].min_lte_joint;
          }
        else
          envelope["min_lte"] = nullptr;
        k = extreme([](const SweepRow &r) { return r.contact_area_fraction; },
                    false);
        entry("min_contact_area_fraction",
              k,
              sweep[k].contact_area_fraction,
              sweep[k].position);
        envelope["min_contact_area_fraction"].erase("at");
        summary["sweep"] = {
          {"steps", sweep.size()},
          {"start", {sweep.front().position[0], sweep.front().position[1]}},
          {"end", {sweep.back().position[0], sweep.back().position[1]}},
          {"envelope", envelope}};
        // the load each position puts on the plate: less than the axles'
        // where a tyre hangs over the edge (a warning says so)
        nlohmann::ordered_json applied = nlohmann::ordered_json::array();
        for (const SweepRow &r : sweep)
          applied.push_back(r.applied_load);
        summary["sweep"]["applied_load"] = applied;
      }
    summary_text      = summary.dump(2) + "\n";
    summary_converged = converged;
    summary_cycles    = cycles.size();
    write_file("summary.json", summary_text);
  }

  void
  ResultsOutput::write_sweep(const std::vector<SweepRow> &sweep) const
  {
    std::ostringstream csv;
    csv << "step,x,y,max_w,max_w_x,max_w_y,max_s1_bottom,max_s1_bottom_x,"
           "max_s1_bottom_y,max_s1_top,max_s1_top_x,max_s1_top_y,"
           "contact_area_fraction,min_lte,min_lte_joint,contact_iterations,"
           "wall_time_s,applied_load\n"
        << std::setprecision(10);
    for (unsigned int k = 0; k < sweep.size(); ++k)
      {
        const SweepRow &r = sweep[k];
        csv << k << ',' << r.position[0] << ',' << r.position[1] << ','
            << r.max_w << ',' << r.max_w_at[0] << ',' << r.max_w_at[1] << ','
            << r.max_stress_bottom << ',' << r.max_stress_bottom_at[0] << ','
            << r.max_stress_bottom_at[1] << ',' << r.max_stress_top << ','
            << r.max_stress_top_at[0] << ',' << r.max_stress_top_at[1] << ','
            << r.contact_area_fraction << ',';
        if (std::isfinite(r.min_lte))
          csv << r.min_lte << ',' << r.min_lte_joint;
        else
          csv << ',';
        csv << ',' << r.contact_iterations << ',' << r.wall_time_s << ','
            << r.applied_load << '\n';
      }
    write_file("sweep.csv", csv.str());
  }


  void
  ResultsOutput::write_profile(const unsigned int    cycle,
                               const MindlinPlate   &plate,
                               const Vector<double> &solution,
                               const ContactState   &contact,
                               const Point<2>       &start,
                               const Point<2>       &end,
                               const unsigned int    n_points) const
  {
    const Vector<double> pressure =
      plate.foundation_field_to_solution(contact.q);
    std::ostringstream csv;
    csv << "x,y,w,q,Mx,My";
    for (const std::string &name : Parameters::fibre_stress_names())
      csv << ',' << name;
    csv << '\n' << std::setprecision(10);
    for (unsigned int k = 0; k < n_points; ++k)
      {
        const Point<2> x = start + (end - start) * (k / double(n_points - 1));
        PointValues    values;
        try
          {
            values = point_values(plate, solution, pressure, x);
          }
        catch (...)
          {
            continue; // off the plate (e.g. across a disk's polygon)
          }
        csv << x[0] << ',' << x[1] << ',' << values.w << ',' << values.q << ','
            << values.mx << ',' << values.my;
        for (const double s : values.stresses.values())
          csv << ',' << s;
        csv << '\n';
      }
    write_file("profile-" + two_digits(cycle) + ".csv", csv.str());
  }

  void
  ResultsOutput::write_nodes_and_gauss_profile(const unsigned int    cycle,
                                               const MindlinPlate   &plate,
                                               const Vector<double> &solution,
                                               const ContactState   &contact,
                                               const Point<2>       &start,
                                               const Point<2>       &end) const
  {
    const FoundationSpace &space = plate.get_foundation_space();
    std::ostringstream     nodes;
    nodes << "x,y,w,q,gap,contact\n" << std::setprecision(10);
    // The whole plate: the nodes of the computed part and, for a symmetric
    // scene, their distinct mirror images.
    for (unsigned int i = 0; i < space.n_nodes(); ++i)
      for (const Point<2> &x : space.symmetry.images(space.node_locations[i]))
        nodes << x[0] << ',' << x[1] << ',' << contact.w[i] << ','
              << contact.q[i] << ',' << contact.gap[i] << ','
              << (contact.in_contact[i] ? 1 : 0) << '\n';
    write_file("nodes-" + two_digits(cycle) + ".csv", nodes.str());

    // Gauss points of the cells the line crosses or borders, keeping those
    // nearest to the line in each cell.
    const Tensor<1, 2> direction = (end - start) / end.distance(start);
    const auto         distance  = [&](const Point<2> &x) {
      const Tensor<1, 2> d = x - start;
      return std::abs(d[0] * direction[1] - d[1] * direction[0]);
    };
    const QGauss<2>                    rule(2);
    FEValues<2>                        values(plate.get_fe(),
                       rule,
                       update_gradients | update_quadrature_points);
    std::vector<Tensor<2, 2>>          grad(rule.size());
    std::vector<std::array<double, 4>> rows;
    // (Mx and My are even across mirror planes: the images of a cell's
    // Gauss points, never on a plane, carry its values.)
    std::vector<std::array<double, 2>> transforms = {{{1., 1.}}};
    for (const auto &signs : space.symmetry.reflections())
      transforms.push_back(signs);
    for (const auto &signs : transforms)
      for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
        {
          values.reinit(cell);
          std::vector<Point<2>> points;
          for (const Point<2> &x : values.get_quadrature_points())
            points.emplace_back(signs[0] * x[0], signs[1] * x[1]);
          double nearest = std::numeric_limits<double>::max();
          for (const Point<2> &x : points)
            nearest = std::min(nearest, distance(x));
          if (nearest > cell->diameter() / 2)
            continue;
          values[FEValuesExtractors::Vector(1)].get_function_gradients(solution,
                                                                       grad);
          for (unsigned int q = 0; q < rule.size(); ++q)
            if (distance(points[q]) <= nearest * (1 + 1e-8))
              {
                const Moments m = plate.moments_of_rotation_gradient(grad[q]);
                rows.push_back({{points[q][0], points[q][1], m.mx, m.my}});
              }
        }
    std::sort(rows.begin(), rows.end(), [&](const auto &a, const auto &b) {
      return (Point<2>(a[0], a[1]) - start) * direction <
             (Point<2>(b[0], b[1]) - start) * direction;
    });
    std::ostringstream csv;
    csv << "x,y,Mx,My\n" << std::setprecision(10);
    for (const auto &r : rows)
      csv << r[0] << ',' << r[1] << ',' << r[2] << ',' << r[3] << '\n';
    write_file("gauss-profile-" + two_digits(cycle) + ".csv", csv.str());
  }

  void
  ResultsOutput::write_vtu(const unsigned int    cycle,
                           const MindlinPlate   &plate,
                           const Vector<double> &solution,
                           const ContactState   &contact)
  {
    // q, gap and the contact indicator share the Q2 space of w: pack them
    // into the three components of one vector on the plate's FESystem.
    const auto    &fe = plate.get_fe();
    Vector<double> indicator(contact.q.size());
    for (unsigned int i = 0; i < indicator.size(); ++i)
      indicator[i] = contact.in_contact[i] ? 1. : 0.;
    const Vector<double> fields[3] = {
      plate.foundation_field_to_solution(contact.q),
      plate.foundation_field_to_solution(contact.gap),
      plate.foundation_field_to_solution(indicator)};
    Vector<double>                       packed(solution.size());
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < 9; ++i)
          for (unsigned int c = 0; c < 3; ++c)
            packed[dofs[fe.component_to_system_index(c, i)]] =
              fields[c][dofs[fe.component_to_system_index(0, i)]];
      }

    PieceDataOut data_out;
    data_out.attach_dof_handler(plate.get_dof_handler());
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      solution_kind = {
        DataComponentInterpretation::component_is_scalar,
        DataComponentInterpretation::component_is_part_of_vector,
        DataComponentInterpretation::component_is_part_of_vector};
    data_out.add_data_vector(solution,
                             std::vector<std::string>{"w", "beta", "beta"},
                             DataOut<2>::type_dof_data,
                             solution_kind);
    data_out.add_data_vector(packed,
                             std::vector<std::string>{"q", "gap", "contact"});
    const MomentsPostprocessor moments(plate);
    data_out.add_data_vector(solution, moments);
    // each cell's slab (plate/slab_grid.h): the joints lie where it changes
    Vector<float> slab(
      plate.get_dof_handler().get_triangulation().n_active_cells());
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      slab[cell->active_cell_index()] = cell->material_id();
    data_out.add_data_vector(slab, "slab", DataOut<2>::type_cell_data);
    const std::string name = "solution-" + two_digits(cycle) + ".vtu";
    if (n_ranks(communicator) == 1)
      {
        data_out.build_patches(2);
        std::ostringstream vtu;
        data_out.write_vtu(vtu);
        write_file(name, vtu.str());
      }
    else
      {
        // Every rank holds the whole solution on the whole mesh; each
        // builds the patches of its own cells (partition_plate_mesh()) and
        // sends its <Piece> to rank 0, which writes the one file as every
        // other: to a temporary name created afresh, never through a link.
        // (MPI-IO would open a path on every rank, following whatever link
        // is planted there.)
        const types::subdomain_id rank = rank_in(communicator);
        data_out.set_cell_selection(
          [rank](const Triangulation<2>::cell_iterator &cell) {
            return cell->is_active() && cell->subdomain_id() == rank;
          });
        data_out.build_patches(2);
        const std::vector<std::string> pieces =
          Utilities::MPI::gather(communicator, data_out.piece(), 0);
        if (writes_files())
          {
            std::ostringstream vtu;
            DataOutBase::write_vtu_header(vtu, DataOutBase::VtkFlags());
            bool any = false;
            for (const std::string &piece : pieces)
              {
                vtu << piece;
                any = any || !piece.empty();
              }
            // a file without any piece is not valid VTU: rank 0 writes its
            // empty one (as DataOut::write_vtu_in_parallel() does)
            if (!any)
              vtu << data_out.piece(true);
            DataOutBase::write_vtu_footer(vtu);
            write_file(name, vtu.str());
          }
      }
    if (!writes_files())
      return;

    pvd_records.erase(std::remove_if(pvd_records.begin(),
                                     pvd_records.end(),
                                     [&](const auto &r) {
                                       return r.second == name;
                                     }),
                      pvd_records.end());
    pvd_records.emplace_back(cycle, name);
    std::ostringstream pvd;
    DataOutBase::write_pvd_record(pvd, pvd_records);
    write_file("solution.pvd", pvd.str());
  }

  void
  ResultsOutput::write_convergence(ConvergenceTable &table) const
  {
    std::ostringstream text;
    table.write_text(text, TableHandler::org_mode_table);
    write_file("convergence.txt", text.str());
  }
} // namespace PlateOnHalfspace
