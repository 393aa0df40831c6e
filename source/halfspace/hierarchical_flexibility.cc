#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/timer.h>

#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>
#include <plate_on_halfspace/halfspace/hierarchical_flexibility.h>

#include <dlfcn.h>
#include <hmat/hmat.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

namespace PlateOnHalfspace
{
  namespace
  {
    /** The advice every failure ends with. */
    const std::string tolerance_advice =
      " Lower Foundation operator/Tolerance (e.g. to 1e-6 or 1e-8), or use "
      "Foundation operator/Storage = dense if the mesh is small.";

    /**
     * hmat-oss's C interface for doubles with its default (sequential)
     * engine, initialised once per process. The default engine runs every
     * callback in the calling thread, so deal.II's task scheduler inside
     * the callbacks cannot re-enter hmat-oss.
     */
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

    /**
     * One BLAS thread while it lives. hmat-oss calls BLAS on many small
     * blocks; OpenBLAS's pthreads busy-wait between such calls, which on
     * this 2-core machine made the H-Cholesky 5 times and the product 4
     * times slower (5373 nodes: 10.6 s against 1.9 s) whenever anything
     * else ran. hmat-oss's own switch for this is compiled out of Debian's
     * build, so look OpenBLAS's up at run time (absent with another BLAS:
     * then nothing to do). The dense LAPACK paths keep their threads.
     */
    class SingleThreadedBlas
    {
    public:
      SingleThreadedBlas()
        : set_threads(reinterpret_cast<void (*)(int)>(
            dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
        , get_threads(reinterpret_cast<int (*)()>(
            dlsym(RTLD_DEFAULT, "openblas_get_num_threads")))
      {
        if (set_threads != nullptr && get_threads != nullptr)
          {
            previous = get_threads();
            set_threads(1);
          }
      }
      ~SingleThreadedBlas()
      {
        if (set_threads != nullptr && get_threads != nullptr)
          set_threads(previous);
      }

    private:
      void (*const set_threads)(int);
      int (*const get_threads)();
      int previous = 1;
    };

    /** Throw the message of a failed hmat-oss call @p what. */
    void
    check_hmat(const int status, const std::string &what)
    {
      AssertThrow(status == 0,
                  ExcMessage("Foundation operator/Tolerance: hmat-oss failed "
                             "in " +
                             what + " (status " + std::to_string(status) +
                             ")." + tolerance_advice));
    }

    bool
    all_finite(const double *values, const std::size_t n)
    {
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(values[i]))
          return false;
      return true;
    }

    double
    norm(const std::vector<double> &v)
    {
      double sum = 0;
      for (const double x : v)
        sum += x * x;
      return std::sqrt(sum);
    }

    /**
     * The entries of A for hmat-oss: A_ij = alpha sum over the computed
     * cells K containing node i, the computed cells L containing node j and
     * the mirror images R of L of the cell-pair integral, ordered as
     * BoussinesqGalerkinOperator::build() orders it (K < L: the pair (K, R
     * L); K > L: the transpose of (L, R K); K = L: (K, K) and the
     * symmetrised self-images), so that the entries are the dense ones.
     */
    class EntryIntegrator
    {
    public:
      EntryIntegrator(const std::vector<FoundationSpace::Cell> &cells,
                      const unsigned int                        n_copies,
                      const unsigned int                        n_nodes,
                      const double                              alpha,
                      const unsigned int                        singular_order)
        : integrator(cells, singular_order)
        , n_computed(cells.size() / n_copies)
        , n_copies(n_copies)
        , alpha(alpha)
        , cells_of_node(n_nodes)
      {
        AssertThrow(n_computed * n_copies == cells.size(),
                    ExcMessage("HierarchicalFlexibility: the cell list must "
                               "hold the computed cells and their mirror "
                               "images (n_copies times as many)."));
        for (unsigned int c = 0; c < n_computed; ++c)
          for (const unsigned int node : integrator.nodes(c))
            {
              AssertThrow(node < n_nodes,
                          ExcMessage("HierarchicalFlexibility: a cell "
                                     "refers to a node beyond the node "
                                     "list."));
              cells_of_node[node].push_back(c);
            }
        integrate_singular_pairs();
      }

