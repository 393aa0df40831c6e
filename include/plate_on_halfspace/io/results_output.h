/**
 * Results of a run in the output directory (doc/outputs.md):
 * summary.json (written atomically after every cycle), profile-NN.csv,
 * solution-NN.vtu with solution.pvd, and convergence.txt.
 */
#ifndef plate_on_halfspace_io_results_output_h
#define plate_on_halfspace_io_results_output_h

#include <deal.II/base/convergence_table.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <string>
#include <utility>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** Values at one point of the plate. */
  struct PointValues
  {
    Point<2> location;
    double   w = 0, q = 0, mx = 0, my = 0;
    /** Fibre stresses at the point (MindlinPlate::fibre_stresses()). */
    FibreStresses stresses;
  };

  /** What summary.json reports for one cycle. */
  struct CycleSummary
  {
    unsigned int cycle = 0, n_cells = 0, n_dofs = 0, n_foundation_dofs = 0;
    unsigned int contact_iterations = 0, contact_nodes = 0;
    double       contact_area_fraction = 0;
    double       applied_load = 0, contact_force = 0;
    double       complementarity_violation = 0;
    unsigned int tensile_nodes             = 0;
    double       max_penetration           = 0;
    /** Peaks of the fields over the plate (plate/field_extrema.h): w, the
     *  pressure field q, the moments and the larger principal moment. */
    double max_w = 0, min_w = 0, max_q = 0, min_q = 0;
    double max_mx = 0, min_mx = 0, max_my = 0, min_my = 0;
    double max_principal_moment = 0;
    /** The largest principal stress of the bottom and the top fibre. */
    double max_principal_stress_bottom = 0, max_principal_stress_top = 0;
    /** Where each peak is (on the computed part of a symmetric scene). */
    Point<2> max_w_at, min_w_at, max_q_at, min_q_at;
    Point<2> max_mx_at, min_mx_at, max_my_at, min_my_at;
    Point<2> max_principal_moment_at;
    Point<2> max_principal_stress_bottom_at, max_principal_stress_top_at;
    /** Wall time of the cycle and its parts: plate assembly (setup,
     *  loads, condensation), half-space operator, contact solve, output. */
    double wall_time_s = 0, assembly_time_s = 0, foundation_time_s = 0;
    double solve_time_s = 0, output_time_s = 0;
    /** The half-space operator's time split: integration, compression
     *  (hierarchical storage), factorisation (FoundationOperator::
     *  BuildTimes); they add up to foundation_time_s. */
    double      foundation_integration_time_s   = 0;
    double      foundation_compression_time_s   = 0;
    double      foundation_factorization_time_s = 0;
    std::string foundation_storage;
    /** The foundation nodes each rank owns (one entry per process). */
    std::vector<unsigned int> foundation_nodes_per_rank;
    std::size_t               foundation_memory_bytes = 0;
    bool                      converged               = true;
    /** 1/κ₁ estimates of the coupled matrix and of the half-space block. */
    double coupled_matrix_rcond = 1, foundation_block_rcond = 1;
    std::vector<PointValues> probes;
    /** Per slab of a grid of slabs (plate/slab_grid.h): the largest
     *  principal stress of the bottom and the top fibre, and where. */
    struct SlabPeaks
    {
      double   max_principal_stress_bottom = 0, max_principal_stress_top = 0;
      Point<2> max_principal_stress_bottom_at, max_principal_stress_top_at;
    };
    std::vector<SlabPeaks> slabs;
    /** What each joint carries (plate/joints.h). */
    std::vector<JointResponse> joints;

    /** The cycle's value and error estimate of Adaptivity/Goal. */
    struct Goal
    {
      std::string quantity; ///< as the scene names it
      double      value = 0;
      /** Where a point value or a peak was taken. */
      bool     has_location = false;
      Point<2> location;
      /** The estimate of |true value - value|: sum of the local
       *  dual-weighted residuals' magnitudes (the contact area: its half
       *  band). */
      double estimated_error = 0;
      /** The dual-weighted residual, the signed estimate of true value
       *  minus value (not for the contact area). */
      bool   has_dwr = false;
      double dwr     = 0;
      /** value minus the previous cycle's (from the second cycle on). */
      bool   has_change = false;
      double change     = 0;
      /**
       * The error bound the run reports and Target error tests:
       * max(estimated_error, |change|) / |value|, estimated_error /
       * |value| on the first cycle (doc/formulation.md, "Goal-oriented
       * refinement").
       */
      double relative_error = 0;
      /** Adaptivity/Target error (0: none), and whether relative_error
       *  met it (never on the first cycle). */
      double target_error = 0;
      bool   target_met   = false;
      /** Wall time (s) of the value, the adjoint solve and the estimate. */
      double time_s = 0;
    };
    bool has_goal = false;
    Goal goal;
  };

  /** One position of Loads/Sweep (doc/outputs.md, "sweep.csv"). */
  struct SweepRow
  {
    /** The offset of every axle group at this position. */
    Point<2> position;
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
   * files. Every file is written to a temporary name and renamed, so no file
   * is ever half written. A run keeps the results of the run before it until
   * it succeeds: the constructor moves them to previous-run/, commit() drops
   * them, abandon() moves this run's files to failed-run/ and restores them.
   */
  class ResultsOutput
  {
  public:
    /**
     * Creates @p directory and sets the earlier run's results aside. Under
     * MPI every rank holds the whole solution on its shared mesh, and only
     * rank 0 of @p communicator touches the directory (doc/parallel.md);
     * summary.json records the number of ranks and the partitioner.
     */
    explicit ResultsOutput(const std::string &directory,
                           const MPI_Comm     communicator = MPI_COMM_SELF);

    /** A run that neither committed nor abandoned is abandoned. */
    ~ResultsOutput();

    /** The run succeeded: its results replace the earlier run's. */
    void
    commit();

    /**
     * The run failed: its files go to failed-run/ (for diagnosis) and the
     * earlier run's results come back. Returns a one-line note saying so,
     * empty if the run had written nothing.
     */
    std::string
    abandon();

    /** Whether @p name is one of the files a run writes (doc/outputs.md). */
    static bool
    is_result_file(const std::string &name);

    /**
     * The peaks of w, q (@p pressure_field: the nodal pressures
     * interpolated in the w-space), Mx, My and the larger principal
     * moment: the extremes of the finite element fields over the plate
     * with their locations (plate/field_extrema.h); the contact area, the
     * counts of nodes in contact and tensile, and the contact measures;
     * per slab and joint of a slab grid, the joints' LTE relative to
     * @p standing (the plate under its standing loads; empty: none).
     */
    void
    evaluate(const MindlinPlate   &plate,
             const Vector<double> &solution,
             const Vector<double> &pressure_field,
             const ContactState   &contact,
             CycleSummary         &summary,
             const Vector<double> &standing = Vector<double>()) const;

    /** w, q, Mx, My at @p x (q from the FE pressure field). */
    PointValues
    point_values(const MindlinPlate   &plate,
                 const Vector<double> &solution,
                 const Vector<double> &pressure_field,
                 const Point<2>       &x) const;

    /** summary.json over all cycles so far; @p slab_grid names the slabs
     *  and joints of the cycles' per-slab and per-joint results; a
     *  non-empty @p sweep adds its envelope. */
    void
    write_summary(const std::vector<CycleSummary> &cycles,
                  const std::string               &symmetry,
                  const bool                       converged,
                  const SlabGrid                  &slab_grid,
                  const std::vector<SweepRow>     &sweep = {}) const;

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

    /** convergence.txt (ConvergenceTable text). */
    void
    write_convergence(ConvergenceTable &table) const;

    /** Write @p text to @p name in the directory, atomically. */
    void
    write_file(const std::string &name, const std::string &text) const;

  private:
    /** Moves this program's result files from @p from to @p to. */
    static unsigned int
    move_result_files(const std::string &from, const std::string &to);

    /** Whether this rank touches the directory: rank 0 only. */
    bool
    writes_files() const;

    std::string directory;
    std::string previous_run, failed_run;
    /** The run's ranks: all write the VTU, rank 0 the other files; their
     *  number goes into summary.json. */
    MPI_Comm                                    communicator;
    bool                                        finished = false;
    std::vector<std::pair<double, std::string>> pvd_records;
  };
} // namespace PlateOnHalfspace

#endif
