/**
 * The split-kernel storage's far field between the foundation nodes and
 * the grid of GridConvolution as one sparse matrix (doc/formulation.md,
 * "Split-kernel FFT storage"):
 *
 *   P_jg = sum over the cells c of node j, over c's Gauss points x_q,
 *          of JxW_q psi_j(x_q) W_g(x_q),
 *
 * W_g(x) the B-spline weight of grid node g at x (GridConvolution::
 * stencil()). The grid charges of nodal values v are P^T v and the far
 * field's tests of grid potentials phi are P phi, so a product reads each
 * stored entry once each way instead of making every Gauss point's
 * stencil twice (doc/performance.md, "The far field's gridding as a
 * sparse matrix"). Row j holds the grid nodes within a stencil of node
 * j's cells: about (2 cell / h + p)^2 for an interior node of cells of
 * size cell, grid spacing h and spline order p.
 *
 * Made in two steps, so that its memory can be checked before it is
 * allocated: the constructor counts the entries, assemble() makes them.
 * The cells' Gauss points are tabulated on demand and only a few at a
 * time are held: P replaces them.
 */
#ifndef plate_on_halfspace_halfspace_grid_projection_h
#define plate_on_halfspace_halfspace_grid_projection_h

#include <deal.II/base/point.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <cstddef>
#include <functional>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  class GridConvolution;

  /** See the file documentation. */
  class GridProjection
  {
  public:
    /** The far field's Gauss points of one cell. */
    struct CellPoints
    {
      std::vector<unsigned int> nodes;
      std::vector<Point<2>>     points;
      /** JxW psi_a at point q: [q * nodes.size() + a]. */
      std::vector<double> weighted_values;
    };

    /** The foundation nodes of cell c. */
    using CellNodes =
      std::function<const std::vector<unsigned int> &(const unsigned int c)>;
    /** The Gauss points of cell c, called from several threads at once. */
    using CellTabulator =
      std::function<void(const unsigned int c, CellPoints &points)>;

    /**
     * Counts the entries of P for the cells c with @p used[c] set (a
     * rank's own cells) on @p n_nodes foundation nodes. @p grid and what
     * the functions refer to must live until assemble().
     */
    GridProjection(const GridConvolution   &grid,
                   const std::vector<bool> &used,
                   const unsigned int       n_nodes,
                   const CellNodes         &cell_nodes,
                   const CellTabulator     &tabulate);

    /** The bytes assemble() allocates, its transients included. */
    std::size_t
    memory_needed() const;

    /** Makes P's pattern and entries. */
    void
    assemble();

    /** @p charges += P^T @p values (one pass, the same sum always). */
    void
    spread(const Vector<double> &values, Vector<double> &charges) const;

    /** @p tests += P @p potentials (rows in parallel, each summed in
     *  order). */
    void
    add_tests(const Vector<double> &potentials, Vector<double> &tests) const;

    /**
     * Keeps only P's columns with a nonzero entry, numbered in increasing
     * order of their grid nodes, and returns those grid nodes: spread()
     * and add_tests() then work on vectors of the nodes this rank's cells
     * reach (a split grid's footprint, GridConvolution::set_footprint()),
     * not of the whole grid. After assemble().
     */
    std::vector<unsigned int>
    keep_reached_columns();

    /** The length of the grid vectors spread() and add_tests() take: the
     *  grid's nodes, or those keep_reached_columns() kept. */
    unsigned int
    n_columns() const
    {
      return pattern.n_cols();
    }

    std::size_t
    n_entries() const
    {
      return entries;
    }

    std::size_t
    memory_consumption() const;

  private:
    /** The cells and local index of each node, for the cells used. */
    std::vector<std::vector<std::pair<unsigned int, unsigned int>>> node_cells;
    std::vector<unsigned int>                                       row_lengths;
    std::size_t                                                     entries = 0;
    /** Valid from the constructor to assemble(). */
    const GridConvolution *grid = nullptr;
    CellTabulator          tabulate;
    SparsityPattern        pattern;
    SparseMatrix<double>   matrix;
  };
} // namespace PlateOnHalfspace

#endif
