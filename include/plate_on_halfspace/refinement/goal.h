/**
 * The goal family (doc/formulation.md, "Goal-oriented refinement";
 * doc/architecture.md, "The goal family"): the quantity of interest of a
 * scene, Adaptivity/Goal. Every goal gives its value on a solved cycle and
 * says how its error is estimated; a goal of the plate's fields also gives
 * its derivative as a load on the plate, the adjoint problem's right-hand
 * side. Points refer to the whole plate; in a symmetric scene a point is
 * mirrored onto the computed part, where the solution takes the same
 * value. Each kind is one class in refinement/goals/ that registers its
 * syntax (GoalKind).
 */
#ifndef plate_on_halfspace_refinement_goal_h
#define plate_on_halfspace_refinement_goal_h

#include <deal.II/base/point.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/vector.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  class MindlinPlate;
  class ResultRecord;
  struct ContactState;
  struct GoalErrorEstimate;

  /** A quantity of interest (see the file documentation). */
  class GoalFunctional
  {
  public:
    /** The goal's value on a solved cycle and where it is linearised. */
    struct Evaluation
    {
      double value = 0;
      /** The point of a point value or of a peak (whole-plate coordinates
       *  of the computed part). */
      Point<2> location;
      bool     has_location = false;
      /** The sign a field odd across the mirror planes (Mxy) takes at the
       *  requested point against its image at location: -1 where the
       *  point was reflected in one plane, 1 otherwise. */
      double odd_field_sign = 1;
      /**
       * The cells the value was taken in, with the point's reference
       * coordinates in each: every cell that holds a point value's point,
       * MindlinPlate::locate()'s first (two on a cell edge, more at a
       * vertex or a joint), whose mean a moment is (doc/outputs.md, "Probe
       * and profile values"); w and q are read in the first. A peak has
       * the one cell it was found in.
       */
      std::vector<
        std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>>
        cells;
      /** Whether the point lies on a mirror plane, where Mxy of the whole
       *  plate, the mean of the cells on both sides, is 0. */
      bool on_mirror_plane = false;
    };

    /** How the goal's error is estimated. */
    enum class Estimate
    {
      /** An adjoint problem whose load is derivative(): a goal of the
       *  plate's deflection and rotations only. */
      dual_weighted_residual,
      /** The located contact area's uncertainty (contact_region.h). */
      contact_region,
      /** None: the change between cycles bounds the error
       *  (no_estimate_reason() says why). */
      change_only
    };

    /** @p text: the entry as the scene wrote it. */
    explicit GoalFunctional(const std::string &text);

    virtual ~GoalFunctional() = default;

    /** The goal as the scene names it. */
    const std::string &
    name() const
    {
      return text;
    }

    /** How the error is estimated: by default an adjoint problem, whose
     *  load derivative() gives. */
    virtual Estimate
    estimate() const
    {
      return Estimate::dual_weighted_residual;
    }

    /** For Estimate::change_only: why no estimate is made. */
    virtual std::string
    no_estimate_reason() const
    {
      return {};
    }

    /**
     * The goal's deflection terms c_k w(x_k) (points on the whole plate),
     * which the adjoint problem's soil residual treats apart; empty for
     * goals without such terms.
     */
    virtual std::vector<std::pair<Point<2>, double>>
    deflection_terms() const
    {
      return {};
    }

    /**
     * The value on the solved cycle: @p solution is the plate's, @p
     * pressure_field q in the plate's w-space.
     */
    virtual Evaluation
    evaluate(const MindlinPlate   &plate,
             const Vector<double> &solution,
             const Vector<double> &pressure_field,
             const ContactState   &contact) const = 0;

    /**
     * The derivative J'(u_h)(phi_i) at @p evaluation for every plate DoF
     * i, assembled with the plate's constraints like its load vector: the
     * adjoint problem's load. Only for Estimate::dual_weighted_residual;
     * the others throw.
     */
    virtual Vector<double>
    derivative(const MindlinPlate   &plate,
               const Vector<double> &solution,
               const Evaluation     &evaluation) const;

  protected:
    /**
     * The evaluation at the whole-plate point @p x: its image on the
     * computed part and the cells that hold it there. Throws naming
     * Adaptivity/Goal if @p x is off the plate.
     */
    static Evaluation
    at_point(const MindlinPlate &plate, const Point<2> &x);

    /** Add the cell vector @p local of @p cell to @p load with the
     *  plate's constraints. */
    static void
    add_cell_vector(const MindlinPlate                                 &plate,
                    const typename DoFHandler<2>::active_cell_iterator &cell,
                    const Vector<double>                               &local,
                    Vector<double>                                     &load);

  private:
    const std::string text;
  };

  /**
   * The goal's object "goal" of a cycle's @p record (doc/outputs.md): its
   * value, its estimate, its change from @p previous (the previous cycle's
   * record; null on the first), the error bound the run reports and
   * whether it met @p target_error (0: none), and @p time_s.
   */
  void
  add_goal_results(const GoalFunctional             &goal,
                   const GoalFunctional::Evaluation &value,
                   const GoalErrorEstimate          &estimate,
                   const ResultRecord               *previous,
                   const double                      target_error,
                   const double                      time_s,
                   ResultRecord                     &record);

  /**
   * A goal kind: how it is written and how a text of it becomes a goal.
   * Registered by the kind's own file (register_goal_kind()).
   */
  struct GoalKind
  {
    /** The syntax, for the message listing the kinds. */
    std::string syntax;
    /** Where the syntax stands in that message. */
    unsigned int position = 0;
    /**
     * The goal of the words of an entry (blanks separate them; "x, y" is
     * one word), or null if they are not of this kind. Throws ExcMessage
     * for words of this kind that are malformed.
     */
    std::function<
      std::unique_ptr<GoalFunctional>(const std::string              &text,
                                      const std::vector<std::string> &words)>
      parse;
  };

  /** Add @p kind to the goal kinds; returns true (for a static). */
  bool
  register_goal_kind(const GoalKind &kind);

  /**
   * The goal Adaptivity/Goal = @p text names; null for an empty text.
   * Throws ExcMessage naming the entry and the registered syntaxes
   * otherwise.
   */
  std::shared_ptr<const GoalFunctional>
  create_goal(const std::string &text);

  /**
   * The point "x,y" of a word of Adaptivity/Goal; none if the word holds
   * another count of points. Throws naming the entry for a word that is
   * not a number list.
   */
  std::optional<Point<2>>
  parse_goal_point(const std::string &word);
} // namespace PlateOnHalfspace

#endif
