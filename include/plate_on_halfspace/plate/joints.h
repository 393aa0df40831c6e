/**
 * The joints' part of the plate's equations on its current mesh
 * (doc/formulation.md, "Joints"): tied joints as identity constraints
 * between the facing DoFs, aggregate interlock as a shear spring along the
 * facing faces, dowels as shear springs at the bars, and what each joint
 * carries once the plate is solved (doc/outputs.md, "Joints").
 */
#ifndef plate_on_halfspace_plate_joints_h
#define plate_on_halfspace_plate_joints_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/plate/slab_grid.h>

#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** The force in one dowel bar (positive: pushes the upper-side slab
   *  down, i.e. w_low > w_high) and the concrete's bearing stress. */
  struct DowelForce
  {
    Point<2> location;
    double   force          = 0;
    double   bearing_stress = 0;
  };

  /** What a joint carries in a solved plate (doc/outputs.md, "Joints"). */
  struct JointResponse
  {
    /** Whether the computed part of the plate holds faces of the joint. */
    bool computed = false;
    /**
     * Load transfer efficiency w_unloaded / w_loaded at the point of the
     * joint where the larger of the two sides' deflections is largest (the
     * loaded side is the one with the larger w there); NaN where neither
     * side deflects downward.
     */
    double   lte = 0;
    Point<2> lte_at;
    double   w_loaded = 0, w_unloaded = 0;
    /** The largest shear force per length of joint the joint transfers
     *  (dowels: bar force / spacing; tied: the plates' shear resultant). */
    double                  max_shear_force = 0;
    std::vector<DowelForce> dowels;
  };

  class JointCoupling
  {
  public:
    /**
     * Pair the facing joint faces of @p dof_handler's mesh and place the
     * dowel bars of @p grid on them. A bar on a mirror plane of
     * @p symmetry counts half; bars in the mirrored part are left out.
     */
    void
    reinit(const SlabGrid       &grid,
           const DoFHandler<2>  &dof_handler,
           const MirrorSymmetry &symmetry);

    /** Tied joints: each DoF on a tied face equals its facing DoF. */
    void
    add_tied_constraints(AffineConstraints<double> &constraints) const;

    /** The couplings of the springs across the joints. */
    void
    add_sparsity(const AffineConstraints<double> &constraints,
                 DynamicSparsityPattern          &dsp) const;

    /** Add the springs' stiffness (aggregate interlock, dowels). */
    void
    assemble(const AffineConstraints<double> &constraints,
             SparseMatrix<double>            &stiffness) const;

    /**
     * The response of every joint of the grid to @p solution (full DoF
     * vector, constraints distributed) of a plate with shear rigidity
     * @p shear_rigidity. The LTE and w_loaded, w_unloaded are those of the
     * deflection the moving loads add to @p standing, the plate under its
     * standing loads alone (weight, temperature, uniform pressure), as a
     * falling-weight test measures them; empty: the deflections
     * themselves. The forces are those of @p solution.
     */
    std::vector<JointResponse>
    responses(const Vector<double> &solution,
              const double          shear_rigidity,
              const Vector<double> &standing = Vector<double>()) const;

  private:
    struct FacePair
    {
      DoFHandler<2>::active_cell_iterator cell_low, cell_high;
      unsigned int                        face_low, face_high;
      unsigned int                        joint;
    };
    struct DowelSite
    {
      unsigned int                        joint;
      Point<2>                            location;
      DoFHandler<2>::active_cell_iterator cell_low, cell_high;
      Point<2>                            reference_low, reference_high;
      /** The bar's stiffness, half on a mirror plane. */
      double stiffness;
      /** 1, or 1/2 for a bar on a mirror plane. */
      double share;
    };

    MirrorSymmetry         symmetry;
    const SlabGrid        *grid        = nullptr;
    const DoFHandler<2>   *dof_handler = nullptr;
    MappingQ1<2>           mapping;
    std::vector<FacePair>  pairs;
    std::vector<DowelSite> dowel_sites;
  };
} // namespace PlateOnHalfspace

#endif