      /** The computed cells containing node @p i. */
      const std::vector<unsigned int> &
      cells_containing(const unsigned int i) const
      {
        return cells_of_node[i];
      }

      /** The computed cells containing some node of @p nodes, each once. */
      std::vector<unsigned int>
      cells_touching(const std::vector<unsigned int> &nodes) const
      {
        std::vector<unsigned int> result;
        for (const unsigned int node : nodes)
          result.insert(result.end(),
                        cells_of_node[node].begin(),
                        cells_of_node[node].end());
        std::sort(result.begin(), result.end());
        result.erase(std::unique(result.begin(), result.end()), result.end());
        return result;
      }

      /**
       * out(p, q) += A_ij for the rows i with row_position(i) = p >= 0 and
       * the columns j with column_position(j) = q >= 0 (out column-major
       * with @p n_rows rows), summing the pairs of @p row_cells and
       * @p column_cells. Large requests (whole near-field blocks, long
       * rows) integrate their cell pairs in parallel, each task into its
       * own buffer.
       */
      template <typename RowPosition, typename ColumnPosition>
      void
      add_entries(const std::vector<unsigned int> &row_cells,
                  const std::vector<unsigned int> &column_cells,
                  const RowPosition               &row_position,
                  const ColumnPosition            &column_position,
                  const unsigned int               n_rows,
                  const unsigned int               n_columns,
                  double                          *out) const
      {
        const std::size_t n_pairs = row_cells.size() * column_cells.size();
        const auto        add_range =
          [&](const std::size_t begin, const std::size_t end, double *target) {
            FullMatrix<double> block;
            std::vector<bool>  rows, columns;
            for (std::size_t pair = begin; pair < end; ++pair)
              add_pair(row_cells[pair / column_cells.size()],
                       column_cells[pair % column_cells.size()],
                       row_position,
                       column_position,
                       n_rows,
                       target,
                       block,
                       rows,
                       columns);
          };
        // Below this many pairs the tasks cost more than they save.
        const std::size_t  parallel_threshold = 64;
        const unsigned int n_tasks =
          std::min<std::size_t>(MultithreadInfo::n_threads(),
                                n_pairs / parallel_threshold);
        if (n_tasks <= 1)
          {
            add_range(0, n_pairs, out);
            return;
          }
        const std::size_t n_entries = std::size_t(n_rows) * n_columns;
        std::vector<std::vector<double>> buffers(n_tasks,
                                                 std::vector<double>(n_entries,
                                                                     0.));
        Threads::TaskGroup<void>         tasks;
        for (unsigned int t = 0; t < n_tasks; ++t)
          tasks += Threads::new_task([&, t]() {
            add_range(n_pairs * t / n_tasks,
                      n_pairs * (t + 1) / n_tasks,
                      buffers[t].data());
          });
        tasks.join_all();
        for (const auto &buffer : buffers)
          for (std::size_t k = 0; k < n_entries; ++k)
            out[k] += buffer[k];
      }

    private:
      const CellPairIntegrator               integrator;
      const unsigned int                     n_computed;
      const unsigned int                     n_copies;
      const double                           alpha;
      std::vector<std::vector<unsigned int>> cells_of_node;

      /**
       * The integral of the computed cell @p first (rows) against the
       * image @p r of the computed cell @p other >= first (columns), as
       * the dense build uses it: a cell against its own image is
       * symmetrised. Only the wanted @p rows and @p columns of a
       * separated pair are integrated.
       */
      void
      pair_integral(const unsigned int       first,
                    const unsigned int       r,
                    const unsigned int       other,
                    FullMatrix<double>      &block,
                    const std::vector<bool> &rows,
                    const std::vector<bool> &columns) const
      {
        const unsigned int image = r * n_computed + other;
        if (first == other && r > 0)
          {
            integrator.integrate_inverse_distance(first, image, block);
            symmetrise_self_image_block(integrator.nodes(first),
                                        integrator.nodes(image),
                                        block);
          }
        else
          integrator.integrate_inverse_distance(
            first, image, block, rows, columns);
      }

