/**
 * HierarchicalFlexibility: the cluster tree, the H-matrix's life cycle,
 * the checks of its accuracy, the product, the H-Cholesky factorisation
 * and the solve. The block assembly from the cell-pair sum is in
 * hierarchical_assembly.cc, the hmat-oss interface in hmat_glue.cc.
 */
#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <plate_on_halfspace/base/progress.h>
#include <plate_on_halfspace/halfspace/cell_pair_summation.h>
#include <plate_on_halfspace/halfspace/hierarchical_flexibility.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "hmat_glue.h"

namespace PlateOnHalfspace
{
  using HmatGlue::CapturedStandardError;
  using HmatGlue::check_hmat;
  using HmatGlue::hmat;
  using HmatGlue::tolerance_advice;

  namespace
  {
    double
    norm(const std::vector<double> &v)
    {
      double sum = 0;
      for (const double x : v)
        sum += x * x;
      return std::sqrt(sum);
    }
  } // namespace

  HierarchicalFlexibility::HierarchicalFlexibility(const Settings &settings)
    : settings(settings)
  {
    std::ostringstream got;
    got << settings.tolerance;
    AssertThrow(std::isfinite(settings.tolerance) && settings.tolerance > 0 &&
                  settings.tolerance <= 1,
                ExcMessage("Foundation operator/Tolerance must lie in (0, 1] "
                           "(got " +
                           got.str() + ")."));
    AssertThrow(settings.leaf_size >= 2 && settings.eta > 0,
                ExcMessage("HierarchicalFlexibility: the leaf size must be "
                           "at least 2 and eta positive."));
  }

  HierarchicalFlexibility::~HierarchicalFlexibility()
  {
    release();
  }

  void
  HierarchicalFlexibility::release()
  {
    if (factor != nullptr)
      hmat().destroy(factor);
    if (matrix != nullptr)
      hmat().destroy(matrix);
    if (column_tree != nullptr && column_tree != row_tree)
      hmat_delete_cluster_tree(column_tree);
    if (row_tree != nullptr)
      hmat_delete_cluster_tree(row_tree);
    factor      = nullptr;
    matrix      = nullptr;
    row_tree    = nullptr;
    column_tree = nullptr;
    row_nodes.clear();
    column_nodes.clear();
    row_unknowns.clear();
    column_unknowns.clear();
    hmat_to_row.clear();
    hmat_to_column.clear();
    symmetric      = true;
    n_nodes        = 0;
    times          = Times();
    row_error      = 0;
    solve_residual = 0;
  }

  void
  HierarchicalFlexibility::build(const FoundationSpace &space,
                                 const SurfaceKernel   &kernel,
                                 const unsigned int     singular_order)
  {
    build(CellPairSummation::cells_with_images(space),
          space.symmetry.n_copies(),
          space.node_locations,
          kernel,
          singular_order);
  }

  void
  HierarchicalFlexibility::build(
    const std::vector<FoundationSpace::Cell> &cells,
    const unsigned int                        n_copies,
    const std::vector<Point<2>>              &node_locations,
    const SurfaceKernel                      &kernel,
    const unsigned int                        singular_order)
  {
    AssertThrow(!node_locations.empty() && n_copies > 0,
                ExcMessage("HierarchicalFlexibility: no foundation nodes."));
    Timer                   timer;
    const CellPairSummation summation(
      cells, n_copies, node_locations.size(), kernel, singular_order);
    const double summation_time = timer.wall_time();
    build(cells, summation, node_locations, {}, {});
    times.integration += summation_time;
  }

