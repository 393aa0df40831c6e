/**
 * What the goals of a plate field at one point share (the point value and
 * the peak): the fields, their names, and the derivative of a field at a
 * point with respect to the plate's DoFs (doc/formulation.md,
 * "Goal-oriented refinement").
 */
#ifndef plate_on_halfspace_refinement_goals_plate_field_goal_h
#define plate_on_halfspace_refinement_goals_plate_field_goal_h

#include <plate_on_halfspace/plate/field_extrema.h>
#include <plate_on_halfspace/refinement/goal.h>

#include <optional>
#include <string>

namespace PlateOnHalfspace
{
  /** A goal that is one plate field at one point (see the file doc). */
  class PlateFieldGoal : public GoalFunctional
  {
  public:
    /** The fields a goal can name. */
    enum class Field
    {
      w,
      q,
      mx,
      my,
      mxy,
      principal_moment, ///< the larger principal moment M1
      stress_bottom,    ///< largest principal stress of the bottom fibre
      stress_top        ///< largest principal stress of the top fibre
    };

    /**
     * The field @p name names (w, q, Mx, My, Mxy, M1, stress_bottom,
     * stress_top), among those a @p peak may name (not w, q or Mxy) or a
     * point value may (not M1); none otherwise.
     */
    static std::optional<Field>
    parse_field(const std::string &name, const bool peak);

    PlateFieldGoal(const std::string &text, const Field field);

    /**
     * The field's derivative at the evaluation: of w and q in its first
     * cell, of a moment or stress through the mean of its cells' moments
     * (the larger principal moment and the fibres' principal stresses
     * linearised at that mean; Mxy's is 0 on a mirror plane).
     */
    Vector<double>
    derivative(const MindlinPlate   &plate,
               const Vector<double> &solution,
               const Evaluation     &evaluation) const override;

  protected:
    /** The field as field_extrema.h evaluates it. */
    PlateQuantity
    field_quantity() const;

    /**
     * The field at @p evaluation's point: w of @p solution, or q of
     * @p pressure_field, in its first cell; a moment or stress from the
     * mean of its cells' moments (Mxy 0 on a mirror plane), with Mxy's
     * sign for a point reflected in one plane (doc/outputs.md, "Probe and
     * profile values").
     */
    double
    value_at(const MindlinPlate   &plate,
             const Vector<double> &solution,
             const Vector<double> &pressure_field,
             const Evaluation     &evaluation) const;

    const Field field;
  };
} // namespace PlateOnHalfspace

#endif
