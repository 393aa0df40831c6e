#include <plate_on_halfspace/base/nested_dissection.h>

#include <metis.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <new>
#include <numeric>

namespace PlateOnHalfspace
{
  namespace
  {
    /** A symmetric graph in compressed rows. */
    struct Graph
    {
      std::vector<int> start, columns;
    };

    /**
     * The pattern's rows and columns in @p rows, renumbered, each row
     * sorted, the diagonal included. The stored zeros count too: a
     * factor's matrix may drop them, and where a coupling vanishes the
     * rows of one node's unknowns would differ there.
     */
    Graph
    restricted_graph(const SparsityPattern                      &pattern,
                     const std::vector<types::global_dof_index> &rows)
    {
      const int        n = static_cast<int>(rows.size());
      std::vector<int> position(pattern.n_rows(), -1);
      for (int i = 0; i < n; ++i)
        position[rows[i]] = i;
      // counted first: the plate's pattern at 10^6 nodes is 2e8 entries;
      // beyond int's range CHOLMOD's own factor would not fit either
      std::size_t n_entries = 0;
      for (int i = 0; i < n; ++i)
        n_entries += pattern.row_length(rows[i]);
      if (n_entries >= std::size_t(std::numeric_limits<int>::max()))
        throw std::bad_alloc();
      Graph graph;
      graph.start.assign(n + 1, 0);
      graph.columns.reserve(n_entries);
      for (int i = 0; i < n; ++i)
        {
          for (auto entry = pattern.begin(rows[i]);
               entry != pattern.end(rows[i]);
               ++entry)
            if (const int j = position[entry->column()]; j >= 0)
              graph.columns.push_back(j);
          std::sort(graph.columns.begin() + graph.start[i],
                    graph.columns.end());
          graph.start[i + 1] = static_cast<int>(graph.columns.size());
        }
      return graph;
    }

    /**
     * The group of each row of @p graph, rows with equal column lists in
     * one group, numbered in the order of their first row; the number of
     * groups in @p n_groups.
     */
    std::vector<int>
    groups_of_equal_rows(const Graph &graph, int &n_groups)
    {
      const int  n         = static_cast<int>(graph.start.size()) - 1;
      const auto row_begin = [&](const int i) {
        return graph.columns.begin() + graph.start[i];
      };
      std::vector<std::pair<std::uint64_t, int>> keys(n);
      for (int i = 0; i < n; ++i)
        {
          std::uint64_t key = graph.start[i + 1] - graph.start[i];
          for (auto c = row_begin(i); c != row_begin(i + 1); ++c)
            key = key * 1000003u + static_cast<std::uint64_t>(*c);
          keys[i] = {key, i};
        }
      std::sort(keys.begin(), keys.end());
      std::vector<int> group(n, -1), first_row;
      for (int from = 0; from < n;)
        {
          int to = from;
          while (to < n && keys[to].first == keys[from].first)
            ++to;
          // equal keys: equal rows, or rows whose hashes collide
          for (int k = from; k < to; ++k)
            if (const int i = keys[k].second; group[i] < 0)
              {
                group[i] = static_cast<int>(first_row.size());
                first_row.push_back(i);
                for (int l = k + 1; l < to; ++l)
                  if (const int j = keys[l].second;
                      group[j] < 0 && std::equal(row_begin(i),
                                                 row_begin(i + 1),
                                                 row_begin(j),
                                                 row_begin(j + 1)))
                    group[j] = group[i];
              }
          from = to;
        }
      n_groups = static_cast<int>(first_row.size());
      std::vector<int> seen(n_groups, -1);
      for (int i = 0, next = 0; i < n; ++i)
        if (seen[group[i]] < 0)
          seen[group[i]] = next++;
      for (int &g : group)
        g = seen[g];
      return group;
    }

  } // namespace

  std::vector<int>
  nested_dissection(const SparsityPattern                      &pattern,
                    const std::vector<types::global_dof_index> &rows)
  {
    const int          n     = static_cast<int>(rows.size());
    Graph              graph = restricted_graph(pattern, rows);
    int                n_groups;
    const auto         group      = groups_of_equal_rows(graph, n_groups);
    idx_t              n_vertices = n_groups;
    std::vector<int>   first_row(n_groups, -1);
    std::vector<idx_t> weights(n_groups, 0), offsets(n_groups + 1, 0);
    for (int i = n - 1; i >= 0; --i)
      {
        first_row[group[i]] = i;
        ++weights[group[i]];
      }
    std::vector<idx_t> adjacency, added_by(n_groups, -1);
    for (int v = 0; v < n_groups; ++v)
      {
        const int i = first_row[v];
        for (int k = graph.start[i]; k < graph.start[i + 1]; ++k)
          if (const idx_t w = group[graph.columns[k]];
              w != v && added_by[w] != v)
            {
              added_by[w] = v;
              adjacency.push_back(w);
            }
        offsets[v + 1] = static_cast<idx_t>(adjacency.size());
      }
    graph = Graph();
    // METIS needs a symmetric graph; the factors' patterns are (the
    // matrices are symmetric), so this only guards the ordering
    for (idx_t v = 0; v < n_vertices; ++v)
      std::sort(adjacency.begin() + offsets[v],
                adjacency.begin() + offsets[v + 1]);
    for (idx_t v = 0; v < n_vertices; ++v)
      for (idx_t k = offsets[v]; k < offsets[v + 1]; ++k)
        if (const idx_t w = adjacency[k];
            !std::binary_search(adjacency.begin() + offsets[w],
                                adjacency.begin() + offsets[w + 1],
                                v))
          return {};
    std::vector<idx_t> options(METIS_NOPTIONS);
    METIS_SetDefaultOptions(options.data());
    options[METIS_OPTION_NUMBERING] = 0;
    std::vector<idx_t> order(n_groups), order_inverse(n_groups);
    std::iota(order.begin(), order.end(), idx_t(0));
    if (!adjacency.empty() && METIS_NodeND(&n_vertices,
                                           offsets.data(),
                                           adjacency.data(),
                                           weights.data(),
                                           options.data(),
                                           order.data(),
                                           order_inverse.data()) != METIS_OK)
      return {};
    std::vector<int> group_start(n_groups + 1, 0), members(n);
    for (int i = 0; i < n; ++i)
      ++group_start[group[i] + 1];
    std::partial_sum(group_start.begin(),
                     group_start.end(),
                     group_start.begin());
    std::vector<int> next(group_start.begin(), group_start.end() - 1);
    for (int i = 0; i < n; ++i)
      members[next[group[i]]++] = i;
    std::vector<int> perm;
    perm.reserve(n);
    for (const idx_t v : order)
      perm.insert(perm.end(),
                  members.begin() + group_start[v],
                  members.begin() + group_start[v + 1]);
    return perm;
  }

  std::mutex &
  metis_ordering_lock()
  {
    static std::mutex lock;
    return lock;
  }
} // namespace PlateOnHalfspace