  namespace
  {
    /**
     * The cluster tree of @p nodes (natural numbers, empty: all), each
     * node's extent its support (HmatGlue::make_support_cluster_tree()):
     * the computed cells of @p summation that contain it.
     */
    hmat_cluster_tree_struct *
    make_cluster_tree(const std::vector<FoundationSpace::Cell> &cells,
                      const CellPairSummation                  &summation,
                      const std::vector<Point<2>>              &node_locations,
                      const std::vector<unsigned int>          &nodes,
                      const unsigned int                        leaf_size,
                      std::vector<unsigned int>                &hmat_to_node)
    {
      return HmatGlue::make_support_cluster_tree(
        node_locations,
        nodes,
        cells,
        summation.n_computed_cells(),
        [&](const unsigned int i) -> const std::vector<unsigned int> & {
          return summation.cells_containing(i);
        },
        leaf_size,
        hmat_to_node);
    }

    /** Each node's place in @p nodes, -1 if absent (empty if all). */
    std::vector<int>
    unknowns_of(const std::vector<unsigned int> &nodes,
                const unsigned int               n_nodes)
    {
      std::vector<int> unknowns;
      if (!nodes.empty())
        {
          unknowns.assign(n_nodes, -1);
          for (unsigned int k = 0; k < nodes.size(); ++k)
            unknowns[nodes[k]] = k;
        }
      return unknowns;
    }
  } // namespace

  void
  HierarchicalFlexibility::build(
    const std::vector<FoundationSpace::Cell> &cells,
    const CellPairSummation                  &summation,
    const std::vector<Point<2>>              &node_locations,
    const std::vector<unsigned int>          &rows,
    const std::vector<unsigned int>          &columns)
  {
    release();
    Timer timer;
    n_nodes = node_locations.size();
    AssertThrow(n_nodes > 0,
                ExcMessage("HierarchicalFlexibility: no foundation nodes."));
    row_nodes       = rows;
    column_nodes    = columns;
    symmetric       = (rows == columns);
    row_unknowns    = unknowns_of(row_nodes, n_nodes);
    column_unknowns = unknowns_of(column_nodes, n_nodes);

    row_tree = make_cluster_tree(cells,
                                 summation,
                                 node_locations,
                                 row_nodes,
                                 settings.leaf_size,
                                 hmat_to_row);
    if (symmetric)
      {
        column_tree    = row_tree;
        hmat_to_column = hmat_to_row;
      }
    else
      column_tree = make_cluster_tree(cells,
                                      summation,
                                      node_locations,
                                      column_nodes,
                                      settings.leaf_size,
                                      hmat_to_column);

    matrix = HmatGlue::make_empty_hmatrix(
      row_tree,
      column_tree,
      symmetric,
      settings.eta,
      settings.tolerance,
      "Foundation operator/Storage = hierarchical: hmat-oss could not create "
      "the H-matrix.");

    timer.restart();
    const double integration_time = HmatGlue::assemble_flexibility(
      matrix,
      summation,
      HmatGlue::TreeNodes{row_nodes, row_unknowns},
      HmatGlue::TreeNodes{column_nodes, column_unknowns},
      symmetric,
      settings.tolerance);
    // ACA+ interleaves the entries it asks for with its own algebra: what
    // the callbacks did not spend is the compression's.
    times.integration += integration_time;
    times.compression = timer.wall_time() - integration_time;

    // The compression must not have produced non-finite entries (the
    // Frobenius norm covers every stored entry).
    const double frobenius = hmat().norm(matrix);
    AssertThrow(std::isfinite(frobenius) && frobenius > 0,
                ExcMessage("Foundation operator/Tolerance: the compressed "
                           "flexibility has non-finite or no entries." +
                           tolerance_advice));

    // ACA+ estimates its error from the entries it has seen; check it on
    // sampled rows against the exactly integrated ones, so that a
    // tolerance too coarse for this mesh stops here with a message rather
    // than giving a wrong answer later. Rows spread over the numbering.
    timer.restart();
    const unsigned int n_rows    = hmat_to_row.size();
    const unsigned int n_samples = std::min<unsigned int>(n_rows, 4);
    for (unsigned int s = 0; s < n_samples; ++s)
      {
        const unsigned int i =
          row_nodes.empty() ? (2 * s + 1) * n_nodes / (2 * n_samples) :
                              row_nodes[(2 * s + 1) * n_rows / (2 * n_samples)];
        const std::vector<double> exact =
          HmatGlue::exact_row(summation, i, n_nodes);
        const Vector<double> row = block_row(i);
        std::vector<double>  difference;
        for (const unsigned int j : hmat_to_column)
          difference.push_back(row[j] - exact[j]);
        // Against the whole row of A: what a product's row is made of when
        // the block is one rank's part of it.
        row_error = std::max(row_error, norm(difference) / norm(exact));
      }
    times.integration += timer.wall_time();
    std::ostringstream measured;
    measured << row_error;
    // The compressed blocks are far-field entries, much smaller than the
    // exact near field that dominates a row, so a correctly compressed row
    // errs by well under the tolerance; 10 times it is a clear failure,
    // and beyond 1e-2 the flexibility is no longer the half-space's.
    AssertThrow(row_error <= std::min(10 * settings.tolerance, 1e-2),
                ExcMessage("Foundation operator/Tolerance: the compressed "
                           "flexibility differs from the exactly integrated "
                           "one by " +
                           measured.str() +
                           " (relative, sampled rows), more than the "
                           "tolerance allows." +
                           tolerance_advice));
  }