      /**
       * Integrate the singular pairs (coincident or touching cells, with
       * their Duffy rules the costly ones) once, in parallel, into the
       * integrator's cache of configurations: hmat-oss asks for the
       * near-field blocks one by one from a single thread. Touching cells
       * share a foundation node (a common vertex, or across a hanging node
       * the constrained vertex's expansion), also a cell and the image of
       * a cell next to a mirror plane, so the candidates of a cell are the
       * cells sharing one of its nodes.
       */
      void
      integrate_singular_pairs() const
      {
        std::vector<std::pair<unsigned int, unsigned int>> pairs;
        for (unsigned int first = 0; first < n_computed; ++first)
          {
            std::vector<unsigned int> neighbours =
              cells_touching(integrator.nodes(first));
            for (const unsigned int other : neighbours)
              if (other >= first)
                for (unsigned int r = 0; r < n_copies; ++r)
                  if (integrator.singular_pair(first, r * n_computed + other))
                    pairs.emplace_back(first, r * n_computed + other);
          }
        integrator.integrate_singular_pairs(pairs);
      }

      /**
       * The ordered pair (K, L) with all mirror images of L: K <= L
       * contributes the pair (K, R L) at rows of K and columns of L, K > L
       * the transpose of (L, R K), as in the dense build.
       */
      template <typename RowPosition, typename ColumnPosition>
      void
      add_pair(const unsigned int    K,
               const unsigned int    L,
               const RowPosition    &row_position,
               const ColumnPosition &column_position,
               const unsigned int    n_rows,
               double               *out,
               FullMatrix<double>   &block,
               std::vector<bool>    &rows,
               std::vector<bool>    &columns) const
      {
        const unsigned int first = std::min(K, L), other = std::max(K, L);
        const bool         transposed = K > L;
        // The functions of the two cells whose entries are asked for.
        const auto wanted = [&](const std::vector<unsigned int> &nodes,
                                const bool                       row_side,
                                std::vector<bool>               &mask) {
          mask.resize(nodes.size());
          bool any = false;
          for (unsigned int a = 0; a < nodes.size(); ++a)
            {
              mask[a] = (row_side ? row_position(nodes[a]) :
                                    column_position(nodes[a])) >= 0;
              any     = any || mask[a];
            }
          return any;
        };
        if (!wanted(integrator.nodes(first), !transposed, rows))
          return;
        for (unsigned int r = 0; r < n_copies; ++r)
          {
            const unsigned int image = r * n_computed + other;
            if (!wanted(integrator.nodes(image), transposed, columns))
              continue;
            pair_integral(first, r, other, block, rows, columns);
            scatter(integrator.nodes(first),
                    integrator.nodes(image),
                    block,
                    transposed,
                    row_position,
                    column_position,
                    n_rows,
                    out);
          }
      }

      /**
       * Add alpha block(a, b) at (node_a, node_b), or at (node_b, node_a)
       * if @p transposed, where those are requested.
       */
      template <typename RowPosition, typename ColumnPosition>
      void
      scatter(const std::vector<unsigned int> &nodes_a,
              const std::vector<unsigned int> &nodes_b,
              const FullMatrix<double>        &block,
              const bool                       transposed,
              const RowPosition               &row_position,
              const ColumnPosition            &column_position,
              const unsigned int               n_rows,
              double                          *out) const
      {
        for (unsigned int a = 0; a < nodes_a.size(); ++a)
          {
            const int p = transposed ? column_position(nodes_a[a]) :
                                       row_position(nodes_a[a]);
            if (p < 0)
              continue;
            for (unsigned int b = 0; b < nodes_b.size(); ++b)
              {
                const int q = transposed ? row_position(nodes_b[b]) :
                                           column_position(nodes_b[b]);
                if (q < 0)
                  continue;
                const std::size_t k = transposed ? q + std::size_t(p) * n_rows :
                                                   p + std::size_t(q) * n_rows;
                out[k] += alpha * block(a, b);
              }
          }
      }
    };

