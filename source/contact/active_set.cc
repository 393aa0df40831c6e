#include <deal.II/base/exceptions.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <plate_on_halfspace/contact/active_set.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>

namespace PlateOnHalfspace
{
  namespace
  {
    double
    max_abs(const Vector<double> &v)
    {
      return v.size() > 0 ? v.linfty_norm() : 0.;
    }

    /** The Gram matrix of the plate's rigid motions over the nodes of
     *  @p set (contact_set_supports_plate()). */
    LAPACKFullMatrix<double>
    motions_gram(const FoundationSpace &space, const std::vector<bool> &set)
    {
      const unsigned int       m = space.rigid_motions.size();
      LAPACKFullMatrix<double> gram(m, m);
      for (unsigned int i = 0; i < set.size(); ++i)
        if (set[i])
          for (unsigned int a = 0; a < m; ++a)
            for (unsigned int b = 0; b < m; ++b)
              gram(a, b) +=
                space.rigid_motions[a][i] * space.rigid_motions[b][i];
      return gram;
    }
  } // namespace

  namespace
  {
    bool plate_weightless = true;
  } // namespace

  void
  set_plate_weightless(const bool weightless)
  {
    plate_weightless = weightless;
  }

  std::string
  plate_is_mechanism_message()
  {
    const std::string what =
      "The plate is a mechanism: the nodes left in contact cannot carry it "
      "(fewer than three non-collinear supporting nodes). ";
    if (plate_weightless)
      return what +
             "A load on or very near the edge of a weightless plate tilts it "
             "about that edge: move the load inward, refine the mesh there "
             "or give the plate its weight (Plate/Unit weight).";
    // A plate with weight: its weight is already there, so the loads
    // outweigh it near an edge or a joint (doc/errors-and-limits.md).
    return what +
           "The loads press the plate down so near an edge or a joint that "
           "they tilt it about that line in spite of its weight: move them "
           "inward, refine the mesh there (Discretization/Initial "
           "refinements or Adaptivity/Refinement = adaptive) or spread a "
           "point load over a patch (Loads/Circular patches).";
  }

  bool
  contact_set_supports_plate(const FoundationSpace   &space,
                             const std::vector<bool> &in_contact)
  {
    Vector<double>     eigenvalues_below;
    FullMatrix<double> eigenvectors_below;
    if (!space.rigid_motions.empty())
      {
        // The contact set holds the plate if no rigid-body motion of it
        // (each slab's, for a grid with free joints) vanishes on the set:
        // with the motions orthonormal over all nodes, the Gram matrix on
        // the set is positive definite, its eigenvalues about the set's
        // share of the nodes where it holds them well.
        const auto n_contact =
          std::count(in_contact.begin(), in_contact.end(), true);
        if (n_contact == 0)
          return false;
        LAPACKFullMatrix<double> gram = motions_gram(space, in_contact);
        gram.compute_eigenvalues_symmetric(-1.,
                                           1e-10 * n_contact /
                                             in_contact.size(),
                                           0.,
                                           eigenvalues_below,
                                           eigenvectors_below);
        return eigenvalues_below.size() == 0;
      }
    // The nodes in contact on the whole plate: those of the computed
    // part and, for a symmetric scene, their mirror images.
    std::vector<Point<2>> points;
    for (unsigned int i = 0; i < in_contact.size(); ++i)
      if (in_contact[i])
        for (const Point<2> &x : space.node_images(i))
          points.push_back(x);
    const unsigned int n = points.size();
    if (n < 3)
      return false;
    Point<2> centre;
    for (const Point<2> &p : points)
      centre += p / n;
    double xx = 0, xy = 0, yy = 0, extent = 0;
    for (const Point<2> &p : points)
      {
        const Tensor<1, 2> d = p - centre;
        xx += d[0] * d[0];
        xy += d[0] * d[1];
        yy += d[1] * d[1];
        extent = std::max(extent, d.norm_square());
      }
    // smallest eigenvalue of the 2x2 second-moment matrix
    const double mean = 0.5 * (xx + yy);
    const double smallest =
      mean - std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
    return smallest > 1e-10 * n * extent;
  }