  Vector<double>
  HierarchicalFlexibility::block_row(const unsigned int i) const
  {
    Vector<double> row(n_nodes);
    if (symmetric)
      {
        // row i = column i
        Vector<double> unit(n_nodes);
        unit[i] = 1.;
        vmult(row, unit);
        return row;
      }
    // row i = A^T e_i
    const unsigned int  n_rows = hmat_to_row.size();
    std::vector<double> x(n_rows, 0.), y(hmat_to_column.size(), 0.);
    for (unsigned int k = 0; k < n_rows; ++k)
      if (hmat_to_row[k] == i)
        x[k] = 1.;
    const double             one = 1., zero = 0.;
    const SingleThreadedBlas single_threaded_blas;
    check_hmat(hmat().gemm_dense(
                 'T', 'N', 'L', &one, matrix, x.data(), &zero, y.data(), 1),
               "a row of the flexibility");
    for (unsigned int k = 0; k < y.size(); ++k)
      row[hmat_to_column[k]] = y[k];
    return row;
  }

  void
  HierarchicalFlexibility::vmult(Vector<double>       &dst,
                                 const Vector<double> &src) const
  {
    AssertThrow(matrix != nullptr,
                ExcMessage("HierarchicalFlexibility::vmult before build()."));
    AssertDimension(src.size(), n_nodes);
    const unsigned int  n_rows = hmat_to_row.size();
    std::vector<double> x(hmat_to_column.size()), y(n_rows, 0.);
    for (unsigned int k = 0; k < x.size(); ++k)
      x[k] = src[hmat_to_column[k]];
    const double             one = 1., zero = 0.;
    const SingleThreadedBlas single_threaded_blas;
    check_hmat(hmat().gemm_dense(
                 'N', 'N', 'L', &one, matrix, x.data(), &zero, y.data(), 1),
               "the product with the flexibility");
    AssertThrow(HmatGlue::all_finite(y.data(), n_rows),
                ExcMessage("Foundation operator/Tolerance: the product with "
                           "the compressed flexibility is not finite." +
                           tolerance_advice));
    dst.reinit(n_nodes);
    for (unsigned int k = 0; k < n_rows; ++k)
      dst[hmat_to_row[k]] = y[k];
  }

  void
  HierarchicalFlexibility::diagonal(Vector<double> &dst) const
  {
    AssertThrow(matrix != nullptr && symmetric,
                ExcMessage("HierarchicalFlexibility::diagonal before "
                           "build(), or of a block off the diagonal."));
    const unsigned int  n_rows = hmat_to_row.size();
    std::vector<double> values(n_rows);
    check_hmat(hmat().extract_diagonal(matrix, values.data(), n_rows),
               "the diagonal of the flexibility");
    // hmat-oss gives the diagonal in the order of the unknowns the cluster
    // tree was made from (the block's nodes), not in its own positions.
    dst.reinit(n_nodes);
    for (unsigned int k = 0; k < n_rows; ++k)
      dst[row_nodes.empty() ? k : row_nodes[k]] = values[k];
  }

