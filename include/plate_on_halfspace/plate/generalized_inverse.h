/**
 * The free plate's rigid-body motions and its flexibility without
 * condensing it (doc/formulation.md, "Plate"): what a contact solver needs
 * of a plate that only the foundation holds in place.
 */
#ifndef plate_on_halfspace_plate_generalized_inverse_h
#define plate_on_halfspace_plate_generalized_inverse_h

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <memory>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  class DistributedSparseDirect;

  /**
   * The rigid-body motions in the kernel of the plate's stiffness K (full
   * DoF vectors, zero at constrained DoFs): of w = 1, (x - c_x)/L,
   * (y - c_y)/L with beta = grad w (c the centre of the foundation nodes, L
   * their largest distance from it), those that the plate's constraints
   * allow. A mirror plane's beta_n = 0 removes the tilt about that plane;
   * supports remove all.
   */
  std::vector<Vector<double>>
  rigid_body_motions(const MindlinPlate &plate);

  /**
   * K^+, a generalised inverse of the sparse stiffness on the unconstrained
   * DoFs, from one factorisation with one foundation deflection per
   * rigid-body motion pinned (chosen by pivoting so that the motions are
   * well conditioned at the pinned nodes): CHOLMOD on one process, MUMPS
   * on the plate's DoFs split over the ranks of a shared mesh
   * (distributed_sparse_direct.h, doc/parallel.md).
   */
  class PlateGeneralizedInverse
  {
  public:
    /**
     * The rigid motions, the pinned DoFs and, on one process, the factor's
     * symbolic analysis: the stage that reads the plate alone and spends
     * most of its time on one core (the ordering), so that it can go
     * beside other work, such as the foundation operator's build
     * (doc/performance.md, "The plate's ordering beside the operator's
     * build"); it makes no MPI call. factorize() completes K^+. Throws
     * ExcMessage if the motions cannot be pinned, or naming the
     * node-count entries if the analysis does not fit the memory.
     */
    explicit PlateGeneralizedInverse(const MindlinPlate &plate);

    /** Whether this is K^+ of @p other: the same object, not set up
     *  again since. */
    bool
    is_of(const MindlinPlate &other) const
    {
      return &plate == &other && setup == other.setup_id();
    }
    ~PlateGeneralizedInverse();

    /** The numerical factorisation (on several processes the whole one,
     *  which is collective), once, before solve(); throws ExcMessage if
     *  the plate has a mechanism of its own. */
    void
    factorize();

    /** u = K^+ f (full DoF vectors; zero at constrained and pinned DoFs). */
    void
    solve(const Vector<double> &f, Vector<double> &u) const;

    /** y = N K^+ N^T x: deflections at the foundation nodes from nodal
     *  forces there, and @p u = K^+ N^T x, the plate's whole response. */
    void
    foundation_flexibility(const Vector<double> &x,
                           Vector<double>       &y,
                           Vector<double>       &u) const;

    /** y = N K^+ N^T x alone: on several processes only the foundation
     *  nodes' deflections are summed over the ranks, not the whole u. */
    void
    foundation_flexibility(const Vector<double> &x, Vector<double> &y) const;

    /** rigid_body_motions() of the plate. */
    const std::vector<Vector<double>> &
    rigid_motions() const
    {
      return motions;
    }

  private:
    const MindlinPlate &plate;
    /** The plate's setup_id() when this was made. */
    const unsigned long long setup;
    /** MUMPS over the plate's ranks (several processes), else CHOLMOD. */
    const bool                                  distributed_factor;
    const std::vector<types::global_dof_index> &foundation_dofs;
    const unsigned int                          n_dofs;
    std::vector<Vector<double>>                 motions;
    std::vector<types::global_dof_index>        solved_dofs;
    SparseCholesky                              factor{"the plate's stiffness"};
    bool                                        factorized = false;
    /** The factorisation on several processes (factor is then unused). */
    std::unique_ptr<DistributedSparseDirect> distributed;
  };
} // namespace PlateOnHalfspace

#endif
