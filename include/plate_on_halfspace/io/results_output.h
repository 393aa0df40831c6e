/**
 * Results of a run in the output directory (doc/outputs.md):
 * summary.json (written atomically after every cycle), profile-NN.csv,
 * solution-NN.vtu with solution.pvd, and convergence.txt.
 */
#ifndef plate_on_halfspace_io_results_output_h
#define plate_on_halfspace_io_results_output_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/base/result_record.h>
#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  class FoundationOperator;

  /** Values at one point of the plate. */
  struct PointValues
  {
    Point<2> location;
    double   w = 0, q = 0, mx = 0, my = 0;
    /** Fibre stresses at the point (MindlinPlate::fibre_stresses()). */
    FibreStresses stresses;
  };

  /** One position of Loads/Sweep (doc/outputs.md, "sweep.csv"). */
  struct SweepRow
  {
    /** The offset of every axle group at this position. */
    Point<2> position;
    /** The load the plate carries at this position (what is off the
     *  plate is not applied; doc/outputs.md, sweep.csv). */
    double   applied_load = 0;
    double   max_w = 0, max_stress_bottom = 0, max_stress_top = 0;
    Point<2> max_w_at, max_stress_bottom_at, max_stress_top_at;
    double   contact_area_fraction = 0;
    /** The LTE of the joint the axles load most (the largest w_loaded;
     *  NaN without joints) and that joint's index. */
    double       min_lte            = 0;
    unsigned int min_lte_joint      = 0;
    unsigned int contact_iterations = 0;
    double       wall_time_s        = 0;
  };

  /**
   * Evaluates a solved cycle (fields, extremes, points) and writes the result
   * files (doc/outputs.md, "Safety of the output directory"):
   * - every file is written to a temporary name created afresh and never
   *   through a link, and renamed into place, so no file is ever half
   *   written and a planted link is never followed;
   * - the constructor locks the directory against a second run, checks that
   *   it takes new files, mends what a killed run left, and moves the
   *   earlier run's results to previous-run/; commit() writes the flag file
   *   `complete` last and drops them, abandon() moves this run's files to
   *   failed-run/ and brings them back;
   * - nothing is removed but this program's own result files (by name), and
   *   previous-run/ and failed-run/ when they are then empty.
   * Only rank 0 touches the directory; the other ranks send it their part
   * of the VTU.
   */
  class ResultsOutput
  {
  public:
    /**
     * Creates, locks and prepares @p directory (above). Under MPI every rank
     * holds the whole solution on its shared mesh, and only rank 0 of
     * @p communicator touches the directory (doc/parallel.md); summary.json
     * records the number of ranks and the partitioner.
     */
    explicit ResultsOutput(const std::string &directory,
                           const MPI_Comm     communicator = MPI_COMM_SELF);

    /** A run that neither committed nor abandoned is abandoned; the lock
     *  is released. */
    ~ResultsOutput();

    ResultsOutput(const ResultsOutput &) = delete;
    ResultsOutput &
    operator=(const ResultsOutput &) = delete;

    /**
     * What the constructor found of a killed earlier run and did about it
     * (one line), or empty.
     */
    const std::string &
    recovery_note() const
    {
      return recovery;
    }

    /**
     * The run succeeded: summary.json is rewritten with "finished": true,
     * the flag file `complete` is written last, and the earlier run's
     * results are dropped; the lock is released.
     */
    void
    commit();

    /**
     * The run failed: its files go to failed-run/ (for diagnosis) and the
     * earlier run's results come back; the lock is released. Returns a
     * one-line note saying so, empty if the run had written nothing.
     */
    std::string
    abandon();

    /** Whether @p name is one of the files a run writes (doc/outputs.md). */
    static bool
    is_result_file(const std::string &name);

    /**
     * A solved cycle's results into its @p record, producer by producer
     * (each declares its keys; base/result_record.h): the peaks of the
     * fields (plate/field_extrema.h; @p pressure_field: the nodal pressures
     * interpolated in the w-space), the contact (contact/contact_results.h),
     * the values at @p probe_points, and per slab and joint of a slab grid
     * (plate/slab_results.h) the joints' LTE relative to @p standing (the
     * plate under its standing loads; empty: none).
     */
    void
    evaluate(const MindlinPlate          &plate,
             const Vector<double>        &solution,
             const Vector<double>        &pressure_field,
             const ContactState          &contact,
             const FoundationOperator    &foundation,
             const std::vector<Point<2>> &probe_points,
             ResultRecord                &record,
             const Vector<double>        &standing = Vector<double>()) const;

    /** w, q, Mx, My at @p x (q from the FE pressure field). */
    PointValues
    point_values(const MindlinPlate   &plate,
                 const Vector<double> &solution,
                 const Vector<double> &pressure_field,
                 const Point<2>       &x) const;

    /** summary.json over the records of all cycles so far; a non-empty
     *  @p sweep adds its envelope (@p slab_grid names its joints). Until
     *  commit() it says "finished": false and "converged": false; commit()
     *  sets both. */
    void
    write_summary(const std::vector<ResultRecord> &cycles,
                  const std::string               &symmetry,
                  const bool                       converged,
                  const SlabGrid                  &slab_grid,
                  const std::vector<SweepRow>     &sweep = {});

    /** sweep.csv: one row per position of Loads/Sweep. */
    void
    write_sweep(const std::vector<SweepRow> &sweep) const;

    /** profile-NN.csv along a line (points off the plate are skipped). */
    void
    write_profile(const unsigned int    cycle,
                  const MindlinPlate   &plate,
                  const Vector<double> &solution,
                  const ContactState   &contact,
                  const Point<2>       &start,
                  const Point<2>       &end,
                  const unsigned int    n_points) const;

    /**
     * nodes-NN.csv: x,y,w,q,gap,contact at every foundation node (the
     * contact map), and gauss-profile-NN.csv: x,y,Mx,My at the 2x2 Gauss
     * points nearest the profile line (the paper plots Mx there).
     */
    void
    write_nodes_and_gauss_profile(const unsigned int    cycle,
                                  const MindlinPlate   &plate,
                                  const Vector<double> &solution,
                                  const ContactState   &contact,
                                  const Point<2>       &start,
                                  const Point<2>       &end) const;

    /**
     * solution-NN.vtu and solution.pvd. On several ranks every rank builds
     * the patches of the cells METIS gave it and all write the one VTU
     * together (doc/parallel.md); collective.
     */
    void
    write_vtu(const unsigned int    cycle,
              const MindlinPlate   &plate,
              const Vector<double> &solution,
              const ContactState   &contact);

    /** convergence.txt: a row per cycle of the declared columns
     *  (declare_results()), as a ConvergenceTable's text. */
    void
    write_convergence(const std::vector<ResultRecord> &cycles) const;

    /** Write @p text to @p name in the directory, atomically. */
    void
    write_file(const std::string &name, const std::string &text) const;

    /**
     * Write @p name as write_file() does, its text made part by part, so
     * that a large file is never held whole: @p next_part points its
     * argument at the next part, which stays valid until the next call,
     * and returns whether more follow.
     */
    void
    write_file_in_parts(
      const std::string                             &name,
      const std::function<bool(std::string_view &)> &next_part) const;

  private:
    /** On rank 0: creates, locks, checks and prepares the directory (the
     *  constructor's work). */
    void
    prepare_directory();

    /** Takes the lock file's flock; a second run is refused at once. */
    void
    lock_directory();

    /** Releases the lock and removes the lock file (if still ours). */
    void
    unlock_directory();

    /** Creates and removes a probe file: the directory takes new files. */
    void
    check_writable() const;

    /** Removes the temporary files (.NAME.tmp) a killed run left. */
    void
    remove_stale_temporaries() const;

    /** After a killed run: the newest complete results back in place. */
    void
    recover_interrupted_run();

    /** The directory's result files into previous-run/, `complete` first. */
    void
    set_earlier_results_aside();

    /** previous-run/'s result files back, `complete` last. */
    void
    restore_earlier_results() const;

    /** The directory's result files into failed-run/. */
    void
    set_failed_run_aside();

    /** previous-run/ or failed-run/ opened (created if @p create), never
     *  through a link; -1 if missing. */
    int
    open_results_folder(const char *name, const bool create) const;

    /** Removes the result files of previous-run/ or failed-run/, then the
     *  folder if it is empty. */
    void
    remove_results_folder(const char *name) const;

    /** The names of the result files (regular files, not links) in the
     *  open directory @p directory. */
    static std::vector<std::string>
    result_files_in(const int directory);

    /** Moves the result files from @p from to @p to (open directories;
     *  @p where names @p to in a message): `complete` first if
     *  @p flag_first, else last. */
    unsigned int
    move_result_files(const int   from,
                      const int   to,
                      const bool  flag_first,
                      std::string where) const;

    /** Removes the result files of the open directory @p directory. */
    static void
    remove_result_files(const int directory);

    /** Whether this rank touches the directory: rank 0 only. */
    bool
    writes_files() const;

    std::string directory;
    std::string previous_run, failed_run;
    /** The output directory and the lock file, open on rank 0 (-1: not). */
    int directory_fd = -1, lock_fd = -1;
    /** The run's ranks: all build the VTU, rank 0 writes every file; their
     *  number goes into summary.json. */
    MPI_Comm                                    communicator;
    bool                                        finished = false;
    std::vector<std::pair<double, std::string>> pvd_records;
    /** The last summary.json written, its cycles and whether they all
     *  converged: commit() rewrites it as finished. */
    std::string  summary_text;
    bool         summary_converged = false;
    unsigned int summary_cycles    = 0;
    /** Result files moved to failed-run/ by the last set_failed_run_aside(). */
    unsigned int failed_files = 0;
    std::string  recovery;
    /** Whether the constructor began to move the earlier results. */
    bool setting_aside = false;
  };
} // namespace PlateOnHalfspace

#endif
