#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/thread_management.h>

#include <plate_on_halfspace/base/interruption.h>
#include <plate_on_halfspace/base/progress.h>
#include <plate_on_halfspace/base/tasks.h>
#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>
#include <plate_on_halfspace/halfspace/cell_pair_summation.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <iterator>
#include <map>
#include <memory>
#include <utility>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * Below this many pairs a request is integrated in the calling thread,
     * and a run of add_entries() has at least this many: the tasks and
     * buffers would cost more than they save (a separated pair takes a
     * microsecond or two).
     */
    constexpr std::size_t parallel_threshold = 64;

    /**
     * Pairs per thread and round of integrate_in_rounds(): the blocks of
     * two rounds are kept until they are summed in order (2 x 256 pairs x
     * 4 images x 9 x 9 doubles per thread, about 1.3 MB), and a round
     * costs one spawn and join of the tasks.
     */
    constexpr std::size_t pairs_per_task = 256;
  } // namespace

  CellPairSummation::CellPairSummation(
    const std::vector<FoundationSpace::Cell> &cells,
    const unsigned int                        n_copies,
    const unsigned int                        n_nodes,
    const SurfaceKernel                      &kernel,
    const unsigned int                        singular_order,
    const std::vector<bool>                  &cell_in_foundation)
    : n_computed(n_copies == 0 ? 0 : cells.size() / n_copies)
    , copies(n_copies)
    , kernel(kernel)
    , cells_of_node(n_nodes)
  {
    AssertThrow(n_copies > 0 && n_computed * n_copies == cells.size(),
                ExcMessage("CellPairSummation: the cell list must hold the "
                           "computed cells and their mirror images (n_copies "
                           "times as many)."));
    AssertThrow(cell_in_foundation.empty() ||
                  cell_in_foundation.size() == n_computed,
                ExcMessage("CellPairSummation: one foundation flag per "
                           "computed cell."));
    in_foundation = cell_in_foundation.empty() ?
                      std::vector<bool>(n_computed, true) :
                      cell_in_foundation;

    integrator =
      std::make_unique<const CellPairIntegrator>(cells, singular_order);
    cell_nodes.resize(cells.size());
    for (unsigned int c = 0; c < cells.size(); ++c)
      cell_nodes[c] = &integrator->nodes(c);
    for (unsigned int c = 0; c < n_computed; ++c)
      for (const unsigned int node : integrator->nodes(c))
        {
          AssertThrow(node < n_nodes,
                      ExcMessage("CellPairSummation: a cell refers to a "
                                 "node beyond the node list."));
          cells_of_node[node].push_back(c);
        }
    integrate_singular_terms(cells);
  }

  CellPairSummation::~CellPairSummation() = default;

  std::vector<FoundationSpace::Cell>
  CellPairSummation::cells_with_images(const FoundationSpace &space)
  {
    std::vector<FoundationSpace::Cell> cells  = space.cells;
    const auto                         images = space.mirror_image_cells();
    cells.insert(cells.end(), images.begin(), images.end());
    return cells;
  }

  std::vector<std::pair<unsigned int, unsigned int>>
  CellPairSummation::canonical_pairs_within(
    const std::vector<Point<2>>                           &centres,
    const unsigned int                                     n_computed,
    const double                                           width,
    const std::function<bool(unsigned int, unsigned int)> &keep)
  {
    const auto bucket = [&](const Point<2> &p) {
      return std::make_pair(static_cast<long long>(std::floor(p[0] / width)),
                            static_cast<long long>(std::floor(p[1] / width)));
    };
    std::map<std::pair<long long, long long>, std::vector<unsigned int>>
      buckets;
    for (unsigned int c = 0; c < centres.size(); ++c)
      buckets[bucket(centres[c])].push_back(c);

    std::vector<std::pair<unsigned int, unsigned int>> pairs, candidates;
    for (unsigned int first = 0; first < n_computed; ++first)
      {
        candidates.clear();
        const auto home = bucket(centres[first]);
        for (long long dx = -1; dx <= 1; ++dx)
          for (long long dy = -1; dy <= 1; ++dy)
            {
              const auto found =
                buckets.find({home.first + dx, home.second + dy});
              if (found == buckets.end())
                continue;
              for (const unsigned int l : found->second)
                {
                  const unsigned int other = l % n_computed, r = l / n_computed;
                  if (other >= first && keep(first, l))
                    candidates.emplace_back(other, r);
                }
            }
        std::sort(candidates.begin(), candidates.end());
        for (const auto &[other, r] : candidates)
          pairs.emplace_back(first, r * n_computed + other);
      }
    return pairs;
  }

  std::vector<CellPairSummation::Pair>
  CellPairSummation::pairs_touching(
    const std::vector<unsigned int> &row_nodes,
    const std::vector<unsigned int> &column_nodes) const
  {
    // The cells of the rows (flag 1) and of the columns (flag 2), each
    // once, sorted.
    if (cell_flags.size() != n_computed)
      cell_flags.assign(n_computed, 0);
    std::vector<unsigned int> row_cells, column_cells;
    const auto collect = [&](const std::vector<unsigned int> &nodes,
                             const char                       flag,
                             std::vector<unsigned int>       &cells) {
      for (const unsigned int node : nodes)
        for (const unsigned int c : cells_of_node[node])
          if ((cell_flags[c] & flag) == 0)
            {
              cell_flags[c] |= flag;
              cells.push_back(c);
            }
      std::sort(cells.begin(), cells.end());
    };
    collect(row_nodes, 1, row_cells);
    collect(column_nodes, 2, column_cells);

    // Entry (i, j) gathers the pairs (K, L) with i in K and j in L; the
    // term of K > L is the pair (L, K) transposed. In canonical order:
    // for each first, the others >= first that pair with it (cells of the
    // columns if first is a row cell, cells of the rows if it is a column
    // cell, merged if both).
    std::vector<unsigned int> firsts;
    firsts.reserve(row_cells.size() + column_cells.size());
    std::set_union(row_cells.begin(),
                   row_cells.end(),
                   column_cells.begin(),
                   column_cells.end(),
                   std::back_inserter(firsts));
    std::vector<Pair> pairs;
    pairs.reserve(row_cells.size() * column_cells.size());
    const auto add = [&](const unsigned int first, const unsigned int other) {
      if (contributes(first, other))
        pairs.push_back({first, other});
    };
    for (const unsigned int first : firsts)
      {
        const auto rows_from =
          std::lower_bound(row_cells.begin(), row_cells.end(), first);
        const auto columns_from =
          std::lower_bound(column_cells.begin(), column_cells.end(), first);
        switch (cell_flags[first])
          {
            case 1: // a row cell: the column cells from first on
              for (auto c = columns_from; c != column_cells.end(); ++c)
                add(first, *c);
              break;
            case 2: // a column cell: the row cells from first on
              for (auto c = rows_from; c != row_cells.end(); ++c)
                add(first, *c);
              break;
            default: // both: merged
              {
                auto r = rows_from, c = columns_from;
                while (r != row_cells.end() || c != column_cells.end())
                  if (c == column_cells.end() ||
                      (r != row_cells.end() && *r < *c))
                    add(first, *r++);
                  else if (r == row_cells.end() || *c < *r)
                    add(first, *c++);
                  else
                    {
                      add(first, *r++);
                      ++c;
                    }
              }
          }
      }
    for (const unsigned int c : firsts)
      cell_flags[c] = 0;
    return pairs;
  }

  void
  CellPairSummation::integrate_singular_terms(
    const std::vector<FoundationSpace::Cell> &cells) const
  {
    // Candidates from a grid of buckets twice the largest diameter wide:
    // cells that touch have centres at most two diameters apart, so in
    // neighbouring buckets. The geometric test (rather than shared nodes)
    // also finds cells that meet only at a constrained vertex.
    const unsigned int    n_cells = cells.size();
    std::vector<Point<2>> centres(n_cells);
    double                largest = 0;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        centres[c] = cells[c].geometry.map(Point<2>(0.5, 0.5));
        largest    = std::max(largest, cells[c].geometry.diameter());
      }
    const auto pairs =
      canonical_pairs_within(centres,
                             n_computed,
                             2 * largest,
                             [&](const unsigned int first,
                                 const unsigned int l) {
                               return contributes(first, l % n_computed) &&
                                      integrator->singular_pair(first, l);
                             });
    integrator->integrate_singular_pairs(pairs, kernel.remainder.get());
  }

  bool
  CellPairSummation::term_masks(const TermIndices &indices,
                                std::vector<bool> &rows,
                                std::vector<bool> &columns)
  {
    const bool direct = indices.direct, transposed = indices.transposed;
    if (!direct && !transposed)
      return false;
    rows.resize(indices.row_a.size());
    columns.resize(indices.row_b.size());
    for (unsigned int a = 0; a < rows.size(); ++a)
      rows[a] = (direct && indices.row_a[a] >= 0) ||
                (transposed && indices.column_a[a] >= 0);
    for (unsigned int b = 0; b < columns.size(); ++b)
      columns[b] = (direct && indices.column_b[b] >= 0) ||
                   (transposed && indices.row_b[b] >= 0);
    return true;
  }

  void
  CellPairSummation::integrate_term(const unsigned int       first,
                                    const unsigned int       other,
                                    const unsigned int       r,
                                    FullMatrix<double>      &block,
                                    const std::vector<bool> &rows,
                                    const std::vector<bool> &columns) const
  {
    const unsigned int image = r * n_computed + other;
    // A cell against its own image is symmetrised, so whole.
    const bool               self_image = first == other && r > 0;
    const std::vector<bool> &a_mask = self_image ? std::vector<bool>() : rows;
    const std::vector<bool> &b_mask =
      self_image ? std::vector<bool>() : columns;
    integrator->integrate_kernel(first, image, kernel, block, a_mask, b_mask);
    if (self_image)
      symmetrise_self_image_block(*cell_nodes[first],
                                  *cell_nodes[image],
                                  block);
  }

  void
  CellPairSummation::integrate_in_rounds(const std::vector<Pair> &pairs,
                                         const Consumer          &consume) const
  {
    const std::vector<bool> all; // no masks: every function
    const unsigned int      n_threads = MultithreadInfo::n_threads();
    if (n_threads == 1 || pairs.size() < parallel_threshold)
      {
        FullMatrix<double> block;
        for (const Pair &pair : pairs)
          for (unsigned int r = 0; r < copies; ++r)
            {
              integrate_term(pair.first, pair.other, r, block, all, all);
              consume(pair.first, pair.other, r, block);
            }
        return;
      }

    // Rounds of pairs: tasks integrate the parts of a round into the
    // blocks of one of two slots; while the calling thread hands a round
    // to @p consume in order, the tasks integrate the next one into the
    // other slot.
    const std::size_t round_size =
      std::min(pairs.size(), pairs_per_task * n_threads);
    const std::size_t slot_size = round_size * copies;
    if (round_blocks.size() < 2 * slot_size)
      round_blocks.resize(2 * slot_size);
    struct Round
    {
      std::size_t                     begin = 0, size = 0;
      FullMatrix<double>             *blocks = nullptr;
      Threads::TaskGroup<void>        tasks;
      std::vector<std::exception_ptr> errors;
    };
    std::array<Round, 2> rounds;
    rounds[0].blocks = round_blocks.data();
    rounds[1].blocks = round_blocks.data() + slot_size;

    const auto start = [&](Round &round, const std::size_t begin) {
      round.begin = begin;
      round.size  = std::min(round_size, pairs.size() - begin);
      // More tasks than threads: pairs differ in cost (rules, cached
      // singular pairs), and an idle thread takes the next part.
      const unsigned int n_tasks = std::max<std::size_t>(
        1,
        std::min<std::size_t>(2 * n_threads, round.size / parallel_threshold));
      round.errors.assign(n_tasks, nullptr);
      round.tasks = Threads::TaskGroup<void>();
      for (unsigned int t = 0; t < n_tasks; ++t)
        round.tasks += Threads::new_task([&, t, n_tasks]() {
          // Every task ends normally, so that none still uses this frame
          // when an error unwinds it.
          try
            {
              for (std::size_t p = round.size * t / n_tasks;
                   p < round.size * (t + 1) / n_tasks;
                   ++p)
                for (unsigned int r = 0; r < copies; ++r)
                  integrate_term(pairs[round.begin + p].first,
                                 pairs[round.begin + p].other,
                                 r,
                                 round.blocks[p * copies + r],
                                 all,
                                 all);
            }
          catch (...)
            {
              round.errors[t] = std::current_exception();
            }
        });
    };
    const auto finish = [](Round &round) {
      round.tasks.join_all();
      for (const std::exception_ptr &error : round.errors)
        if (error)
          std::rethrow_exception(error);
    };

    start(rounds[0], 0);
    for (unsigned int k = 0;; ++k)
      {
        Round &current = rounds[k % 2], &next = rounds[(k + 1) % 2];
        finish(current);
        const std::size_t next_begin = current.begin + current.size;
        const bool        more       = next_begin < pairs.size();
        if (more)
          start(next, next_begin);
        try
          {
            for (std::size_t p = 0; p < current.size; ++p)
              for (unsigned int r = 0; r < copies; ++r)
                consume(pairs[current.begin + p].first,
                        pairs[current.begin + p].other,
                        r,
                        current.blocks[p * copies + r]);
          }
        catch (...)
          {
            if (more)
              next.tasks.join_all();
            throw;
          }
        if (!more)
          break;
      }
  }

  void
  CellPairSummation::integrate_all(const Consumer &consume,
                                   ProgressReport *progress) const
  {
    // Batches of many rounds (integrate_in_rounds() overlaps them); the
    // progress moves batch by batch.
    const std::size_t batch_size =
      16 * pairs_per_task * std::max(1u, MultithreadInfo::n_threads());
    std::vector<Pair> batch;
    batch.reserve(batch_size);
    std::uint64_t n_enumerated = 0;
    const auto    flush        = [&]() {
      integrate_in_rounds(batch, consume);
      batch.clear();
      if (progress != nullptr)
        progress->add(n_enumerated);
      n_enumerated = 0;
      // Between batches no task runs: a long assembly of a serial run
      // stops here on SIGINT/SIGTERM (base/interruption.h; the ranks of
      // a parallel run agree at the next collective check instead).
      Interruption::check_if_alone();
    };
    for (unsigned int first = 0; first < n_computed; ++first)
      for (unsigned int other = first; other < n_computed; ++other)
        {
          ++n_enumerated;
          if (!contributes(first, other))
            continue;
          batch.push_back({first, other});
          if (batch.size() == batch_size)
            flush();
        }
    flush();
  }

  void
  CellPairSummation::sum_in_runs(
    const std::size_t n_pairs,
    const std::size_t n_entries,
    double           *out,
    const std::function<void(std::size_t, std::size_t, double *, Workspace &)>
      &sum_run) const
  {
    // Runs of at least 64 pairs, at most 16 of them, and buffers of at
    // most 16 entries per pair (a row of ACA+ touches few of its entries
    // per pair; zeroing and adding long buffers would cost more than the
    // pairs): a function of the request only.
    const std::size_t max_runs = std::max<std::size_t>(
      1,
      std::min<std::size_t>(
        {n_pairs / parallel_threshold,
         16,
         16 * n_pairs / std::max<std::size_t>(n_entries, 1)}));
    const std::size_t run_size = (n_pairs + max_runs - 1) / max_runs;
    const std::size_t n_runs =
      n_pairs == 0 ? 0 : (n_pairs + run_size - 1) / run_size;
    if (n_runs <= 1)
      {
        Workspace work;
        sum_run(0, n_pairs, out, work);
        return;
      }
    // Each run zeroes its own buffer in its task, and tasks add the
    // buffers to parts of out, run by run: every entry is summed in run
    // order, only the entries are shared out.
    const std::unique_ptr<double[]> buffers(new double[n_runs * n_entries]);
    const unsigned int n_threads = std::max(1u, MultithreadInfo::n_threads());
    // pieces of work in at most two tasks per thread
    const auto in_tasks = [n_threads](const std::size_t n_parts,
                                      const auto       &work) {
      const unsigned int n_tasks =
        std::min<std::size_t>(n_parts, 2 * n_threads);
      run_tasks(n_tasks, [&](const unsigned int t) { work(t, n_tasks); });
    };
    in_tasks(n_runs, [&](const unsigned int t, const unsigned int n_tasks) {
      Workspace work;
      for (std::size_t run = t; run < n_runs; run += n_tasks)
        {
          double *const buffer = buffers.get() + run * n_entries;
          std::fill(buffer, buffer + n_entries, 0.);
          sum_run(run * run_size,
                  std::min(n_pairs, (run + 1) * run_size),
                  buffer,
                  work);
        }
    });
    // Parts of out of at least 4096 entries.
    in_tasks(std::max<std::size_t>(1, n_entries / 4096),
             [&](const unsigned int t, const unsigned int n_tasks) {
               const std::size_t begin = n_entries * t / n_tasks,
                                 end   = n_entries * (t + 1) / n_tasks;
               for (std::size_t run = 0; run < n_runs; ++run)
                 {
                   const double *buffer = buffers.get() + run * n_entries;
                   for (std::size_t k = begin; k < end; ++k)
                     out[k] += buffer[k];
                 }
             });
  }
} // namespace PlateOnHalfspace
