/**
 * The dual-weighted residual estimate of a goal's error (doc/formulation.md,
 * "Goal-oriented refinement"): the plate's residual of the solved cycle,
 * weighted by the adjoint solution's reconstruction error, localised by
 * the partition of unity of the bilinear hat functions.
 */
#ifndef plate_on_halfspace_refinement_dual_weighted_residual_h
#define plate_on_halfspace_refinement_dual_weighted_residual_h

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/refinement/goal.h>
#include <plate_on_halfspace/scene/parameters.h>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** The estimate of one cycle. */
  struct GoalErrorEstimate
  {
    /**
     * The error the run reports: sum of |eta_i| over the hat functions
     * (eta without cancellation; doc/formulation.md, "Goal-oriented
     * refinement"), or the contact area's half band.
     */
    double estimated_error = 0;
    /** ContactState::rounding_limited_residual of the adjoint solve. */
    double adjoint_rounding_limited_residual = 0;
    /** eta = sum of eta_i, the estimate of J(u) - J(u_h) (signed). */
    bool   has_dwr = false;
    double dwr     = 0;
    /** |eta| of each active cell (the plate's cell order), for marking. */
    Vector<float> cell_indicators;
  };

  /**
   * The foundation's part of the cycle: the nodal pressure and the contact
   * set of the solved cycle, the adjoint problem's pressure (as a field in
   * the plate's w-space) and the foundation operator, whose settlement law
   * the residual evaluates.
   */
  struct FoundationResidualData
  {
    const Vector<double>     &nodal_pressure;
    const std::vector<bool>  &contact_set;
    const Vector<double>     &adjoint_pressure_field;
    const FoundationOperator &foundation;
    /**
     * The goal's deflection terms c_k w(x_k) (w at a point, a difference),
     * points on the computed part; empty for other goals.
     */
    std::vector<std::pair<Point<2>, double>> goal_point_terms;
  };

  /**
   * eta = rho(I z_h - z_h) + rho_F(I zeta_h - zeta_h), the sum of
   *  - the residual of the plate equation, rho(v) = (p - q_h, v_w) -
   *    a_h(u_h, v), of the cycle (@p solution, the pressure @p
   *    pressure_field in the w-space, the scene's @p loads on the computed
   *    part, the plate's weight among them), a_h integrating the
   *    shear term like the element does, and
   *  - the residual of the foundation's equation, rho_F(mu) = (mu, u(q_h)
   *    - w_h) with u(q_h) the settlement of q_h (FoundationOperator::
   *    settlement_at_points()), on the cells whose nodes
   *    are all in the contact set,
   * z_h, zeta_h the adjoint solution @p adjoint_solution and its pressure,
   * and I the biquartic interpolation on patches of 2 x 2 cells (the mesh
   * must have been refined once everywhere, Triangulation::patch_level_1).
   * The adjoint pressure of a goal with deflection terms is the goal's
   * density (Dirac at its points) minus the plate's reaction; the density's
   * part of rho_F is sum_k c_k (u(q_h) - w_h)(x_k) exactly, for points in
   * contact, and @p foundation's adjoint pressure must then be the
   * reaction's part alone (doc/formulation.md, "Goal-oriented
   * refinement").
   */
  /**
   * The adjoint pressure @p adjoint_pressure (nodal) without the part of
   * the goal's Dirac densities that the soil carries at the goal's points
   * (doc/formulation.md, "Goal-oriented refinement"). For each term c_k
   * w(x_k) of @p terms: the point's discrete density d_k = M_CC^{-1} c_k
   * phi(x_k) on the contact set C (@p contact_set, @p mass the nodal mass
   * matrix) and the share theta_k in [0, 1] of d_k(x_k) that the adjoint
   * pressure holds at x_k (1 for a plate too flexible to spread a point's
   * load over the cells around it, 0 for one stiff enough to spread it
   * far). Returns adjoint_pressure - sum theta_k d_k and scales each
   * term's coefficient by theta_k.
   */
  Vector<double>
  remove_carried_goal_density(const MindlinPlate         &plate,
                              const SparseMatrix<double> &mass,
                              const std::vector<bool>    &contact_set,
                              const Vector<double>       &adjoint_pressure,
                              std::vector<std::pair<Point<2>, double>> &terms);

  GoalErrorEstimate
  estimate_goal_error(const MindlinPlate           &plate,
                      const Vector<double>         &solution,
                      const Vector<double>         &pressure_field,
                      const Vector<double>         &adjoint_solution,
                      const FoundationResidualData &foundation,
                      const LoadList               &loads);
  /**
   * The contact area's error, which no adjoint problem describes (the area
   * is not differentiable in the solution): in each cell the contact
   * boundary crosses, how much the located area changes when the
   * indicator field is interpolated from the cell's vertices alone instead
   * of its nine nodes (ContactState::cell_contact_area_uncertainty). The
   * estimate is their sum (whole plate: @p copies times the computed
   * part), each cell's indicator its own.
   */
  GoalErrorEstimate
  estimate_contact_area_error(const ContactState &contact,
                              const unsigned int  copies);

  /** What a cycle's goal estimate needs of the scene beyond the solution. */
  struct GoalEstimateScene
  {
    /** The loads on the computed part, the plate's weight among them. */
    const LoadList &loads;
    /** The cycle's foundation operator (its settlement law). */
    const FoundationOperator &foundation;
  };

  /**
   * The cycle's estimate of the error of @p goal, whatever the goal: for a
   * goal of the plate's fields the dual-weighted residual above, its
   * adjoint problem solved by the cycle's @p contact_solver on the final
   * contact set of @p contact and the goal's carried density removed with
   * the mass matrix of the scene's foundation operator; for the contact
   * area estimate_contact_area_error(); for q at a point none (zero).
   * @p value is the goal on the cycle, @p pressure_field q_h in the
   * plate's w-space.
   */
  GoalErrorEstimate
  estimate_goal_error(const GoalFunctional             &goal,
                      const GoalFunctional::Evaluation &value,
                      const MindlinPlate               &plate,
                      const ContactState               &contact,
                      const Vector<double>             &pressure_field,
                      ContactSolver                    &contact_solver,
                      const GoalEstimateScene          &scene);
} // namespace PlateOnHalfspace

#endif