  bool
  carried_on_knife_edge(const FoundationSpace &space, const ContactState &state)
  {
    const Vector<double> &q = state.pressure_coefficients;
    if (q.size() != state.in_contact.size() ||
        !contact_set_supports_plate(space, state.in_contact))
      return false;
    const double      negligible = 1e-6 * max_abs(q);
    std::vector<bool> loaded(state.in_contact);
    for (unsigned int i = 0; i < loaded.size(); ++i)
      loaded[i] = loaded[i] && q[i] > negligible;
    return !contact_set_supports_plate(space, loaded);
  }

  void
  evaluate_contact_conditions(const Vector<double>    &plate_settlement,
                              const std::vector<bool> &supported,
                              ContactState            &state)
  {
    const double q_scale   = std::max(max_abs(state.q), 1e-300);
    const double gap_scale = std::max(max_abs(plate_settlement), 1e-300);
    double       tension = 0, penetration = 0, product = 0;
    state.tensile_nodes = 0;
    for (unsigned int i = 0; i < state.q.size(); ++i)
      {
        tension = std::max(tension, -state.q[i] / q_scale);
        if (state.q[i] < 0)
          ++state.tensile_nodes;
        // Only the soil under the plate's foundation area is constrained.
        if (supported[i])
          {
            penetration = std::max(penetration, -state.gap[i] / gap_scale);
            product     = std::max(product,
                               std::abs(state.q[i] * state.gap[i]) /
                                 (q_scale * gap_scale));
          }
      }
    state.complementarity_violation =
      std::max({tension, penetration, product, 0.});
    state.max_penetration = std::max(penetration, 0.);
  }

  std::vector<bool>
  initial_contact_set(const FoundationSpace   &space,
                      const std::vector<bool> &supported,
                      const std::vector<bool> &seed)
  {
    std::vector<bool> set(supported);
    if (seed.size() == set.size() && contact_set_supports_plate(space, seed))
      for (unsigned int i = 0; i < set.size(); ++i)
        set[i] = set[i] && seed[i];
    return set;
  }

  ActiveSetUpdate::ActiveSetUpdate(const FoundationSpace      &space,
                                   const std::vector<bool>    &supported,
                                   const std::vector<bool>    &initial_contact,
                                   const SparseMatrix<double> &test_coupling)
    : space(space)
    , test_coupling(test_coupling)
    , supported(supported)
    , active(initial_contact_set(space, supported, initial_contact))
  {}

  unsigned int
  ActiveSetUpdate::n_contact_nodes() const
  {
    return std::count(active.begin(), active.end(), true);
  }

  unsigned int
  ActiveSetUpdate::find_violations(const Vector<double> &q,
                                   const Vector<double> &gap,
                                   const double          q_tolerance,
                                   const double          g_tolerance)
  {
    next = active;
    changes.clear();
    for (unsigned int i = 0; i < active.size(); ++i)
      {
        if (!supported[i])
          continue;
        const bool violated =
          active[i] ? (q[i] < -q_tolerance) : (gap[i] < -g_tolerance);
        if (violated)
          {
            next[i] = !active[i];
            changes.push_back(i);
          }
      }
    return changes.size();
  }

  bool
  ActiveSetUpdate::step(const Vector<double> &q,
                        const Vector<double> &gap,
                        const double          q_tolerance,
                        const double          g_tolerance,
                        const unsigned int    iteration,
                        const unsigned int    verbosity,
                        std::ostream         &log)
  {
    const unsigned int n_changes =
      find_violations(q, gap, q_tolerance, g_tolerance);
    if (verbosity > 0)
      log << "   contact iteration " << iteration << ": nodes in contact "
          << n_contact_nodes() << ", changes " << n_changes
          << (single_pivot_mode ? " (single pivots)" : "") << std::endl;
    if (n_changes == 0)
      return true;
    if (detect_cycle() && verbosity > 0)
      log << "   contact iteration " << iteration
          << ": cycle detected, switching to single pivots" << std::endl;
    advance(q, gap);
    return false;
  }

  void
  ActiveSetUpdate::forget_visited_sets()
  {
    visited.clear();
    single_pivot_mode = false;
  }

