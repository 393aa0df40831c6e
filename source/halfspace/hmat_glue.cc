#include "hmat_glue.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <plate_on_halfspace/base/progress.h>

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace PlateOnHalfspace
{
  namespace HmatGlue
  {
    using namespace dealii;

    // Lowering the tolerance helps only while it is coarse; it cannot go
    // below 1e-14 (Parameters::FoundationOperator), so the advice says
    // what else to do (doc/errors-and-limits.md).
    const std::string tolerance_advice =
      " If Foundation operator/Tolerance is coarser than 1e-8, lower it (it "
      "is the compression's accuracy); otherwise, or if the mesh is small, "
      "use Foundation operator/Storage = dense (exactly integrated; its "
      "memory grows with the square of the foundation nodes).";

    hmat_interface_t &
    hmat()
    {
      static hmat_interface_t interface = []() {
        hmat_interface_t i;
        hmat_init_default_interface(&i, HMAT_DOUBLE_PRECISION);
        AssertThrow(i.init() == 0,
                    ExcMessage("Foundation operator/Storage = hierarchical: "
                               "the hmat-oss library could not be "
                               "initialised."));
        return i;
      }();
      return interface;
    }

    void
    check_hmat(const int status, const std::string &what)
    {
      AssertThrow(status == 0,
                  ExcMessage("Foundation operator/Tolerance: hmat-oss failed "
                             "in " +
                             what + " (status " + std::to_string(status) +
                             ")." + tolerance_advice));
    }

    hmat_cluster_tree_t *
    make_cluster_tree(std::vector<double>       &coordinates,
                      std::vector<unsigned int> &span_ends,
                      std::vector<unsigned int> &spans,
                      const unsigned int         leaf_size,
                      std::vector<unsigned int> &position_to_unknown)
    {
      const unsigned int           n      = span_ends.size();
      hmat_clustering_algorithm_t *median = hmat_create_clustering_median();
      hmat_clustering_algorithm_t *clustering =
        hmat_create_clustering_max_dof(median, leaf_size);
      hmat_cluster_tree_builder_t *builder =
        hmat_create_cluster_tree_builder(clustering);
      hmat_cluster_tree_create_context_t context;
      context.dimension         = 2;
      context.number_of_points  = coordinates.size() / 2;
      context.coordinates       = coordinates.data();
      context.number_of_dof     = n;
      context.span_offsets      = span_ends.data();
      context.spans             = spans.data();
      context.group_index       = nullptr;
      context.builder           = builder;
      hmat_cluster_tree_t *tree = hmat_create_cluster_tree_generic(&context);
      hmat_delete_cluster_tree_builder(builder);
      hmat_delete_clustering(clustering);
      hmat_delete_clustering(median);
      AssertThrow(tree != nullptr,
                  ExcMessage("Foundation operator/Storage = hierarchical: "
                             "hmat-oss could not build the cluster tree."));

      const int *indices = hmat_cluster_get_indices(tree);
      position_to_unknown.resize(n);
      std::vector<bool> seen(n, false);
      for (unsigned int k = 0; k < n; ++k)
        {
          const int unknown = indices[k];
          AssertThrow(unknown >= 0 && unknown < static_cast<int>(n) &&
                        !seen[unknown],
                      ExcMessage("HierarchicalFlexibility: the cluster tree's "
                                 "numbering is not a permutation."));
          seen[unknown]          = true;
          position_to_unknown[k] = unknown;
        }
      return tree;
    }

    hmat_matrix_t *
    make_empty_hmatrix(hmat_cluster_tree_t *rows,
                       hmat_cluster_tree_t *columns,
                       const bool           lower_symmetric,
                       const double         eta,
                       const double         tolerance,
                       const std::string   &failure)
    {
      hmat_admissibility_param_t parameters;
      hmat_init_admissibility_param(&parameters);
      parameters.eta = eta;
      hmat_admissibility_t *admissibility =
        hmat_create_admissibility(&parameters);
      hmat_matrix_t *matrix = hmat().create_empty_hmatrix_admissibility(
        rows, columns, lower_symmetric ? 1 : 0, admissibility);
      hmat_delete_admissibility(admissibility);
      AssertThrow(matrix != nullptr, ExcMessage(failure));
      hmat().set_low_rank_epsilon(matrix, tolerance);
      return matrix;
    }

    hmat_cluster_tree_t *
    make_support_cluster_tree(
      const std::vector<Point<2>>              &node_locations,
      const std::vector<unsigned int>          &nodes,
      const std::vector<FoundationSpace::Cell> &cells,
      const unsigned int                        n_cells,
      const std::function<const std::vector<unsigned int> &(unsigned int)>
                                &cells_containing,
      const unsigned int         leaf_size,
      std::vector<unsigned int> &hmat_to_node)
    {
      const unsigned int n_tree =
        nodes.empty() ? node_locations.size() : nodes.size();
      const auto node = [&](const unsigned int k) {
        return nodes.empty() ? k : nodes[k];
      };
      std::vector<double> coordinates;
      coordinates.reserve(2 * (n_tree + 4 * n_cells));
      for (unsigned int k = 0; k < n_tree; ++k)
        {
          coordinates.push_back(node_locations[node(k)][0]);
          coordinates.push_back(node_locations[node(k)][1]);
        }
      for (unsigned int c = 0; c < n_cells; ++c)
        for (const Point<2> &v : cells[c].geometry.get_vertices())
          {
            coordinates.push_back(v[0]);
            coordinates.push_back(v[1]);
          }
      std::vector<unsigned int> span_ends(n_tree), spans;
      for (unsigned int k = 0; k < n_tree; ++k)
        {
          const std::vector<unsigned int> &support = cells_containing(node(k));
          AssertThrow(!support.empty(),
                      ExcMessage("HierarchicalFlexibility: foundation node " +
                                 std::to_string(node(k)) +
                                 " lies in no cell."));
          spans.push_back(k);
          for (const unsigned int c : support)
            for (unsigned int v = 0; v < 4; ++v)
              spans.push_back(n_tree + 4 * c + v);
          span_ends[k] = spans.size();
        }
      std::vector<unsigned int> position_to_unknown;
      hmat_cluster_tree_t      *tree = make_cluster_tree(
        coordinates, span_ends, spans, leaf_size, position_to_unknown);
      hmat_to_node.resize(n_tree);
      for (unsigned int k = 0; k < n_tree; ++k)
        hmat_to_node[k] = node(position_to_unknown[k]);
      return tree;
    }

    namespace
    {
      /** The context of an assembly: the entries and the first error. */
      struct AssemblyContext
      {
        const BlockEntries *entries;
        ProgressReport     *progress;
        std::string         error;
        double              entries_time = 0;
      };

      /** What the prepare callback hands to the compute callback. */
      struct PreparedBlock
      {
        AssemblyContext *context;
        BlockPosition    position;
      };

      /** hmat-oss is done with a block (full, or compressed by ACA+). */
      void
      release_block(void *data)
      {
        const PreparedBlock *block = static_cast<PreparedBlock *>(data);
        if (block->context->progress != nullptr)
          block->context->progress->add();
        delete block;
      }

      void
      prepare_block(int                row_start,
                    int                row_count,
                    int                column_start,
                    int                column_count,
                    int               *row_hmat_to_unknown,
                    int               *row_unknown_to_hmat,
                    int               *column_hmat_to_unknown,
                    int               *column_unknown_to_hmat,
                    void              *context,
                    hmat_block_info_t *info)
      {
        (void)row_count;
        (void)column_count;
        info->block_type = hmat_block_full;
        info->user_data =
          new PreparedBlock{static_cast<AssemblyContext *>(context),
                            {row_start,
                             column_start,
                             row_hmat_to_unknown,
                             row_unknown_to_hmat,
                             column_hmat_to_unknown,
                             column_unknown_to_hmat}};
        info->release_user_data = release_block;
      }

      /**
       * hmat-oss's block callback. An exception must not cross the C
       * interface unannounced: keep its message for the caller and
       * rethrow, which makes hmat-oss abandon the assembly with a non-zero
       * status.
       */
      void
      compute_block(void *data,
                    int   row_begin,
                    int   n_rows,
                    int   column_begin,
                    int   n_columns,
                    void *values)
      {
        const PreparedBlock &block   = *static_cast<PreparedBlock *>(data);
        AssemblyContext     &context = *block.context;
        const Timer          timer;
        try
          {
            (*context.entries)(block.position,
                               row_begin,
                               n_rows,
                               column_begin,
                               n_columns,
                               static_cast<double *>(values));
            context.entries_time += timer.wall_time();
          }
        catch (const std::exception &e)
          {
            if (context.error.empty())
              context.error = e.what();
            throw;
          }
      }
    } // namespace

    double
    assemble_with_aca(hmat_matrix_t      *matrix,
                      const bool          lower_symmetric,
                      const double        tolerance,
                      const BlockEntries &entries,
                      ProgressReport     *progress,
                      const std::string  &failure,
                      const std::string  &what)
    {
      AssemblyContext         context{&entries, progress, "", 0};
      hmat_assemble_context_t assembly;
      hmat_assemble_context_init(&assembly);
      hmat_compression_algorithm_t *compression =
        hmat_create_compression_aca_plus(tolerance);
      assembly.compression     = compression;
      assembly.user_context    = &context;
      assembly.prepare         = prepare_block;
      assembly.block_compute   = compute_block;
      assembly.lower_symmetric = lower_symmetric ? 1 : 0;
      assembly.factorization   = hmat_factorization_none;
      assembly.progress        = nullptr; // hmat-oss's own bar is on stdout
      int status;
      {
        const SingleThreadedBlas single_threaded_blas;
        status = hmat().assemble_generic(matrix, &assembly);
      }
      hmat_delete_compression(compression);
      AssertThrow(context.error.empty(), ExcMessage(failure + context.error));
      check_hmat(status, what);
      return context.entries_time;
    }

    bool
    all_finite(const double *values, const std::size_t n)
    {
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(values[i]))
          return false;
      return true;
    }

    hmat_info_t
    info_of(hmat_matrix_t *matrix)
    {
      hmat_info_t info;
      check_hmat(hmat().get_info(matrix, &info),
                 "reading the H-matrix statistics");
      return info;
    }

    CapturedStandardError::CapturedStandardError()
    {
      // On a terminal the progress reports (base/progress.h) share stderr
      // with the library and are left alone.
      if (isatty(STDERR_FILENO))
        return;
      std::cerr.flush();
      std::fflush(stderr);
      int ends[2];
      if (pipe2(ends, O_NONBLOCK | O_CLOEXEC) != 0)
        return;
      saved = fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0);
      if (saved < 0 || dup2(ends[1], STDERR_FILENO) < 0)
        {
          if (saved >= 0)
            close(saved);
          saved = -1;
          close(ends[0]);
          close(ends[1]);
          return;
        }
      close(ends[1]);
      reader = ends[0];
    }

    std::string
    CapturedStandardError::release()
    {
      std::string text;
      if (saved < 0)
        return text;
      std::cerr.flush();
      std::fflush(stderr);
      // Restoring fd 2 closes the pipe's last write end: the reads below
      // end at its end of file or, non-blocking, at an empty pipe.
      dup2(saved, STDERR_FILENO);
      close(saved);
      saved = -1;
      char    buffer[4096];
      ssize_t n;
      while ((n = read(reader, buffer, sizeof(buffer))) > 0)
        text.append(buffer, static_cast<std::size_t>(n));
      close(reader);
      reader = -1;
      // One line for the message that quotes it: no trailing blanks or
      // line breaks.
      while (!text.empty() &&
             std::isspace(static_cast<unsigned char>(text.back())))
        text.pop_back();
      return text;
    }

    CapturedStandardError::~CapturedStandardError()
    {
      release();
    }
  } // namespace HmatGlue
} // namespace PlateOnHalfspace
