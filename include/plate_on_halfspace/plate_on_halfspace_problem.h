/**
 * The application: the adaptive loop of doc/formulation.md ("Adaptive
 * refinement") around the contact iteration, driven by a scene file
 * (step-41/42 and ASPECT are the models).
 */
#ifndef plate_on_halfspace_plate_on_halfspace_problem_h
#define plate_on_halfspace_plate_on_halfspace_problem_h

#include <deal.II/base/convergence_table.h>
#include <deal.II/base/timer.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/direct_solver.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/scene/mirror_symmetry.h>
#include <plate_on_halfspace/scene/parameters.h>
#include <plate_on_halfspace/io/results_output.h>

#include <memory>
#include <optional>
#include <ostream>
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
     * failed solve (results of completed cycles stay on disk). Returns false
     * if a verification check failed.
     */
    bool
    run();

    const std::vector<CycleSummary> &
    summaries() const
    {
      return cycle_summaries;
    }
    const MindlinPlate &
    plate() const
    {
      return *mindlin_plate;
    }
    const Vector<double> &
    solution() const
    {
      return plate_solution;
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

    /** w, q, Mx, My at a point of the plate (last cycle). */
    PointValues
    values_at(const Point<2> &x) const;

  private:
    void
    solve_cycle(const unsigned int cycle, const std::vector<bool> &seed);
    /** Refine, set up the plate anew and transfer the contact set; none if
     *  Adaptivity/Max cells stops the refinement. */
    std::optional<std::vector<bool>>
    refine_and_transfer_contact();
    bool
    run_checks() const;
    /** Append the cycle's row to convergence.txt's table. */
    void
    add_convergence_row(const CycleSummary &summary);

    const SceneParameters parameters;
    std::ostream         &log;
    /** The mirror planes the scene is solved with, and its loads on the
     *  computed part (mirror_symmetry.h). */
    MirrorSymmetry    symmetry;
    Parameters::Loads computed_loads;
    /** Wall time of the plate setup (DoFs, constraints, stiffness) of the
     *  current cycle. */
    double                              setup_time_s = 0;
    Triangulation<2>                    triangulation;
    std::unique_ptr<MindlinPlate>       mindlin_plate;
    std::unique_ptr<FoundationOperator> foundation_operator;
    Vector<double>                      plate_solution;
    /** q as a field on the plate's w-space (for point values). */
    Vector<double>                 pressure_field;
    ContactState                   contact;
    std::vector<CycleSummary>      cycle_summaries;
    ConvergenceTable               convergence;
    std::unique_ptr<ResultsOutput> output;
    /** Wall times per phase, printed with Output/Verbosity = 2. */
    TimerOutput timer_output;
  };

  /**
   * The message of an error for the user: the "Additional information" of
   * a deal.II exception (the text of ExcMessage, naming the parameter or
   * the physical reason), else what(), on one line.
   */
  std::string
  short_error_message(const std::exception &error);
} // namespace PlateOnHalfspace

#endif
