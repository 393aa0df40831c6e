#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>

#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>
#include <boost/math/interpolators/cubic_hermite.hpp>
#include <boost/math/tools/roots.hpp>

#include <plate_on_halfspace/soil/layered_soil.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    /** The most knots a tabulation may take before it gives up. */
    constexpr unsigned int most_knots = 1u << 16;
    /** The most wave numbers of the Hankel integral's rule. */
    constexpr double most_wave_numbers = 1e6;
  } // namespace

  struct TabulatedLayeredRemainder::Implementation
  {
    double top_thickness = 0, span = 0, achieved = 0, largest_share = 0;
    /** The closed-form far field: (C_b - C1)/(2 pi) and (2 D)^2. */
    double far_coefficient = 0, depth_squared = 0;
    /** The Hankel integral's nodes and weighted integrand over 2 pi. */
    std::vector<double>                                         nodes, weighted;
    boost::math::interpolators::cardinal_cubic_b_spline<double> spline;
    /** The same piecewise cubic in Hermite form (values and slopes at the
     *  knots), which evaluates in half the time. */
    using Hermite = boost::math::interpolators::cardinal_cubic_hermite_aos<
      std::vector<std::array<double, 2>>>;
    std::unique_ptr<Hermite> hermite;
    double                   t_end = 0;
    unsigned int             knots = 0;

    /**
     * The evaluation table: the same R as a cubic Hermite interpolant on
     * knots uniform in s = sqrt(r / h1), (R, dR/ds ds) at s = i ds. In s
     * no transcendental function maps r to the table (two square roots
     * instead of asinh), R is as smooth (R is even in r) and the knots
     * crowd where R bends, near r = h1; its cubic is evaluated here, not
     * by Boost's cardinal_cubic_hermite, which takes floor() and checks
     * the range at each of the integration's 10^8 and more calls.
     */
    std::vector<std::array<double, 2>> fast;
    /** 1 / (sqrt(h1) ds), and the last interval's index. */
    double       fast_scale = 0;
    unsigned int fast_last  = 0;

    double
    fast_value(const double sqrt_r) const
    {
      const double       x = sqrt_r * fast_scale;
      const unsigned int i =
        std::min(static_cast<unsigned int>(x), fast_last); // x >= 0
      const double t = std::min(x - i, 1.);
      const double u = 1. - t;
      const auto  &a = fast[i], &b = fast[i + 1];
      return u * u * (a[0] * (1. + 2. * t) + a[1] * t) +
             t * t * (b[0] * (3. - 2. * t) - b[1] * u);
    }

    // The C library's j0 and j1 (POSIX): a tenth of the time of Boost's
    // cyl_bessel_j, which dispatches on the order and promotes to long
    // double, and as accurate (1e-16 apart over the integrand's range).
    double
    integral(const double r) const
    {
      double sum = 0;
      for (std::size_t j = 0; j < nodes.size(); ++j)
        sum += weighted[j] * ::j0(nodes[j] * r);
      return far_coefficient / std::sqrt(r * r + depth_squared) + sum;
    }

    /** dR/dr: the spline's slope at the range's end (a finite-difference
     *  estimate there would cost the spline two orders). */
    double
    slope(const double r) const
    {
      double sum = 0;
      for (std::size_t j = 0; j < nodes.size(); ++j)
        sum -= weighted[j] * nodes[j] * ::j1(nodes[j] * r);
      return sum - far_coefficient * r / std::pow(r * r + depth_squared, 1.5);
    }

    double
    distance(const double t) const
    {
      return top_thickness * std::sinh(t);
    }
  };

  namespace
  {
    /**
     * The panels of the Hankel integral up to @p k_end: [k, k + width(k)],
     * width(k) = @p scale min(pi / range, max(w0, k / 2)), w0 = @p
     * tolerance min(pi / range, 1 / D). J0(k r) turns by at most half a
     * period per panel at scale 1 up to the range. The compliance changes
     * on scales down to the smallest of its stiffness ratios: a stiff
     * bonded layer restrains the layers below it in plane over a length
     * E1 h1 / mu_below, which can exceed the plate by orders of magnitude
     * (doc/soil-models.md, "The kernel"). Panels growing geometrically
     * from w0 resolve every such scale at a cost of log(1/w0) panels; what
     * lies below w0 weighs at most about w0 times the range relative to R.
     * Frictionless interfaces pass no shear, so no such length arises:
     * there w0 = 1e-3 min(pi / range, 1 / D), which also keeps k h of thin
     * layers above where their (k h)^2 horizontal stiffness is lost to
     * rounding. Stops early, short of k_end, at more than @p most_panels
     * panels.
     */
    std::vector<double>
    panel_ends(const LayeredProfile &profile,
               const double          scale,
               const double          tolerance,
               const double          range,
               const double          k_end,
               const std::size_t     most_panels)
    {
      const double widest = numbers::PI / range;
      const double finest =
        (profile.interfaces == LayeredProfile::Interfaces::frictionless ?
           1e-3 :
           tolerance) *
        std::min(widest, 1. / profile.depth());
      std::vector<double> ends{0.};
      while (ends.back() < k_end && ends.size() <= most_panels)
        {
          const double k = ends.back();
          ends.push_back(
            std::min(k_end,
                     k + scale * std::min(widest, std::max(finest, 0.5 * k))));
        }
      return ends;
    }

    /** The larger of @p a and @p b, NaN if either is (std::max keeps its
     *  first argument against a NaN). */
    double
    worse(const double a, const double b)
    {
      return (std::isnan(b) || b > a) ? b : a;
    }

    /**
     * The nodes and weights (over 2 pi) of the Hankel integral on the
     * panels @p ends, 10 Gauss-Legendre points each.
     */
    void
    make_rule(const LayeredProfile      &profile,
              const std::vector<double> &ends,
              std::vector<double>       &nodes,
              std::vector<double>       &weighted)
    {
      const SoilLayer &top = profile.layers.front();
      const double C1 = 2. * (1. - top.poissons_ratio * top.poissons_ratio) /
                        top.youngs_modulus;
      const double far       = profile.far_field_coefficient() - C1;
      const double D         = profile.depth();
      const auto   integrand = [&](const double k) {
        return profile.compliance_remainder(k) - far * std::exp(-2. * k * D);
      };
      const QGauss<1>   gauss(10);
      const std::size_t n_panels = ends.size() - 1;
      nodes.resize(n_panels * gauss.size());
      weighted.resize(nodes.size());
      parallel::apply_to_subranges(
        std::size_t(0),
        n_panels,
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t p = begin; p < end; ++p)
            for (unsigned int q = 0; q < gauss.size(); ++q)
              {
                const double      width = ends[p + 1] - ends[p];
                const double      k     = ends[p] + gauss.point(q)[0] * width;
                const std::size_t j     = p * gauss.size() + q;
                nodes[j]                = k;
                weighted[j] =
                  gauss.weight(q) * width / (2. * numbers::PI) * integrand(k);
              }
        },
        64);
    }
  } // namespace

  TabulatedLayeredRemainder::TabulatedLayeredRemainder(
    const LayeredProfile &profile,
    const double          range,
    const double          tolerance)
    : data(std::make_unique<Implementation>())
  {
    AssertThrow(range > 0 && std::isfinite(range),
                ExcMessage("The layered kernel's range must be > 0."));
    const SoilLayer &top = profile.layers.front();
    const double     C1 =
      2. * (1. - top.poissons_ratio * top.poissons_ratio) / top.youngs_modulus;
    const double alpha = C1 / (2. * numbers::PI);
    const double D     = profile.depth();
    // Deeper layers are, for the plate, a half-space of their material,
    // and the tabulation's smallest wave numbers (w0 ~ 1/D) reach where
    // the condensation of a stiff layer over them loses the compliance to
    // rounding (doc/soil-models.md, "Limits").
    constexpr double deepest = 1e6;
    if (!(D <= deepest * range))
      {
        std::ostringstream message;
        message << "Foundation/Layers: the layers are " << D
                << " deep in all, more than " << deepest
                << " times the distances on the plate (up to " << range
                << "): for the plate a layer that deep is a half-space of "
                   "its material, and the layered kernel loses its digits "
                   "there. End the Layers above the deep layer and give it "
                   "as the base (Base = half-space with Foundation/Young's "
                   "modulus and Poisson's ratio).";
        AssertThrow(false, ExcMessage(message.str()));
      }
    data->top_thickness = top.thickness;
    data->span          = range;
    data->far_coefficient =
      (profile.far_field_coefficient() - C1) / (2. * numbers::PI);
    data->depth_squared = 4. * D * D;

    // The integrand decays like (k h1)^2 exp(-2 k h1) and exp(-2 k D)
    // (h1 <= D): both are below 1e-15 of their scale at k_end.
    const double k_end       = 20. / top.thickness;
    double       scale       = 1.;
    const auto   most_panels = static_cast<std::size_t>(most_wave_numbers / 10);
    // About a second of Bessel functions per 10^5 wave numbers and 100
    // knots; beyond this the top layer is too thin for the plate.
    const std::vector<double> first_panels =
      panel_ends(profile, scale, tolerance, range, k_end, most_panels);
    if (first_panels.back() < k_end)
      {
        std::ostringstream message;
        message << "Foundation/Layers: the top layer (" << top.thickness
                << " thick) is too thin for distances up to " << range
                << " on the plate, on layers " << D
                << " deep: the layered kernel would need more than "
                << most_wave_numbers
                << " wave numbers. Merge the thin top layer into the plate "
                   "or the layer below, or make it thicker.";
        AssertThrow(false, ExcMessage(message.str()));
      }
    make_rule(profile, first_panels, data->nodes, data->weighted);

    // The quadrature's error: the same integral on panels half as wide, at
    // the ends and the middle of the range. Panels are halved until that
    // difference is within the tolerance, and the finer rule is kept, so
    // the difference bounds its error.
    while (true)
      {
        const std::vector<double> fine_panels =
          panel_ends(profile, scale / 2., tolerance, range, k_end, most_panels);
        if (fine_panels.back() < k_end)
          {
            std::ostringstream message;
            message << "Foundation/Layers: the layered kernel's wave-number "
                       "integral could not be brought to "
                    << tolerance << " with " << most_wave_numbers
                    << " wave numbers";
            if (data->achieved > 0)
              message << " (it reached " << data->achieved << ")";
            message << "; the layers' stiffness contrast, a Poisson's "
                       "ratio very close to 0.5 (above about 0.4999 with "
                       "layers much thinner than the plate), or the ratio "
                       "of the plate to the top layer's thickness is too "
                       "large.";
            AssertThrow(false, ExcMessage(message.str()));
          }
        std::vector<double> fine_nodes, fine_weighted;
        make_rule(profile, fine_panels, fine_nodes, fine_weighted);
        Implementation fine;
        fine.far_coefficient = data->far_coefficient;
        fine.depth_squared   = data->depth_squared;
        fine.nodes           = std::move(fine_nodes);
        fine.weighted        = std::move(fine_weighted);
        double difference    = 0;
        for (const double r : {0., 0.01 * range, 0.5 * range, range})
          difference = worse(difference,
                             std::abs(fine.integral(r) - data->integral(r)) /
                               (alpha / std::max(r, top.thickness) +
                                std::abs(fine.integral(r))));
        data->nodes    = std::move(fine.nodes);
        data->weighted = std::move(fine.weighted);
        scale /= 2.;
        data->achieved = difference;
        AssertThrow(std::isfinite(difference),
                    ExcMessage("Foundation/Layers: the layered kernel's "
                               "wave-number integral is not a finite number; "
                               "check the layers' moduli and Poisson's "
                               "ratios."));
        if (difference <= tolerance)
          break;
      }

    // The spline: knots doubled until every midpoint agrees.
    const double t_end = std::asinh(range / top.thickness);
    // dR/dt at the end, for the spline's end condition (even in t, the
    // slope at t = 0 is zero).
    const double end_slope =
      data->slope(range) * top.thickness * std::cosh(t_end);
    unsigned int        n = 32; // intervals
    std::vector<double> values(n + 1);
    parallel::apply_to_subranges(
      0u,
      n + 1,
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int i = begin; i < end; ++i)
          values[i] = data->integral(data->distance(t_end * i / n));
      },
      4);
    while (true)
      {
        const double h = t_end / n;
        data->spline =
          boost::math::interpolators::cardinal_cubic_b_spline<double>(
            values.begin(), values.end(), 0., h, 0., end_slope);
        std::vector<double> midpoints(n);
        parallel::apply_to_subranges(
          0u,
          n,
          [&](const unsigned int begin, const unsigned int end) {
            for (unsigned int i = begin; i < end; ++i)
              midpoints[i] = data->integral(data->distance((i + 0.5) * h));
          },
          4);
        double worst = 0;
        for (unsigned int i = 0; i < n; ++i)
          {
            const double t = (i + 0.5) * h, r = data->distance(t);
            worst = worse(worst,
                          std::abs(data->spline(t) - midpoints[i]) /
                            (alpha / r + std::abs(midpoints[i])));
          }
        if (worst <= tolerance || 2 * n > most_knots)
          {
            AssertThrow(worst <= tolerance,
                        ExcMessage(
                          "Foundation/Layers: the layered kernel could not be "
                          "tabulated to " +
                          std::to_string(tolerance) + " with " +
                          std::to_string(most_knots) +
                          " knots; the layers' stiffness contrast or the "
                          "ratio of the plate to the top layer's thickness "
                          "is too large."));
            data->achieved = std::max(data->achieved, worst);
            data->knots    = n + 1;
            data->t_end    = t_end;
            std::vector<std::array<double, 2>> hermite_data(n + 1);
            for (unsigned int i = 0; i <= n; ++i)
              hermite_data[i] = {
                {data->spline(i * h), data->spline.prime(i * h)}};
            data->hermite =
              std::make_unique<Implementation::Hermite>(std::move(hermite_data),
                                                        0.,
                                                        h);
            break;
          }
        std::vector<double> doubled(2 * n + 1);
        for (unsigned int i = 0; i < n; ++i)
          {
            doubled[2 * i]     = values[i];
            doubled[2 * i + 1] = midpoints[i];
          }
        doubled[2 * n] = values[n];
        values.swap(doubled);
        n *= 2;
      }
    AssertThrow(std::isfinite(data->achieved),
                ExcMessage("Foundation/Layers: the layered kernel is not "
                           "finite; check the layers' moduli."));

    // The evaluation table from the spline: intervals doubled until it
    // agrees with the spline at every midpoint to a tenth of the
    // tolerance; its error then adds to the spline's.
    const double h1        = top.thickness;
    const double s_end     = std::sqrt(range / h1);
    const auto   spline_at = [&](const double s) -> std::array<double, 2> {
      // R and dR/ds at s = sqrt(r / h1): t = asinh(s^2), dt/ds = 2 s /
      // sqrt(1 + s^4).
      // Boost's own end of the range, which can be an ulp below t_end.
      const double t =
        std::min(std::asinh(s * s), data->hermite->domain().second);
      return {
        {(*data->hermite)(t),
         data->hermite->prime(t) * 2. * s / std::sqrt(1. + s * s * s * s)}};
    };
    for (unsigned int n_s = 64;; n_s *= 2)
      {
        const double ds = s_end / n_s;
        data->fast.resize(n_s + 1);
        for (unsigned int i = 0; i <= n_s; ++i)
          {
            data->fast[i] = spline_at(i * ds);
            data->fast[i][1] *= ds;
          }
        data->fast_scale = 1. / (std::sqrt(h1) * ds);
        data->fast_last  = n_s - 1;
        double worst     = 0;
        for (unsigned int i = 0; i < n_s; ++i)
          {
            const double s = (i + 0.5) * ds, r = h1 * s * s;
            const double exact = spline_at(s)[0];
            worst              = worse(worst,
                          std::abs(data->fast_value(std::sqrt(r)) - exact) /
                            (alpha / r + std::abs(exact)));
          }
        if (worst <= 0.1 * tolerance)
          {
            data->achieved += worst;
            for (unsigned int i = 1; i <= n_s; ++i)
              {
                const double r = h1 * (i * ds) * (i * ds);
                const double R = std::abs(data->fast[i][0]);
                data->largest_share =
                  worse(data->largest_share, R / (alpha / r + R));
              }
            break;
          }
        AssertThrow(2 * n_s <= (1u << 24),
                    ExcMessage("Foundation/Layers: the layered kernel's "
                               "evaluation table would need more than 2^24 "
                               "knots; the ratio of the plate to the top "
                               "layer's thickness is too large."));
      }
  }

  TabulatedLayeredRemainder::~TabulatedLayeredRemainder() = default;

  double
  TabulatedLayeredRemainder::value(const double r) const
  {
    Assert(r >= 0 && r <= data->span * (1. + 1e-12),
           ExcMessage("The layered kernel is asked beyond its range."));
    return data->fast_value(std::sqrt(std::min(r, data->span)));
  }

  void
  TabulatedLayeredRemainder::add_values(const double      *distances,
                                        double            *values,
                                        const unsigned int n) const
  {
    const Implementation &table = *data;
    for (unsigned int i = 0; i < n; ++i)
      values[i] += table.fast_value(std::sqrt(distances[i]));
  }

  double
  TabulatedLayeredRemainder::length_scale() const
  {
    return data->top_thickness;
  }

  double
  TabulatedLayeredRemainder::range() const
  {
    return data->span;
  }

  double
  TabulatedLayeredRemainder::error() const
  {
    return data->achieved;
  }

  double
  TabulatedLayeredRemainder::largest_share() const
  {
    return data->largest_share;
  }

  unsigned int
  TabulatedLayeredRemainder::n_knots() const
  {
    return data->knots;
  }

  LayeredSoil::LayeredSoil(const LayeredProfile &profile,
                           const unsigned int    singular_order)
    : ElasticSoil(singular_order)
    , profile(profile)
  {}

  std::string
  LayeredSoil::name() const
  {
    return "layered";
  }

  SurfaceKernel
  LayeredSoil::kernel(const double max_distance) const
  {
    const SoilLayer &top   = profile.layers.front();
    const double     alpha = (1. - top.poissons_ratio * top.poissons_ratio) /
                         (numbers::PI * top.youngs_modulus);
    const std::lock_guard<std::mutex> lock(table_mutex);
    if (!table || table->range() < max_distance)
      {
        const auto start = std::chrono::steady_clock::now();
        // A margin, so that a slightly larger plate (an adaptive mesh's
        // curved boundary) does not tabulate again.
        table =
          std::make_shared<const TabulatedLayeredRemainder>(profile,
                                                            1.1 * max_distance,
                                                            kernel_tolerance);
        table_seconds = std::chrono::duration<double>(
                          std::chrono::steady_clock::now() - start)
                          .count();
      }
    // A remainder below the tabulation's own accuracy everywhere (layers of
    // one material over a half-space of it) leaves the top layer's
    // half-space kernel, which takes the half-space's rules and cost
    // (doc/soil-models.md, "The kernel").
    if (remainder_negligible())
      return SurfaceKernel(alpha);
    return SurfaceKernel(alpha, table);
  }

  bool
  LayeredSoil::remainder_negligible() const
  {
    return table->largest_share() <= kernel_tolerance;
  }

  double
  LayeredSoil::typical_settlement(const double force, const double area) const
  {
    double flexibility = 0;
    for (const SoilLayer &layer : profile.layers)
      flexibility =
        std::max(flexibility,
                 (1. - layer.poissons_ratio * layer.poissons_ratio) /
                   layer.youngs_modulus);
    if (profile.base == LayeredProfile::Base::half_space)
      flexibility = std::max(flexibility,
                             (1. - profile.base_poissons_ratio *
                                     profile.base_poissons_ratio) /
                               profile.base_youngs_modulus);
    return force / std::sqrt(area) * flexibility;
  }

  double
  LayeredSoil::patch_stiffness(const double size) const
  {
    // The top layer's half-space: the limit of a patch small against the
    // top layer, which is what a cell at the contact boundary should be.
    const SoilLayer &top   = profile.layers.front();
    const double alpha_top = (1. - top.poissons_ratio * top.poissons_ratio) /
                             (M_PI * top.youngs_modulus);
    return 1. / (alpha_top * mean_inverse_distance_over_square * size);
  }

  double
  LayeredSoil::radius_of_relative_stiffness(
    const double flexural_rigidity) const
  {
    AssertThrow(flexural_rigidity > 0 && std::isfinite(flexural_rigidity),
                ExcMessage("The flexural rigidity must be > 0."));
    // log(D k^4 G(k)) at k = exp(-s), s = log(l): decreasing in s, from +inf
    // (G ~ C1/k as k -> inf) to -inf (G bounded, or ~ C_b/k, as k -> 0).
    const double log_rigidity = std::log(flexural_rigidity);
    const auto   excess       = [&](const double s) {
      return log_rigidity - 4. * s +
             std::log(profile.surface_compliance(std::exp(-s)));
    };
    // The top layer's own half-space radius as the first guess, and a
    // bracket widened additively in s (a multiplicative step on s would
    // stall at s = 0, l = 1 in whatever unit the scene uses).
    const SoilLayer &top = profile.layers.front();
    const double     guess =
      (log_rigidity +
       std::log(2. * (1. - top.poissons_ratio * top.poissons_ratio) /
                top.youngs_modulus)) /
      3.;
    double lower = guess - 1., upper = guess + 1., step = 1.;
    double f_lower = excess(lower), f_upper = excess(upper);
    for (unsigned int i = 0; i < 60 && !(f_lower >= 0. && f_upper <= 0.); ++i)
      {
        step *= 2.;
        if (f_lower < 0.)
          f_lower = excess(lower -= step);
        if (f_upper > 0.)
          f_upper = excess(upper += step);
      }
    AssertThrow(std::isfinite(f_lower) && std::isfinite(f_upper) &&
                  f_lower >= 0. && f_upper <= 0.,
                ExcMessage("The radius of relative stiffness on the layered "
                           "soil was not found: D k^4 G(k) = 1 has no root "
                           "for the plate's D = " +
                           std::to_string(flexural_rigidity) +
                           "; check the plate's and the layers' moduli."));
    std::uintmax_t iterations = 200;
    const auto     root       = boost::math::tools::toms748_solve(
      excess,
      lower,
      upper,
      f_lower,
      f_upper,
      boost::math::tools::eps_tolerance<double>(40),
      iterations);
    const double s = 0.5 * (root.first + root.second);
    AssertThrow(iterations < 200 && std::abs(excess(s)) < 1e-6,
                ExcMessage("The radius of relative stiffness on the layered "
                           "soil was not found."));
    return std::exp(s);
  }

  double
  LayeredSoil::relative_stiffness(const double flexural_rigidity,
                                  const double length) const
  {
    const double k = 1. / length;
    return flexural_rigidity * std::pow(k, 4) * profile.surface_compliance(k);
  }

  std::string
  LayeredSoil::kernel_report() const
  {
    const std::lock_guard<std::mutex> lock(table_mutex);
    if (!table)
      return {};
    std::ostringstream report;
    report << "Layered soil: kernel tabulated on " << table->n_knots()
           << " knots up to r = " << table->range()
           << ", error <= " << std::max(table->error(), 1e-16)
           << " of alpha1/r + |R(r)| (tolerance " << kernel_tolerance << ") in "
           << table_seconds << " s";
    if (remainder_negligible())
      report << "; R is below the tolerance everywhere, which leaves the top "
                "layer's half-space kernel";
    return report.str();
  }

  std::string
  LayeredSoil::definiteness_advice() const
  {
    // Over cells much wider than h1, alpha1/r and R(r) nearly cancel
    // (a thin layer on a stiff base) and their integrals' errors are not
    // small against the difference (doc/soil-models.md, "Limits").
    std::ostringstream advice;
    advice << "On the layered soil, cells much wider than the top layer ("
           << profile.layers.front().thickness
           << " thick) lose it too: refine the mesh (Discretization/Initial "
              "refinements) until the cells are at most about 3 times as "
              "wide as the top layer, or merge a thin top layer into the "
              "plate or the layer below.";
    return advice.str();
  }
} // namespace PlateOnHalfspace
