/**
 * The contact family's interface (doc/architecture.md, "The contact family";
 * doc/formulation.md, "Tensionless contact"): solve the plate on the
 * half-space, bonded or tensionless, starting from a seed of the contact
 * set, and return the state of the foundation. The direct solver (the plate
 * condensed onto the foundation nodes, dense LAPACK) and the iterative one
 * (the sparse plate, projected conjugate gradients on the contact
 * pressures) both implement it; the active-set step, the scene checks, the
 * rigid motions and the mechanism diagnosis they share are written once
 * (contact_iteration.h, active_set.h, plate/generalized_inverse.h).
 */
#ifndef plate_on_halfspace_contact_interface_h
#define plate_on_halfspace_contact_interface_h

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/scene/parameters.h>

#include <memory>
#include <ostream>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  class FoundationOperator;
  class MindlinPlate;

  /** The state of the foundation after a contact solve (foundation nodes). */
  struct ContactState
  {
    Vector<double> w; ///< plate deflection at the foundation nodes
    Vector<double> q; ///< nodal contact pressure, compression positive
    /**
     * The pressure's coefficients in the basis of the contact conditions
     * (equal to q unless the positive pressure basis is used,
     * doc/formulation.md, "Positive pressure basis"): what complementarity,
     * tensile_nodes and FoundationOperator::nodal_forces() refer to.
     */
    Vector<double> pressure_coefficients;
    Vector<double> gap; ///< F q - B w: soil surface minus plate
    /**
     * The plate's full solution vector (w, beta_x, beta_y at every DoF,
     * constraints distributed).
     */
    Vector<double> plate_solution;
    /** Where the pressure acts: the active set and every node with q > 0. */
    std::vector<bool> in_contact;
    /**
     * The solver's active set (coefficients free to carry pressure): what
     * the next cycle's iteration starts from.
     */
    std::vector<bool> active_set;
    std::vector<bool> cell_in_foundation; ///< element exclusion's cell set
    /**
     * Per plate cell, the area where the soil carries the plate, located
     * from the fields inside the cells, and how much that area changes
     * when the field is interpolated from the cell's vertices alone: the
     * contact-area goal's error indicator (contact_region.h).
     */
    std::vector<double> cell_contact_area, cell_contact_area_uncertainty;
    unsigned int        iterations = 0;
    bool                converged  = false;
    /**
     * max of (-min q)+, (-min gap)+, max |q gap|, each relative to the
     * problem's scale (max |q|, max |B w|) (doc/outputs.md).
     */
    double complementarity_violation = 0;
    /** Nodes in contact with a tensile pressure (q < 0). */
    unsigned int tensile_nodes = 0;
    /** Largest penetration -gap, relative to max |B w| (0 if none). */
    double max_penetration = 0;
    /**
     * LAPACK's estimates of 1/κ₁ of the coupled matrix K̄ + S and of the
     * flexibility block F_CC of the last contact set (direct solver;
     * condition_estimate.h); 1 where the solver forms no such matrix.
     */
    double coupled_rcond = 1, contact_block_rcond = 1;
    /**
     * Wall time (s) the solver spent factorising the half-space flexibility
     * (the first contact block, or the approximate inverse), and the bytes
     * that factor holds (with an iterative solver's recorded directions).
     */
    double      factorization_time_s = 0;
    std::size_t factor_memory_bytes  = 0;

    /** One linear solve of an iterative contact solver. */
    struct LinearSolve
    {
      unsigned int contact_iteration = 0; ///< 1, 2, ... of the active set
      unsigned int contact_nodes     = 0; ///< size of the contact set
      unsigned int iterations        = 0; ///< conjugate gradient iterations
      /** Achieved |residual| / |settlement| on the contact set
       *  (recomputed, not the recursive estimate). */
      double relative_residual = 0;
    };
    /**
     * Conjugate gradient iterations of the iterative solver's estimate of
     * the contact set before the active set
     * (IterativeContactSolver::predict_contact_set(); 0 if none).
     */
    unsigned int prediction_iterations = 0;
    /**
     * The relative residual of the last solve where rounding stopped the
     * iterations above their tolerance (a plate far more flexible than
     * the soil, iterative_solver.h); 0 where the tolerance was reached.
     */
    double rounding_limited_residual = 0;
    /** One entry per contact iteration (iterative solvers only). */
    std::vector<LinearSolve> linear_solves;
  };

  /** The area in contact on the computed part: the sum of the cells'. */
  double
  contact_area(const ContactState &state);

  /**
   * Where a contact solve starts: a contact set and a pressure, e.g. the
   * previous cycle's transferred to the present mesh. Either may be empty.
   */
  struct ContactSeed
  {
    ContactSeed() = default;

    /** A seed of the contact set alone. */
    ContactSeed(std::vector<bool> contact_set)
      : contact_set(std::move(contact_set))
    {}

    std::vector<bool> contact_set;
    /** Nodal values on the foundation nodes (not coefficients). */
    Vector<double> pressure;
  };

  /** A contact solver (see the file documentation). */
  class ContactSolver
  {
  public:
    virtual ~ContactSolver() = default;

    /**
     * Solve @p plate (set up) under the load vector @p load
     * (MindlinPlate::load_vector()) on @p foundation (built on the plate's
     * foundation space with every cell in the foundation). @p seed (may be
     * empty) seeds the contact set and, for a solver that can use it, the
     * pressure, e.g. transferred from the previous cycle; it decides how
     * many steps the solve takes, never the answer. Throws ExcMessage
     * naming the reason if the load is zero, lifts
     * the plate off as a whole, leaves it a mechanism or cannot be solved
     * to the solver's tolerance.
     */
    virtual ContactState
    solve(MindlinPlate         &plate,
          FoundationOperator   &foundation,
          const Vector<double> &load,
          const ContactSeed    &seed) = 0;

    /**
     * After solve(): the coupled problem linearised on the last solve()'s
     * final contact set (the gap closed there, no pressure elsewhere) under
     * the load vector @p load. The operator is symmetric for the Galerkin
     * half-space, so this is the adjoint problem of a goal whose derivative
     * @p load is (doc/formulation.md, "Goal-oriented refinement"); a bonded
     * scene's solver solves a new load on its factorisation this way.
     */
    virtual ContactState
    solve_linearised(const Vector<double> &load) = 0;

    /**
     * solve_linearised() to the accuracy an error estimate needs rather
     * than the one the fields need: the goal's adjoint problem. The
     * iterative solver stops at 1e-6 of the settlement, or at the fields'
     * accuracy where that is coarser (doc/formulation.md, "Goal-oriented
     * refinement").
     */
    virtual ContactState
    solve_adjoint(const Vector<double> &load) = 0;
  };

  /**
   * The solver @p solver (direct or iterative; SceneParameters::
   * contact_solver() resolves auto) for the scene's Contact and Foundation
   * entries. Per-iteration lines go to @p log when @p verbosity > 0.
   * With @p contact_set_only the solve stops once the set no longer
   * changes at the accuracy of the solves while it changes: enough for a
   * seed (the nested start's coarse solves), not for the fields.
   */
  std::unique_ptr<ContactSolver>
  create_contact_solver(const SceneParameters            &parameters,
                        const Parameters::Contact::Solver solver,
                        const unsigned int                verbosity,
                        std::ostream                     &log,
                        const bool contact_set_only = false);
} // namespace PlateOnHalfspace

#endif
