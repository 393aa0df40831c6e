#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <plate_on_halfspace/base/number_list.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/refinement/goal.h>

#include <algorithm>
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
    Evaluation e;
    e.location     = plate.get_foundation_space().symmetry.to_computed_part(x);
    e.has_location = true;
    try
      {
        std::tie(e.cell, e.reference_point) = plate.locate(e.location);
      }
    catch (...)
      {
        AssertThrow(false,
                    ExcMessage(
                      "Adaptivity/Goal: the point (" + std::to_string(x[0]) +
                      ", " + std::to_string(x[1]) + ") is not on the plate."));
      }
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
} // namespace PlateOnHalfspace