    /** The context of an assembly: the entries and the first error. */
    struct AssemblyContext
    {
      const EntryIntegrator *entries;
      std::string            error;
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

    void
    release_block_request(void *data)
    {
      delete static_cast<BlockRequest *>(data);
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
     * column-major into @p values: the whole block, one row or one column
     * (ACA+).
     */
    void
    compute_block(const BlockRequest &request,
                  const int           row_begin,
                  const int           n_rows,
                  const int           column_begin,
                  const int           n_columns,
                  double             *out)
    {
      const int first_row    = request.row_start + row_begin;
      const int first_column = request.column_start + column_begin;
      std::vector<unsigned int> row_nodes(n_rows), column_nodes(n_columns);
      for (int p = 0; p < n_rows; ++p)
        row_nodes[p] = request.row_hmat_to_node[first_row + p];
      for (int q = 0; q < n_columns; ++q)
        column_nodes[q] = request.column_hmat_to_node[first_column + q];
      std::fill(out, out + std::size_t(n_rows) * n_columns, 0.);
      const auto row_position = [&](const unsigned int node) {
        const int p = request.row_node_to_hmat[node] - first_row;
        return (p >= 0 && p < n_rows) ? p : -1;
      };
      const auto column_position = [&](const unsigned int node) {
        const int q = request.column_node_to_hmat[node] - first_column;
        return (q >= 0 && q < n_columns) ? q : -1;
      };
      const EntryIntegrator &entries = *request.context->entries;
      entries.add_entries(entries.cells_touching(row_nodes),
                          entries.cells_touching(column_nodes),
                          row_position,
                          column_position,
                          n_rows,
                          n_columns,
                          out);
    }

    /**
     * hmat-oss's block callback. An exception must not cross the C
     * interface unannounced: keep its message for build() and rethrow,
     * which makes hmat-oss abandon the assembly with a non-zero status.
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
    if (tree != nullptr)
      hmat_delete_cluster_tree(tree);
    factor = nullptr;
    matrix = nullptr;
    tree   = nullptr;
    hmat_to_node.clear();
    n_nodes        = 0;
    times          = Times();
    row_error      = 0;
    solve_residual = 0;
  }

  void
  HierarchicalFlexibility::build(const FoundationSpace &space,
                                 const double           alpha,
                                 const unsigned int     singular_order)
  {
    std::vector<FoundationSpace::Cell> cells  = space.cells;
    const auto                         images = space.mirror_image_cells();
    cells.insert(cells.end(), images.begin(), images.end());
    build(cells,
          space.symmetry.n_copies(),
          space.node_locations,
          alpha,
          singular_order);
  }

  void
  HierarchicalFlexibility::build(
    const std::vector<FoundationSpace::Cell> &cells,
    const unsigned int                        n_copies,
    const std::vector<Point<2>>              &node_locations,
    const double                              alpha,
    const unsigned int                        singular_order)
  {
    release();
    Timer timer;
    n_nodes = node_locations.size();
    AssertThrow(n_nodes > 0 && n_copies > 0,
                ExcMessage("HierarchicalFlexibility: no foundation nodes."));
    const EntryIntegrator entries(
      cells, n_copies, n_nodes, alpha, singular_order);
    times.integration             = timer.wall_time();
    const unsigned int n_computed = cells.size() / n_copies;

    // The cluster tree. Points: the nodes, then the vertices of the
    // computed cells; the extent ("span") of node i is the node itself
    // and the vertices of the cells containing it, its support. hmat-oss
    // 1.8.1 leaves out all but the first span point of the first node of a
    // cluster from the cluster's bounding box, so that first point is the
    // node itself, which always lies in the box.
    {
      std::vector<double> coordinates;
      coordinates.reserve(2 * (n_nodes + 4 * n_computed));
      for (const Point<2> &p : node_locations)
        {
          coordinates.push_back(p[0]);
          coordinates.push_back(p[1]);
        }
      for (unsigned int c = 0; c < n_computed; ++c)
        for (const Point<2> &v : cells[c].geometry.get_vertices())
          {
            coordinates.push_back(v[0]);
            coordinates.push_back(v[1]);
          }
      std::vector<unsigned int> span_ends(n_nodes), spans;
      for (unsigned int i = 0; i < n_nodes; ++i)
        {
          AssertThrow(!entries.cells_containing(i).empty(),
                      ExcMessage("HierarchicalFlexibility: foundation node " +
                                 std::to_string(i) + " lies in no cell."));
          spans.push_back(i);
          for (const unsigned int c : entries.cells_containing(i))
            for (unsigned int v = 0; v < 4; ++v)
              spans.push_back(n_nodes + 4 * c + v);
          span_ends[i] = spans.size();
        }
      hmat_clustering_algorithm_t *median = hmat_create_clustering_median();
      hmat_clustering_algorithm_t *clustering =
        hmat_create_clustering_max_dof(median, settings.leaf_size);
      hmat_cluster_tree_builder_t *builder =
        hmat_create_cluster_tree_builder(clustering);
      hmat_cluster_tree_create_context_t context;
      context.dimension        = 2;
      context.number_of_points = coordinates.size() / 2;
      context.coordinates      = coordinates.data();
      context.number_of_dof    = n_nodes;
      context.span_offsets     = span_ends.data();
      context.spans            = spans.data();
      context.group_index      = nullptr;
      context.builder          = builder;
      tree                     = hmat_create_cluster_tree_generic(&context);
      hmat_delete_cluster_tree_builder(builder);
      hmat_delete_clustering(clustering);
      hmat_delete_clustering(median);
      AssertThrow(tree != nullptr,
                  ExcMessage("Foundation operator/Storage = hierarchical: "
                             "hmat-oss could not build the cluster tree."));
    }
    {
      const int *indices = hmat_cluster_get_indices(tree);
      hmat_to_node.assign(indices, indices + n_nodes);
      std::vector<bool> seen(n_nodes, false);
      for (const unsigned int node : hmat_to_node)
        {
          AssertThrow(node < n_nodes && !seen[node],
                      ExcMessage("HierarchicalFlexibility: the cluster tree's "
                                 "numbering is not a permutation."));
          seen[node] = true;
        }
    }

    hmat_admissibility_param_t admissibility_parameters;
    hmat_init_admissibility_param(&admissibility_parameters);
    admissibility_parameters.eta = settings.eta;
    hmat_admissibility_t *admissibility =
      hmat_create_admissibility(&admissibility_parameters);
    matrix = hmat().create_empty_hmatrix_admissibility(tree,
                                                       tree,
                                                       /*lower_symmetric=*/1,
                                                       admissibility);
    hmat_delete_admissibility(admissibility);
    AssertThrow(matrix != nullptr,
                ExcMessage("Foundation operator/Storage = hierarchical: "
                           "hmat-oss could not create the H-matrix."));
    // Without this, hmat-oss recompresses at its default 1e-4 whatever the
    // assembly tolerance.
    hmat().set_low_rank_epsilon(matrix, settings.tolerance);

