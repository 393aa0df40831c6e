#include <deal.II/base/array_view.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_local_storage.h>

#include <boost/container_hash/hash.hpp>

#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>
#include <plate_on_halfspace/halfspace/cell_pair_summation.h>
#include <plate_on_halfspace/halfspace/compressed_settlement.h>
#include <plate_on_halfspace/halfspace/fractional_laplace_inverse.h>
#include <plate_on_halfspace/halfspace/grid_convolution.h>
#include <plate_on_halfspace/halfspace/memory_guard.h>
#include <plate_on_halfspace/halfspace/split_kernel_operator.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <iomanip>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace PlateOnHalfspace
{
  namespace
  {
    /** The median of the cells' sizes, the square roots of their areas:
     *  the split length sigma and the mesh obstacle's reference size. */
    double
    median_cell_size(const std::vector<FoundationSpace::Cell> &cells)
    {
      std::vector<double> sizes;
      sizes.reserve(cells.size());
      for (const auto &cell : cells)
        sizes.push_back(std::sqrt(cell.geometry.area()));
      std::nth_element(sizes.begin(),
                       sizes.begin() + sizes.size() / 2,
                       sizes.end());
      return sizes[sizes.size() / 2];
    }

    /** alpha erf(r / sigma) / r, the smooth far field (value at 0 too). */
    double
    far_kernel(const double alpha, const double sigma, const double r)
    {
      return r > 0 ? alpha * std::erf(r / sigma) / r :
                     alpha * 2. / (sigma * std::sqrt(M_PI));
    }

    /**
     * -alpha erf(r / sigma) / r: the remainder that turns the integrator's
     * alpha / r into the near field alpha erfc(r / sigma) / r.
     */
    class MinusFarField : public SmoothRadialFunction
    {
    public:
      MinusFarField(const double alpha, const double sigma)
        : alpha(alpha)
        , sigma(sigma)
      {}

      double
      value(const double r) const override
      {
        return -far_kernel(alpha, sigma, r);
      }

      double
      length_scale() const override
      {
        return sigma;
      }

    private:
      const double alpha, sigma;
    };

    /** A term of the near field: computed cell first, cell l (an image). */
    struct Term
    {
      unsigned int first, cell;
    };

    /**
     * The near field's blocks shared by translated pairs. The block of two
     * cells depends only on where their vertices lie relative to each
     * other and on how their shape functions expand into their nodes
     * (the same on cells without hanging nodes): on a uniform mesh, and
     * among the cells of one level of an adaptive one, most pairs repeat
     * an earlier pair's block. A pair takes an earlier
     * one's block when its seven vertices relative to the first cell's
     * first agree with that pair's to 1e-10 of the first cell's diameter;
     * translates agree to rounding. At most @p capacity blocks are kept
     * (a Gmsh mesh has few translates).
     */
    class TranslatedPairs
    {
    public:
      TranslatedPairs(const std::vector<FoundationSpace::Cell> &cells,
                      const std::size_t                         capacity)
        : cells(cells)
        , capacity(capacity)
      {
        // each cell's expansion as positions in its node list and weights:
        // cells with equal ones have the same node shape functions
        std::map<std::vector<std::pair<unsigned int, double>>, unsigned int>
          kinds;
        expansion_kind.reserve(cells.size());
        for (const FoundationSpace::Cell &cell : cells)
          {
            const std::vector<unsigned int>              nodes = cell.nodes();
            std::vector<std::pair<unsigned int, double>> form;
            for (const auto &terms : cell.expansion)
              {
                for (const auto &[node, weight] : terms)
                  form.emplace_back(
                    std::find(nodes.begin(), nodes.end(), node) - nodes.begin(),
                    weight);
                form.emplace_back(numbers::invalid_unsigned_int, 0.);
              }
            expansion_kind.push_back(
              kinds.emplace(std::move(form), kinds.size()).first->second);
          }
      }

      /**
       * The block that pair (@p k, @p l) shares with its translates, and
       * whether this pair is the first of them (which integrates it);
       * {nullptr, true} where the pair's block is its own.
       */
      std::pair<FullMatrix<double> *, bool>
      find_or_add(const unsigned int k, const unsigned int l)
      {
        const auto &first     = cells[k].geometry.get_vertices(),
                   &second    = cells[l].geometry.get_vertices();
        const Point<2> origin = first[0];
        Offsets        offsets;
        for (unsigned int v = 1; v < 4; ++v)
          for (unsigned int d = 0; d < 2; ++d)
            offsets[2 * (v - 1) + d] = first[v][d] - origin[d];
        for (unsigned int v = 0; v < 4; ++v)
          for (unsigned int d = 0; d < 2; ++d)
            offsets[6 + 2 * v + d] = second[v][d] - origin[d];
        const double diameter = cells[k].geometry.diameter();
        // keys in units of 2^-24 of the diameter's power of two, which
        // the key holds too: different scales never share a key
        const int    exponent = std::ilogb(diameter);
        const double unit     = std::ldexp(1., exponent - 24);
        Key          key;
        for (unsigned int i = 0; i < offsets.size(); ++i)
          key[i] = std::llround(offsets[i] / unit);
        key[14]        = exponent;
        key[15]        = expansion_kind[k];
        key[16]        = expansion_kind[l];
        const auto hit = index.find(key);
        if (hit != index.end())
          {
            for (unsigned int i = 0; i < offsets.size(); ++i)
              if (std::abs(offsets[i] - hit->second->offsets[i]) >
                  1e-10 * diameter)
                return {nullptr, true};
            return {&hit->second->block, false};
          }
        if (entries.size() >= capacity)
          return {nullptr, true};
        Entry &entry  = entries.emplace_back();
        entry.offsets = offsets;
        index.emplace(key, &entry);
        return {&entry.block, true};
      }

    private:
      using Offsets = std::array<double, 14>;
      using Key     = std::array<long long, 17>;
      struct Entry
      {
        Offsets            offsets;
        FullMatrix<double> block;
      };
      const std::vector<FoundationSpace::Cell>          &cells;
      const std::size_t                                  capacity;
      std::vector<unsigned int>                          expansion_kind;
      std::unordered_map<Key, Entry *, boost::hash<Key>> index;
      std::deque<Entry>                                  entries;
    };

    /** One term's block added to the rows of @p cell's nodes: the block
     *  itself (the term's first cell) or its transpose (its other cell). */
    struct Addition
    {
      unsigned int cell;
      std::size_t  term;
      bool         transposed;
    };

    /** A row of the near field being summed: values by column, and which
     *  columns the row has touched. */
    struct ScratchRow
    {
      std::vector<double>       values;
      std::vector<unsigned int> stamp;
      unsigned int              current = 0;

      void
      resize(const unsigned int n)
      {
        if (values.size() != n)
          {
            values.assign(n, 0.);
            stamp.assign(n, 0);
            current = 0;
          }
      }

      void
      start_row()
      {
        ++current;
      }

      void
      add(const unsigned int column, const double value)
      {
        if (stamp[column] != current)
          {
            stamp[column]  = current;
            values[column] = value;
          }
        else
          values[column] += value;
      }

      bool
      touched(const unsigned int column) const
      {
        return stamp[column] == current;
      }
    };

    /**
     * The near field's pattern, its upper triangle (the near field is
     * symmetric; symmetric_near_product() multiplies by it): row i holds
     * the nodes j >= i of every cell paired (a term, either way round)
     * with a cell that has node i, which are the entries the terms' blocks
     * add.
     */
    class NearFieldGraph
    {
    public:
      NearFieldGraph(const CellPairIntegrator &integrator,
                     const unsigned int        n_cells,
                     const std::vector<Term>  &terms,
                     const unsigned int        n_nodes)
        : integrator(integrator)
        , partners(n_cells)
        , node_cells(n_nodes)
      {
        for (const Term &t : terms)
          {
            partners[t.first].push_back(t.cell);
            if (t.cell != t.first)
              partners[t.cell].push_back(t.first);
          }
        for (unsigned int c = 0; c < n_cells; ++c)
          if (!partners[c].empty())
            for (const unsigned int i : integrator.nodes(c))
              node_cells[i].push_back(c);
      }

      /**
       * The upper triangle's entries, counted on every k-th row (k such
       * that about 4096 rows are counted) and scaled: the blocks the terms
       * add overlap (neighbouring cells share nodes), so counting the
       * blocks' entries overestimated the matrix several times over
       * (7 times on a uniform mesh).
       */
      std::size_t
      estimated_entries() const
      {
        const unsigned int        n    = node_cells.size();
        const unsigned int        step = std::max(1u, n / 4096);
        std::vector<unsigned int> taken_by(n, numbers::invalid_unsigned_int);
        std::vector<unsigned int> columns;
        std::size_t               counted = 0, rows = 0;
        for (unsigned int i = 0; i < n; i += step, ++rows)
          {
            columns.clear();
            add_row(i, taken_by, columns);
            counted += columns.size();
          }
        return rows == 0 ? 0 : counted * n / rows;
      }

      /** Builds the pattern in blocks of rows, in parallel. */
      void
      make_pattern(SparsityPattern &sparsity) const
      {
        // Each block's columns in one list: a vector per row held half
        // again as much, in many small blocks that stayed resident.
        const unsigned int n_nodes = node_cells.size();
        const unsigned int grain =
          n_nodes / (4 * MultithreadInfo::n_threads()) + 1;
        const unsigned int n_blocks = (n_nodes + grain - 1) / grain;
        std::vector<std::vector<unsigned int>> block_columns(n_blocks);
        std::vector<std::size_t>               row_end(n_nodes);
        parallel::apply_to_subranges(
          0u,
          n_blocks,
          [&](const unsigned int block_from, const unsigned int block_to) {
            std::vector<unsigned int> taken_by(n_nodes,
                                               numbers::invalid_unsigned_int);
            for (unsigned int b = block_from; b < block_to; ++b)
              {
                std::vector<unsigned int> &columns = block_columns[b];
                for (unsigned int i = b * grain;
                     i < std::min(n_nodes, (b + 1) * grain);
                     ++i)
                  {
                    const std::size_t row_start = columns.size();
                    add_row(i, taken_by, columns);
                    std::sort(columns.begin() + row_start, columns.end());
                    row_end[i] = columns.size();
                  }
                columns.shrink_to_fit();
              }
          },
          1);
        std::vector<ArrayView<const unsigned int>> rows(n_nodes);
        for (unsigned int i = 0; i < n_nodes; ++i)
          {
            const std::vector<unsigned int> &columns = block_columns[i / grain];
            const std::size_t start = i % grain == 0 ? 0 : row_end[i - 1];
            rows[i]                 = make_array_view(columns.data() + start,
                                      columns.data() + row_end[i]);
          }
        sparsity.copy_from(n_nodes, n_nodes, rows.begin(), rows.end());
      }

    private:
      /** Appends row @p i's columns, unsorted; @p taken_by marks the row
       *  that last took each column. */
      void
      add_row(const unsigned int         i,
              std::vector<unsigned int> &taken_by,
              std::vector<unsigned int> &columns) const
      {
        for (const unsigned int c : node_cells[i])
          for (const unsigned int d : partners[c])
            for (const unsigned int j : integrator.nodes(d))
              if (j >= i && taken_by[j] != i)
                {
                  taken_by[j] = i;
                  columns.push_back(j);
                }
      }

      const CellPairIntegrator              &integrator;
      std::vector<std::vector<unsigned int>> partners, node_cells;
    };

    using NearRowBlocks = std::array<unsigned int, 9>;

    /**
     * The rows of @p pattern cut into blocks of about equal entries, for
     * symmetric_near_product(): block b starts after the row at which
     * b / n_blocks of the entries are passed.
     */
    NearRowBlocks
    near_row_blocks(const SparsityPattern &pattern)
    {
      constexpr unsigned int n_blocks = NearRowBlocks().size() - 1;
      const unsigned int     n        = pattern.n_rows();
      const std::size_t      entries  = pattern.n_nonzero_elements();
      NearRowBlocks          first_row;
      first_row[0]         = 0;
      std::size_t  counted = 0;
      unsigned int b       = 1;
      for (unsigned int i = 0; i < n && b < n_blocks; ++i)
        {
          counted += pattern.row_length(i);
          while (b < n_blocks && counted * n_blocks >= b * entries)
            first_row[b++] = i + 1;
        }
      while (b <= n_blocks)
        first_row[b++] = n;
      return first_row;
    }

    /**
     * s += N v for the symmetric N of which @p upper holds the upper
     * triangle, the diagonal included (deal.II stores it first in each
     * row). @p first_row cuts the rows into blocks (near_row_blocks()),
     * the same whatever the threads; each block adds its rows' sums and,
     * into a vector of its own, the transposed entries' contributions,
     * which are summed block after block: the result does not depend on
     * the threads.
     */
    void
    symmetric_near_product(const SparseMatrix<double> &upper,
                           const NearRowBlocks        &first_row,
                           const Vector<double>       &v,
                           Vector<double>             &s)
    {
      constexpr unsigned int n_blocks = NearRowBlocks().size() - 1;
      const unsigned int     n        = upper.m();
      const SparsityPattern &pattern  = upper.get_sparsity_pattern();
      std::array<Vector<double>, n_blocks> transposed;
      parallel::apply_to_subranges(
        0u,
        n_blocks,
        [&](const unsigned int from, const unsigned int to) {
          for (unsigned int block = from; block < to; ++block)
            {
              Vector<double> &t = transposed[block];
              t.reinit(n);
              for (unsigned int i = first_row[block]; i < first_row[block + 1];
                   ++i)
                {
                  // A row's values lie together, its diagonal first, and
                  // are read through a pointer: the matrix's iterators
                  // took four times as long for the same sums
                  // (doc/performance.md).
                  const double      *values = &upper(i, i);
                  const unsigned int length = pattern.row_length(i);
                  Assert(pattern.column_number(i, 0) == i, ExcInternalError());
                  const double vi  = v[i];
                  double       sum = values[0] * vi;
                  for (unsigned int k = 1; k < length; ++k)
                    {
                      const unsigned int j = pattern.column_number(i, k);
                      sum += values[k] * v[j];
                      t[j] += values[k] * vi;
                    }
                  s[i] += sum;
                }
            }
        },
        1);
      for (const Vector<double> &t : transposed)
        s += t;
    }
  } // namespace

  SplitKernelSettings
  split_kernel_settings(const double tolerance)
  {
    // doc/formulation.md, "Split-kernel FFT storage": the cutoff makes the
    // dropped erfc tail a tenth of the tolerance; the spline order and
    // sigma / h bound the gridding error (about (h / sigma)^p), the Gauss
    // points the far field's quadrature on a cell of size sigma.
    SplitKernelSettings settings;
    if (tolerance >= 1e-4)
      settings = {4, 3., 0., 3};
    else if (tolerance >= 1e-5)
      settings = {6, 2.5, 0., 4};
    else if (tolerance >= 1e-6)
      settings = {6, 3., 0., 4};
    else
      settings = {8, 3., 0., 5};
    const double target = 0.1 * tolerance;
    double       low = 0.5, high = 10.;
    for (unsigned int i = 0; i < 60; ++i)
      {
        const double mid                       = 0.5 * (low + high);
        (std::erfc(mid) > target ? low : high) = mid;
      }
    settings.cutoff = high;
    return settings;
  }

  SplitKernelFftOperator::SplitKernelFftOperator(
    std::shared_ptr<const ElasticSoil> soil,
    const double                       tolerance,
    const bool                         soil_inverse_used)
    : elastic(std::move(soil))
    , tolerance(tolerance)
    , soil_inverse_used(soil_inverse_used)
  {
    soil_model = elastic;
  }

  std::string
  split_kernel_mesh_obstacle(const FoundationSpace &space)
  {
    // The measured bound (doc/performance.md, "Which storage auto picks"):
    // the largest cell at most 4 times the median size.
    constexpr double largest_over_median = 4;
    if (space.cells.empty())
      return "";
    double largest = 0;
    for (const auto &cell : space.cells)
      largest = std::max(largest, std::sqrt(cell.geometry.area()));
    const double       median = median_cell_size(space.cells);
    std::ostringstream text;
    text << std::setprecision(3);
    if (largest > largest_over_median * median)
      text << "the largest cell is " << largest / median
           << " times the median size (graded mesh; fft pays up to "
           << largest_over_median << ")";
    return text.str();
  }

  /**
   * The far field's Gauss points of a cell merged into g x g groups
   * (their weights summed, at their mean point) for flexibility_diagonal():
   * g from 2 on cells up to sigma wide to 8 on cells many sigma wide,
   * where erf(r / sigma) / r varies across the cell. The springs need the
   * local flexibility to a factor of a few (contact/
   * pressure_preconditioner.h); all points would cost m^4 kernel values
   * per pair of cells, and holding them all would double the far field's
   * memory beside its GridProjection.
   */
  struct SplitKernelFftOperator::LumpedCell
  {
    std::vector<unsigned int> nodes;
    std::vector<Point<2>>     points;
    /** summed JxW psi_a of group g at [g * nodes + a] */
    std::vector<double> weights;
    Point<2>            centre;
    double              radius = 0;

    LumpedCell() = default;
    LumpedCell(const CellPoints &cp, const double sigma);
  };

  SplitKernelFftOperator::LumpedCell::LumpedCell(const CellPoints &cp,
                                                 const double      sigma)
    : nodes(cp.nodes)
  {
    const unsigned int n_nodes_c = cp.nodes.size();
    if (cp.points.empty())
      return; // not tabulated on this rank
    // QGauss<2> is the tensor rule, x fastest (point i + m j)
    const auto m = static_cast<unsigned int>(
      std::lround(std::sqrt(double(cp.points.size()))));
    double extent = 0;
    for (const Point<2> &p : cp.points)
      extent = std::max(extent, p.distance(cp.points[0]));
    const unsigned int g =
      std::min({m,
                8u,
                std::max(2u,
                         static_cast<unsigned int>(
                           std::ceil(2. * extent / (std::sqrt(2.) * sigma))))});
    points.assign(g * g, Point<2>());
    weights.assign(g * g * n_nodes_c, 0.);
    std::vector<unsigned int> count(g * g, 0);
    for (unsigned int j = 0; j < m; ++j)
      for (unsigned int i = 0; i < m; ++i)
        {
          const unsigned int q = i + m * j, group = i * g / m + g * (j * g / m);
          points[group] += cp.points[q];
          ++count[group];
          for (unsigned int a = 0; a < n_nodes_c; ++a)
            weights[group * n_nodes_c + a] +=
              cp.weighted_values[q * n_nodes_c + a];
        }
    for (unsigned int group = 0; group < g * g; ++group)
      {
        points[group] /= count[group];
        centre += points[group] / (g * g);
      }
    for (const Point<2> &p : cp.points)
      radius = std::max(radius, p.distance(centre));
  }

  SplitKernelFftOperator::~SplitKernelFftOperator() = default;

  void
  SplitKernelFftOperator::build(const FoundationSpace   &space,
                                const std::vector<bool> &cell_in_foundation)
  {
    AssertThrow(std::find(cell_in_foundation.begin(),
                          cell_in_foundation.end(),
                          false) == cell_in_foundation.end(),
                ExcMessage("Foundation operator/Storage = fft does not "
                           "support Contact/Method = element exclusion "
                           "(use active set)."));
    // a previous cycle's gridding, freed before this one's memory check
    projection.reset();
    build_mass_matrix(space, cell_in_foundation);
    set_pressure_basis(space, true);
    space.assemble_laplace_matrix(mass_sparsity, laplace);
    plate_area = space.area() * space.symmetry.n_copies();
    inverse_analysis.reset();
    const SurfaceKernel kernel = elastic->kernel(maximal_distance(space));
    AssertThrow(!kernel.remainder,
                ExcMessage("Foundation operator/Storage = fft holds the "
                           "homogeneous half-space only; Foundation/Model = " +
                           elastic->name() + " needs dense or hierarchical."));
    alpha = kernel.alpha;

    const std::vector<FoundationSpace::Cell> cells =
      CellPairSummation::cells_with_images(space);
    n_computed                 = space.cells.size();
    const unsigned int n_cells = cells.size();
    // On several processes a rank takes the cells whose first node it
    // owns: their near pairs, far-field charges and tests (the header).
    communicator     = space.communicator;
    const bool split = n_ranks(communicator) > 1;
    own_node.assign(space.n_nodes(), true);
    if (split)
      for (unsigned int j = 0; j < space.n_nodes(); ++j)
        own_node[j] = space.owned_nodes.is_element(j);
    own_cell.assign(n_computed, true);
    if (split)
      for (unsigned int c = 0; c < n_computed; ++c)
        {
          const std::vector<unsigned int> nodes = space.cells[c].nodes();
          own_cell[c] = !nodes.empty() && own_node[nodes[0]];
        }

    // The split length: the median cell size, so that most cells meet
    // their near field within a few neighbours; the grid no finer than 64
    // nodes per cell on average; and no shorter than a 16th of the largest
    // cell, whose touching pairs integrate erf(r / sigma) / r with
    // (3 H / sigma)^2 points per cell (CellPairIntegrator::integrate_smooth).
    const SplitKernelSettings settings = split_kernel_settings(tolerance);
    std::vector<Point<2>>     centres(n_cells);
    std::vector<double>       diameters(n_cells);
    Point<2>                  low(std::numeric_limits<double>::max(),
                 std::numeric_limits<double>::max());
    Point<2>                  high = -low;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        centres[c]   = cells[c].geometry.map(Point<2>(0.5, 0.5));
        diameters[c] = cells[c].geometry.diameter();
        for (const Point<2> &v : cells[c].geometry.get_vertices())
          for (unsigned int d = 0; d < 2; ++d)
            {
              low[d]  = std::min(low[d], v[d]);
              high[d] = std::max(high[d], v[d]);
            }
      }
    double       sigma = median_cell_size(space.cells);
    const double area  = (high[0] - low[0]) * (high[1] - low[1]);
    const double largest =
      *std::max_element(diameters.begin(), diameters.end());
    sigma                = std::max({sigma,
                                     settings.sigma_over_h * std::sqrt(area / (64. * n_cells)),
                                     largest / 16.});
    const double spacing = sigma / settings.sigma_over_h;
    const double cutoff  = settings.cutoff * sigma;

    // The near field's terms, in CellPairSummation's canonical order
    // (first, other, image), from buckets as wide as the reach of a pair.
    std::vector<Term> terms;
    for (const auto &[first, l] : CellPairSummation::canonical_pairs_within(
           centres,
           n_computed,
           cutoff + largest,
           [&](const unsigned int first, const unsigned int l) {
             return centres[first].distance(centres[l]) -
                      0.5 * (diameters[first] + diameters[l]) <
                    cutoff;
           }))
      if (own_cell[first])
        terms.push_back({first, l});
    // Only the computed cells and the images that the terms meet (next to
    // the mirror planes) need the integrator's nodes and expansions.
    std::vector<bool> met(n_cells, false);
    std::fill(met.begin(), met.begin() + n_computed, true);
    for (const Term &t : terms)
      met[t.cell] = true;
    const CellPairIntegrator                           integrator(cells,
                                        elastic->singular_quadrature_order(),
                                        met);
    std::vector<std::pair<unsigned int, unsigned int>> singular;
    for (const Term &t : terms)
      if (integrator.singular_pair(t.first, t.cell))
        singular.emplace_back(t.first, t.cell);

    // The far field: Gauss points on every cell, more on cells larger
    // than sigma (its quadrature error grows with size / sigma). On
    // several processes only on the cells a rank spreads and tests, and
    // on those that flexibility_diagonal() needs for its own nodes' basis
    // functions.
    std::vector<bool> tabulated(own_cell);
    if (split)
      {
        std::vector<bool> near_own(own_node);
        if (positive_basis)
          for (unsigned int j = 0; j < transform.m(); ++j)
            for (auto t = transform.begin(j); t != transform.end(j); ++t)
              if (own_node[t->column()])
                near_own[j] = true;
        for (unsigned int c = 0; c < n_computed; ++c)
          for (const unsigned int j : integrator.nodes(c))
            tabulated[c] = tabulated[c] || near_own[j];
      }
    std::vector<unsigned int>         points_1d(n_computed);
    std::map<unsigned int, QGauss<2>> rules;
    for (unsigned int c = 0; c < n_computed; ++c)
      {
        const double ratio = diameters[c] / (std::sqrt(2.) * sigma);
        points_1d[c] =
          std::min(64u,
                   std::max(settings.gauss_points,
                            static_cast<unsigned int>(std::ceil(
                              settings.gauss_points * ratio - 1e-9))));
        rules.try_emplace(points_1d[c], points_1d[c]);
      }
    const auto tabulate = [&](const unsigned int c, CellPoints &cp) {
      cp.nodes = integrator.nodes(c);
      integrator.tabulate(c,
                          rules.at(points_1d[c]),
                          cp.points,
                          cp.weighted_values);
    };
    std::size_t n_points = 0;
    for (unsigned int c = 0; c < n_computed; ++c)
      if (own_cell[c])
        n_points += points_1d[c] * points_1d[c];
    // flexibility_diagonal()'s lumped points
    lumped_cells.assign(n_computed, LumpedCell());
    parallel::apply_to_subranges(
      0u,
      n_computed,
      [&](const unsigned int from, const unsigned int to) {
        CellPoints cp;
        for (unsigned int c = from; c < to; ++c)
          if (tabulated[c])
            {
              tabulate(c, cp);
              lumped_cells[c] = LumpedCell(cp, sigma);
            }
          else
            lumped_cells[c].nodes = integrator.nodes(c);
      },
      256);
    // The grid is symmetric about its centre: on the mirror planes, so
    // that the images' charges are the reflected grid charges.
    Point<2> centre = 0.5 * (low + high);
    if (space.symmetry.x)
      centre[0] = 0.;
    if (space.symmetry.y)
      centre[1] = 0.;
    reflections = space.symmetry.reflections();
    grid        = std::make_unique<GridConvolution>(
      centre,
      spacing,
      std::array<double, 2>{
               {std::max(high[0] - centre[0], centre[0] - low[0]) + spacing,
                std::max(high[1] - centre[1], centre[1] - low[1]) + spacing}},
      settings.spline_order,
      [a = alpha, sigma](const double r) { return far_kernel(a, sigma, r); },
      std::array<bool, 2>{{space.symmetry.x, space.symmetry.y}},
      communicator);
    // made in place only once whole: it calls back into this function's
    // integrator until assemble()
    auto gridding = std::make_unique<GridProjection>(
      *grid,
      own_cell,
      space.n_nodes(),
      [&](const unsigned int c) -> const std::vector<unsigned int> & {
        return integrator.nodes(c);
      },
      tabulate);

    // The near field's memory before its pattern is made: a strongly
    // graded mesh puts (cutoff / h)^2 cells into the reach of each cell of
    // size h below sigma.
    {
      // The soil inverse's factors share this analysis, and its factor
      // size enters the estimate. Without the soil inverse (plate on
      // springs) there is nothing to analyse. Made this late, an ordering
      // that runs beside the build (the plate's) has usually ended:
      // sparse_cholesky.cc orders one matrix at a time, and this one
      // would wait for it.
      if (soil_inverse_used)
        analyze_inverse_pattern();
      const NearFieldGraph near_graph(integrator,
                                      n_cells,
                                      terms,
                                      space.n_nodes());
      const std::size_t    entries = near_graph.estimated_entries();
      // the upper triangle (diagonal included): a value and a column
      // index, and the column lists the pattern is copied from
      const std::size_t near_bytes =
        entries * (sizeof(double) + 2 * sizeof(unsigned int));
      // The soil inverse: one factor per node of its rule and M's, shared
      // out over the ranks, and the shifted Laplacian.
      const std::size_t inverse_bytes =
        soil_inverse_used ?
          FractionalLaplaceInverse::n_factors_on_a_rank(
            plate_area,
            FractionalLaplaceInverse::largest_eigenvalue_estimate(space),
            n_ranks(communicator)) *
              inverse_analysis->factor_bytes() +
            laplace.memory_consumption() :
          0;
      // On several processes the ranks on one machine share its memory,
      // and all ranks decide alike (Storage = auto falls back on all).
      const std::size_t     far_bytes = gridding->memory_needed();
      const MemoryOnMachine memory =
        memory_on_machine(near_bytes + far_bytes + inverse_bytes, communicator);
      double finest = std::numeric_limits<double>::max();
      for (const auto &cell : space.cells)
        finest = std::min(finest, std::sqrt(cell.geometry.area()));
      if (!memory.fits)
        {
          std::ostringstream text;
          text << std::setprecision(3)
               << "Foundation operator/Storage = fft: the near field needs "
                  "about "
               << near_bytes / 1073741824. << " GiB (" << terms.size()
               << " cell pairs within " << cutoff
               << " of each other), the far field's gridding "
               << far_bytes / 1073741824. << " GiB";
          if (inverse_bytes > 0)
            text << " and the soil inverse's sparse factors "
                 << inverse_bytes / 1073741824.
                 << " GiB (none with Contact/Preconditioner = plate on "
                    "springs)";
          text << machine_shortfall_text(memory) << ' ';
          if (finest < 0.25 * sigma)
            text << "The kernel is split at sigma = " << sigma
                 << ", the median cell size, and the cells down to " << finest
                 << " wide each reach many others: the mesh is too strongly "
                    "graded for one split length. ";
          throw StorageDoesNotFit(
            text.str(),
            "Use Foundation operator/Storage = hierarchical, or reduce the "
            "node count (Discretization/Subdivisions x and y, "
            "Discretization/Initial refinements, Adaptivity/Max cells).");
        }
      near_graph.make_pattern(near_sparsity);
    }
    gridding->assemble();
    // a split grid reads and writes only the nodes this rank's cells reach
    if (grid->split())
      grid->set_footprint(gridding->keep_reached_columns());
    projection                = std::move(gridding);
    const auto near_remainder = std::make_shared<MinusFarField>(alpha, sigma);
    const SurfaceKernel near_kernel(alpha, near_remainder);
    integrator.integrate_singular_pairs(singular, near_remainder.get());

    near_field.reinit(near_sparsity);
    near_row_blocks = PlateOnHalfspace::near_row_blocks(near_sparsity);

    // Integrate in chunks (tasks), then add each chunk to the near field:
    // the sums do not depend on the threads.
    const unsigned int row_grain =
      space.n_nodes() / (4 * MultithreadInfo::n_threads()) + 1;
    // A chunk holds at most own_limit blocks of its own (a translate's
    // block costs none), and at most term_limit terms.
    const std::size_t               own_limit = 16384, term_limit = 262144;
    std::vector<FullMatrix<double>> own_blocks(
      std::min(own_limit, terms.size()));
    // the block each term of the chunk adds, and which the chunk computes
    std::vector<const FullMatrix<double> *>                   blocks;
    std::vector<std::pair<std::size_t, FullMatrix<double> *>> to_integrate;
    std::vector<Addition>                                     additions;
    Threads::ThreadLocalStorage<ScratchRow>                   scratch_rows;
    TranslatedPairs translates(cells, 16384);
    std::size_t     shared = 0;
    // a cell paired with its own mirror image: its block is symmetrised
    const auto own_image = [n_computed = n_computed](const Term &t) {
      return t.first == t.cell % n_computed && t.cell >= n_computed;
    };
    for (std::size_t begin = 0, end = 0; begin < terms.size(); begin = end)
      {
        // Which terms take a translate's block is decided in term order,
        // so the blocks do not depend on the threads.
        to_integrate.clear();
        blocks.clear();
        std::size_t n_own = 0;
        for (end = begin; end < terms.size() && end - begin < term_limit &&
                          n_own < own_limit;
             ++end)
          {
            const Term &t = terms[end];
            // a cell and its own image are symmetrised below; singular
            // pairs have their own rules
            auto [block, first] =
              own_image(t) || integrator.singular_pair(t.first, t.cell) ?
                std::pair<FullMatrix<double> *, bool>{nullptr, true} :
                translates.find_or_add(t.first, t.cell);
            if (block == nullptr)
              block = &own_blocks[n_own++];
            if (first)
              to_integrate.emplace_back(end, block);
            else
              ++shared;
            blocks.push_back(block);
          }
        parallel::apply_to_subranges(
          std::size_t(0),
          to_integrate.size(),
          [&](const std::size_t from, const std::size_t to) {
            const std::vector<bool> all;
            for (std::size_t m = from; m < to; ++m)
              {
                const Term         &t     = terms[to_integrate[m].first];
                FullMatrix<double> &block = *to_integrate[m].second;
                // erfc(r / sigma) / r is 1/r closer than sigma, where a
                // graded mesh's fine cells meet, and erfc(gap / sigma) of
                // it beyond: the rule needs that much less accuracy
                // relative to the near kernel, on cells narrower than
                // about 2 sigma, which it varies over smoothly
                // (doc/formulation.md, "Split-kernel FFT storage", Near
                // field).
                const double wider =
                  std::max(diameters[t.first], diameters[t.cell]);
                const double gap =
                  std::max(0.,
                           centres[t.first].distance(centres[t.cell]) -
                             0.5 * (diameters[t.first] + diameters[t.cell]));
                const double share =
                  wider < 2 * sigma ? std::erfc(gap / sigma) : 1.;
                integrator.integrate_kernel(t.first,
                                            t.cell,
                                            near_kernel,
                                            block,
                                            all,
                                            all,
                                            SurfaceKernel::separated_accuracy /
                                              std::max(share, 1e-300));
                if (own_image(t))
                  symmetrise_self_image_block(integrator.nodes(t.first),
                                              integrator.nodes(t.cell),
                                              block);
              }
          },
          64);
        // The chunk's additions grouped by the cell whose nodes are the
        // rows: each term adds its block to its first cell's nodes and,
        // unless it pairs a cell with its own image, the transposed block
        // to its other cell's. Each group's terms are summed per row in
        // term order into a scratch row, which is added to the row in one
        // walk along it. Rows are split among tasks; the sums do not
        // depend on the threads.
        additions.clear();
        for (std::size_t k = begin; k < end; ++k)
          {
            const Term &t = terms[k];
            additions.push_back({t.first, k, false});
            if (t.first != t.cell % n_computed)
              additions.push_back({t.cell, k, true});
          }
        std::stable_sort(additions.begin(),
                         additions.end(),
                         [](const Addition &x, const Addition &y) {
                           return x.cell < y.cell;
                         });
        parallel::apply_to_subranges(
          0u,
          space.n_nodes(),
          [&](const unsigned int row_from, const unsigned int row_to) {
            ScratchRow &scratch = scratch_rows.get();
            scratch.resize(space.n_nodes());
            for (std::size_t g = 0, g_end = 0; g < additions.size(); g = g_end)
              {
                const unsigned int cell = additions[g].cell;
                for (g_end = g;
                     g_end < additions.size() && additions[g_end].cell == cell;
                     ++g_end)
                  ;
                const auto &rows = integrator.nodes(cell);
                for (unsigned int r = 0; r < rows.size(); ++r)
                  {
                    if (rows[r] < row_from || rows[r] >= row_to)
                      continue;
                    scratch.start_row();
                    for (std::size_t m = g; m < g_end; ++m)
                      {
                        const Addition           &addition = additions[m];
                        const Term               &t = terms[addition.term];
                        const FullMatrix<double> &block =
                          *blocks[addition.term - begin];
                        const auto &columns = integrator.nodes(
                          addition.transposed ? t.first : t.cell);
                        // the lower triangle is not stored
                        for (unsigned int j = 0; j < columns.size(); ++j)
                          if (columns[j] >= rows[r])
                            scratch.add(columns[j],
                                        addition.transposed ? block(j, r) :
                                                              block(r, j));
                      }
                    // the group fills most of the row: walk the row
                    for (auto entry = near_field.begin(rows[r]);
                         entry != near_field.end(rows[r]);
                         ++entry)
                      if (scratch.touched(entry->column()))
                        entry->value() += scratch.values[entry->column()];
                  }
              }
          },
          row_grain);
      }

    chosen.sigma        = sigma;
    chosen.spacing      = spacing;
    chosen.cutoff       = cutoff;
    chosen.spline_order = settings.spline_order;
    chosen.grid_nodes   = grid->n_grid_nodes();
    // each rank holds its own pairs: the pairs and points summed over the
    // ranks, the entries the most one rank holds (the report's)
    chosen.near_entries =
      Utilities::MPI::max(near_sparsity.n_nonzero_elements(), communicator);
    chosen.near_pairs        = Utilities::MPI::sum(terms.size(), communicator);
    chosen.translated_pairs  = Utilities::MPI::sum(shared, communicator);
    chosen.quadrature_points = Utilities::MPI::sum(n_points, communicator);
  }

  void
  SplitKernelFftOperator::apply_far_field(const Vector<double> &values,
                                          Vector<double> &settlement) const
  {
    Vector<double> charges(projection->n_columns()), potentials;
    projection->spread(values, charges);
    // with the other ranks' cells' charges (the grid's slabs sum them) and
    // the mirror images, which carry the same pressure at the reflected
    // points (doc/formulation.md, "Symmetry")
    grid->convolve(charges, potentials);
    projection->add_tests(potentials, settlement);
  }

  void
  SplitKernelFftOperator::apply_to_values(const Vector<double> &values,
                                          Vector<double> &settlement) const
  {
    settlement.reinit(values.size());
    symmetric_near_product(near_field, near_row_blocks, values, settlement);
    apply_far_field(values, settlement);
    // each rank's near pairs and far-field tests (the header)
    sum_shared_entries_over_ranks(make_array_view(settlement), communicator);
  }

  void
  SplitKernelFftOperator::apply(const Vector<double> &q,
                                Vector<double>       &s) const
  {
    apply_in_pressure_basis(
      q, s, [this](const Vector<double> &values, Vector<double> &settlement) {
        apply_to_values(values, settlement);
      });
  }

  std::vector<double>
  SplitKernelFftOperator::settlement_at_points(
    const FoundationSpace       &space,
    const Vector<double>        &nodal_pressure,
    const std::vector<Point<2>> &points) const
  {
    if (!grid_serves(space, points) ||
        double(points.size()) * n_loaded_cells(space, nodal_pressure) <
          grid_settlement_threshold)
      return FoundationOperator::settlement_at_points(space,
                                                      nodal_pressure,
                                                      points);
    return grid_settlement_at_points(space, nodal_pressure, points);
  }

  bool
  SplitKernelFftOperator::grid_serves(const FoundationSpace       &space,
                                      const std::vector<Point<2>> &points) const
  {
    return projection && grid && !grid->split() &&
           std::all_of(space.cells.begin(),
                       space.cells.end(),
                       [this](const FoundationSpace::Cell &cell) {
                         return cell.geometry.diameter() <= 3 * chosen.sigma;
                       }) &&
           std::all_of(points.begin(), points.end(), [this](const Point<2> &x) {
             return grid->covers(x);
           });
  }

  std::vector<double>
  SplitKernelFftOperator::grid_settlement_at_points(
    const FoundationSpace       &space,
    const Vector<double>        &nodal_pressure,
    const std::vector<Point<2>> &points) const
  {
    AssertDimension(nodal_pressure.size(), n_nodes());
    Assert(grid_serves(space, points), ExcInternalError());
    // the near field: alpha / r minus the far field's kernel, within the
    // cutoff beyond which erfc(r / sigma) drops below the tolerance
    std::vector<double> settlement = near_settlement_at_points(
      space,
      nodal_pressure,
      points,
      SurfaceKernel(alpha,
                    std::make_shared<MinusFarField>(alpha, chosen.sigma)),
      elastic->singular_quadrature_order(),
      chosen.cutoff);
    // the far field: the pressure's grid potentials (with the mirror
    // images' charges) read at each point by its B-spline stencil
    Vector<double> charges(projection->n_columns()), potentials;
    projection->spread(nodal_pressure, charges);
    grid->convolve(charges, potentials);
    const unsigned int order = grid->order();
    const unsigned int row   = grid->grid_sizes()[0];
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(points.size()),
      [&](const unsigned int from, const unsigned int to) {
        for (unsigned int p = from; p < to; ++p)
          {
            const GridConvolution::Stencil stencil = grid->stencil(points[p]);
            double                         sum     = 0;
            for (unsigned int l = 0; l < order; ++l)
              {
                const std::size_t first =
                  std::size_t(stencil.first_y + l) * row + stencil.first_x;
                double along_x = 0;
                for (unsigned int k = 0; k < order; ++k)
                  along_x += stencil.x[k] * potentials[first + k];
                sum += stencil.y[l] * along_x;
              }
            settlement[p] += sum;
          }
      },
      256);

    // the check: the direct sum
    const double error =
      sampled_settlement_error(points,
                               settlement,
                               [&](const std::vector<Point<2>> &samples) {
                                 return PlateOnHalfspace::settlement_at_points(
                                   space,
                                   nodal_pressure,
                                   samples,
                                   elastic->kernel(maximal_distance(space)),
                                   elastic->singular_quadrature_order());
                               });
    AssertThrow(std::all_of(settlement.begin(),
                            settlement.end(),
                            [](const double u) { return std::isfinite(u); }) &&
                  error <= std::min(10 * tolerance, 1e-2),
                ExcMessage("Foundation operator/Tolerance: the settlement of "
                           "the goal's estimate through the fft storage's "
                           "grid differs from the exactly integrated one by " +
                           Utilities::to_string(error) +
                           " (relative, sampled points), more than the "
                           "tolerance " +
                           Utilities::to_string(tolerance) +
                           " allows; a smaller Tolerance refines the grid."));
    return settlement;
  }

  Vector<double>
  SplitKernelFftOperator::flexibility_diagonal() const
  {
    const unsigned int n     = n_nodes();
    const double       sigma = chosen.sigma;
    // the far field's A_jj on the lumped rules (LumpedCell)
    // Basis function i as node values: T's column i, or node i itself.
    std::vector<std::vector<std::pair<unsigned int, double>>> columns(n);
    if (positive_basis)
      for (unsigned int j = 0; j < transform.m(); ++j)
        for (auto t = transform.begin(j); t != transform.end(j); ++t)
          columns[t->column()].emplace_back(j, t->value());
    else
      for (unsigned int i = 0; i < n; ++i)
        columns[i] = {{i, 1.}};
    std::vector<std::vector<unsigned int>> cells_of(n);
    for (unsigned int c = 0; c < lumped_cells.size(); ++c)
      for (const unsigned int j : lumped_cells[c].nodes)
        cells_of[j].push_back(c);
    std::vector<std::array<double, 2>> signs = {{{1., 1.}}};
    signs.insert(signs.end(), reflections.begin(), reflections.end());
    Vector<double> diagonal(n);
    parallel::apply_to_subranges(
      0u,
      n,
      [&](const unsigned int from, const unsigned int to) {
        std::vector<unsigned int>        support;
        std::vector<std::vector<double>> weights;
        std::vector<double>              totals;
        for (unsigned int i = from; i < to; ++i)
          {
            // the near part exactly: (T^T N T)_ii
            double sum = 0;
            for (const auto &[j, tj] : columns[i])
              for (const auto &[k, tk] : columns[i])
                sum += tj * tk * near_field.el(std::min(j, k), std::max(j, k));
            // the far part from the rank owning i (its cells are
            // tabulated), the near part from each rank's pairs
            if (!own_node[i])
              {
                diagonal[i] = sum;
                continue;
              }
            // the far part: basis function i's lumped weights per cell
            support.clear();
            for (const auto &column_entry : columns[i])
              for (const unsigned int c : cells_of[column_entry.first])
                support.push_back(c);
            std::sort(support.begin(), support.end());
            support.erase(std::unique(support.begin(), support.end()),
                          support.end());
            weights.assign(support.size(), {});
            totals.assign(support.size(), 0.);
            for (unsigned int s = 0; s < support.size(); ++s)
              {
                const LumpedCell &l = lumped_cells[support[s]];
                weights[s].assign(l.points.size(), 0.);
                for (unsigned int a = 0; a < l.nodes.size(); ++a)
                  for (const auto &[j, tj] : columns[i])
                    if (j == l.nodes[a])
                      for (unsigned int g = 0; g < l.points.size(); ++g)
                        weights[s][g] += tj * l.weights[g * l.nodes.size() + a];
                totals[s] =
                  std::accumulate(weights[s].begin(), weights[s].end(), 0.);
              }
            for (unsigned int s = 0; s < support.size(); ++s)
              for (unsigned int t = 0; t < support.size(); ++t)
                for (const auto &sign : signs)
                  {
                    const LumpedCell &lk = lumped_cells[support[s]],
                                     &ll = lumped_cells[support[t]];
                    // an image beyond the near field's reach as the
                    // cells' total weights at their centres
                    const Point<2> image(sign[0] * ll.centre[0],
                                         sign[1] * ll.centre[1]);
                    if (&sign != &signs[0] &&
                        lk.centre.distance(image) - lk.radius - ll.radius >
                          chosen.cutoff)
                      {
                        sum +=
                          totals[s] * totals[t] *
                          far_kernel(alpha, sigma, lk.centre.distance(image));
                        continue;
                      }
                    for (unsigned int p = 0; p < lk.points.size(); ++p)
                      for (unsigned int r = 0; r < ll.points.size(); ++r)
                        {
                          const Point<2> y(sign[0] * ll.points[r][0],
                                           sign[1] * ll.points[r][1]);
                          sum +=
                            weights[s][p] * weights[t][r] *
                            far_kernel(alpha, sigma, lk.points[p].distance(y));
                        }
                  }
            diagonal[i] = sum;
          }
      },
      256);
    sum_shared_entries_over_ranks(make_array_view(diagonal), communicator);
    return diagonal;
  }

  namespace
  {
    /** An inverse on nodal values in the positive pressure basis:
     *  q = T^{-1} F̃^{-1} T^{-T} s (FoundationOperator::set_pressure_basis()).
     */
    class InverseInPressureBasis : public ApproximateInverse
    {
    public:
      using Map = std::function<void(const Vector<double> &, Vector<double> &)>;

      InverseInPressureBasis(std::unique_ptr<ApproximateInverse> on_values,
                             Map inverse_transpose_transform,
                             Map coefficients_from_values)
        : on_values(std::move(on_values))
        , to_values_test(std::move(inverse_transpose_transform))
        , to_coefficients(std::move(coefficients_from_values))
      {}

      void
      vmult(Vector<double> &q, const Vector<double> &s) const override
      {
        Vector<double> tested(s.size()), values;
        to_values_test(s, tested);
        on_values->vmult(values, tested);
        q.reinit(s.size());
        to_coefficients(values, q);
      }

      std::size_t
      memory_consumption() const override
      {
        return on_values->memory_consumption();
      }

    private:
      const std::unique_ptr<ApproximateInverse> on_values;
      const Map                                 to_values_test, to_coefficients;
    };
  } // namespace

  std::unique_ptr<ApproximateInverse>
  SplitKernelFftOperator::make_approximate_inverse()
  {
    // The fractional Laplacian (halfspace/fractional_laplace_inverse.h):
    // the near field alone misses the far field's long waves, which cost
    // four to six times the CG iterations (doc/performance.md, "With the
    // fractional soil inverse").
    if (!inverse_analysis)
      analyze_inverse_pattern();
    auto on_values = std::make_unique<FractionalLaplaceInverse>(
      mass, laplace, alpha, plate_area, *inverse_analysis, communicator);
    if (!positive_basis)
      return on_values;
    return std::make_unique<InverseInPressureBasis>(
      std::move(on_values),
      [this](const Vector<double> &x, Vector<double> &y) {
        apply_inverse_transpose_transform(x, y);
      },
      [this](const Vector<double> &x, Vector<double> &y) {
        coefficients_from_values(x, y);
      });
  }

  void
  SplitKernelFftOperator::analyze_inverse_pattern()
  {
    inverse_analysis = std::make_unique<SparseCholesky>(
      "the fractional soil inverse's L + (c + t^2) M");
    inverse_analysis->analyze(mass);
  }

  std::string
  SplitKernelFftOperator::build_report() const
  {
    if (!grid)
      return "Foundation operator/Storage = fft: not built";
    std::ostringstream text;
    text << std::setprecision(3) << "Foundation operator/Storage = fft: "
         << "kernel split at sigma = " << chosen.sigma << ", near field of "
         << chosen.near_pairs << " cell pairs within " << chosen.cutoff << " ("
         << chosen.translated_pairs << " of them translates of another; "
         << chosen.near_entries
         << " entries in the upper triangle), far field on "
         << chosen.quadrature_points << " Gauss points and a grid of "
         << chosen.grid_nodes << " nodes (spacing " << chosen.spacing
         << ", B-splines of order " << chosen.spline_order << ", ";
    const std::array<bool, 2> cosine = grid->cosine_transform_directions();
    if (cosine[0] && cosine[1])
      text << "cosine transforms of the quarter ";
    else if (cosine[0] || cosine[1])
      text << "cosine transforms in " << (cosine[0] ? "x" : "y")
           << " and FFT in " << (cosine[0] ? "y" : "x") << " of the half ";
    else
      text << "FFT ";
    text << grid->fft_sizes()[0] << " x " << grid->fft_sizes()[1] << ")";
    if (n_ranks(communicator) > 1)
      text << "; on " << n_ranks(communicator)
           << " processes, each holding the near pairs and far-field "
              "charges of its own cells (the entries: the most any holds) "
              "and a slab of the grid's transforms";
    return text.str();
  }

  std::size_t
  SplitKernelFftOperator::memory_consumption() const
  {
    std::size_t bytes =
      coupling_memory_consumption() + near_field.memory_consumption() +
      near_sparsity.memory_consumption() + laplace.memory_consumption() +
      (inverse_analysis ? inverse_analysis->memory_consumption() : 0) +
      (grid ? grid->memory_consumption() : 0) +
      (projection ? projection->memory_consumption() : 0);
    for (const LumpedCell &l : lumped_cells)
      bytes += l.nodes.size() * sizeof(unsigned int) +
               l.points.size() * sizeof(Point<2>) +
               l.weights.size() * sizeof(double);
    return bytes;
  }
} // namespace PlateOnHalfspace
