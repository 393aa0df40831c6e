#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

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
      /** The context of an assembly: the entries and the first error. */
      struct AssemblyContext
      {
        const CellPairSummation *summation;
        /** The nodes of the row and column trees. */
        const TreeNodes *rows, *columns;
        /** Counts the blocks done. */
        ProgressReport *progress;
        std::string     error;
        /** Wall time spent integrating entries inside the callbacks. */
        double integration_time = 0;
      };

      /** What hmat-oss's prepare callback hands to the compute callback. */
      struct BlockRequest
      {
        AssemblyContext *context;
        int              row_start, row_count, column_start, column_count;
        const int       *row_hmat_to_node, *row_node_to_hmat;
        const int       *column_hmat_to_node, *column_node_to_hmat;
      };

      /** hmat-oss is done with a block (full, or compressed by ACA+). */
      void
      release_block_request(void *data)
      {
        const BlockRequest *request = static_cast<BlockRequest *>(data);
        request->context->progress->add();
        delete request;
      }

      void
      prepare_block(int                row_start,
                    int                row_count,
                    int                column_start,
                    int                column_count,
                    int               *row_hmat_to_node,
                    int               *row_node_to_hmat,
                    int               *column_hmat_to_node,
                    int               *column_node_to_hmat,
                    void              *context,
                    hmat_block_info_t *info)
      {
        info->block_type = hmat_block_full;
        info->user_data =
          new BlockRequest{static_cast<AssemblyContext *>(context),
                           row_start,
                           row_count,
                           column_start,
                           column_count,
                           row_hmat_to_node,
                           row_node_to_hmat,
                           column_hmat_to_node,
                           column_node_to_hmat};
        info->release_user_data = release_block_request;
      }

      /**
       * The sub-block (rows row_begin + [0, n_rows), columns column_begin +
       * [0, n_columns)) of a prepared block, in hmat-oss's ordering,
       * column-major into @p out: the whole block (near field), or one row
       * or column (ACA+).
       */
      void
      compute_block(const BlockRequest &request,
                    const int           row_begin,
                    const int           n_rows,
                    const int           column_begin,
                    const int           n_columns,
                    double             *out)
      {
        const int        first_row    = request.row_start + row_begin;
        const int        first_column = request.column_start + column_begin;
        const TreeNodes &rows         = *request.context->rows;
        const TreeNodes &columns      = *request.context->columns;
        // hmat-oss numbers each tree's unknowns; the summation the nodes.
        std::vector<unsigned int> row_nodes(n_rows), column_nodes(n_columns);
        for (int p = 0; p < n_rows; ++p)
          row_nodes[p] = rows.node(request.row_hmat_to_node[first_row + p]);
        for (int q = 0; q < n_columns; ++q)
          column_nodes[q] =
            columns.node(request.column_hmat_to_node[first_column + q]);
        std::fill(out, out + std::size_t(n_rows) * n_columns, 0.);
        const auto row_position = [&](const unsigned int node) {
          const int k = rows.unknown(node);
          if (k < 0)
            return -1;
          const int p = request.row_node_to_hmat[k] - first_row;
          return (p >= 0 && p < n_rows) ? p : -1;
        };
        const auto column_position = [&](const unsigned int node) {
          const int k = columns.unknown(node);
          if (k < 0)
            return -1;
          const int q = request.column_node_to_hmat[k] - first_column;
          return (q >= 0 && q < n_columns) ? q : -1;
        };
        request.context->summation->add_entries(row_nodes,
                                                column_nodes,
                                                row_position,
                                                column_position,
                                                n_rows,
                                                n_columns,
                                                out);
      }

      /**
       * hmat-oss's block callback. An exception must not cross the C
       * interface unannounced: keep its message for the caller and
       * rethrow, which makes hmat-oss abandon the assembly with a non-zero
       * status.
       */
      void
      compute_block_callback(void *data,
                             int   row_begin,
                             int   n_rows,
                             int   column_begin,
                             int   n_columns,
                             void *values)
      {
        const BlockRequest &request = *static_cast<BlockRequest *>(data);
        const Timer         timer;
        try
          {
            compute_block(request,
                          row_begin,
                          n_rows,
                          column_begin,
                          n_columns,
                          static_cast<double *>(values));
            request.context->integration_time += timer.wall_time();
          }
        catch (const std::exception &e)
          {
            if (request.context->error.empty())
              request.context->error = e.what();
            throw;
          }
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
      AssemblyContext   context{&summation, &rows, &columns, &progress, "", 0};

      hmat_assemble_context_t assembly;
      hmat_assemble_context_init(&assembly);
      hmat_compression_algorithm_t *compression =
        hmat_create_compression_aca_plus(tolerance);
      assembly.compression     = compression;
      assembly.user_context    = &context;
      assembly.prepare         = prepare_block;
      assembly.block_compute   = compute_block_callback;
      assembly.lower_symmetric = lower_symmetric ? 1 : 0;
      assembly.factorization   = hmat_factorization_none;
      assembly.progress        = nullptr; // hmat-oss's own bar is on stdout
      int status;
      {
        const SingleThreadedBlas single_threaded_blas;
        status = hmat().assemble_generic(matrix, &assembly);
      }
      hmat_delete_compression(compression);
      AssertThrow(context.error.empty(),
                  ExcMessage("Foundation operator/Storage = hierarchical: "
                             "integrating the flexibility failed: " +
                             context.error));
      check_hmat(status, "the assembly of the flexibility");
      progress.finish();
      return context.integration_time;
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
