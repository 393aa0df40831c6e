#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <plate_on_halfspace/base/number_list.h>
#include <plate_on_halfspace/base/result_record.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/refinement/dual_weighted_residual.h>
#include <plate_on_halfspace/refinement/goal.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    std::vector<GoalKind> &
    kinds()
    {
      static std::vector<GoalKind> list;
      return list;
    }

    /** A convergence.txt column of the goal object's @p value. */
    ConvergenceColumn
    goal_column(const std::string                                 &name,
                const std::string                                 &meaning,
                const std::function<double(const ResultRecord &)> &value,
                const bool                                         with_change,
                const unsigned int                                 precision)
    {
      return {name,
              meaning,
              [value](const ResultRecord &r, double &v) {
                if (!r.has("goal"))
                  return false;
                // a value without meaning (a relative one of a zero
                // goal) reads "-"
                v = value(r.object("goal"));
                return std::isfinite(v);
              },
              precision,
              true,
              with_change};
    }

    const bool declared_cycle = declare_results(
      "cycles",
      45,
      {{{"goal"},
        "–",
        "with `Adaptivity/Goal` only: the goal's value and error "
        "([below](#the-goal))",
        ResultKind::object}},
      {goal_column(
         "goal",
         "with `Adaptivity/Goal`: its `value`",
         [](const ResultRecord &g) { return g.number("value"); },
         true,
         6),
       goal_column(
         "goal estimate",
         "with `Adaptivity/Goal`: `estimated_error` / \\|`value`\\|",
         [](const ResultRecord &g) {
           return g.number("value") == 0 ?
                    std::numeric_limits<double>::quiet_NaN() :
                    g.number("estimated_error") / std::abs(g.number("value"));
         },
         false,
         2),
       goal_column(
         "goal error",
         "with `Adaptivity/Goal`: the reported error `relative_error`",
         [](const ResultRecord &g) {
           return g.is_number("relative_error") ?
                    g.number("relative_error") :
                    std::numeric_limits<double>::quiet_NaN();
         },
         false,
         2)});

    const bool declared_goal = declare_results(
      "cycles.goal",
      0,
      {{{"quantity"},
        "–",
        "the entry `Adaptivity/Goal` as written",
        ResultKind::text},
       {{"value"}, "the goal's", "its value on this cycle"},
       {{"at"},
        "length",
        "`[x, y]` of a point value or a peak, on the computed part (point "
        "values and peaks only)",
        ResultKind::location},
       {{"estimated_error"},
        "the goal's",
        "the estimate of \\|true − value\\|: Σ of the local dual-weighted "
        "residuals' magnitudes; for the contact area the cells' location "
        "uncertainties ([Contact area](#contact-area)); 0 for a goal without "
        "an estimate (`Refinement = goal` refuses it)"},
       {{"dwr"},
        "the goal's",
        "their signed sum, the estimate of true − value; `null` where there "
        "is no adjoint problem (the contact area, a pressure at a point)"},
       {{"change"},
        "the goal's",
        "value minus the previous cycle's; `null` on the first"},
       {{"relative_error"},
        "–",
        "the error the run reports (`null` when the value is 0): "
        "max(estimated_error, \\|change\\|, ρ/(1 − ρ) \\|change\\|) / "
        "\\|value\\|, ρ = change / the previous cycle's change where it "
        "lies in (1/2, 1); estimated_error / \\|value\\| on the first cycle. "
        "An estimate, not a guaranteed bound: on coarse meshes the true "
        "error has been up to 1.5 times it "
        "([formulation.md](formulation.md#goal-oriented-refinement))"},
       {{"target_error"}, "–", "`Adaptivity/Target error` (0: none)"},
       {{"target_met"},
        "–",
        "whether it was met: `relative_error` below it, the previous "
        "cycle's at most 4 times it, and the changes shrinking (never on "
        "the first two cycles: the changes' ratio needs two changes)",
        ResultKind::flag},
       {{"time_s"},
        "s",
        "wall time of the value, the adjoint solve and the estimate"}});
  } // namespace

  GoalFunctional::GoalFunctional(const std::string &text)
    : text(text)
  {}

  Vector<double>
  GoalFunctional::derivative(const MindlinPlate &,
                             const Vector<double> &,
                             const Evaluation &) const
  {
    AssertThrow(false,
                ExcMessage("Adaptivity/Goal = " + text +
                           " has no adjoint problem."));
    return {};
  }

  GoalFunctional::Evaluation
  GoalFunctional::at_point(const MindlinPlate &plate, const Point<2> &x)
  {
    Evaluation            e;
    const MirrorSymmetry &symmetry = plate.get_foundation_space().symmetry;
    e.location                     = symmetry.to_computed_part(x);
    e.has_location                 = true;
    e.odd_field_sign               = symmetry.odd_field_sign(x);
    try
      {
        e.cells = plate.cells_at(e.location);
      }
    catch (...)
      {
        AssertThrow(false,
                    ExcMessage("Adaptivity/Goal: the point " +
                               point_text(x[0], x[1]) +
                               " is not on the plate."));
      }
    e.on_mirror_plane = plate.on_mirror_plane(e.location);
    return e;
  }

  void
  GoalFunctional::add_cell_vector(
    const MindlinPlate                                 &plate,
    const typename DoFHandler<2>::active_cell_iterator &cell,
    const Vector<double>                               &local,
    Vector<double>                                     &load)
  {
    std::vector<types::global_dof_index> dofs(local.size());
    cell->get_dof_indices(dofs);
    plate.get_constraints().distribute_local_to_global(local, dofs, load);
  }

  bool
  register_goal_kind(const GoalKind &kind)
  {
    auto &list = kinds();
    list.push_back(kind);
    // the message lists the kinds in their stated order, whatever the
    // link order
    std::sort(list.begin(), list.end(), [](const auto &a, const auto &b) {
      return a.position < b.position;
    });
    return true;
  }

  std::shared_ptr<const GoalFunctional>
  create_goal(const std::string &entry)
  {
    const std::string text = Utilities::trim(entry);
    // "0, 0" and "0 ,0" are one word
    std::string compact = text;
    for (std::size_t at; (at = compact.find(", ")) != std::string::npos;)
      compact.erase(at + 1, 1);
    for (std::size_t at; (at = compact.find(" ,")) != std::string::npos;)
      compact.erase(at, 1);
    std::istringstream       stream(compact);
    std::vector<std::string> words;
    for (std::string word; stream >> word;)
      words.push_back(word);
    if (words.empty())
      return nullptr;
    for (const GoalKind &kind : kinds())
      if (std::unique_ptr<GoalFunctional> goal = kind.parse(text, words))
        return goal;
    std::string allowed;
    for (const GoalKind &kind : kinds())
      allowed += (allowed.empty() ? "" : " ; ") + kind.syntax;
    AssertThrow(false,
                ExcMessage("Adaptivity/Goal must be one of: " + allowed +
                           " (got <" + entry + ">)."));
    return nullptr;
  }

  std::optional<Point<2>>
  parse_goal_point(const std::string &word)
  {
    const std::vector<std::vector<double>> numbers =
      parse_number_list(word, 2, "Adaptivity/Goal", "x,y");
    if (numbers.size() != 1)
      return std::nullopt;
    return Point<2>(numbers[0][0], numbers[0][1]);
  }

  void
  add_goal_results(const GoalFunctional             &goal,
                   const GoalFunctional::Evaluation &value,
                   const GoalErrorEstimate          &estimate,
                   const ResultRecord               *previous,
                   const double                      target_error,
                   const double                      time_s,
                   ResultRecord                     &record)
  {
    (void)declared_cycle;
    (void)declared_goal;
    ResultRecord &g = record.set_object("goal");
    g.set("quantity", goal.name());
    g.set("value", value.value);
    if (value.has_location)
      g.set("at", value.location);
    g.set("estimated_error", estimate.estimated_error);
    if (estimate.has_dwr)
      g.set("dwr", estimate.dwr);
    else
      g.set_null("dwr");
    // The dual-weighted residual underestimates where the adjoint
    // solution is singular at the mesh's scale (doc/verification.md,
    // "Goal error estimates"): the bound also takes the last change.
    double     bound      = estimate.estimated_error;
    const bool has_change = previous != nullptr && previous->has("goal");
    // Whether the value's changes shrink: known from the second change on.
    bool converging = false;
    if (has_change)
      {
        const ResultRecord &before = previous->object("goal");
        const double        change = value.value - before.number("value");
        g.set("change", change);
        bound = std::max(bound, std::abs(change));
        // Where the changes shrink by a ratio rho, the error left is
        // rho/(1 - rho) times the last change: more than the change itself
        // once rho > 1/2 (a convergence order below 1 per halving).
        // Changes that do not shrink in magnitude (alternating ones
        // included, and any change after none) are not converging yet.
        if (before.is_number("change"))
          {
            const double previous_change = before.number("change");
            const double rho =
              previous_change != 0 ? change / previous_change :
              change != 0          ? std::numeric_limits<double>::infinity() :
                                     0.;
            converging = std::abs(rho) < 1;
            if (converging && rho > 0.5)
              bound = std::max(bound, rho / (1 - rho) * std::abs(change));
          }
      }
    else
      g.set_null("change");
    // A goal whose value is 0 (q where the plate has lifted) has no
    // relative error: NaN, written as null, which meets no target.
    const double relative_error = value.value != 0 ?
                                    bound / std::abs(value.value) :
                                    std::numeric_limits<double>::quiet_NaN();
    g.set_or_null("relative_error", relative_error);
    g.set("target_error", target_error);
    // A sudden drop below the target is not yet evidence: on coarse meshes
    // the estimate and one change can both be small while the value still
    // moves, or overshoots (doc/formulation.md, "Goal-oriented
    // refinement"). The target is met when the changes shrink (from the
    // third cycle on) and the previous cycle's error was within 4 times
    // the target: an error falls by at most 4 in a cycle of global
    // second-order refinement, and by less in an adaptive one.
    const bool previous_near =
      has_change && previous->object("goal").is_number("relative_error") &&
      previous->object("goal").number("relative_error") <= 4 * target_error;
    g.set("target_met",
          target_error > 0 && converging && previous_near &&
            relative_error <= target_error);
    g.set("time_s", time_s);
  }
} // namespace PlateOnHalfspace