    AssemblyContext         context{&entries, ""};
    hmat_assemble_context_t assembly;
    hmat_assemble_context_init(&assembly);
    hmat_compression_algorithm_t *compression =
      hmat_create_compression_aca_plus(settings.tolerance);
    assembly.compression     = compression;
    assembly.user_context    = &context;
    assembly.prepare         = prepare_block;
    assembly.block_compute   = compute_block_callback;
    assembly.lower_symmetric = 1;
    assembly.factorization   = hmat_factorization_none;
    assembly.progress        = nullptr; // no progress bar on stdout
    int status;
    timer.restart();
    {
      const SingleThreadedBlas single_threaded_blas;
      status = hmat().assemble_generic(matrix, &assembly);
    }
    // ACA+ interleaves the entries it asks for with its own algebra: what
    // the callbacks did not spend is the compression's.
    times.integration += context.integration_time;
    times.compression = timer.wall_time() - context.integration_time;
    hmat_delete_compression(compression);
    AssertThrow(context.error.empty(),
                ExcMessage("Foundation operator/Storage = hierarchical: "
                           "integrating the flexibility failed: " +
                           context.error));
    check_hmat(status, "the assembly of the flexibility");

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
    const unsigned int        n_samples = std::min<unsigned int>(n_nodes, 4);
    std::vector<unsigned int> all_nodes(n_nodes);
    for (unsigned int j = 0; j < n_nodes; ++j)
      all_nodes[j] = j;
    const std::vector<unsigned int> all_cells =
      entries.cells_touching(all_nodes);
    Vector<double> unit(n_nodes), row(n_nodes);
    for (unsigned int s = 0; s < n_samples; ++s)
      {
        const unsigned int  i = (2 * s + 1) * n_nodes / (2 * n_samples);
        std::vector<double> exact(n_nodes, 0.);
        entries.add_entries(
          entries.cells_containing(i),
          all_cells,
          [i](const unsigned int node) { return node == i ? 0 : -1; },
          [](const unsigned int node) { return int(node); },
          1,
          n_nodes,
          exact.data());
        unit    = 0.;
        unit[i] = 1.;
        vmult(row, unit); // A symmetric: row i = column i
        std::vector<double> difference(n_nodes);
        for (unsigned int j = 0; j < n_nodes; ++j)
          difference[j] = row[j] - exact[j];
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

  void
  HierarchicalFlexibility::to_hmat_order(const double *natural,
                                         double       *ordered) const
  {
    for (unsigned int k = 0; k < n_nodes; ++k)
      ordered[k] = natural[hmat_to_node[k]];
  }

  void
  HierarchicalFlexibility::to_natural_order(const double *ordered,
                                            double       *natural) const
  {
    for (unsigned int k = 0; k < n_nodes; ++k)
      natural[hmat_to_node[k]] = ordered[k];
  }

  void
  HierarchicalFlexibility::vmult(Vector<double>       &dst,
                                 const Vector<double> &src) const
  {
    AssertThrow(matrix != nullptr,
                ExcMessage("HierarchicalFlexibility::vmult before build()."));
    AssertDimension(src.size(), n_nodes);
    std::vector<double> x(n_nodes), y(n_nodes, 0.);
    to_hmat_order(src.data(), x.data());
    const double             one = 1., zero = 0.;
    const SingleThreadedBlas single_threaded_blas;
    check_hmat(hmat().gemm_dense(
                 'N', 'N', 'L', &one, matrix, x.data(), &zero, y.data(), 1),
               "the product with the flexibility");
    AssertThrow(all_finite(y.data(), n_nodes),
                ExcMessage("Foundation operator/Tolerance: the product with "
                           "the compressed flexibility is not finite." +
                           tolerance_advice));
    dst.reinit(n_nodes);
    to_natural_order(y.data(), dst.data());
  }

  void
  HierarchicalFlexibility::factorize()
  {
    AssertThrow(matrix != nullptr,
                ExcMessage("HierarchicalFlexibility::factorize before "
                           "build()."));
    const Timer timer;
    if (factor != nullptr)
      hmat().destroy(factor);
    // hmat-oss factorises in place; the product keeps the original.
    factor = hmat().copy(matrix);
    AssertThrow(factor != nullptr,
                ExcMessage("Foundation operator/Storage = hierarchical: "
                           "hmat-oss could not copy the H-matrix."));
    // The factor only preconditions conjugate gradients, whose answer
    // does not depend on it: recompress it more coarsely than A (first the
    // copy, then every update of the factorisation). At n = 4961 a factor
    // at 1e-3 instead of 1e-6 took a quarter of the time and the same CG
    // iterations (388 against 389, benchmarks/hierarchical_scaling.py).
    const double factor_tolerance =
      std::max(settings.tolerance, settings.factor_tolerance);
    hmat().set_low_rank_epsilon(factor, factor_tolerance);
    if (factor_tolerance > settings.tolerance)
      check_hmat(hmat().truncate(factor),
                 "the recompression of the copy to factorise");
    hmat_factorization_context_t context;
    hmat_factorization_context_init(&context);
    context.factorization = hmat_factorization_llt;
    context.progress      = nullptr;
    int status;
    {
      const SingleThreadedBlas single_threaded_blas;
      status = hmat().factorize_generic(factor, &context);
    }
    if (status != 0)
      {
        hmat().destroy(factor);
        factor = nullptr;
        AssertThrow(false,
                    ExcMessage("Foundation operator/Tolerance: the H-Cholesky "
                               "factorisation of the compressed flexibility "
                               "failed (hmat-oss status " +
                               std::to_string(status) +
                               "): at this tolerance the compressed matrix "
                               "is not positive definite." +
                               tolerance_advice));
      }

    // Check the factor on a known vector: a smooth pressure plus a
    // node-to-node oscillation, so that both ends of the spectrum count.
    Vector<double> x(n_nodes), b(n_nodes), solution(n_nodes), residual;
    for (unsigned int i = 0; i < n_nodes; ++i)
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
        AssertThrow(false,
                    ExcMessage("Foundation operator/Tolerance: the H-Cholesky "
                               "factor of the compressed flexibility solves "
                               "a test system only to a relative residual "
                               "of " +
                               measured.str() + "." + tolerance_advice));
      }
    times.factorization = timer.wall_time();
  }

