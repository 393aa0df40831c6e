#include <deal.II/base/exceptions.h>
#include <deal.II/base/parallel.h>

#include <plate_on_halfspace/base/progress.h>
#include <plate_on_halfspace/halfspace/compressed_settlement.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "hmat_glue.h"

namespace PlateOnHalfspace
{
  using HmatGlue::check_hmat;
  using HmatGlue::hmat;

  namespace
  {
    /** What the block entries read: the influences and both numberings. */
    struct InfluenceColumns
    {
      const SettlementInfluence   *influence;
      const std::vector<Point<2>> *points;
      /** The node of each column unknown, and each node's unknown (-1:
       *  not a column). */
      const std::vector<unsigned int> *column_nodes;
      const std::vector<int>          *column_unknowns;
    };

    /**
     * The sub-block (rows row_begin + [0, n_rows), columns column_begin +
     * [0, n_columns)) of a prepared block, column-major into @p out: each
     * row's point against the cells of the columns' supports. Rows are
     * split over the threads; a single row (ACA+) splits its cells into
     * fixed chunks summed in order, so that the result does not depend on
     * the number of threads.
     */
    void
    compute_influence_block(const InfluenceColumns        &context,
                            const HmatGlue::BlockPosition &block,
                            const int                      row_begin,
                            const int                      n_rows,
                            const int                      column_begin,
                            const int                      n_columns,
                            double                        *out)
    {
      const SettlementInfluence &influence = *context.influence;
      const FoundationSpace     &space     = influence.foundation_space();
      const int                  first_row = block.row_start + row_begin;
      const int first_column               = block.column_start + column_begin;

      // The block's columns in each cell of their supports: which local
      // shape function, with which weight, adds to which column.
      struct Contribution
      {
        unsigned int shape;
        double       weight;
        int          column;
      };
      struct SupportCell
      {
        unsigned int              cell;
        unsigned int              needed = 0;
        std::vector<Contribution> contributions;
      };
      std::vector<unsigned int> cell_list;
      for (int q = 0; q < n_columns; ++q)
        {
          const unsigned int node =
            (*context
                .column_nodes)[block.column_hmat_to_unknown[first_column + q]];
          for (const unsigned int c : influence.cells_containing(node))
            cell_list.push_back(c);
        }
      std::sort(cell_list.begin(), cell_list.end());
      cell_list.erase(std::unique(cell_list.begin(), cell_list.end()),
                      cell_list.end());
      std::vector<SupportCell> cells;
      for (const unsigned int c : cell_list)
        {
          SupportCell support{c, 0, {}};
          for (unsigned int i = 0; i < 9; ++i)
            for (const auto &term : space.cells[c].expansion[i])
              {
                const int unknown = (*context.column_unknowns)[term.first];
                if (unknown < 0)
                  continue;
                const int q =
                  block.column_unknown_to_hmat[unknown] - first_column;
                if (q < 0 || q >= n_columns)
                  continue;
                support.needed |= 1u << i;
                support.contributions.push_back({i, term.second, q});
              }
          cells.push_back(support);
        }

      // row[q stride] += the influences of cells [begin, end)
      const auto add_cells = [&](const Point<2>    &x,
                                 const unsigned int begin,
                                 const unsigned int end,
                                 double            *row,
                                 const int          stride) {
        for (unsigned int k = begin; k < end; ++k)
          {
            const std::array<double, 9> moments =
              influence.far_influences(cells[k].cell, x, cells[k].needed);
            for (const Contribution &term : cells[k].contributions)
              row[term.column * stride] += term.weight * moments[term.shape];
          }
      };

      std::fill(out, out + std::size_t(n_rows) * n_columns, 0.);
      const auto point_of = [&](const int r) {
        return (*context.points)[block.row_hmat_to_unknown[first_row + r]];
      };
      if (n_rows > 1)
        parallel::apply_to_subranges(
          0,
          n_rows,
          [&](const int begin, const int end) {
            for (int r = begin; r < end; ++r)
              add_cells(point_of(r), 0, cells.size(), out + r, n_rows);
          },
          8);
      else
        {
          const unsigned int chunk    = 16;
          const unsigned int n_chunks = (cells.size() + chunk - 1) / chunk;
          std::vector<std::vector<double>> sums(n_chunks,
                                                std::vector<double>(n_columns,
                                                                    0.));
          const Point<2>                   x = point_of(0);
          parallel::apply_to_subranges(
            0u,
            n_chunks,
            [&](const unsigned int begin, const unsigned int end) {
              for (unsigned int k = begin; k < end; ++k)
                add_cells(x,
                          k * chunk,
                          std::min<unsigned int>(cells.size(), (k + 1) * chunk),
                          sums[k].data(),
                          1);
            },
            1);
          for (const auto &sum : sums)
            for (int q = 0; q < n_columns; ++q)
              out[q] += sum[q];
        }
    }

