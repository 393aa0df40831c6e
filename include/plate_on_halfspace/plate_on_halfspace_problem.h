/**
 * The application (doc/architecture.md, "One cycle"): the adaptive loop of
 * doc/formulation.md ("Adaptive refinement") around the contact iteration,
 * driven by a scene file. Each cycle runs named phases, as deal.II's
 * step-42 does: set up the plate, build the foundation operator, solve
 * contact, postprocess, write, and refine for the next cycle. The driver
 * chooses the variants from the scene (storage, contact solver) and talks
 * to each family only through its interface.
 */
#ifndef plate_on_halfspace_plate_on_halfspace_problem_h
#define plate_on_halfspace_plate_on_halfspace_problem_h

#include <deal.II/base/timer.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/io/results_output.h>
#include <plate_on_halfspace/plate/generalized_inverse.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/refinement/dual_weighted_residual.h>
#include <plate_on_halfspace/refinement/goal.h>
#include <plate_on_halfspace/scene/mirror_symmetry.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** A scene solved cycle by cycle; results go to the output directory. */
  class PlateOnHalfspaceProblem
  {
  public:
    /** @p log receives the per-cycle and per-iteration lines. */
    PlateOnHalfspaceProblem(const SceneParameters &parameters,
                            std::ostream          &log);

    /**
     * Run all cycles and the verification checks. Throws on bad input or a
     * failed solve (the earlier run's results stay on disk). Returns false
     * if a verification check failed.
     */
    bool
    run();

    const std::vector<ResultRecord> &
    summaries() const
    {
      return cycle_summaries;
    }
    const MindlinPlate &
    plate() const
    {
      return *mindlin_plate;
    }
    /** The last cycle's plate, e.g. to solve it again in a test. */
    MindlinPlate &
    plate()
    {
      return *mindlin_plate;
    }
    const Vector<double> &
    solution() const
    {
      return contact.plate_solution;
    }
    const ContactState &
    contact_state() const
    {
      return contact;
    }
    const FoundationOperator &
    foundation() const
    {
      return *foundation_operator;
    }
    FoundationOperator &
    foundation()
    {
      return *foundation_operator;
    }

    /** w, q, Mx, My at a point of the plate (last cycle). */
    PointValues
    values_at(const Point<2> &x) const;

    /** The warnings of the run so far, each also printed on stderr as
     *  "Warning: ..." (by rank 0): loads partly off the plate, a load
     *  resultant near the outline (plate/load_checks.h). */
    const std::vector<std::string> &
    warnings() const
    {
      return run_warnings;
    }

  private:
    /**
     * The coarse mesh, the mirror planes the scene is solved with, its
     * loads on the computed part (mirror_symmetry.h) and the initial
     * global refinements.
     */
    void
    make_mesh();

    /**
     * Refuse a plate more than largest_relative_stiffness times stiffer
     * than the soil across its narrowest extent @p plate_width (its
     * bounding box's, or its narrowest slab's), naming the entries (see
     * the implementation).
     */
    void
    check_plate_against_soil(const double plate_width) const;

    /** The largest SoilModel::relative_stiffness() of the plate at its
     *  size that a run accepts (doc/errors-and-limits.md, "Stiffness
     *  ratio"); check_plate_against_soil()'s message spells it 1e6. */
    static constexpr double largest_relative_stiffness = 1e6;

    /** Distribute DoFs and assemble the plate's stiffness, the latter
     *  only if @p stiffness_needed (asked once the DoFs are there) says so
     *  or is empty. */
    void
    setup_plate(const std::function<bool()> &stiffness_needed = {});

    /** For setup_plate(): the stiffness unless the nested start is about
     *  to coarsen the mesh. */
    std::function<bool()>
    stiffness_unless_coarsened() const;

    /**
     * Why solve_on_coarser_mesh() does not coarsen the present mesh: an
     * empty text where Contact/Nested start leaves it alone without a
     * word (false, or auto below its node count), else the reason that
     * `true` warns of; nullopt where it coarsens. Reads the plate's
     * foundation nodes (set up at least by MindlinPlate::setup_dofs()).
     */
    std::optional<std::string>
    nested_start_obstacle() const;

    /** The level of every active cell, or -1 if they differ. */
    int
    nested_start_level() const;

    /**
     * Refine for the next cycle, set up the plate anew and transfer the
     * active set and the pressure as the next seed. Returns false if
     * Adaptivity/Max cells
     * stops the refinement.
     */
    bool
    refine_mesh();

    /**
     * Refine where @p mark flags the cells (false: nothing flagged, no
     * refinement), set up the plate anew and carry the active set and
     * the pressure over as the seed. Returns what @p mark returned.
     */
    bool
    refine_and_carry_seed(const std::function<bool()> &mark);

    /**
     * Contact/Nested start: where it applies to the first cycle, solve
     * the scene on the mesh one refinement coarser (every cell coarsened
     * once), quietly, refine back and seed the cycle with that contact
     * set and pressure (doc/formulation.md, "Nested start"). The coarse
     * solve is seeded the same way where its mesh qualifies in turn
     * (@p within_nested: such an inner call, which does not warn).
     * Returns the wall time it took, 0 where it does not apply.
     */
    double
    solve_on_coarser_mesh(const bool within_nested = false);

    /** The plate's loads and the cycle's first summary entries. */
    void
    assemble_loads(const unsigned int cycle);

    /**
     * Make (when the storage changes) and build the half-space operator
     * on the plate's foundation space, after the memory guard.
     */
    void
    build_foundation_operator();

    /**
     * Solve contact from the seed with the cycle's contact solver. Where
     * Contact/Solver and Foundation operator/Storage are both auto and the
     * conjugate gradients fail (a plate far more flexible than the soil),
     * rebuild the operator dense and solve with the direct solver, for
     * this and the later cycles, if the dense block fits the memory
     * (doc/errors-and-limits.md, "Stiffness ratio").
     */
    void
    solve_contact();

    /** The cycle's storage and contact solver: the scene's choice for
     *  @p n_foundation_nodes, or dense and direct after a failure of the
     *  conjugate gradients (solve_contact()), or hierarchical where auto
     *  chose fft and the mesh does not suit it or its near field did not
     *  fit the memory (build_foundation_operator()). */
    Parameters::FoundationOperator::Storage
    cycle_storage(const unsigned int n_foundation_nodes) const;

    Parameters::Contact::Solver
    cycle_solver(const unsigned int n_foundation_nodes) const;

    /**
     * Whether Storage and Solver = auto take dense and direct for
     * @p n_foundation_nodes although the scene's choice is a compressed
     * storage (hierarchical or fft) and iterative: where the plate is so much
     * more flexible than the soil that rounding would stop the iterative
     * solver's pressures near or above accepted_rounding_floor
     * (contact/pressure_preconditioner.h), and the dense block fits the memory.
     */
    bool
    direct_for_flexible_plate(const unsigned int n_foundation_nodes) const;

    /**
     * Warn if a solve stopped at the rounding floor above the tolerance:
     * @p residual is its ContactState::rounding_limited_residual (0: it
     * did not), @p what names the solve.
     */
    void
    warn_rounding_floor(const double residual, const std::string &what);

    /**
     * Warn (once per run) if the cycle's contact region, located inside
     * the cells, measures less than the smallest cell that carries it: a
     * plate that bears on a few nodes, whose contact area and pressure
     * peak the mesh does not resolve.
     */
    void
    warn_unresolved_contact_region();

    /**
     * Warn (once per run) if the cycle's contact set carries the plate
     * only through nodes without pressure (carried_on_knife_edge()).
     */
    void
    warn_knife_edge();

    /**
     * Why the goal's estimated error leaves out part of the cycle's error
     * (doc/errors-and-limits.md, "Goal error estimates"): element exclusion
     * stops with nodes in tension, and the estimate is of the
     * discretisation on that contact set only. Empty otherwise.
     */
    std::string
    goal_estimate_beside_tensile_nodes() const;

    /** Cells too coarse for a feature they carry: how many times its
     *  allowed ratio the worst exceeds (0 where none does), and why. */
    struct UnresolvedCells
    {
      double      excess = 0;
      std::string warning;
    };

    /**
     * Why the mesh, solved for @p loads with the contact @p state, does
     * not resolve the length over which the deflection varies
     * (doc/errors-and-limits.md, "Cells larger than l"): a cell carrying
     * a load's edge (Load::jump_on()) larger than the larger of l and the
     * load's size, a cell on a free edge the temperature curls (unless
     * @p moving_features_only: the features a sweep's position moves), or
     * a cell on the line where a tensionless plate lifts off larger than
     * l. @p mesh names the mesh and position in the warning.
     */
    UnresolvedCells
    cells_larger_than_deflection_length(const LoadList     &loads,
                                        const ContactState &state,
                                        const bool         moving_features_only,
                                        const std::string &mesh) const;

    /**
     * The goal's value and the dual-weighted residual estimate of its
     * error (doc/formulation.md, "Goal-oriented refinement"): the adjoint
     * problem on the cycle's contact set, solved by the cycle's contact
     * solver.
     */
    void
    estimate_goal_error();

    /** Fill the cycle's summary: equilibrium, extremes, probes. */
    void
    postprocess();

    /** The result files of the cycle and the per-cycle log lines. */
    void
    write_output();

    /** standing_solution: the plate under its weight, temperature and
     *  uniform pressure alone, for the joints' LTE. */
    void
    solve_standing_loads();

    /** Every position of Loads/Sweep has its loads on the plate. */
    void
    check_sweep_positions();

    /**
     * The checks of the assembled loads of @p loads on this mesh
     * (plate/load_checks.h): a warning for each patch and tyre partly off
     * the plate (if @p warn_off_plate), and on a tensionless foundation
     * the refusal of a resultant on the outline, or a warning when the
     * plate is carried on a region smaller than the cells (if
     * @p warn_resultant). @p where starts every message.
     */
    void
    check_loads_on_plate(const LoadList    &loads,
                         const std::string &where,
                         const bool         warn_off_plate,
                         const bool         warn_resultant);

    /**
     * The scene's loads with the axles moved by @p offset (Loads/Sweep),
     * the plate's weight among them: on the whole plate, or on the
     * computed part of a symmetric scene if @p computed_part.
     */
    LoadList
    loads_at(const Tensor<1, 2> &offset, const bool computed_part) const;

    /**
     * Refuse a scene whose results would not fit the output files, before
     * anything is computed: the scales of the results that the assembled
     * loads give (doc/errors-and-limits.md, "Finite results").
     */
    void
    check_result_magnitudes() const;

    /**
     * Refuse, before anything is computed, a point of Output/Probe points
     * or Verification/Checks that is not on the plate, naming the entry
     * and the point: on the first mesh, which covers the plate exactly
     * but for a disk, whose outline is then |x| <= radius.
     */
    void
    check_points_on_plate() const;

    /**
     * Refuse to write a cycle whose results hold a NaN or an infinity, or
     * a value beyond what the VTU files hold, naming the quantity.
     */
    void
    check_results_are_finite() const;

    /** Print "Warning: @p text" on stderr (rank 0) and keep it. */
    void
    warn(const std::string &text);

    /** Loads/Sweep: move the axles along the path on the last mesh and
     *  write the envelope (sweep.csv, summary.json "sweep"). */
    void
    run_sweep();

    bool
    run_checks() const;

    const SceneParameters parameters;
    std::ostream         &log;
    MirrorSymmetry        symmetry;
    /** The loads on the computed part (loads_at() without an offset). */
    LoadList computed_loads;
    /** Whether a cycle has warned about load_integration_error. */
    bool integration_error_warned = false;
    /** Whether a cycle has warned about an unresolved contact region. */
    bool unresolved_contact_warned = false;
    /** Whether a cycle has warned about a plate on a knife edge. */
    bool knife_edge_warned = false;
    /** The plate's radius of relative stiffness l on the soil. */
    double relative_stiffness_radius = 0;
    /** cells_larger_than_deflection_length() of the last cycle. */
    std::string unresolved_deflection_length;
    /** goal_estimate_beside_tensile_nodes() of the last cycle. */
    std::string unmet_contact_conditions;
    /** The nested start's coarse solve is running: warn() holds its text
     *  back (the first cycle checks that mesh again), and the contact
     *  solve stops at the contact set, a seed needing no more. */
    bool coarse_solve_running = false;
    /** Contact/Nested start = true whose coarse solve stopped: said once
     *  the first cycle has solved, so that a scene refused on the mesh as
     *  given shows its refusal alone. */
    std::string nested_start_note;
    /** The nested start is running on the coarser meshes: the phases
     *  (plate setup, operator, contact solve) are timed in its own
     *  TimerOutput section, not in theirs, which then hold the mesh the
     *  cycle solves only (Output/Verbosity = 2). */
    bool timing_nested_start = false;
    /** MPI_COMM_WORLD under MPI, else MPI_COMM_SELF: the ranks that
     *  share the mesh (doc/parallel.md). */
    const MPI_Comm   communicator;
    Triangulation<2> triangulation;

    /** The slabs and joints (one slab unless Plate/Shape = slabs). */
    std::unique_ptr<SlabGrid>     slab_grid;
    std::unique_ptr<MindlinPlate> mindlin_plate;
    /** The cycle's contact solver (the adjoint problem reuses it). */
    std::unique_ptr<ContactSolver> contact_solver;
    /** The plate's K^+ analysed beside the operator's build, for the
     *  iterative contact solver of the same cycle (nullptr otherwise). */
    std::unique_ptr<PlateGeneralizedInverse> plate_inverse;
    /** Adaptivity/Goal (none: no estimate) and the cycle's estimate. */
    std::shared_ptr<const GoalFunctional> goal;
    GoalErrorEstimate                     goal_estimate;
    /** The soil (Foundation/Model), made once per run. */
    std::shared_ptr<const SoilModel> soil;
    /** What the log last said of the soil's kernel (said once). */
    std::string last_kernel_report;
    /** Whether the coarse-cells warning of a layered soil was given. */
    bool                                coarse_cell_warned = false;
    std::unique_ptr<FoundationOperator> foundation_operator;
    /** The storage foundation_operator was made with. */
    Parameters::FoundationOperator::Storage operator_storage;
    /** The conjugate gradients failed in a cycle where auto chose them:
     *  that and every later cycle use dense storage and the direct
     *  solver. */
    bool direct_after_failed_iterations = false;
    /** Storage = auto chose fft and its near field did not fit the
     *  memory: that and every later cycle use the hierarchical storage. */
    bool hierarchical_after_fft_did_not_fit = false;
    /** Storage = auto would choose fft, but this cycle's mesh is too
     *  graded for it to pay (split_kernel_mesh_obstacle()):
     *  the hierarchical storage. */
    bool fft_unsuited_cycle = false;
    /** direct_for_flexible_plate() of this cycle, decided once by all
     *  ranks together in build_foundation_operator(). */
    bool direct_for_flexible_plate_cycle = false;
    /** The active set and the pressure of the previous cycle on the
     *  current mesh. */
    ContactSeed  seed;
    ContactState contact;
    /** q as a field on the plate's w-space (for point values). */
    Vector<double> pressure_field;
    /** The plate under its standing loads alone (solve_standing_loads()),
     *  empty where the joints' LTE needs none. */
    Vector<double> standing_solution;

    /** The record of the cycle being solved and of all cycles so far
     *  (doc/outputs.md, "summary.json"). */
    ResultRecord                   summary;
    std::vector<ResultRecord>      cycle_summaries;
    std::unique_ptr<ResultsOutput> output;

    /** Wall times of the cycle (s): plate setup, and the cycle so far;
     *  building the foundation operator. */
    double setup_time_s = 0, foundation_time_s = 0;
    /** Wall time of the first cycle's nested start (s; 0 without). */
    double nested_start_time_s = 0;
    Timer  cycle_timer;
    /** Wall times per phase, printed with Output/Verbosity = 2. */
    TimerOutput timer_output;
    /** warnings() */
    std::vector<std::string> run_warnings;
  };

  /**
   * The message of an error for the user: the "Additional information" of
   * a deal.II exception (the text of ExcMessage, naming the parameter or
   * the physical reason), else what(), on one line, its control
   * characters escaped (printable(), scene/input_checks.h).
   */
  std::string
  short_error_message(const std::exception &error);
} // namespace PlateOnHalfspace

#endif
