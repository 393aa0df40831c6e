#include <deal.II/base/array_view.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parallel.h>

#include <plate_on_halfspace/halfspace/grid_convolution.h>
#include <plate_on_halfspace/halfspace/grid_projection.h>

#include <algorithm>
#include <array>
#include <limits>

namespace PlateOnHalfspace
{
  namespace
  {
    using CellPoints = GridProjection::CellPoints;
    using NodeCells  = std::vector<std::pair<unsigned int, unsigned int>>;

    /**
     * One row of P: node j's Gauss points with their stencils and the
     * weights JxW psi_j, and the box of grid nodes the stencils reach
     * (x fastest, as the grid's own numbering).
     */
    class RowStencils
    {
    public:
      void
      make(const GridConvolution               &grid,
           const GridProjection::CellTabulator &tabulate,
           const NodeCells                     &cells_of_node)
      {
        stencils.clear();
        weights.clear();
        for (const auto &[c, a] : cells_of_node)
          {
            const Cached      &cell = cached(grid, tabulate, c);
            const unsigned int n    = cell.points.nodes.size();
            stencils.insert(stencils.end(),
                            cell.stencils.begin(),
                            cell.stencils.end());
            for (unsigned int q = 0; q < cell.points.points.size(); ++q)
              weights.push_back(cell.points.weighted_values[q * n + a]);
          }
        order   = grid.order();
        n_x     = grid.grid_sizes()[0];
        first_x = first_y = std::numeric_limits<int>::max();
        int end_x = std::numeric_limits<int>::min(), end_y = end_x;
        for (const auto &s : stencils)
          {
            first_x = std::min(first_x, s.first_x);
            first_y = std::min(first_y, s.first_y);
            end_x   = std::max(end_x, s.first_x + int(order));
            end_y   = std::max(end_y, s.first_y + int(order));
          }
        width  = stencils.empty() ? 0 : end_x - first_x;
        height = stencils.empty() ? 0 : end_y - first_y;
      }

      std::size_t
      box_size() const
      {
        return std::size_t(width) * height;
      }

      /** Box position of the stencil's node (k, l). */
      std::size_t
      position(const GridConvolution::Stencil &s,
               const unsigned int              k,
               const unsigned int              l) const
      {
        return std::size_t(s.first_y + l - first_y) * width +
               (s.first_x + k - first_x);
      }

      /** Sets @p reached[b] for the box positions some stencil reaches. */
      void
      mark(std::vector<unsigned char> &reached) const
      {
        reached.assign(box_size(), 0);
        for (const auto &s : stencils)
          for (unsigned int l = 0; l < order; ++l)
            for (unsigned int k = 0; k < order; ++k)
              reached[position(s, k, l)] = 1;
      }

      /** @p sums[b] = the row's entry at box position b. */
      void
      accumulate(std::vector<double> &sums) const
      {
        sums.assign(box_size(), 0.);
        for (unsigned int p = 0; p < stencils.size(); ++p)
          {
            const auto &s = stencils[p];
            for (unsigned int l = 0; l < order; ++l)
              {
                const double w  = weights[p] * s.y[l];
                double      *at = sums.data() + position(s, 0, l);
                for (unsigned int k = 0; k < order; ++k)
                  at[k] += w * s.x[k];
              }
          }
      }

      /** The grid node at box position @p b. */
      unsigned int
      grid_node(const std::size_t b) const
      {
        return (first_y + b / width) * n_x + first_x + b % width;
      }

      /** The box position of grid node @p g, or box_size() outside. */
      std::size_t
      box_position(const unsigned int g) const
      {
        const int x = int(g % n_x) - first_x, y = int(g / n_x) - first_y;
        if (x < 0 || y < 0 || x >= width || y >= height)
          return box_size();
        return std::size_t(y) * width + x;
      }

    private:
      struct Cached
      {
        unsigned int cell = numbers::invalid_unsigned_int;
        CellPoints   points;
        std::vector<GridConvolution::Stencil> stencils;
      };

