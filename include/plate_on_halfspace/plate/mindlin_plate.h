/**
 * The Reissner-Mindlin plate (doc/formulation.md, "Plate"; the paper's (P1)):
 * an FESystem of three FE_Q<2>(2) fields (w, beta_x, beta_y), the element
 * variant (serendipity / heterosis / lagrange) realised by constraining cell
 * centre values, the sparse stiffness with reduced, selective or full shear
 * integration, the load vector, and the condensation of everything but the
 * foundation nodes (the paper's (P18)-(P19)).
 */
#ifndef plate_on_halfspace_plate_mindlin_plate_h
#define plate_on_halfspace_plate_mindlin_plate_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/loads/load.h>
#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/plate/joints.h>
#include <plate_on_halfspace/plate/slab_grid.h>
#include <plate_on_halfspace/plate/thermal_load.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** Bending moments per unit width (doc/formulation.md sign convention). */
  struct Moments
  {
    double mx = 0, my = 0, mxy = 0;
  };

  /**
   * The bending moments of the rotation gradient @p grad_beta
   * (grad_beta[c][d] = d beta_c / d x_d) of a plate of flexural rigidity
   * @p D and Poisson's ratio @p nu: M = -D ((1 - nu) sym(grad beta) +
   * nu tr(grad beta) I), the sign of doc/formulation.md, "Conventions".
   * The one statement of the plate's moment law: the stiffness, the
   * moments, the goals' derivatives and the error estimate's residual all
   * use it.
   */
  inline Moments
  bending_moments(const double        D,
                  const double        nu,
                  const Tensor<2, 2> &grad_beta)
  {
    Moments m;
    m.mx  = -D * (grad_beta[0][0] + nu * grad_beta[1][1]);
    m.my  = -D * (grad_beta[1][1] + nu * grad_beta[0][0]);
    m.mxy = -D * 0.5 * (1. - nu) * (grad_beta[0][1] + grad_beta[1][0]);
    return m;
  }

  /**
   * Bending stresses of the bottom (soil-side) and the top fibre, tension
   * positive (doc/formulation.md, "Stresses"): sxx, syy, sxy of each face
   * and its largest principal stress.
   */
  struct FibreStresses
  {
    std::array<double, 3> bottom{{0, 0, 0}}, top{{0, 0, 0}};
    double                principal_bottom = 0, principal_top = 0;

    /** In the order of Parameters::fibre_stress_names(). */
    std::array<double, 8>
    values() const
    {
      return {{bottom[0],
               bottom[1],
               bottom[2],
               principal_bottom,
               top[0],
               top[1],
               top[2],
               principal_top}};
    }
  };

  /**
   * Add to @p constraints the conditions of a symmetric scene's mirror
   * planes on a field with the plate's components (w, beta_x, beta_y) on
   * @p dof_handler: the rotation across each plane of @p symmetry vanishes
   * there (faces with mirror_plane_x/y_boundary_id). Serves the plate and
   * fields in its component layout of another degree.
   */
  void
  add_mirror_plane_constraints(const DoFHandler<2>       &dof_handler,
                               const MirrorSymmetry      &symmetry,
                               AffineConstraints<double> &constraints);

  /**
   * The plate on a given triangulation. Component 0 is w (downward), 1 and 2
   * are beta_x, beta_y (slopes of the normal, = dw/dx, dw/dy when thin).
   */
  class MindlinPlate
  {
  public:
    MindlinPlate(const Parameters::Plate          &plate,
                 const Parameters::Discretization &discretization);

    /**
     * Distribute DoFs on @p triangulation, build the constraints (hanging
     * nodes, element centre constraints, and the homogeneous constraints
     * @p extra_constraints add, e.g. supports in tests), the foundation
     * space and the sparse stiffness.
     */
    void
    setup(const Triangulation<2> &triangulation,
          const std::function<void(const DoFHandler<2> &,
                                   AffineConstraints<double> &)>
            &extra_constraints = {});

    /**
     * setup() without the sparse stiffness and what is made from it (the
     * foundation space's rigid motions): the DoFs, the constraints, the
     * foundation space and the cells' search tree, enough to count the
     * nodes and to assemble loads. complete_setup() adds the rest; a mesh
     * that is only counted before it is coarsened (the nested start)
     * needs no stiffness.
     */
    void
    setup_dofs(const Triangulation<2> &triangulation,
               const std::function<void(const DoFHandler<2> &,
                                        AffineConstraints<double> &)>
                 &extra_constraints = {});

    /** The sparse stiffness and the rigid motions after setup_dofs();
     *  nothing if they are made already. */
    void
    complete_setup();

    /**
     * Solve the computed part of a symmetric scene (mirror_symmetry.h): the
     * mesh given to setup() is that part, its faces on the mirror planes
     * carry mirror_plane_x/y_boundary_id. Call before setup().
     */
    void
    set_mirror_symmetry(const MirrorSymmetry &mirror_symmetry)
    {
      symmetry = mirror_symmetry;
    }

    /**
     * Share the plate among the ranks of @p communicator (doc/parallel.md):
     * the mesh given to setup() carries each cell's rank as its subdomain
     * id (partition_plate_mesh()), each rank's DoFs are numbered
     * contiguously, and the rank owns the DoFs of its cells
     * (locally_owned_dofs()). Every rank still holds every cell and DoF.
     * Call before setup(); without it the plate is on one process.
     */
    void
    set_communicator(const MPI_Comm mpi_communicator)
    {
      communicator = mpi_communicator;
    }

    MPI_Comm
    get_communicator() const
    {
      return communicator;
    }

    /** The DoFs this rank owns (all of them on one process). */
    const IndexSet &
    locally_owned_dofs() const
    {
      return owned_dofs;
    }

    /**
     * The slabs and joints of the plate (slab_grid.h): the mesh given to
     * setup() holds each slab's cells with the slab's index as material
     * id, and the joints couple the facing faces (joints.h). Call before
     * setup(); without it the plate is one slab.
     */
    void
    set_slab_grid(const SlabGrid &grid)
    {
      slab_grid.emplace(grid);
    }

    /** The slab grid given by set_slab_grid(), or nullptr. */
    const SlabGrid *
    get_slab_grid() const
    {
      return slab_grid ? &*slab_grid : nullptr;
    }

    /** What each joint of the slab grid carries in @p solution (full DoF
     *  vector, constraints distributed), its LTE of the deflections
     *  relative to @p standing (JointCoupling::responses()); empty without
     *  joints. */
    std::vector<JointResponse>
    joint_responses(const Vector<double> &solution,
                    const Vector<double> &standing = Vector<double>()) const;

    /**
     * The temperature through the thickness (thermal_load.h): its moment
     * joins the load vector of assemble_loads() and the moments(), its
     * remainder the fibre_stresses(). Call before assemble_loads().
     */
    void
    set_thermal_load(const ThermalLoad &load)
    {
      thermal = load;
    }

    const ThermalLoad &
    get_thermal_load() const
    {
      return thermal;
    }

    /**
     * The load vector of @p loads (downward positive; each integrated by
     * its own rule, Load::on_cell()) and of the thermal moment:
     * M_T ∫ div(beta_v) (doc/formulation.md, "Temperature"), a DoF vector
     * with the constraints applied. Throws if a load misses the plate.
     */
    Vector<double>
    load_vector(const LoadList &loads) const;

    /** The scene's load vector: load_vector(@p loads), kept by the plate. */
    void
    assemble_loads(const LoadList &loads);

    /**
     * The vertical resultant (force) of the load vector @p load: the
     * w-shape functions are a partition of unity, also after the
     * constraints, so it is the sum of the w-entries.
     */
    double
    resultant(const Vector<double> &load) const;

    /** The resultant of the scene's load vector. */
    double
    applied_load() const
    {
      return total_load;
    }

    /**
     * Solve the plate alone (no foundation) with the constraints given at
     * setup; they must remove the rigid-body modes.
     */
    void
    solve_unsupported(Vector<double> &solution) const;

    /**
     * The plate's stiffness condensed onto the foundation nodes (P18):
     * K̄ = K_ff - K_fr K_rr^{-1} K_rf, with f the foundation nodes
     * (unconstrained w-DOFs) and r all other unconstrained DOFs. Only this
     * Schur complement, of the size of the foundation block, is dense; K
     * itself stays sparse and K_rr is factorised by CHOLMOD
     * (sparse_cholesky.h).
     */
    void
    condense(LAPACKFullMatrix<double> &stiffness);

    /**
     * The load vector @p load condensed likewise (P19),
     * P̄ = P_f - K_fr K_rr^{-1} P_r, after condense() (its factor of K_rr
     * is reused).
     */
    Vector<double>
    condensed_load(const Vector<double> &load) const;

    /**
     * Full solution vector under the load vector @p load from the
     * foundation deflections (recovers the rotations,
     * r = K_rr^{-1}(P_r - K_rf w_f), and the constrained values), after
     * condense().
     */
    void
    expand(const Vector<double> &foundation_w,
           const Vector<double> &load,
           Vector<double>       &solution) const;

    /** Foundation values (w-DOFs) from a full solution vector. */
    Vector<double>
    restrict_to_foundation(const Vector<double> &solution) const;

    /** Scalar field on the foundation nodes as a full vector (component 0). */
    Vector<double>
    foundation_field_to_solution(const Vector<double> &field) const;

    /**
     * Moments at the reference point @p p of @p cell of a solution under
     * the scene's loads: -D (curvatures) plus the thermal moment in Mx and
     * My (doc/formulation.md, "Conventions" and "Temperature").
     */
    Moments
    moments(const typename DoFHandler<2>::active_cell_iterator &cell,
            const Point<2>                                     &p,
            const Vector<double>                               &solution) const;

    /**
     * The mean of moments() of @p solution over @p cells (cells_at() of a
     * point, with the point's reference coordinates in each): the moments
     * at a point on a cell edge, a vertex or a joint (doc/outputs.md,
     * "Probe and profile values").
     */
    Moments
    mean_moments(
      const std::vector<std::pair<typename DoFHandler<2>::active_cell_iterator,
                                  Point<2>>> &cells,
      const Vector<double>                   &solution) const;

    /**
     * The moments of the rotation gradient @p grad_beta (grad_beta[c][d] =
     * d beta_c / d x_d): -D (curvatures) plus the thermal moment in Mx and
     * My (doc/formulation.md, "Conventions" and "Temperature"). What
     * moments(), the peaks and the outputs evaluate.
     */
    Moments
    moments_of_rotation_gradient(const Tensor<2, 2> &grad_beta) const
    {
      Moments m = bending_moments(grad_beta);
      m.mx += thermal.moment;
      m.my += thermal.moment;
      return m;
    }

    /** The plate's bending_moments() of @p grad_beta, without the thermal
     *  moment: what a change of the solution changes. */
    Moments
    bending_moments(const Tensor<2, 2> &grad_beta) const
    {
      return PlateOnHalfspace::bending_moments(plate.flexural_rigidity(),
                                               plate.poissons_ratio,
                                               grad_beta);
    }

    /**
     * The fibre stresses of the moments @p m (of moments()): +-6 M/t^2 at
     * the bottom and the top face plus the thermal remainder's stress.
     */
    FibreStresses
    fibre_stresses(const Moments &m) const;

    double
    thickness() const
    {
      return plate.thickness;
    }

    /** Cell of the plate containing @p x and the reference point there. */
    std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>
    locate(const Point<2> &x) const;

    /**
     * locate() on every slab (cell material id) that holds @p x: one cell
     * inside a slab, one on each side of a joint, up to four where joints
     * cross. A force at a point on a joint is shared equally by the slabs
     * there (doc/loads.md, "Point loads"), so that its answer does not
     * depend on which side a search meets first, nor on a mirror plane.
     */
    std::vector<
      std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>>
    locate_on_each_slab(const Point<2> &x) const;

    /**
     * Every cell that holds @p x, locate()'s first: one inside a cell, two
     * on an edge, more at a vertex, of every slab on a joint. The moments
     * jump across cell edges, so a value at such a point is their mean
     * (doc/outputs.md, "Probe and profile values").
     */
    std::vector<
      std::pair<typename DoFHandler<2>::active_cell_iterator, Point<2>>>
    cells_at(const Point<2> &x) const;

    /**
     * Whether @p x of the computed part lies on a mirror plane of a
     * symmetric scene, to the tolerance by which cells_at() takes a cell
     * as holding a point: exactly where the whole plate's cells_at() meets
     * the mirrored cells too, whose Mxy is the opposite.
     */
    bool
    on_mirror_plane(const Point<2> &x) const;

    /** Value of component @p component of @p solution at @p x. */
    double
    point_value(const Vector<double> &solution,
                const Point<2>       &x,
                const unsigned int    component = 0) const;

    const DoFHandler<2> &
    get_dof_handler() const
    {
      return dof_handler;
    }
    const FESystem<2> &
    get_fe() const
    {
      return fe;
    }
    const AffineConstraints<double> &
    get_constraints() const
    {
      return constraints;
    }
    const FoundationSpace &
    get_foundation_space() const
    {
      return foundation_space;
    }
    /** The sparse stiffness K; assembled again (the same bits) if
     *  release_stiffness() freed it. The reference lasts until the next
     *  release_stiffness() or setup_dofs(). */
    const SparseMatrix<double> &
    get_stiffness_matrix() const;
    /**
     * Free K and its pattern (about 170 MB at 10^5 foundation nodes) once
     * a factor of it is made and the solve reads K no more: the contact
     * solve's peak memory then does not hold them (doc/performance.md,
     * "The plate's stiffness after its factor"). Whatever reads K later
     * gets it assembled again. Call it only where no other thread reads
     * K (the contact solve's own thread, after K^+).
     */
    void
    release_stiffness();
    /** Whether K is in memory (not released since it was made). */
    bool
    holds_stiffness() const;
    /** A number of each setup_dofs(), unique in the process: what was
     *  made of the plate (K^+) holds for its mesh while this stays. */
    unsigned long long
    setup_id() const
    {
      return current_setup;
    }
    const Vector<double> &
    get_load_vector() const
    {
      return load;
    }
    /** Number of unconstrained DOFs. */
    unsigned int
    n_unconstrained_dofs() const;
    /** The DoF of each foundation node. */
    const std::vector<types::global_dof_index> &
    get_foundation_dofs() const
    {
      return foundation_dofs;
    }
    double
    flexural_rigidity() const
    {
      return plate.flexural_rigidity();
    }
    double
    poissons_ratio() const
    {
      return plate.poissons_ratio;
    }
    /** D_s = k G t, k = 5/6 (doc/formulation.md, "Plate"). */
    double
    shear_rigidity() const;
    /** Gauss points per direction of the element's shear term. */
    unsigned int
    shear_quadrature_points() const;

  private:
    void
    add_centre_constraints();
    void
    build_foundation_space();
    /** The pattern and K from the cells (complete_setup(), and again
     *  after release_stiffness()). */
    void
    make_stiffness() const;
    void
    assemble_stiffness() const;
    /** K, made again first if released; every reader inside goes through
     *  here. */
    const SparseMatrix<double> &
    assembled_stiffness() const;
    /** Free K and its pattern. */
    void
    discard_stiffness() const;

    const Parameters::Plate          plate;
    const Parameters::Discretization discretization;
    MirrorSymmetry                   symmetry;
    MPI_Comm                         communicator = MPI_COMM_SELF;
    IndexSet                         owned_dofs;
    std::optional<SlabGrid>          slab_grid;
    JointCoupling                    joint_coupling;

    FESystem<2>               fe;
    MappingQ1<2>              mapping;
    DoFHandler<2>             dof_handler;
    const Triangulation<2>   *attached_triangulation = nullptr;
    AffineConstraints<double> constraints;
    /** K and its pattern: mutable, as a reader may make them again
     *  after release_stiffness(), under stiffness_mutex. K is empty
     *  after a complete setup only if released. */
    mutable SparsityPattern      sparsity;
    mutable SparseMatrix<double> stiffness;
    mutable std::mutex           stiffness_mutex;
    unsigned long long           current_setup = 0;
    /** Whether complete_setup() has run since setup_dofs(). */
    bool           setup_complete = false;
    Vector<double> load;
    double         total_load = 0;
    ThermalLoad    thermal;

    std::vector<types::global_dof_index> foundation_dofs;
    std::vector<int> foundation_index; ///< per DoF, -1 if none
    FoundationSpace  foundation_space;

    /** The unconstrained DoFs that are not foundation nodes, and the
     *  Cholesky factor of K_rr. */
    std::vector<types::global_dof_index> rest_dofs;
    SparseCholesky rest_factor{"the plate's rotation block"};

    /** The active cells' bounding boxes in an R-tree (locate()), made by
     *  setup(); defined in the source, so that the header stays lean. */
    struct CellBoxes;
    std::shared_ptr<const CellBoxes> cell_boxes;

    /** A cell near a point (cells_near()), defined in the source. */
    struct NearCell;
    /** The cells whose bounding boxes come within @p tolerance of @p x, in
     *  the order of the active cells, with the point's reference
     *  coordinates clamped to each and their distance from @p x. */
    std::vector<NearCell>
    cells_near(const Point<2> &x, const double tolerance) const;
    /** The cells that hold @p x (within 1e-10 (1 + |x|)), the nearest
     *  first (the first in the order of the cells among equals), the
     *  others in that order; throws if none does. */
    std::vector<NearCell>
    cells_holding(const Point<2> &x) const;
  };
} // namespace PlateOnHalfspace

#endif