  bool
  ActiveSetUpdate::detect_cycle()
  {
    visited.insert(active);
    if (visited.count(next) > 0 && !single_pivot_mode)
      {
        // The full step returns to a set seen before: a cycle. Fall back
        // to Murty's least-index rule, one status change per iteration,
        // which terminates for the SPD Galerkin problem.
        single_pivot_mode = true;
        return true;
      }
    return false;
  }

  void
  ActiveSetUpdate::advance(const Vector<double> &q, const Vector<double> &gap)
  {
    if (single_pivot_mode)
      {
        // the least index whose change leaves a set that carries the plate
        next = active;
        for (const unsigned int i : changes)
          {
            next[i] = !active[i];
            if (contact_set_supports_plate(space, next))
              break;
            next[i] = active[i];
          }
      }
    else if (!contact_set_supports_plate(space, next))
      {
        // A plate that lifts off almost entirely (a load at an edge or a
        // corner) can make the full step drop too many nodes at once. Take
        // every entry, then the exits in order for as long as the rest
        // still carries the plate.
        next = active;
        for (const unsigned int i : changes)
          if (!active[i])
            next[i] = true;
        for (const unsigned int i : changes)
          if (active[i])
            {
              next[i] = false;
              if (!contact_set_supports_plate(space, next))
                next[i] = true;
            }
      }
    if (next == active)
      next = exchange_tensile_node(q, gap);
    AssertThrow(next != active, ExcMessage(plate_is_mechanism_message()));
    active = next;
  }

  std::vector<bool>
  ActiveSetUpdate::exchange_tensile_node(const Vector<double> &q,
                                         const Vector<double> &gap) const
  {
    const std::vector<Vector<double>> &motions   = space.rigid_motions;
    const unsigned int                 n_motions = motions.size();
    if (n_motions == 0)
      return active;
    // the most tensile node first
    std::vector<unsigned int> tensile;
    for (const unsigned int i : changes)
      if (active[i])
        tensile.push_back(i);
    std::sort(tensile.begin(),
              tensile.end(),
              [&](const unsigned int a, const unsigned int b) {
                return q[a] < q[b];
              });
    for (const unsigned int k : tensile)
      {
        // The motion that the set without k no longer holds: the
        // eigenvector of the smallest eigenvalue of the motions' Gram
        // matrix on that set (contact_set_supports_plate()).
        std::vector<bool> rest(active);
        rest[k]                       = false;
        LAPACKFullMatrix<double> gram = motions_gram(space, rest);
        Vector<double>           eigenvalues;
        FullMatrix<double>       eigenvectors;
        gram.compute_eigenvalues_symmetric(-1.,
                                           std::numeric_limits<double>::max(),
                                           0.,
                                           eigenvalues,
                                           eigenvectors);
        if (eigenvalues.size() == 0)
          continue;
        Vector<double> motion(active.size());
        for (unsigned int a = 0; a < n_motions; ++a)
          motion.add(eigenvectors(a, 0), motions[a]);
        // w is positive downward: k lifts (its tension held it down)
        if (motion[k] == 0)
          continue;
        if (motion[k] > 0)
          motion *= -1.;
        // the gaps close by B m: the first to reach zero among the nodes
        // that go down (a ratio test)
        Vector<double> closing(active.size());
        test_coupling.vmult(closing, motion);
        const double negligible = 1e-12 * closing.linfty_norm();
        unsigned int entering   = numbers::invalid_unsigned_int;
        double       first      = std::numeric_limits<double>::max();
        for (unsigned int i = 0; i < active.size(); ++i)
          if (supported[i] && !active[i] && closing[i] > negligible)
            {
              const double distance = std::max(gap[i], 0.) / closing[i];
              if (distance < first)
                {
                  first    = distance;
                  entering = i;
                }
            }
        if (entering == numbers::invalid_unsigned_int)
          continue;
        // a set seen before would start a cycle: a plate that no exchange
        // carries is a mechanism
        rest[entering] = true;
        if (visited.count(rest) == 0 && contact_set_supports_plate(space, rest))
          return rest;
      }
    return active;
  }

} // namespace PlateOnHalfspace