      /**
       * Cell @p c's points and their stencils, from a small cache: each
       * cell serves the rows of all its nodes, and rows are made in node
       * order, where neighbours share cells.
       */
      const Cached &
      cached(const GridConvolution               &grid,
             const GridProjection::CellTabulator &tabulate,
             const unsigned int                   c)
      {
        Cached &entry = cache[c % cache.size()];
        if (entry.cell != c)
          {
            entry.cell = c;
            tabulate(c, entry.points);
            entry.stencils.resize(entry.points.points.size());
            for (unsigned int q = 0; q < entry.points.points.size(); ++q)
              entry.stencils[q] = grid.stencil(entry.points.points[q]);
          }
        return entry;
      }

      std::array<Cached, 1024>              cache;
      std::vector<GridConvolution::Stencil> stencils;
      std::vector<double>                   weights;
      unsigned int                          order = 0, n_x = 0;
      int first_x = 0, first_y = 0, width = 0, height = 0;
    };

    /**
     * Rows in parallel, each task with its own scratch and cache of
     * cells: a few long runs of rows, so that few cells are tabulated
     * twice.
     */
    template <typename RowFunction>
    void
    for_rows(const unsigned int n_rows, const RowFunction &row_function)
    {
      parallel::apply_to_subranges(
        0u,
        n_rows,
        [&](const unsigned int from, const unsigned int to) {
          RowStencils                row;
          std::vector<unsigned char> reached;
          std::vector<double>        sums;
          for (unsigned int j = from; j < to; ++j)
            row_function(j, row, reached, sums);
        },
        std::max(256u, n_rows / (8 * MultithreadInfo::n_threads())));
    }
  } // namespace

  GridProjection::GridProjection(const GridConvolution   &grid,
                                 const std::vector<bool> &used,
                                 const unsigned int       n_nodes,
                                 const CellNodes         &cell_nodes,
                                 const CellTabulator     &tabulate)
    : node_cells(n_nodes)
    , row_lengths(n_nodes, 0)
    , grid(&grid)
    , tabulate(tabulate)
  {
    for (unsigned int c = 0; c < used.size(); ++c)
      if (used[c])
        {
          const std::vector<unsigned int> &nodes = cell_nodes(c);
          for (unsigned int a = 0; a < nodes.size(); ++a)
            node_cells[nodes[a]].emplace_back(c, a);
        }
    for_rows(n_nodes,
             [&](const unsigned int          j,
                 RowStencils                &row,
                 std::vector<unsigned char> &reached,
                 std::vector<double> &) {
               row.make(grid, tabulate, node_cells[j]);
               row.mark(reached);
               row_lengths[j] = static_cast<unsigned int>(
                 std::count(reached.begin(), reached.end(), 1));
             });
    for (const unsigned int length : row_lengths)
      entries += length;
  }

  std::size_t
  GridProjection::memory_needed() const
  {
    // Per entry: the value, the pattern's column index, and while the
    // pattern is made the column lists it is copied from and the copy
    // SparsityPattern::compress() makes. Per row: the pattern's and the
    // lists' starts, the lists' views, two row lengths and the row's list
    // of cells (held by the constructor already, counted all the same).
    std::size_t pairs = 0;
    for (const NodeCells &cells_of_node : node_cells)
      pairs += cells_of_node.size();
    return entries * (sizeof(double) + 3 * sizeof(unsigned int)) +
           row_lengths.size() *
             (2 * sizeof(std::size_t) + sizeof(ArrayView<const unsigned int>) +
              2 * sizeof(unsigned int) + sizeof(NodeCells)) +
           pairs * sizeof(NodeCells::value_type);
  }