  void
  HierarchicalFlexibility::solve(Vector<double>       &dst,
                                 const Vector<double> &src) const
  {
    AssertDimension(src.size(), n_nodes);
    FullMatrix<double> rhs(n_nodes, 1);
    for (unsigned int i = 0; i < n_nodes; ++i)
      rhs(i, 0) = src[i];
    solve(rhs);
    dst.reinit(n_nodes);
    for (unsigned int i = 0; i < n_nodes; ++i)
      dst[i] = rhs(i, 0);
  }

  void
  HierarchicalFlexibility::solve(FullMatrix<double> &rhs) const
  {
    AssertThrow(factor != nullptr,
                ExcMessage("HierarchicalFlexibility::solve before "
                           "factorize()."));
    AssertDimension(rhs.m(), n_nodes);
    const unsigned int  n_rhs = rhs.n();
    std::vector<double> ordered(std::size_t(n_nodes) * n_rhs);
    // column-major, hmat order
    for (unsigned int c = 0; c < n_rhs; ++c)
      for (unsigned int k = 0; k < n_nodes; ++k)
        ordered[k + std::size_t(c) * n_nodes] = rhs(hmat_to_node[k], c);
    const SingleThreadedBlas single_threaded_blas;
    check_hmat(hmat().solve_dense(factor, ordered.data(), n_rhs),
               "the solve with the H-Cholesky factor");
    AssertThrow(all_finite(ordered.data(), ordered.size()),
                ExcMessage("Foundation operator/Tolerance: the solve with "
                           "the H-Cholesky factor is not finite." +
                           tolerance_advice));
    for (unsigned int c = 0; c < n_rhs; ++c)
      for (unsigned int k = 0; k < n_nodes; ++k)
        rhs(hmat_to_node[k], c) = ordered[k + std::size_t(c) * n_nodes];
  }

  namespace
  {
    hmat_info_t
    info_of(hmat_matrix_struct *m)
    {
      hmat_info_t info;
      check_hmat(hmat().get_info(m, &info), "reading the H-matrix statistics");
      return info;
    }
  } // namespace

  std::size_t
  HierarchicalFlexibility::memory_consumption() const
  {
    std::size_t bytes = hmat_to_node.capacity() * sizeof(unsigned int);
    if (matrix != nullptr)
      bytes += info_of(matrix).compressed_size * sizeof(double);
    if (factor != nullptr)
      bytes += info_of(factor).compressed_size * sizeof(double);
    return bytes;
  }

  double
  HierarchicalFlexibility::compression_ratio() const
  {
    if (matrix == nullptr)
      return 0;
    return double(info_of(matrix).compressed_size) /
           (double(n_nodes) * double(n_nodes));
  }

  std::size_t
  HierarchicalFlexibility::n_low_rank_blocks() const
  {
    return matrix == nullptr ? 0 : info_of(matrix).rk_count;
  }

  std::size_t
  HierarchicalFlexibility::n_full_blocks() const
  {
    return matrix == nullptr ? 0 : info_of(matrix).full_count;
  }
} // namespace PlateOnHalfspace
