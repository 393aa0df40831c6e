/**
 * The Galerkin half-space operator with the flexibility A split into a
 * sparse near field and a smooth far field applied by the FFT:
 * Foundation operator/Storage = fft (doc/formulation.md, "Split-kernel FFT
 * storage"). With the kernel alpha / r split at the length sigma,
 *
 *   alpha / r = alpha erfc(r / sigma) / r  +  alpha erf(r / sigma) / r,
 *
 * the first part decays like exp(-r^2 / sigma^2): its Galerkin entries,
 * integrated exactly by the cell-pair rules (CellPairIntegrator, the
 * second part as the smooth remainder), vanish beyond a cutoff of a few
 * sigma and are stored sparse. The second part is smooth everywhere, also
 * at r = 0: it is integrated by Gauss rules on the cells, whose point
 * charges go through GridConvolution (B-spline gridding, FFT convolution,
 * B-spline interpolation), the gridding and interpolation of all points
 * made once into the sparse GridProjection. No correction of the near field is
 * needed, so the operator handles graded and Gmsh meshes alike; the grid is
 * uniform over the plate and its mirror images.
 *
 * Products cost about n log n, memory grows like n. The accuracy follows
 * Foundation operator/Tolerance through the cutoff (erfc), the spline
 * order and sigma / h (split_kernel_settings()). The approximate inverse
 * (the soil-inverse preconditioner) is the fractional Laplacian of
 * fractional_laplace_inverse.h on the pressure nodes: the near field
 * alone would miss the far field's long waves.
 *
 * Like the hierarchical storage: no element exclusion, no direct solver
 * (no dense block), the homogeneous half-space only (a layered soil's
 * remainder would join the far field once its grid resolves the top
 * layer).
 *
 * On several processes each rank integrates and holds the near field of
 * its own cells' pairs and spreads and tests the far field on its own
 * cells; the grid's convolution is split by slabs (GridConvolution), and
 * a product sums the ranks' settlements (doc/parallel.md, "The fft
 * storage on several processes"). The approximate inverse is whole on
 * every rank.
 */
#ifndef plate_on_halfspace_halfspace_split_kernel_operator_h
#define plate_on_halfspace_halfspace_split_kernel_operator_h

