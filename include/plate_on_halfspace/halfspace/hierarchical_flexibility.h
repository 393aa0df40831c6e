/**
 * The Galerkin half-space flexibility (doc/formulation.md, "Default variant"),
 *   A_ij = alpha ∫∫ φ_i(x) φ_j(y) / |x - y| dy dx,
 * stored as a hierarchical matrix (hmat-oss): the same matrix as
 * BoussinesqGalerkinOperator::flexibility_matrix(), with the blocks of node
 * clusters whose supports are well separated replaced by low-rank
 * approximations (ACA+) to a relative tolerance, so that storage, assembly
 * and the product grow like n log n instead of n², and an H-Cholesky
 * factorisation replaces the n³ dense one. It holds the whole of A, or one
 * block A(rows, columns) of it: a rank's share of a run on several
 * processes (doc/parallel.md, "The half-space").
 */
#ifndef plate_on_halfspace_halfspace_hierarchical_flexibility_h
#define plate_on_halfspace_halfspace_hierarchical_flexibility_h

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/soil/soil_model.h>

#include <string>
#include <vector>

// hmat-oss's opaque C types (hmat/hmat.h), declared here so that users of
// this header need not include hmat-oss.
struct hmat_matrix_struct;
struct hmat_cluster_tree_struct;

namespace PlateOnHalfspace
{
  using namespace dealii;

  class CellPairSummation;

  /**
   * The Galerkin flexibility A as an H-matrix.
   *
   * Entries: every entry hmat-oss asks for is a sum of CellPairSummation
   * (cell_pair_summation.h), the one the dense
   * BoussinesqGalerkinOperator::build() sums too: the same cell pairs,
   * mirror images, symmetrisation and order, so the near-field blocks are
   * the dense matrix's entries (to rounding) with their singular
   * quadrature, and only admissible blocks are approximated
   * (doc/formulation.md, "Hierarchical storage").
   *
   * Admissibility: a node's extent for the cluster tree is its support (the
   * vertices of the cells that contain it), so a block is admissible only
   * when the supports of its two node clusters are separated by at least
   * diameter / eta (Hackbusch's condition); on such blocks the kernel is
   * smooth and no singular cell pair is evaluated during compression.
   *
   * Numbering: hmat-oss reorders the nodes along its cluster tree; this
   * class takes and returns vectors in the natural (foundation node)
   * numbering and permutes internally.
   *
   * Errors: every hmat-oss call is checked; a failed assembly, a
   * non-finite entry, a compressed matrix that differs from exact sampled
   * rows by more than the tolerance allows, or a failed / inaccurate
   * factorisation throws ExcMessage naming Foundation operator/Tolerance.
   *
   * Threading: hmat-oss's default (sequential) engine is used; it calls the
   * entry callback from the calling thread only. Inside that callback the
   * cell pairs of a request are integrated and summed with deal.II's
   * task-based parallelism (CellPairSummation::add_entries()), with the
   * same result for any number of threads. Calls to one object must not
   * overlap.
   *
   * Progress: the integration of the singular pairs, the assembly (blocks
   * done) and the H-Cholesky factorisation (rows done, as hmat-oss reports
   * them) show a ProgressReport (base/progress.h) when enabled.
   */
  class HierarchicalFlexibility
  {
  public:
    /** How the H-matrix is built; the defaults are the tuned values. */
    struct Settings
    {
      /**
       * Relative accuracy of the compressed blocks (ACA+ stopping
       * criterion) and of every recompression in the H-Cholesky
       * factorisation (hmat-oss's low-rank epsilon): Foundation
       * operator/Tolerance.
       */
      double tolerance = 1e-6;
      /**
       * Relative accuracy of the recompressions in the H-Cholesky factor
       * when it is coarser than @p tolerance (the larger of the two is
       * used): the factor preconditions conjugate gradients, which reach
       * their own tolerance whatever it is; solve() is then accurate to
       * about this, not to @p tolerance.
       */
      double factor_tolerance = 1e-3;
      /** Largest number of nodes in a leaf of the cluster tree. */
      unsigned int leaf_size = 48;
      /** Hackbusch's eta: admissible when min diameter <= eta distance. */
      double eta = 2.;
      /** Appended to the message of a factorisation that fails at every
       *  tolerance: what else the soil says can cost definiteness
       *  (SoilModel::definiteness_advice()). */
      std::string definiteness_advice;
    };

    explicit HierarchicalFlexibility(const Settings &settings);
    ~HierarchicalFlexibility();

    HierarchicalFlexibility(const HierarchicalFlexibility &) = delete;
    HierarchicalFlexibility &
    operator=(const HierarchicalFlexibility &) = delete;

    /**
     * Build the H-matrix of A over all foundation nodes.
     * @param cells the space's cells followed, for a symmetric scene, by
     *   their mirror images (FoundationSpace::mirror_image_cells(), image of
     *   cell c under reflection r at r * n_computed + c), as
     *   BoussinesqGalerkinOperator::build() lists them.
     * @param n_copies 1 + the number of reflections (cells.size() / number
     *   of computed cells).
     * @param node_locations the foundation nodes (x, y).
     * @param kernel the soil's point-load kernel (a number alpha: the
     *   homogeneous half-space's alpha / r).
     * @param singular_order Gauss points per direction of the singular
     *   cell pairs (Discretization/Singular quadrature order).
     */
    void
    build(const std::vector<FoundationSpace::Cell> &cells,
          const unsigned int                        n_copies,
          const std::vector<Point<2>>              &node_locations,
          const SurfaceKernel                      &kernel,
          const unsigned int                        singular_order);

