#include <deal.II/base/multithread_info.h>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

#include <plate_on_halfspace/base/single_threaded_blas.h>
#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/base/tasks.h>
#include <plate_on_halfspace/halfspace/fractional_laplace_inverse.h>
#include <plate_on_halfspace/halfspace/memory_guard.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * The margin on the power iteration's estimate of the largest
     * eigenvalue (an estimate from below), and the largest ratio between
     * the extremes of r(x) x^{1/2} over the spectrum that the rule may
     * leave: within 1 -+ 7 % of x^{1/2} (doc/performance.md, "Zolotarev's
     * rule for the soil inverse").
     */
    constexpr double margin = 2., largest_ratio = 1.15;

    /** c of A = L + c M: the constant pressure of the rigid disk of the
     *  plate's area, 4 / (pi r) per unit settlement over 2 pi alpha. */
    double
    shift(const double area)
    {
      return 16. / (M_PI * area);
    }

    /**
     * x^{1/2} = x r(x) on the spectrum [c, margin^2 largest] of M^{-1} A,
     * with r Zolotarev's best relative approximation of x^{-1/2} there
     * (Zolotarev 1877; in the form of Chiu, Hsieh, Huang and Huang, Phys.
     * Rev. D 66 (2002) 114502): for y = x / c in [1, b],
     *   y^{-1/2} ≈ d prod_l (y + c_{2l}) / (y + c_{2l-1}),
     *   c_l = sn^2(l K / (2n + 1); k) / cn^2(l K / (2n + 1); k),
     *   k = (1 - 1/b)^{1/2}, K = K(k),
     * d scaling the relative error to equioscillate. In partial fractions
     * the product is 1 + sum_l a_l / (y + c_{2l-1}) with a_l > 0 (zeros
     * and poles interlace), so
     *   x^{1/2} ≈ (d / sqrt c) [x + sum_l a_l c - sum_l a_l c t_l^2 /
     *             (x + t_l^2)],   t_l^2 = c c_{2l-1},
     * positive for every x > 0: one sparse factor of A + t_l^2 M per
     * pole, with the fewest poles n that keep the ratio within
     * largest_ratio. The weights are those of the vmult() formula, in
     * units of 2 / pi.
     */
    struct Rule
    {
      std::vector<double> t, weight;
      double              identity_weight = 0, top_weight = 0;
    };

    Rule
    zolotarev_rule(const double c, const double largest)
    {
      // The interval's ratio b, rounded up to a power of 2^(1/8): the
      // pole count then grows with b, also where rounding decides the
      // ratio's test (the memory estimate's count must cover the
      // constructor's). Beyond 1e15 k rounds to 1.
      const double ratio = margin * margin * std::max(largest, c) / c;
      AssertThrow(std::isfinite(ratio) && ratio < 1e15,
                  ExcMessage("FractionalLaplaceInverse: the spectrum of the "
                             "pressure nodes' Laplacian spans " +
                             std::to_string(ratio) +
                             " times its lowest eigenvalue; at most 1e15 is "
                             "supported (a degenerate or far too fine "
                             "mesh)."));
      const double b = std::exp2(std::ceil(8. * std::log2(ratio)) / 8.);
      const double k = std::sqrt(1. - 1. / b);
      const double K = boost::math::ellint_1(k);
      // the ratio of r(y) y^{1/2} between its extremes on [1, b], sampled
      // in log y (2n interior extrema and the two ends, smooth in log y)
      const auto extremes = [b](const std::vector<double> &coefficients) {
        const unsigned int n   = coefficients.size() / 2;
        double             low = std::numeric_limits<double>::max(), high = 0;
        constexpr unsigned int samples = 4000;
        for (unsigned int i = 0; i <= samples; ++i)
          {
            const double y     = std::pow(b, double(i) / samples);
            double       value = std::sqrt(y);
            for (unsigned int l = 0; l < n; ++l)
              value *=
                (y + coefficients[2 * l + 1]) / (y + coefficients[2 * l]);
            low  = std::min(low, value);
            high = std::max(high, value);
          }
        return std::make_pair(low, high);
      };
      std::vector<double>       coefficients; // c_1, c_2, ..., c_2n
      std::pair<double, double> range;
      for (unsigned int n = 1;; ++n)
        {
          coefficients.resize(2 * n);
          for (unsigned int l = 1; l <= 2 * n; ++l)
            {
              double       cn = 0, dn = 0;
              const double sn =
                boost::math::jacobi_elliptic(k, l * K / (2 * n + 1), &cn, &dn);
              coefficients[l - 1] = sn * sn / (cn * cn);
            }
          range = extremes(coefficients);
          if (range.second <= largest_ratio * range.first || n >= 16)
            break;
        }
      const unsigned int n = coefficients.size() / 2;
      const double       d = 2. / (range.first + range.second);
      Rule               rule;
      rule.top_weight = 0.5 * M_PI * d / std::sqrt(c);
      for (unsigned int l = 0; l < n; ++l)
        {
          const double pole = coefficients[2 * l];
          double       a    = 1;
          for (unsigned int m = 0; m < n; ++m)
            {
              a *= coefficients[2 * m + 1] - pole;
              if (m != l)
                a /= coefficients[2 * m] - pole;
            }
          rule.t.push_back(std::sqrt(c * pole));
          rule.weight.push_back(rule.top_weight * a * c);
          rule.identity_weight += rule.weight.back();
        }
      return rule;
    }

    void
    solve_with(const SparseCholesky &factor,
               const Vector<double> &b,
               Vector<double>       &x)
    {
      std::vector<double> block(b.begin(), b.end());
      factor.solve(block, 1);
      x.reinit(b.size(), true);
      std::copy(block.begin(), block.end(), x.begin());
    }
  } // namespace

  unsigned int
  FractionalLaplaceInverse::n_factors(const double area,
                                      const double largest_eigenvalue)
  {
    const double c = shift(area);
    return zolotarev_rule(c, largest_eigenvalue + c).t.size() + 1;
  }

  std::vector<unsigned int>
  FractionalLaplaceInverse::part_owners(const unsigned int n_poles,
                                        const unsigned int n_ranks)
  {
    AssertThrow(n_ranks > 0, ExcMessage("part_owners: no ranks."));
    std::vector<unsigned int> owners(n_poles + 1);
    std::vector<unsigned int> solves(n_ranks, 0);
    const auto                least_busy = [&solves]() {
      return static_cast<unsigned int>(
        std::min_element(solves.begin(), solves.end()) - solves.begin());
    };
    // the chain's two solves first, then the poles in order
    owners[n_poles] = least_busy();
    solves[owners[n_poles]] += 2;
    for (unsigned int l = 0; l < n_poles; ++l)
      {
        owners[l] = least_busy();
        solves[owners[l]] += 1;
      }
    return owners;
  }

  unsigned int
  FractionalLaplaceInverse::n_factors_on_a_rank(const double area,
                                                const double largest_eigenvalue,
                                                const unsigned int n_ranks)
  {
    const unsigned int        n_poles = n_factors(area, largest_eigenvalue) - 1;
    std::vector<unsigned int> factors(n_ranks, 0);
    // one factor per part: a pole's, or M's for the chain
    for (const unsigned int owner : part_owners(n_poles, n_ranks))
      ++factors[owner];
    return *std::max_element(factors.begin(), factors.end());
  }

  unsigned int
  FractionalLaplaceInverse::n_factors_here() const
  {
    unsigned int held = mass_factor ? 1 : 0;
    for (const Pole &pole : poles)
      held += pole.factor ? 1 : 0;
    return held;
  }

  double
  FractionalLaplaceInverse::largest_eigenvalue_estimate(
    const FoundationSpace &space)
  {
    double largest = 0;
    for (const auto &cell : space.cells)
      largest = std::max(
        largest,
        120. * std::pow(cell.geometry.diameter() / cell.geometry.area(), 2));
    return largest;
  }

  FractionalLaplaceInverse::FractionalLaplaceInverse(
    const SparseMatrix<double> &mass,
    const SparseMatrix<double> &laplace,
    const double                alpha,
    const double                area,
    const SparseCholesky       &analysis,
    const MPI_Comm              communicator)
    : communicator(communicator)
    , shifted(mass.get_sparsity_pattern())
    , mass_factor(std::make_unique<SparseCholesky>(
        "the mass matrix of the pressure nodes"))
    , scale(1. / (M_PI * M_PI * alpha))
  {
    const unsigned int n = mass.m();
    AssertThrow(n > 0 && area > 0 && alpha > 0,
                ExcMessage("FractionalLaplaceInverse: empty foundation."));
    // A + t^2 M are summed entry by entry on one pattern
    AssertThrow(&laplace.get_sparsity_pattern() == &mass.get_sparsity_pattern(),
                ExcMessage("FractionalLaplaceInverse: L and M must share "
                           "the mass matrix's pattern."));
    const double c = shift(area);
    shifted.copy_from(laplace);
    shifted.add(c, mass);
    mass_factor->factorize_as(analysis, mass);

    // The largest eigenvalue of M^{-1} A: a Rayleigh quotient after a few
    // power steps from a rough vector, an estimate from below that the
    // margin covers.
    double largest = c;
    {
      Vector<double> v(n), av(n), mv(n), next;
      for (unsigned int i = 0; i < n; ++i)
        v[i] = std::cos(0.37 * i) + 0.3 * std::sin(2.1 * double(i) * i);
      shifted.vmult(av, v);
      for (unsigned int step = 0; step < 20; ++step)
        {
          // av = A v from the last step's quotient
          solve_with(*mass_factor, av, next);
          const double norm = next.l2_norm();
          if (!(norm > 0))
            break;
          v = next;
          v /= norm;
          shifted.vmult(av, v);
          // v^T M v through a product and a Vector dot product, whose sums
          // run in a fixed order (SparseMatrix::matrix_norm_square's
          // parallel reduction does not)
          mass.vmult(mv, v);
          largest = std::max(largest, (v * av) / (v * mv));
        }
    }
    // The ranks share out the rule's parts (part_owners()), so they must
    // find the same rule: the same bound on every rank.
    if (n_ranks(communicator) > 1)
      largest = Utilities::MPI::max(largest, communicator);

    const Rule rule = zolotarev_rule(c, largest);
    identity_weight = rule.identity_weight;
    top_weight      = rule.top_weight;
    // Every rank has made M's factor for the power steps; only the chain's
    // rank keeps it.
    const unsigned int              rank = rank_in(communicator);
    const std::vector<unsigned int> owners =
      part_owners(rule.t.size(), n_ranks(communicator));
    if (owners.back() != rank)
      mass_factor.reset();
    unsigned int own_poles = 0;
    for (unsigned int j = 0; j < rule.t.size(); ++j)
      own_poles += owners[j] == rank ? 1 : 0;
    // The poles' factors are the preconditioner's memory: refuse before
    // allocating them rather than be stopped by the system halfway.
    {
      const MemoryOnMachine memory =
        memory_on_machine(own_poles * analysis.factor_bytes(), communicator);
      if (!memory.fits)
        {
          std::ostringstream text;
          text << std::setprecision(3)
               << "Contact/Preconditioner = soil inverse with Foundation "
                  "operator/Storage = fft: the fractional soil inverse's "
               << rule.t.size() << " sparse factors on " << n
               << " pressure nodes";
          if (n_ranks(communicator) > 1)
            text << " (" << own_poles << " of them on this process)";
          text << " need about "
               << own_poles * analysis.factor_bytes() / 1073741824. << " GiB"
               << machine_shortfall_text(memory) << ' ';
          throw StorageDoesNotFit(
            text.str(),
            "Use Contact/Preconditioner = plate on springs, or reduce the "
            "node count (Discretization/Subdivisions x and y, "
            "Discretization/Initial refinements, Adaptivity/Max cells).");
        }
    }
    SparseMatrix<double> matrix(shifted.get_sparsity_pattern());
    for (unsigned int j = 0; j < rule.t.size(); ++j)
      {
        Pole &pole  = poles.emplace_back();
        pole.t      = rule.t[j];
        pole.weight = rule.weight[j];
        if (owners[j] != rank)
          continue;
        matrix.copy_from(shifted);
        matrix.add(pole.t * pole.t, mass);
        pole.factor = std::make_unique<SparseCholesky>(
          "the fractional soil inverse's L + (c + t^2) M");
        pole.factor->factorize_as(analysis, matrix);
      }
  }

  FractionalLaplaceInverse::~FractionalLaplaceInverse() = default;

  void
  FractionalLaplaceInverse::vmult(Vector<double>       &q,
                                  const Vector<double> &s) const
  {
    // (M^{-1}A)^{1/2} M^{-1} s = (2/pi) [ identity_weight M^{-1} s
    //   - sum w_j t_j^2 (A + t_j^2 M)^{-1} s + top_weight M^{-1} A M^{-1} s ]
    // The mass chain and the poles' solves are independent: each rank
    // applies the parts whose factors it holds. With the BLAS on one
    // thread (the contact solve's guard) they run as tasks side by side,
    // each with its own factor and CHOLMOD workspace; with the BLAS's own
    // threads, concurrent solves were 2.6 times slower than these one
    // after the other (doc/performance.md, "With the fractional soil
    // inverse"). Either way a rank adds its parts in one fixed order, and
    // the ranks' sums are joined on one rank and sent to all
    // (sum_shared_entries_over_ranks()), so every rank has the same bits.
    std::vector<unsigned int> own_parts;
    for (unsigned int j = 0; j < poles.size(); ++j)
      if (poles[j].factor)
        own_parts.push_back(j);
    if (mass_factor)
      own_parts.push_back(poles.size());
    Vector<double>              inverse_mass, top;
    std::vector<Vector<double>> pole_solutions(poles.size());
    const auto                  solve_part = [&](const unsigned int k) {
      const unsigned int part = own_parts[k];
      if (part < poles.size())
        solve_with(*poles[part].factor, s, pole_solutions[part]);
      else
        {
          solve_with(*mass_factor, s, inverse_mass);
          Vector<double> a_times(s.size());
          shifted.vmult(a_times, inverse_mass);
          solve_with(*mass_factor, a_times, top);
        }
    };
    const unsigned int n_parts = own_parts.size();
    if (MultithreadInfo::n_threads() > 1 && SingleThreadedBlas::in_effect())
      {
        run_tasks(n_parts, solve_part);
      }
    else
      for (unsigned int k = 0; k < n_parts; ++k)
        solve_part(k);
    q.reinit(s.size());
    if (mass_factor)
      q.add(identity_weight, inverse_mass, top_weight, top);
    for (unsigned int j = 0; j < poles.size(); ++j)
      if (poles[j].factor)
        q.add(-poles[j].weight * poles[j].t * poles[j].t, pole_solutions[j]);
    sum_shared_entries_over_ranks(make_array_view(q), communicator);
    q *= scale;
  }

  std::size_t
  FractionalLaplaceInverse::memory_consumption() const
  {
    std::size_t bytes = shifted.memory_consumption() +
                        (mass_factor ? mass_factor->memory_consumption() : 0);
    for (const Pole &pole : poles)
      bytes += pole.factor ? pole.factor->memory_consumption() : 0;
    return bytes;
  }
} // namespace PlateOnHalfspace
