/**
 * The Galerkin half-space flexibility (doc/formulation.md, "Default
 * variant") as a sum over cell pairs, with the mirror images of a
 * symmetric scene (doc/formulation.md, "Symmetry"):
 *
 *   A_ij = sum_K sum_L sum_R ∫_K ∫_{R L} psi_i(x) psi_j(R y) K(|x - y|)
 *
 * with the soil's point-load kernel K(r) = alpha / r + remainder(r)
 * (soil/soil_model.h: SurfaceKernel; the homogeneous half-space has no
 * remainder),
 * over the computed cells K and L and the reflections R (the identity
 * first), psi the node shape functions. This is the one statement of which
 * cell pairs and images contribute to an entry, in which order, with which
 * symmetrisation and factor: the dense operator (galerkin_operator.h) sums
 * every term, the hierarchical one (hierarchical_flexibility.h) the terms
 * of the entries hmat-oss asks for, so the two cannot drift apart.
 */
#ifndef plate_on_halfspace_halfspace_cell_pair_summation_h
#define plate_on_halfspace_halfspace_cell_pair_summation_h

#include <deal.II/lac/full_matrix.h>

#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/soil/soil_model.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace PlateOnHalfspace
{
  class CellPairIntegrator;
  class ProgressReport;

  /**
   * The sum over cell pairs (see file doc).
   *
   * Terms: the pairs first <= other of computed cells, and for each the
   * images r = 0, 1, ... of @p other (r = 0: the cell itself), in the
   * canonical order (first, other, r), lexicographic. A term integrates
   * B(a, b) = ∫_first ∫_{R other} psi_a psi_b K(|x - y|) (CellPairIntegrator:
   * alpha times the 1/r integral, plus the remainder's) and adds B(a, b)
   *  - at (node a of first, node b of R other): test cell first,
   *    pressure cell other;
   *  - when first != other, also at (node b, node a): test cell other,
   *    pressure cell first. The image pair (other, R first) is the
   *    transpose of (first, R other), R being an isometry and an
   *    involution, so the pairs first <= other cover all.
   * A cell against its own image (first == other, r > 0) is symmetrised
   * (symmetrise_self_image_block()). Within a term the entries follow B
   * row by row, each direct contribution before its transposed one.
   *
   * Order of summation: add_all() (the dense matrix) adds the terms one by
   * one in canonical order. add_entries() (blocks of hmat-oss) adds them in
   * canonical order within runs of consecutive terms, each run into its
   * own buffer, then the runs in order; the runs are cut by the size of
   * the request alone. Both results are independent of the number of
   * threads, and an entry of the two differs by rounding only (the
   * grouping into runs, and a separated pair integrated for a few rows or
   * columns: integrate_inverse_distance() with masks).
   *
   * Partial foundation (@p cell_in_foundation, the paper's element
   * exclusion): a contribution counts for the flexibility (the settlement
   * of the whole plate) when its pressure cell is in the foundation, and
   * for the system flexibility when its test cell is too. Pairs with
   * neither cell in the foundation are skipped.
   *
   * Threads: the terms are integrated by deal.II tasks; add_all() hands
   * them to its sink from the calling thread, a round of a few hundred
   * pairs per thread behind the tasks, add_entries() sums its runs in
   * tasks. The singular pairs are integrated once in the constructor, in
   * canonical order (CellPairIntegrator::integrate_singular_pairs()), so
   * that the cache of congruent configurations is deterministic too. Calls
   * to one object must not overlap.
   */
  class CellPairSummation
  {
  public:
    /** Two computed cells, first <= other. */
    struct Pair
    {
      unsigned int first, other;
    };

    /**
     * @param cells the computed cells followed, for a symmetric scene, by
     *   their mirror images (image of cell c under reflection r at
     *   r * n_computed + c, FoundationSpace::mirror_image_cells()); must
     *   outlive this object.
     * @param n_copies 1 + the number of reflections.
     * @param n_nodes number of foundation nodes.
     * @param kernel the soil's kernel (a number alpha: alpha / r).
     * @param singular_order Gauss points per direction of the singular
     *   pairs (CellPairIntegrator).
     * @param cell_in_foundation per computed cell; empty: all.
     */
    CellPairSummation(const std::vector<FoundationSpace::Cell> &cells,
                      const unsigned int                        n_copies,
                      const unsigned int                        n_nodes,
                      const SurfaceKernel                      &kernel,
                      const unsigned int                        singular_order,
                      const std::vector<bool> &cell_in_foundation = {});

    ~CellPairSummation();

    /** A space's cells followed by their mirror images (see above). */
    static std::vector<FoundationSpace::Cell>
    cells_with_images(const FoundationSpace &space);

    /**
     * The terms (first, l) in canonical order (first, then other, then the
     * image r, l = r n_computed + other, other >= first) for which
     * @p keep(first, l) holds, among the cells whose @p centres (of
     * cells_with_images()) lie in neighbouring buckets of width
     * @p width: @p keep must hold only for cells whose centres are less
     * than @p width apart.
     */
    static std::vector<std::pair<unsigned int, unsigned int>>
    canonical_pairs_within(
      const std::vector<Point<2>>                           &centres,
      const unsigned int                                     n_computed,
      const double                                           width,
      const std::function<bool(unsigned int, unsigned int)> &keep);

    unsigned int
    n_computed_cells() const
    {
      return n_computed;
    }

    /** Number of pairs first <= other (progress reports count them). */
    std::uint64_t
    n_pairs() const
    {
      return std::uint64_t(n_computed) * (n_computed + 1) / 2;
    }

    /** The computed cells containing node @p i. */
    const std::vector<unsigned int> &
    cells_containing(const unsigned int i) const
    {
      return cells_of_node[i];
    }

    /**
     * Add every term to @p sink, in canonical order: sink(i, j, value,
     * in_system) for each contribution value to A_ij whose pressure cell
     * is in the foundation, in_system saying whether its test cell is too
     * (see class doc). @p progress, if given, counts pairs.
     */
    template <typename Sink>
    void
    add_all(const Sink &sink, ProgressReport *progress = nullptr) const;

    /**
     * out(p, q) += A_ij for the rows i with p = row_index(i) >= 0 and the
     * columns j with q = column_index(j) >= 0 (out column-major with
     * @p n_rows rows and @p n_columns columns), from the terms of the
     * pairs of cells containing a node of @p row_nodes and cells
     * containing one of @p column_nodes; a separated pair integrates only
     * the functions asked for. The terms are summed in canonical order in
     * runs of consecutive terms (in parallel, one buffer each), and the
     * runs in order; how the terms are cut into runs depends on the
     * number of pairs and entries only, not on the threads. @p row_index
     * and @p column_index are called from several threads.
     */
    template <typename RowIndex, typename ColumnIndex>
    void
    add_entries(const std::vector<unsigned int> &row_nodes,
                const std::vector<unsigned int> &column_nodes,
                const RowIndex                  &row_index,
                const ColumnIndex               &column_index,
                const unsigned int               n_rows,
                const unsigned int               n_columns,
                double                          *out) const;

  private:
    /** Receives each integrated block, serially, in canonical order. */
    using Consumer = std::function<void(const unsigned int        first,
                                        const unsigned int        other,
                                        const unsigned int        r,
                                        const FullMatrix<double> &block)>;

    const unsigned int  n_computed;
    const unsigned int  copies;
    const SurfaceKernel kernel;
    /** Per computed cell; all true without exclusion. */
    std::vector<bool> in_foundation;
    /** Node lists of all cells, images included (the integrator's). */
    std::vector<const std::vector<unsigned int> *> cell_nodes;
    std::vector<std::vector<unsigned int>>         cells_of_node;
    std::unique_ptr<const CellPairIntegrator>      integrator;
    /** The blocks of two rounds of integrate_in_rounds(), kept between
     *  calls. */
    mutable std::vector<FullMatrix<double>> round_blocks;
    /** Per computed cell, pairs_touching()'s marks (zero between calls). */
    mutable std::vector<char> cell_flags;

    bool
    contributes(const unsigned int first, const unsigned int other) const
    {
      return in_foundation[first] || in_foundation[other];
    }

    /** The pairs of cells containing a node of @p row_nodes and cells
     *  containing one of @p column_nodes, canonical order. */
    std::vector<Pair>
    pairs_touching(const std::vector<unsigned int> &row_nodes,
                   const std::vector<unsigned int> &column_nodes) const;

    /** Integrate the singular terms (same or touching cells) of all
     *  contributing pairs, in canonical order, into the integrator's
     *  cache. */
    void
    integrate_singular_terms(
      const std::vector<FoundationSpace::Cell> &cells) const;

    /**
     * B of the term (first, other, r) into @p block, only the @p rows of
     * first and @p columns of the image of other if given (empty: all),
     * a cell against its own image whole and symmetrised.
     */
    void
    integrate_term(const unsigned int       first,
                   const unsigned int       other,
                   const unsigned int       r,
                   FullMatrix<double>      &block,
                   const std::vector<bool> &rows,
                   const std::vector<bool> &columns) const;

    /**
     * Where the contributions of a term go: for each node of first (a) and
     * of the image of other (b) its row and column index, negative where
     * the node is not wanted or the kind of contribution does not count
     * (its pressure cell is out of the foundation). Direct contributions
     * go to (row_a, column_b), transposed ones to (row_b, column_a).
     */
    struct TermIndices
    {
      std::vector<int> row_a, column_a, row_b, column_b;
      /** Whether some direct (some transposed) contribution is wanted. */
      bool direct = false, transposed = false;
    };

    /** What integrating and scattering terms needs, one per task. */
    struct Workspace
    {
      FullMatrix<double> block;
      std::vector<bool>  rows, columns;
      TermIndices        indices;
    };

    template <typename RowIndex, typename ColumnIndex>
    void
    term_indices(const unsigned int first,
                 const unsigned int other,
                 const unsigned int r,
                 const RowIndex    &row_index,
                 const ColumnIndex &column_index,
                 TermIndices       &indices) const;

    /**
     * The functions of a term with @p indices that contribute to wanted
     * entries, as masks for integrate_term(); false if none do.
     */
    static bool
    term_masks(const TermIndices &indices,
               std::vector<bool> &rows,
               std::vector<bool> &columns);

    /**
     * The contributions of the term (first, other, r) with block @p block
     * and @p indices: sink(row, column, value, in_system) in the order of
     * the class doc, in_system saying whether the test cell is in the
     * foundation too.
     */
    template <typename Sink>
    void
    scatter(const unsigned int        first,
            const unsigned int        other,
            const FullMatrix<double> &block,
            const TermIndices        &indices,
            const Sink               &sink) const;

    /**
     * Integrate every term of @p pairs (all functions) and hand the
     * blocks to @p consume serially, in canonical order; many pairs are
     * integrated by tasks, a round ahead of @p consume.
     */
    void
    integrate_in_rounds(const std::vector<Pair> &pairs,
                        const Consumer          &consume) const;

    /**
     * Every contributing pair in canonical order through
     * integrate_in_rounds(); @p progress counts the pairs.
     */
    void
    integrate_all(const Consumer &consume, ProgressReport *progress) const;

    /**
     * Cut @p n_pairs pairs into runs of consecutive pairs (see
     * add_entries()), have @p sum_run(begin, end, buffer, workspace) add
     * the terms of each run to its own zeroed buffer of @p n_entries (in
     * parallel, a workspace per task), and add the buffers to @p out in
     * order. A single run goes straight to @p out.
     */
    void
    sum_in_runs(
      const std::size_t n_pairs,
      const std::size_t n_entries,
      double           *out,
      const std::function<void(std::size_t, std::size_t, double *, Workspace &)>
        &sum_run) const;
  };



  template <typename RowIndex, typename ColumnIndex>
  void
  CellPairSummation::term_indices(const unsigned int first,
                                  const unsigned int other,
                                  const unsigned int r,
                                  const RowIndex    &row_index,
                                  const ColumnIndex &column_index,
                                  TermIndices       &indices) const
  {
    const std::vector<unsigned int> &nodes_a = *cell_nodes[first];
    const std::vector<unsigned int> &nodes_b =
      *cell_nodes[r * n_computed + other];
    // Direct: test cell first, pressure cell other; transposed: the
    // other way round (see class doc).
    const bool direct     = in_foundation[other];
    const bool transposed = (first != other) && in_foundation[first];
    indices.row_a.resize(nodes_a.size());
    indices.column_a.resize(nodes_a.size());
    indices.row_b.resize(nodes_b.size());
    indices.column_b.resize(nodes_b.size());
    bool row_a = false, column_a = false, row_b = false, column_b = false;
    for (unsigned int a = 0; a < nodes_a.size(); ++a)
      {
        indices.row_a[a]    = direct ? row_index(nodes_a[a]) : -1;
        indices.column_a[a] = transposed ? column_index(nodes_a[a]) : -1;
        row_a               = row_a || indices.row_a[a] >= 0;
        column_a            = column_a || indices.column_a[a] >= 0;
      }
    for (unsigned int b = 0; b < nodes_b.size(); ++b)
      {
        indices.row_b[b]    = transposed ? row_index(nodes_b[b]) : -1;
        indices.column_b[b] = direct ? column_index(nodes_b[b]) : -1;
        row_b               = row_b || indices.row_b[b] >= 0;
        column_b            = column_b || indices.column_b[b] >= 0;
      }
    // Each kind counts only with both a wanted row and a wanted column.
    indices.direct     = row_a && column_b;
    indices.transposed = row_b && column_a;
  }



  template <typename Sink>
  void
  CellPairSummation::scatter(const unsigned int        first,
                             const unsigned int        other,
                             const FullMatrix<double> &block,
                             const TermIndices        &indices,
                             const Sink               &sink) const
  {
    const bool first_in = in_foundation[first], other_in = in_foundation[other];
    const unsigned int n_a = indices.row_a.size(), n_b = indices.row_b.size();
    for (unsigned int a = 0; a < n_a; ++a)
      {
        const int p = indices.row_a[a], q = indices.column_a[a];
        if (p < 0 && q < 0)
          continue;
        for (unsigned int b = 0; b < n_b; ++b)
          {
            const double value = block(a, b);
            if (p >= 0 && indices.column_b[b] >= 0)
              sink(p, indices.column_b[b], value, first_in);
            if (q >= 0 && indices.row_b[b] >= 0)
              sink(indices.row_b[b], q, value, other_in);
          }
      }
  }



  template <typename Sink>
  void
  CellPairSummation::add_all(const Sink &sink, ProgressReport *progress) const
  {
    const auto  node = [](const unsigned int i) { return static_cast<int>(i); };
    TermIndices indices;
    integrate_all(
      [&](const unsigned int        first,
          const unsigned int        other,
          const unsigned int        r,
          const FullMatrix<double> &block) {
        term_indices(first, other, r, node, node, indices);
        scatter(first,
                other,
                block,
                indices,
                [&](const int    i,
                    const int    j,
                    const double value,
                    const bool   in_system) {
                  sink(static_cast<unsigned int>(i),
                       static_cast<unsigned int>(j),
                       value,
                       in_system);
                });
      },
      progress);
  }



  template <typename RowIndex, typename ColumnIndex>
  void
  CellPairSummation::add_entries(const std::vector<unsigned int> &row_nodes,
                                 const std::vector<unsigned int> &column_nodes,
                                 const RowIndex                  &row_index,
                                 const ColumnIndex               &column_index,
                                 const unsigned int               n_rows,
                                 const unsigned int               n_columns,
                                 double                          *out) const
  {
    const std::vector<Pair> pairs = pairs_touching(row_nodes, column_nodes);
    sum_in_runs(
      pairs.size(),
      std::size_t(n_rows) * n_columns,
      out,
      [&](const std::size_t begin,
          const std::size_t end,
          double           *target,
          Workspace        &work) {
        for (std::size_t p = begin; p < end; ++p)
          for (unsigned int r = 0; r < copies; ++r)
            {
              const unsigned int first = pairs[p].first, other = pairs[p].other;
              term_indices(
                first, other, r, row_index, column_index, work.indices);
              if (!term_masks(work.indices, work.rows, work.columns))
                continue;
              integrate_term(
                first, other, r, work.block, work.rows, work.columns);
              scatter(
                first,
                other,
                work.block,
                work.indices,
                [&](const int i, const int j, const double value, const bool) {
                  target[i + std::size_t(j) * n_rows] += value;
                });
            }
      });
  }
} // namespace PlateOnHalfspace

#endif
