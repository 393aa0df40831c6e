#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/base/progress.h>
#include <plate_on_halfspace/halfspace/cell_pair_summation.h>

#include <algorithm>
#include <string>
#include <vector>

#include "hmat_glue.h"

namespace PlateOnHalfspace
{
  namespace HmatGlue
  {
    using namespace dealii;

    namespace
    {
      /**
       * The sub-block (rows row_begin + [0, n_rows), columns column_begin +
       * [0, n_columns)) of @p block, in hmat-oss's ordering, column-major
       * into @p out, from the cell-pair sum.
       */
      void
      compute_block(const CellPairSummation &summation,
                    const TreeNodes         &rows,
                    const TreeNodes         &columns,
                    const BlockPosition     &block,
                    const int                row_begin,
                    const int                n_rows,
                    const int                column_begin,
                    const int                n_columns,
                    double                  *out)
      {
        const int first_row    = block.row_start + row_begin;
        const int first_column = block.column_start + column_begin;
        // hmat-oss numbers each tree's unknowns; the summation the nodes.
        std::vector<unsigned int> row_nodes(n_rows), column_nodes(n_columns);
        for (int p = 0; p < n_rows; ++p)
          row_nodes[p] = rows.node(block.row_hmat_to_unknown[first_row + p]);
        for (int q = 0; q < n_columns; ++q)
          column_nodes[q] =
            columns.node(block.column_hmat_to_unknown[first_column + q]);
        std::fill(out, out + std::size_t(n_rows) * n_columns, 0.);
        const auto row_position = [&](const unsigned int node) {
          const int k = rows.unknown(node);
          if (k < 0)
            return -1;
          const int p = block.row_unknown_to_hmat[k] - first_row;
          return (p >= 0 && p < n_rows) ? p : -1;
        };
        const auto column_position = [&](const unsigned int node) {
          const int k = columns.unknown(node);
          if (k < 0)
            return -1;
          const int q = block.column_unknown_to_hmat[k] - first_column;
          return (q >= 0 && q < n_columns) ? q : -1;
        };
        summation.add_entries(row_nodes,
                              column_nodes,
                              row_position,
                              column_position,
                              n_rows,
                              n_columns,
                              out);
      }
    } // namespace

    double
    assemble_flexibility(hmat_matrix_t           *matrix,
                         const CellPairSummation &summation,
                         const TreeNodes         &rows,
                         const TreeNodes         &columns,
                         const bool               lower_symmetric,
                         const double             tolerance)
    {
      // The empty H-matrix has its leaves already: the blocks to assemble.
      const hmat_info_t leaves = info_of(matrix);
      ProgressReport    progress("Hierarchical flexibility (ACA+)",
                              leaves.full_count + leaves.rk_count);
      const double      integration_time = assemble_with_aca(
        matrix,
        lower_symmetric,
        tolerance,
        [&](const BlockPosition &block,
            const int            row_begin,
            const int            n_rows,
            const int            column_begin,
            const int            n_columns,
            double              *out) {
          compute_block(summation,
                        rows,
                        columns,
                        block,
                        row_begin,
                        n_rows,
                        column_begin,
                        n_columns,
                        out);
        },
        &progress,
        "Foundation operator/Storage = hierarchical: integrating the "
             "flexibility failed: ",
        "the assembly of the flexibility");
      progress.finish();
      return integration_time;
    }

    std::vector<double>
    exact_row(const CellPairSummation &summation,
              const unsigned int       i,
              const unsigned int       n_nodes)
    {
      std::vector<unsigned int> all_nodes(n_nodes);
      for (unsigned int j = 0; j < n_nodes; ++j)
        all_nodes[j] = j;
      std::vector<double> row(n_nodes, 0.);
      summation.add_entries(
        {i},
        all_nodes,
        [i](const unsigned int node) { return node == i ? 0 : -1; },
        [](const unsigned int node) { return static_cast<int>(node); },
        1,
        n_nodes,
        row.data());
      return row;
    }
  } // namespace HmatGlue
} // namespace PlateOnHalfspace