  void
  GridProjection::assemble()
  {
    Assert(grid != nullptr, ExcMessage("GridProjection: assembled twice."));
    const unsigned int n_rows = node_cells.size();
    {
      std::vector<std::size_t> row_start(n_rows + 1, 0);
      for (unsigned int j = 0; j < n_rows; ++j)
        row_start[j + 1] = row_start[j] + row_lengths[j];
      std::vector<unsigned int> columns(entries);
      for_rows(n_rows,
               [&](const unsigned int          j,
                   RowStencils                &row,
                   std::vector<unsigned char> &reached,
                   std::vector<double> &) {
                 row.make(*grid, tabulate, node_cells[j]);
                 row.mark(reached);
                 std::size_t at = row_start[j];
                 for (std::size_t b = 0; b < reached.size(); ++b)
                   if (reached[b])
                     columns[at++] = row.grid_node(b);
                 Assert(at == row_start[j + 1], ExcInternalError());
               });
      std::vector<ArrayView<const unsigned int>> rows(n_rows);
      for (unsigned int j = 0; j < n_rows; ++j)
        rows[j] = make_array_view(columns.data() + row_start[j],
                                  columns.data() + row_start[j + 1]);
      pattern.copy_from(n_rows, grid->n_grid_nodes(), rows.begin(), rows.end());
    }
    matrix.reinit(pattern);
    // a square P holds every diagonal entry besides (zero outside a row's
    // box)
    entries = pattern.n_nonzero_elements();
    // the pattern's own order of each row (a square P would hold its
    // diagonal first)
    for_rows(n_rows,
             [&](const unsigned int j,
                 RowStencils       &row,
                 std::vector<unsigned char> &,
                 std::vector<double> &sums) {
               row.make(*grid, tabulate, node_cells[j]);
               row.accumulate(sums);
               for (auto entry = matrix.begin(j); entry != matrix.end(j);
                    ++entry)
                 {
                   const std::size_t b = row.box_position(entry->column());
                   entry->value()      = b < sums.size() ? sums[b] : 0.;
                 }
             });
    node_cells  = {};
    row_lengths = {};
    grid        = nullptr;
    tabulate    = nullptr;
  }

  void
  GridProjection::spread(const Vector<double> &values,
                         Vector<double>       &charges) const
  {
    matrix.Tvmult_add(charges, values);
  }

  void
  GridProjection::add_tests(const Vector<double> &potentials,
                            Vector<double>       &tests) const
  {
    matrix.vmult_add(tests, potentials);
  }

  std::vector<unsigned int>
  GridProjection::keep_reached_columns()
  {
    Assert(grid == nullptr, ExcMessage("GridProjection: assemble() first."));
    // A square P also stores a zero diagonal (deal.II's convention for
    // square patterns): only nonzero entries count as reached.
    std::vector<bool> is_reached(pattern.n_cols(), false);
    for (auto entry = matrix.begin(); entry != matrix.end(); ++entry)
      if (entry->value() != 0.)
        is_reached[entry->column()] = true;
    // the new number of each reached grid node
    std::vector<unsigned int> reached, column_of(pattern.n_cols());
    for (unsigned int g = 0; g < is_reached.size(); ++g)
      if (is_reached[g])
        {
          column_of[g] = reached.size();
          reached.push_back(g);
        }
    // A rank whose cells' charges all vanish on the grid (a few cells
    // shared by several ranks) reaches no node; deal.II keeps no rows in a
    // pattern without columns, so it keeps the first node, never written.
    if (reached.empty() && !is_reached.empty())
      reached.push_back(0);
    // each row's kept entries, by their new columns
    const unsigned int n_rows = pattern.n_rows();
    std::vector<std::vector<std::pair<unsigned int, double>>> kept(n_rows);
    for (unsigned int j = 0; j < n_rows; ++j)
      {
        for (auto entry = matrix.begin(j); entry != matrix.end(j); ++entry)
          if (entry->value() != 0.)
            kept[j].emplace_back(column_of[entry->column()], entry->value());
        std::sort(kept[j].begin(), kept[j].end());
      }
    matrix.clear();
    {
      std::vector<std::vector<unsigned int>> columns(n_rows);
      for (unsigned int j = 0; j < n_rows; ++j)
        for (const auto &[column, value] : kept[j])
          columns[j].push_back(column);
      pattern.copy_from(n_rows, reached.size(), columns.begin(), columns.end());
    }
    matrix.reinit(pattern);
    for (unsigned int j = 0; j < n_rows; ++j)
      for (const auto &[column, value] : kept[j])
        matrix.set(j, column, value);
    entries = pattern.n_nonzero_elements();
    return reached;
  }

  std::size_t
  GridProjection::memory_consumption() const
  {
    return pattern.memory_consumption() + matrix.memory_consumption();
  }
} // namespace PlateOnHalfspace