  void
  HierarchicalFlexibility::factorize()
  {
    AssertThrow(matrix != nullptr && symmetric,
                ExcMessage("HierarchicalFlexibility::factorize before "
                           "build(), or of a block off the diagonal."));
    const Timer timer;
    // The factor only preconditions conjugate gradients, whose answer
    // does not depend on it: recompress it more coarsely than A (first the
    // copy, then every update of the factorisation). At n = 4961 a factor
    // at 1e-3 instead of 1e-6 took a quarter of the time and the same CG
    // iterations (388 against 389, benchmarks/hierarchical_scaling.py).
    // A flexibility whose spectrum spans more (stiff thin layers over a
    // soft soil, doc/soil-models.md) may lose its positive definiteness at
    // that accuracy: then the factor is made again 100 times finer, down
    // to the compression's own tolerance.
    for (double factor_tolerance =
           std::max(settings.tolerance, settings.factor_tolerance);
         ;
         factor_tolerance =
           std::max(settings.tolerance, 1e-2 * factor_tolerance))
      {
        const std::string failure = try_factorize(factor_tolerance);
        if (failure.empty())
          {
            used_factor_tolerance = factor_tolerance;
            break;
          }
        AssertThrow(factor_tolerance > settings.tolerance,
                    ExcMessage(failure +
                               (settings.definiteness_advice.empty() ?
                                  std::string() :
                                  " " + settings.definiteness_advice)));
      }
    times.factorization = timer.wall_time();
  }

  std::string
  HierarchicalFlexibility::try_factorize(const double factor_tolerance)
  {
    if (factor != nullptr)
      hmat().destroy(factor);
    // hmat-oss factorises in place; the product keeps the original.
    factor = hmat().copy(matrix);
    AssertThrow(factor != nullptr,
                ExcMessage("Foundation operator/Storage = hierarchical: "
                           "hmat-oss could not copy the H-matrix."));
    hmat().set_low_rank_epsilon(factor, factor_tolerance);
    if (factor_tolerance > settings.tolerance)
      check_hmat(hmat().truncate(factor),
                 "the recompression of the copy to factorise");
    // hmat-oss reports the rows factorised so far (after each diagonal
    // leaf) through the update function of a progress bar.
    const unsigned int n_rows = hmat_to_row.size();
    ProgressReport     progress("H-Cholesky factorisation", n_rows);
    hmat_progress_t    bar;
    bar.max       = n_rows;
    bar.current   = 0;
    bar.user_data = &progress;
    bar.update    = [](hmat_progress_t *self) {
      static_cast<ProgressReport *>(self->user_data)
        ->advance_to(std::max(self->current, 0));
    };
    hmat_factorization_context_t context;
    hmat_factorization_context_init(&context);
    context.factorization = hmat_factorization_llt;
    context.progress      = &bar;
    int         status;
    std::string library_says;
    {
      const SingleThreadedBlas single_threaded_blas;
      CapturedStandardError    library_output;
      status       = hmat().factorize_generic(factor, &context);
      library_says = library_output.release();
    }
    // The factor keeps the bar for later factorisations; it ends here.
    hmat().set_progressbar(factor, nullptr);
    if (status != 0)
      {
        hmat().destroy(factor);
        factor = nullptr;
        return "Foundation operator/Tolerance: the H-Cholesky "
               "factorisation of the compressed flexibility failed (hmat-oss "
               "status " +
               std::to_string(status) +
               (library_says.empty() ? std::string() : ", " + library_says) +
               "): at this tolerance the compressed matrix is not positive "
               "definite." +
               tolerance_advice;
      }

    progress.finish();

    // Check the factor on a known vector: a smooth pressure plus a
    // node-to-node oscillation, so that both ends of the spectrum count.
    Vector<double> x(n_nodes), b(n_nodes), solution(n_nodes), residual;
    for (const unsigned int i : hmat_to_row)
      x[i] = 1. + 0.5 * std::sin(0.7 * i) + 0.25 * ((i % 2) ? 1. : -1.);
    vmult(b, x);
    solve(solution, b);
    vmult(residual, solution);
    residual -= b;
    solve_residual = residual.l2_norm() / b.l2_norm();
    std::ostringstream measured;
    measured << solve_residual;
    // A factor whose solve leaves more than 1 % of the right-hand side
    // unexplained is no solver (nor a useful preconditioner) for A.
    if (!(solve_residual <= 1e-2))
      {
        hmat().destroy(factor);
        factor = nullptr;
        return "Foundation operator/Tolerance: the H-Cholesky factor of the "
               "compressed flexibility solves a test system only to a "
               "relative residual of " +
               measured.str() + "." + tolerance_advice;
      }
    return {};
  }