    /** The H-matrix and its trees, released in any case. */
    struct InfluenceMatrix
    {
      hmat_cluster_tree_t *rows = nullptr, *columns = nullptr;
      hmat_matrix_t       *matrix = nullptr;

      ~InfluenceMatrix()
      {
        if (matrix != nullptr)
          hmat().destroy(matrix);
        if (columns != nullptr)
          hmat_delete_cluster_tree(columns);
        if (rows != nullptr)
          hmat_delete_cluster_tree(rows);
      }
    };
  } // namespace

  std::vector<double>
  compressed_settlement_at_points(const FoundationSpace       &space,
                                  const Vector<double>        &nodal_pressure,
                                  const std::vector<Point<2>> &points,
                                  const SurfaceKernel         &kernel,
                                  const unsigned int           singular_order,
                                  const double                 tolerance,
                                  CompressedSettlementReport  *report)
  {
    std::vector<double> settlement(points.size(), 0.);
    // The columns: the loaded nodes (the product needs no others).
    std::vector<unsigned int> column_nodes;
    std::vector<int>          column_unknowns(space.n_nodes(), -1);
    for (unsigned int i = 0; i < space.n_nodes(); ++i)
      if (nodal_pressure[i] != 0)
        {
          column_unknowns[i] = column_nodes.size();
          column_nodes.push_back(i);
        }
    if (points.empty() || column_nodes.empty())
      return settlement;

    const SettlementInfluence influence(space, kernel, singular_order);
    const unsigned int        leaf_size = 48;

    // Column tree: each node's extent its support.
    InfluenceMatrix           column_holder;
    std::vector<unsigned int> column_order;
    column_holder.columns = HmatGlue::make_support_cluster_tree(
      space.node_locations,
      column_nodes,
      space.cells,
      space.cells.size(),
      [&](const unsigned int i) -> const std::vector<unsigned int> & {
        return influence.cells_containing(i);
      },
      leaf_size,
      column_order);
    std::vector<double> x(column_order.size());
    for (unsigned int k = 0; k < x.size(); ++k)
      x[k] = nodal_pressure[column_order[k]];

    // The points in batches, so that one batch's H-matrix is held at a
    // time: its memory grows like points^1.3 (doc/performance.md).
    const std::size_t  batch_size = 1u << 15;
    const unsigned int n_batches =
      (points.size() + batch_size - 1) / batch_size;
    ProgressReport progress("Goal estimate: settlement (ACA+)", n_batches);
    double         stored_entries = 0;
    for (unsigned int b = 0; b < n_batches; ++b)
      {
        const std::size_t begin = b * batch_size,
                          end   = std::min(points.size(), begin + batch_size);
        const std::vector<Point<2>> batch(points.begin() + begin,
                                          points.begin() + end);
        InfluenceMatrix             held;
        std::vector<unsigned int>   row_order;
        {
          // each point its own extent
          std::vector<double>       coordinates;
          std::vector<unsigned int> span_ends, spans;
          for (unsigned int p = 0; p < batch.size(); ++p)
            {
              coordinates.push_back(batch[p][0]);
              coordinates.push_back(batch[p][1]);
              spans.push_back(p);
              span_ends.push_back(spans.size());
            }
          held.rows = HmatGlue::make_cluster_tree(
            coordinates, span_ends, spans, leaf_size, row_order);
        }
        held.matrix = HmatGlue::make_empty_hmatrix(
          held.rows,
          column_holder.columns,
          false,
          2.,
          tolerance,
          "Adaptivity/Goal: hmat-oss could not create the settlement's "
          "influence matrix.");
        const InfluenceColumns context{&influence,
                                       &batch,
                                       &column_nodes,
                                       &column_unknowns};
        HmatGlue::assemble_with_aca(
          held.matrix,
          false,
          tolerance,
          [&](const HmatGlue::BlockPosition &block,
              const int                      row_begin,
              const int                      n_rows,
              const int                      column_begin,
              const int                      n_columns,
              double                        *out) {
            compute_influence_block(
              context, block, row_begin, n_rows, column_begin, n_columns, out);
          },
          nullptr,
          "Adaptivity/Goal: integrating the settlement's influence matrix "
          "failed: ",
          "the assembly of the settlement's influence matrix");
        // u = G q in hmat-oss's numbering, back to the points'
        std::vector<double> y(row_order.size(), 0.);
        {
          const SingleThreadedBlas single_threaded_blas;
          const double             one = 1., zero = 0.;
          check_hmat(
            hmat().gemm_dense(
              'N', 'N', 'L', &one, held.matrix, x.data(), &zero, y.data(), 1),
            "the product with the settlement's influence matrix");
        }
        stored_entries += HmatGlue::info_of(held.matrix).compressed_size;
        for (unsigned int k = 0; k < y.size(); ++k)
          settlement[begin + row_order[k]] = y[k];
        progress.add();
      }
    progress.finish();


    // q_h at each cell's Q2 nodes, for the near corrections and the check.
    std::vector<std::array<double, 9>> q2;
    for (const auto &cell : space.cells)
      q2.push_back(cell.local_values(nodal_pressure));
    const auto add = [&](const std::array<double, 9> &influences,
                         const unsigned int           c) {
      double sum = 0;
      for (unsigned int i = 0; i < 9; ++i)
        sum += influences[i] * q2[c][i];
      return sum;
    };
    const auto near_part = [&](const Point<2> &point) {
      double sum = 0;
      for (const unsigned int c : influence.near_cells(point))
        sum += add(influence.near_corrections(c, point), c);
      return sum;
    };
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(points.size()),
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int p = begin; p < end; ++p)
          settlement[p] += near_part(points[p]);
      },
      64);
    AssertThrow(HmatGlue::all_finite(settlement.data(), settlement.size()),
                ExcMessage("Foundation operator/Tolerance: the compressed "
                           "settlement of the goal's estimate is not "
                           "finite." +
                           HmatGlue::tolerance_advice));

    // The check of the compression: the same sum uncompressed.
    const double error = sampled_settlement_error(
      points, settlement, [&](const std::vector<Point<2>> &samples) {
        std::vector<double> exact;
        for (const Point<2> &x : samples)
          {
            exact.push_back(near_part(x));
            for (unsigned int c = 0; c < space.cells.size(); ++c)
              exact.back() += add(influence.far_influences(c, x), c);
          }
        return exact;
      });
    if (report != nullptr)
      {
        report->sampled_error = error;
        report->compression_ratio =
          stored_entries /
          (double(points.size()) * double(column_nodes.size()));
      }
    std::ostringstream measured;
    measured << error;
    AssertThrow(error <= std::min(10 * tolerance, 1e-2),
                ExcMessage("Foundation operator/Tolerance: the compressed "
                           "settlement of the goal's estimate differs from "
                           "the exactly integrated one by " +
                           measured.str() +
                           " (relative, sampled points), more than the "
                           "tolerance allows." +
                           HmatGlue::tolerance_advice));
    return settlement;
  }

  double
  sampled_settlement_error(
    const std::vector<Point<2>> &points,
    const std::vector<double>   &computed,
    const std::function<std::vector<double>(const std::vector<Point<2>> &)>
      &exact)
  {
    const std::size_t n_samples = std::min<std::size_t>(points.size(), 8);
    std::vector<std::size_t> sampled;
    std::vector<Point<2>>    samples;
    for (std::size_t s = 0; s < n_samples; ++s)
      {
        sampled.push_back((2 * s + 1) * points.size() / (2 * n_samples));
        samples.push_back(points[sampled.back()]);
      }
    const std::vector<double> reference = exact(samples);
    double                    scale = 0, difference = 0;
    for (std::size_t s = 0; s < n_samples; ++s)
      {
        scale = std::max(scale, std::abs(reference[s]));
        difference =
          std::max(difference, std::abs(computed[sampled[s]] - reference[s]));
      }
    return scale > 0 ? difference / scale : difference;
  }
} // namespace PlateOnHalfspace