    /** The same for a whole FoundationSpace (its cells and their images). */
    void
    build(const FoundationSpace &space,
          const SurfaceKernel   &kernel,
          const unsigned int     singular_order);

    /**
     * Build the block A(@p rows, @p columns) (natural node numbers; empty:
     * all nodes) from the entries of @p summation, which was made on
     * @p cells. Equal rows and columns give a symmetric block in
     * lower-symmetric storage, which factorize() can factorise; other
     * blocks are stored whole.
     */
    void
    build(const std::vector<FoundationSpace::Cell> &cells,
          const CellPairSummation                  &summation,
          const std::vector<Point<2>>              &node_locations,
          const std::vector<unsigned int>          &rows,
          const std::vector<unsigned int>          &columns);

    /**
     * dst = A src, natural numbering (units of A: length^3/force): for a
     * block, the rows of dst from the columns of src, all other entries of
     * dst zero. Both vectors have every node's entry.
     */
    void
    vmult(Vector<double> &dst, const Vector<double> &src) const;

    /**
     * @p dst = the diagonal of A on the block's rows (other entries zero),
     * natural numbering; the block must be symmetric (a diagonal block).
     */
    void
    diagonal(Vector<double> &dst) const;

    /**
     * H-Cholesky factorisation A ≈ L L^T of a copy of A (the product keeps
     * using A), with every recompression at the larger of the tolerance
     * and the factor tolerance. Checks the factor by solving for a known
     * vector. If hmat-oss reports a failure (A not positive definite at
     * that accuracy) or the factor does not reproduce the vector, makes it
     * again with a 100 times finer factor tolerance, and throws only when
     * it fails at the tolerance itself.
     */
    void
    factorize();

    /** The factor tolerance factorize() ended with. */
    double
    factor_tolerance() const
    {
      return used_factor_tolerance;
    }

    /** dst = (L L^T)^{-1} src, natural numbering, on the block's rows
     *  (other entries of dst zero); needs factorize(). */
    void
    solve(Vector<double> &dst, const Vector<double> &src) const;

    /** The same for the columns of @p rhs (overwritten by the solutions on
     *  the block's rows, the other rows left as they are). */
    void
    solve(FullMatrix<double> &rhs) const;

    /** Number of foundation nodes n (A is n x n; a block is part of it). */
    unsigned int
    size() const
    {
      return n_nodes;
    }

    bool
    is_factorized() const
    {
      return factor != nullptr;
    }

    /** Bytes of the stored entries of the H-matrix and its factor, and of
     *  the permutation (hmat-oss's tree nodes are not counted). */
    std::size_t
    memory_consumption() const;

    /**
     * Stored entries of A's H-matrix over its rows times its columns. The
     * storage of a symmetric block is lower symmetric (diagonal blocks and
     * the blocks below them), so a matrix without low-rank blocks gives
     * about 0.5.
     */
    double
    compression_ratio() const;

    /** Number of admissible (low-rank) leaves of A's H-matrix. */
    std::size_t
    n_low_rank_blocks() const;

    /** Number of full (near-field) leaves of A's H-matrix. */
    std::size_t
    n_full_blocks() const;

    /** The relative accuracy asked of the compression (Settings). */
    double
    tolerance() const
    {
      return settings.tolerance;
    }

    /**
     * Largest relative 2-norm difference between sampled rows of the
     * H-matrix and the same rows integrated exactly (measured by build()).
     */
    double
    sampled_row_error() const
    {
      return row_error;
    }

    /** Wall times of build() and factorize(), in seconds. */
    struct Times
    {
      /** Integrating entries: the singular cell pairs once, every entry
       *  ACA+ and the near field ask for, the sampled rows of the check. */
      double integration = 0;
      /** ACA+'s own algebra during the assembly (the rest of it). */
      double compression = 0;
      /** The H-Cholesky factorisation and its check. */
      double factorization = 0;
    };

    const Times &
    build_times() const
    {
      return times;
    }

    /**
     * ||A x - b|| / ||b|| of the factor's solve of a known b (measured by
     * factorize(); A the H-matrix).
     */
    double
    factorization_residual() const
    {
      return solve_residual;
    }

  private:
    /**
     * One factorisation with recompressions at @p factor_tolerance and its
     * check: the reason it failed, or empty.
     */
    std::string
    try_factorize(const double factor_tolerance);

    Settings     settings;
    unsigned int n_nodes = 0;
    /** The block's nodes (empty: all) and each node's place among them
     *  (-1: not in the block), for rows and columns. */
    std::vector<unsigned int> row_nodes, column_nodes;
    std::vector<int>          row_unknowns, column_unknowns;
    /** Whether rows and columns are the same nodes (lower storage). */
    bool symmetric = true;
    /** hmat position k of the rows (columns) holds node
     *  hmat_to_row[k] (hmat_to_column[k]). */
    std::vector<unsigned int> hmat_to_row, hmat_to_column;
    /** The cluster trees of the rows and of the columns (the same tree for
     *  a symmetric block). */
    hmat_cluster_tree_struct *row_tree = nullptr, *column_tree = nullptr;
    /** A or its block; lower-symmetric storage if symmetric. */
    hmat_matrix_struct *matrix = nullptr;
    /** The H-Cholesky factor of a copy of A (nullptr before factorize()). */
    hmat_matrix_struct *factor    = nullptr;
    double              row_error = 0;
    /** The recompression accuracy the factor was made with (factorize()
     *  tightens Settings::factor_tolerance when it must). */
    double used_factor_tolerance = 0;
    double solve_residual        = 0;
    Times  times;

    void
    release();

    /** Row @p i of the block (its columns' entries, zero elsewhere). */
    Vector<double>
    block_row(const unsigned int i) const;
  };
} // namespace PlateOnHalfspace

#endif
