#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/halfspace/fractional_laplace_inverse.h>
#include <plate_on_halfspace/halfspace/memory_guard.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * The rule's step in log t and the margins beyond the spectrum: within
     * 0.94 ... 1.02 of x^{1/2} over eigenvalues 1 ... 7.5e6 times the
     * lowest (a 10^5-node plate), a ratio of 1.08 between the extremes; the
     * CG iterations did not change between steps 1.5 and 2.5
     * (doc/performance.md, "With the fractional soil inverse").
     */
    constexpr double log_step = 2.;
    constexpr double margin   = 2.;

    /** c of A = L + c M: the constant pressure of the rigid disk of the
     *  plate's area, 4 / (pi r) per unit settlement over 2 pi alpha. */
    double
    shift(const double area)
    {
      return 16. / (M_PI * area);
    }

    /** The trapezoidal rule in log t from sqrt(c) / margin to margin
     *  sqrt(largest eigenvalue of M^{-1} A), and its tails' weights. */
    struct Rule
    {
      std::vector<double> t, weight;
      double              identity_weight = 0, top_weight = 0;
    };

    Rule
    trapezoid_rule(const double c, const double largest)
    {
      const double t_low      = std::sqrt(c) / margin,
                   t_high     = margin * std::sqrt(std::max(largest, c));
      const double       from = std::log(t_low), to = std::log(t_high);
      const unsigned int intervals =
        std::max(1u,
                 static_cast<unsigned int>(std::ceil((to - from) / log_step)));
      const double h = (to - from) / intervals;
      Rule         rule;
      rule.identity_weight = t_low;
      rule.top_weight      = 1. / t_high;
      for (unsigned int j = 0; j <= intervals; ++j)
        {
          const double t = std::exp(from + j * h);
          rule.t.push_back(t);
          rule.weight.push_back((j == 0 || j == intervals ? 0.5 : 1.) * h * t);
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
    return trapezoid_rule(c, largest_eigenvalue + c).t.size() + 1;
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
    const SparseCholesky       &analysis)
    : shifted(mass.get_sparsity_pattern())
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
      Vector<double> v(n), av(n), next;
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
          largest = std::max(largest, (v * av) / mass.matrix_norm_square(v));
        }
    }

    const Rule rule = trapezoid_rule(c, largest);
    identity_weight = rule.identity_weight;
    top_weight      = rule.top_weight;
    // The poles' factors are the preconditioner's memory: refuse before
    // allocating them rather than be stopped by the system halfway.
    {
      const std::size_t needed    = rule.t.size() * analysis.factor_bytes();
      const std::size_t available = available_memory_bytes();
      if (available > 0 && needed > available)
        {
          std::ostringstream text;
          text << std::setprecision(3)
               << "Contact/Preconditioner = soil inverse with Foundation "
                  "operator/Storage = fft: the fractional soil inverse's "
               << rule.t.size() << " sparse factors on " << n
               << " pressure nodes need about " << needed / 1073741824.
               << " GiB, but only " << available / 1073741824.
               << " GiB are available. ";
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
    // (M^{-1}A)^{1/2} M^{-1} s = (2/pi) [ (t_low + sum w_j) M^{-1} s
    //   - sum w_j t_j^2 (A + t_j^2 M)^{-1} s + M^{-1} A M^{-1} s / t_high ]
    // One solve after the other: CHOLMOD's triangular solves call BLAS,
    // whose own threads made concurrent solves 2.6 times slower than these
    // (doc/performance.md, "With the fractional soil inverse").
    Vector<double> inverse_mass, top, solution;
    solve_with(*mass_factor, s, inverse_mass);
    Vector<double> a_times(s.size());
    shifted.vmult(a_times, inverse_mass);
    solve_with(*mass_factor, a_times, top);
    q.reinit(s.size());
    q.add(identity_weight, inverse_mass, top_weight, top);
    for (const Pole &pole : poles)
      {
        solve_with(*pole.factor, s, solution);
        q.add(-pole.weight * pole.t * pole.t, solution);
      }
    q *= scale;
  }

  std::size_t
  FractionalLaplaceInverse::memory_consumption() const
  {
    std::size_t bytes =
      shifted.memory_consumption() + mass_factor->memory_consumption();
    for (const Pole &pole : poles)
      bytes += pole.factor->memory_consumption();
    return bytes;
  }
} // namespace PlateOnHalfspace
