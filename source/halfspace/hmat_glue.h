/**
 * Internal to HierarchicalFlexibility (hierarchical_flexibility.h): the
 * hmat-oss C interface and the assembly of the flexibility's H-matrix from
 * the cell-pair sum. A private header, so that hmat-oss stays out of the
 * public ones.
 *  - hmat_glue.cc: the interface object and status checks (BLAS runs on
 *    one thread inside hmat-oss calls: base/single_threaded_blas.h);
 *  - hierarchical_assembly.cc: the block callbacks of the assembly and the
 *    exactly integrated rows of the accuracy check.
 */
#ifndef plate_on_halfspace_source_halfspace_hmat_glue_h
#define plate_on_halfspace_source_halfspace_hmat_glue_h

#include <plate_on_halfspace/base/single_threaded_blas.h>
#include <plate_on_halfspace/plate/foundation_space.h>

#include <hmat/hmat.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  class CellPairSummation;
  class ProgressReport;

  namespace HmatGlue
  {
    /** The advice every failure ends with. */
    extern const std::string tolerance_advice;

    /**
     * hmat-oss's C interface for doubles with its default (sequential)
     * engine, initialised once per process. The default engine runs every
     * callback in the calling thread, so deal.II's task scheduler inside
     * the callbacks cannot re-enter hmat-oss.
     */
    hmat_interface_t &
    hmat();

    /** Throw the message of a failed hmat-oss call @p what. */
    void
    check_hmat(const int status, const std::string &what);

    bool
    all_finite(const double *values, const std::size_t n);

    /** Statistics of an H-matrix (leaf counts, stored entries). */
    hmat_info_t
    info_of(hmat_matrix_t *matrix);

    /**
     * What hmat-oss writes to the standard error while it lives, kept
     * instead of printed. hmat-oss reports a failed factorisation (a
     * non-positive pivot) on stderr as well as in its status; the program
     * retries such a factorisation more finely, and reports a final
     * failure in its own message, which quotes this text
     * (doc/errors-and-limits.md: one "Error:" line). Captured through a
     * non-blocking pipe: text beyond the pipe's buffer is lost, never
     * blocking the library. On a terminal (where the progress reports
     * share stderr) or where the pipe cannot be made, nothing is captured
     * and the library prints as before.
     */
    class CapturedStandardError
    {
    public:
      CapturedStandardError();
      ~CapturedStandardError();
      CapturedStandardError(const CapturedStandardError &) = delete;
      CapturedStandardError &
      operator=(const CapturedStandardError &) = delete;

      /** Restore the standard error and return what was written to it. */
      std::string
      release();

    private:
      int saved = -1, reader = -1;
    };

    /**
     * hmat-oss's cluster tree of unknowns 0 .. span_ends.size() - 1 in the
     * plane: @p coordinates holds x, y of the points, and unknown k's
     * extent is the points spans[span_ends[k - 1] .. span_ends[k]) (from 0
     * for k = 0), the first of them its own location (hmat-oss 1.8.1 keeps
     * only that one of a cluster's first unknown in the cluster's box).
     * Median clustering down to @p leaf_size unknowns per leaf. Returns the
     * tree and, in @p position_to_unknown, which unknown each of its
     * positions holds; throws if hmat-oss fails.
     */
    hmat_cluster_tree_t *
    make_cluster_tree(std::vector<double>       &coordinates,
                      std::vector<unsigned int> &span_ends,
                      std::vector<unsigned int> &spans,
                      const unsigned int         leaf_size,
                      std::vector<unsigned int> &position_to_unknown);

    /**
     * An empty H-matrix on the trees @p rows and @p columns (lower-symmetric
     * storage if @p lower_symmetric) with Hackbusch's admissibility of
     * parameter @p eta, recompressing at @p tolerance (hmat-oss's low-rank
     * epsilon; without it hmat-oss recompresses at its default 1e-4
     * whatever the assembly's tolerance). Throws @p failure if hmat-oss
     * fails.
     */
    hmat_matrix_t *
    make_empty_hmatrix(hmat_cluster_tree_t *rows,
                       hmat_cluster_tree_t *columns,
                       const bool           lower_symmetric,
                       const double         eta,
                       const double         tolerance,
                       const std::string   &failure);

    /**
     * The cluster tree of the foundation nodes @p nodes (natural numbers;
     * empty: all of @p node_locations), each with its support as extent:
     * the node itself, then the vertices of the cells @p cells_containing
     * it (indices into the first @p n_cells of @p cells, whose vertices are
     * the tree's points). Returns the tree and, in
     * @p hmat_to_node, the node at each of its positions. Throws if a node
     * lies in no cell.
     */
    hmat_cluster_tree_t *
    make_support_cluster_tree(
      const std::vector<Point<2>>              &node_locations,
      const std::vector<unsigned int>          &nodes,
      const std::vector<FoundationSpace::Cell> &cells,
      const unsigned int                        n_cells,
      const std::function<const std::vector<unsigned int> &(unsigned int)>
                                &cells_containing,
      const unsigned int         leaf_size,
      std::vector<unsigned int> &hmat_to_node);

    /**
     * One leaf block as hmat-oss prepares it: its first row and column in
     * hmat-oss's numbering, and the maps between that numbering and the
     * unknowns of the row and column trees.
     */
    struct BlockPosition
    {
      int        row_start, column_start;
      const int *row_hmat_to_unknown, *row_unknown_to_hmat;
      const int *column_hmat_to_unknown, *column_unknown_to_hmat;
    };

    /**
     * Fill the sub-block (rows row_begin + [0, n_rows), columns
     * column_begin + [0, n_columns)) of a block, column-major into out:
     * the whole block (near field), or one row or column (ACA+).
     */
    using BlockEntries = std::function<void(const BlockPosition &block,
                                            int                  row_begin,
                                            int                  n_rows,
                                            int                  column_begin,
                                            int                  n_columns,
                                            double              *out)>;

    /**
     * Assemble the empty H-matrix @p matrix with ACA+ at @p tolerance,
     * every entry from @p entries, with one BLAS thread. @p progress, if
     * given, counts the blocks done. An exception of @p entries is kept and
     * rethrown after hmat-oss has abandoned the assembly, as ExcMessage
     * @p failure followed by its message; a failed hmat-oss status throws
     * naming @p what. Returns the wall time spent inside @p entries.
     */
    double
    assemble_with_aca(hmat_matrix_t      *matrix,
                      const bool          lower_symmetric,
                      const double        tolerance,
                      const BlockEntries &entries,
                      ProgressReport     *progress,
                      const std::string  &failure,
                      const std::string  &what);

    /**
     * The foundation nodes of a cluster tree: its k-th unknown is node
     * natural[k] (natural numbering); local[i] is the unknown of node i,
     * -1 for nodes not in the tree. Empty vectors: every node, in order.
     */
    struct TreeNodes
    {
      const std::vector<unsigned int> &natural;
      const std::vector<int>          &local;

      unsigned int
      node(const int k) const
      {
        return natural.empty() ? k : natural[k];
      }

      int
      unknown(const unsigned int i) const
      {
        return local.empty() ? static_cast<int>(i) : local[i];
      }
    };

    /**
     * Assemble the empty H-matrix @p matrix (hmat-oss's numbering, rows on
     * the tree of @p rows, columns on that of @p columns; lower-symmetric
     * storage if @p lower_symmetric) with ACA+ at @p tolerance, every
     * entry from @p summation (doc/formulation.md, "Hierarchical
     * storage"). Shows the progress in blocks (ProgressReport). Returns the
     * wall time spent integrating entries inside the callbacks; throws
     * with the callbacks' first error or hmat-oss's failure.
     */
    double
    assemble_flexibility(hmat_matrix_t           *matrix,
                         const CellPairSummation &summation,
                         const TreeNodes         &rows,
                         const TreeNodes         &columns,
                         const bool               lower_symmetric,
                         const double             tolerance);

    /** Row @p i of A (natural numbering, @p n_nodes entries), exactly
     *  integrated: the reference of the sampled-row check. */
    std::vector<double>
    exact_row(const CellPairSummation &summation,
              const unsigned int       i,
              const unsigned int       n_nodes);
  } // namespace HmatGlue
} // namespace PlateOnHalfspace

#endif