#include <plate_on_halfspace/halfspace/grid_projection.h>
#include <plate_on_halfspace/halfspace/interface.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  class CellPairIntegrator;
  class GridConvolution;
  class SparseCholesky;

  /** How the kernel is split and gridded for a tolerance. */
  struct SplitKernelSettings
  {
    unsigned int spline_order; ///< B-spline order of the gridding
    double       sigma_over_h; ///< split length over grid spacing
    double       cutoff;       ///< near field within cutoff * sigma
    unsigned int gauss_points; ///< per direction, on a cell of size sigma
  };

  /** The settings for Foundation operator/Tolerance @p tolerance. */
  SplitKernelSettings
  split_kernel_settings(const double tolerance);

  /**
   * Why the split kernel would be slower than the hierarchical storage on
   * @p space, or "" where it is the faster: its split length is the median
   * cell size, so cells much larger than that (a strongly graded mesh)
   * multiply its Gauss points and near pairs (doc/performance.md, "Which
   * storage auto picks").
   * Storage = auto takes the hierarchical storage where this is not empty.
   */
  std::string
  split_kernel_mesh_obstacle(const FoundationSpace &space);

  /** See the file documentation. */
  class SplitKernelFftOperator : public FoundationOperator
  {
  public:
    /**
     * @p soil_inverse_used: whether the contact solver may precondition
     * with make_approximate_inverse() (Contact/Preconditioner not plate
     * on springs), whose sparse factors the memory check then counts.
     */
    SplitKernelFftOperator(std::shared_ptr<const ElasticSoil> soil,
                           const double                       tolerance,
                           const bool soil_inverse_used = true);
    ~SplitKernelFftOperator() override;

    void
    build(const FoundationSpace   &space,
          const std::vector<bool> &cell_in_foundation) override;
    void
    apply(const Vector<double> &q, Vector<double> &s) const override;
    /** Near field exactly, far field from its own 2 x 2 Gauss points. */
    Vector<double>
    flexibility_diagonal() const override;
    /**
     * The settlement at @p points through this operator's split (a goal's
     * error estimate, doc/formulation.md, "Goal-oriented refinement"): the
     * far field's grid potentials of the pressure read at the points by
     * the B-splines, plus the near field alpha erfc(r / sigma) / r over
     * the cells within the cutoff (near_settlement_at_points(),
     * soil/surface_settlement.h). About n log n + points work. Below
     * grid_settlement_threshold points × loaded cells, or where
     * grid_serves() says no: the base class's evaluation. Compared at 8 points
     * with the direct sum; more than 10 × Tolerance apart throws, naming
     * Foundation operator/Tolerance.
     */
    std::vector<double>
    settlement_at_points(const FoundationSpace       &space,
                         const Vector<double>        &nodal_pressure,
                         const std::vector<Point<2>> &points) const override;

    /**
     * Whether grid_settlement_at_points() can serve @p points on @p space:
     * one process's whole grid, every point's stencil on it, and no cell
     * wider than 3 sigma, beyond which the near field's Gauss rules for
     * erf(r / sigma) / r (at most 12 points per direction) no longer
     * resolve it (the operator's own pairs subdivide such cells).
     */
    bool
    grid_serves(const FoundationSpace       &space,
                const std::vector<Point<2>> &points) const;

    /** settlement_at_points() through the grid whatever the size; needs
     *  grid_serves(@p space, @p points). */
    std::vector<double>
    grid_settlement_at_points(const FoundationSpace       &space,
                              const Vector<double>        &nodal_pressure,
                              const std::vector<Point<2>> &points) const;

    /** Points × loaded cells from which settlement_at_points() takes the
     *  grid: about where it becomes faster than the direct sum
     *  (doc/performance.md, "Goal error estimate"). */
    static constexpr double grid_settlement_threshold = 1e6;

    std::unique_ptr<ApproximateInverse>
    make_approximate_inverse() override;
    bool
    is_symmetric() const override
    {
      return true;
    }
    std::string
    storage_name() const override
    {
      return "fft";
    }
    /** sigma, the cutoff, the near field's size and the grid. */
    std::string
    build_report() const override;
    /** Foundation operator/Tolerance. */
    double
    relative_accuracy() const override
    {
      return tolerance;
    }

    std::size_t
    memory_consumption() const override;

    /** A on nodal values (no pressure basis): for tests. */
    void
    apply_to_values(const Vector<double> &values,
                    Vector<double>       &settlement) const;

    /** What the build chose (the log and the benchmark print it). */
    struct Layout
    {
      double       sigma = 0, spacing = 0, cutoff = 0;
      unsigned int spline_order = 0;
      std::size_t  grid_nodes = 0, near_entries = 0, near_pairs = 0;
      /** Near pairs that took the block of an earlier translate. */
      std::size_t translated_pairs  = 0;
      std::size_t quadrature_points = 0;
    };
    const Layout &
    layout() const
    {
      return chosen;
    }

  private:
    using CellPoints = GridProjection::CellPoints;
    /** A cell's Gauss points merged for flexibility_diagonal(). */
    struct LumpedCell;

    void
    apply_far_field(const Vector<double> &values,
                    Vector<double>       &settlement) const;

    /** inverse_analysis of the mass matrix's pattern. */
    void
    analyze_inverse_pattern();

    const std::shared_ptr<const ElasticSoil> elastic;
    const double                             tolerance;
    const bool                               soil_inverse_used;
    /** The ranks sharing the mesh (FoundationSpace::communicator). */
    MPI_Comm communicator = MPI_COMM_SELF;
    /** Per computed cell: whether this rank spreads and tests its far
     *  field and integrates its near pairs (the rank owning the cell's
     *  first node; all on one process). */
    std::vector<bool> own_cell;
    /** Per foundation node: whether this rank owns it (all on one
     *  process); its flexibility_diagonal() entry's far part. */
    std::vector<bool> own_node;
    double            alpha      = 0;
    unsigned int      n_computed = 0;
    /** The far field's gridding of this rank's cells (the images'
     *  charges are the reflected grid's). */
    std::unique_ptr<GridProjection> projection;
    /** Per computed cell; its points where tabulated on this rank. */
    std::vector<LumpedCell> lumped_cells;
    /** The scene's reflections (MirrorSymmetry::reflections()). */
    std::vector<std::array<double, 2>> reflections;
    std::unique_ptr<GridConvolution>   grid;
    SparsityPattern                    near_sparsity;
    SparseMatrix<double>               near_field;
    /** The near field's rows cut into 8 blocks of about equal entries:
     *  block b is rows near_row_blocks[b] to near_row_blocks[b + 1] - 1. */
    std::array<unsigned int, 9> near_row_blocks{};
    /** The Laplacian on the mass matrix's pattern, and the plate's area
     *  with its mirror images: the approximate inverse's. */
    SparseMatrix<double> laplace;
    double               plate_area = 0;
    /** The symbolic analysis of the mass pattern that the approximate
     *  inverse's factors share. */
    std::unique_ptr<SparseCholesky> inverse_analysis;
    Layout                          chosen;
  };
} // namespace PlateOnHalfspace

#endif
