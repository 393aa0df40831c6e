/**
 * The quantity of interest of a scene, Adaptivity/Goal (doc/formulation.md,
 * "Goal-oriented refinement"): its value on a solved cycle and its
 * derivative as a load on the plate, the right-hand side of the adjoint
 * problem. Points refer to the whole plate; in a symmetric scene a point
 * is mirrored onto the computed part, where the solution takes the same
 * value.
 */
#ifndef plate_on_halfspace_refinement_goal_h
#define plate_on_halfspace_refinement_goal_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/scene/mirror_symmetry.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <string>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** See the file documentation. */
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
      /** The cell and reference point the value was taken in. */
      typename DoFHandler<2>::active_cell_iterator cell;
      Point<2>                                     reference_point;
    };

    GoalFunctional(const Parameters::Goal &goal,
                   const MirrorSymmetry   &symmetry);

    /** The goal as the scene names it. */
    const std::string &
    name() const
    {
      return goal.text;
    }

    /**
     * Whether the goal depends on the plate's deflection and rotations
     * only, so that its adjoint problem has a plate load alone (not the
     * contact area and not q, which depend on the pressure).
     */
    bool
    depends_on_plate_only() const;

    /** Whether the goal is the contact area. */
    bool
    measures_contact_area() const;

    /**
     * The goal's deflection terms c_k w(x_k) (w at a point: one, a
     * difference: two), points on the computed part; empty for the other
     * goals.
     */
    std::vector<std::pair<Point<2>, double>>
    deflection_terms() const;

    /**
     * The value on the solved cycle: @p solution is the plate's, @p
     * pressure_field q in the plate's w-space.
     */
    Evaluation
    evaluate(const MindlinPlate   &plate,
             const Vector<double> &solution,
             const Vector<double> &pressure_field,
             const ContactState   &contact) const;

    /**
     * The derivative J'(u_h)(phi_i) at @p evaluation for every plate DoF
     * i, assembled with the plate's constraints like its load vector: the
     * adjoint problem's load. Only for depends_on_plate_only().
     */
    Vector<double>
    derivative(const MindlinPlate   &plate,
               const Vector<double> &solution,
               const Evaluation     &evaluation) const;

  private:
    const Parameters::Goal goal;
    const MirrorSymmetry   symmetry;
  };
} // namespace PlateOnHalfspace

#endif