  void
  HierarchicalFlexibility::solve(Vector<double>       &dst,
                                 const Vector<double> &src) const
  {
    AssertDimension(src.size(), n_nodes);
    FullMatrix<double> rhs(n_nodes, 1);
    for (const unsigned int i : hmat_to_row)
      rhs(i, 0) = src[i];
    solve(rhs);
    dst.reinit(n_nodes);
    for (const unsigned int i : hmat_to_row)
      dst[i] = rhs(i, 0);
  }

  void
  HierarchicalFlexibility::solve(FullMatrix<double> &rhs) const
  {
    AssertThrow(factor != nullptr,
                ExcMessage("HierarchicalFlexibility::solve before "
                           "factorize()."));
    AssertDimension(rhs.m(), n_nodes);
    const unsigned int  n_rhs  = rhs.n();
    const unsigned int  n_rows = hmat_to_row.size();
    std::vector<double> ordered(std::size_t(n_rows) * n_rhs);
    // column-major, hmat order
    for (unsigned int c = 0; c < n_rhs; ++c)
      for (unsigned int k = 0; k < n_rows; ++k)
        ordered[k + std::size_t(c) * n_rows] = rhs(hmat_to_row[k], c);
    const SingleThreadedBlas single_threaded_blas;
    check_hmat(hmat().solve_dense(factor, ordered.data(), n_rhs),
               "the solve with the H-Cholesky factor");
    AssertThrow(HmatGlue::all_finite(ordered.data(), ordered.size()),
                ExcMessage("Foundation operator/Tolerance: the solve with "
                           "the H-Cholesky factor is not finite." +
                           tolerance_advice));
    for (unsigned int c = 0; c < n_rhs; ++c)
      for (unsigned int k = 0; k < n_rows; ++k)
        rhs(hmat_to_row[k], c) = ordered[k + std::size_t(c) * n_rows];
  }


  std::size_t
  HierarchicalFlexibility::memory_consumption() const
  {
    std::size_t bytes = (hmat_to_row.capacity() + hmat_to_column.capacity()) *
                        sizeof(unsigned int);
    if (matrix != nullptr)
      bytes += HmatGlue::info_of(matrix).compressed_size * sizeof(double);
    if (factor != nullptr)
      bytes += HmatGlue::info_of(factor).compressed_size * sizeof(double);
    return bytes;
  }

  double
  HierarchicalFlexibility::compression_ratio() const
  {
    if (matrix == nullptr)
      return 0;
    return double(HmatGlue::info_of(matrix).compressed_size) /
           (double(hmat_to_row.size()) * double(hmat_to_column.size()));
  }

  std::size_t
  HierarchicalFlexibility::n_low_rank_blocks() const
  {
    return matrix == nullptr ? 0 : HmatGlue::info_of(matrix).rk_count;
  }

  std::size_t
  HierarchicalFlexibility::n_full_blocks() const
  {
    return matrix == nullptr ? 0 : HmatGlue::info_of(matrix).full_count;
  }
} // namespace PlateOnHalfspace
