#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>

#include <plate_on_halfspace/halfspace/grid_convolution.h>

#include <fftw3.h>

#include <cmath>
#include <mutex>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * The pieces of the cardinal B-spline M_n of order @p n (support
     * [0, n]) as polynomials: coefficients[k * max_order + e] multiplies
     * u^e in M_n(u + k), k < n, 0 <= u < 1. The recursion
     * M_j(x) = (x M_{j-1}(x) + (j - x) M_{j-1}(x - 1)) / (j - 1)
     * run on coefficient arrays.
     */
    void
    cardinal_bspline_polynomials(const unsigned int n, double *coefficients)
    {
      constexpr unsigned int                   m = GridConvolution::max_order;
      std::array<std::array<double, m + 1>, m> p{};
      p[0][1] = 1.; // u
      p[1][0] = 1.; // 1 - u
      p[1][1] = -1.;
      for (unsigned int j = 3; j <= n; ++j)
        {
          const double inverse = 1. / (j - 1);
          p[j - 1].fill(0.);
          for (unsigned int k = j - 1; k > 0; --k)
            {
              // ((u + k) p_k + (j - u - k) p_{k-1}) / (j - 1)
              std::array<double, m + 1> next{};
              for (unsigned int e = 0; e < m; ++e)
                {
                  next[e + 1] += p[k][e] - p[k - 1][e];
                  next[e] += double(k) * p[k][e] + double(j - k) * p[k - 1][e];
                }
              for (double &c : next)
                c *= inverse;
              p[k] = next;
            }
          std::array<double, m + 1> next{};
          for (unsigned int e = 0; e < m; ++e)
            next[e + 1] = p[0][e] * inverse;
          p[0] = next;
        }
      for (unsigned int k = 0; k < n; ++k)
        for (unsigned int e = 0; e < m; ++e)
          coefficients[k * m + e] = p[k][e];
    }

    /**
     * FFTW's planner is not thread-safe, and its threads are set up once
     * per process: plans are made and destroyed under this lock, each for
     * deal.II's thread count (MultithreadInfo::n_threads()).
     */
    std::mutex &
    planner_mutex()
    {
      static std::mutex mutex;
      return mutex;
    }

    void
    plan_with_deal_ii_threads()
    {
      static const bool initialised = fftw_init_threads() != 0;
      AssertThrow(initialised,
                  ExcMessage("GridConvolution: FFTW's threads did not start."));
      fftw_plan_with_nthreads(static_cast<int>(MultithreadInfo::n_threads()));
    }

    /**
     * A plan made by @p make_plan under the planner's lock, executed once
     * and destroyed: the kernel's transforms.
     */
    template <typename MakePlan>
    void
    execute_once(const MakePlan &make_plan)
    {
      fftw_plan plan;
      {
        const std::lock_guard<std::mutex> lock(planner_mutex());
        plan_with_deal_ii_threads();
        plan = make_plan();
      }
      AssertThrow(plan, ExcMessage("GridConvolution: FFTW made no plan."));
      fftw_execute(plan);
      const std::lock_guard<std::mutex> lock(planner_mutex());
      fftw_destroy_plan(plan);
    }

    /**
     * The index on the half of a direction of 2 @p half nodes mirrored
     * about its centre: the nodes half + a and half - 1 - a (a charge and
     * its image) share the index a.
     */
    unsigned int
    half_index(const unsigned int i, const unsigned int half)
    {
      return i >= half ? i - half : half - 1 - i;
    }

    /** The smallest m >= @p n with no prime factor above 7 (fast FFTs). */
    unsigned int
    fast_fft_size(const unsigned int n)
    {
      for (unsigned int m = n;; ++m)
        {
          unsigned int r = m;
          for (const unsigned int f : {2u, 3u, 5u, 7u})
            while (r % f == 0)
              r /= f;
          if (r == 1)
            return m;
        }
    }

    /**
     * Nodes past the largest offset the convolution needs before the
     * padded period wraps. The filter 1 / B(w)^2 has coefficients that
     * fall geometrically (its double poles at the B-spline's roots:
     * about 0.27^k, 0.43^k and 0.54^k for orders 4, 6 and 8); past these
     * margins they are below 1e-12 of the centre one, so the wrapped
     * tail stays below every tolerance the order serves
     * (doc/formulation.md, "Split-kernel FFT storage").
     */
    unsigned int
    filter_margin(const unsigned int order)
    {
      return order <= 4 ? 24 : order <= 6 ? 37 : 50;
    }
  } // namespace

  /**
   * The transforms of convolve(), pruned to the rows that hold data: the
   * rows' transforms over the grid's rows only (the padding rows are zero
   * going in and not wanted coming out), the columns' over all padded
   * rows. @p real holds the folded charges in rows along x (padded[0] to
   * a row), except on the half mirrored in x: there along y. The whole
   * grid's are real-to-complex ones (real rows, complex columns); the
   * quarter's cosine transforms in place on @p real; the half's a real
   * FFT along its rows (the free direction) and cosine transforms along
   * the columns (the mirrored one) on the spectrum's real and imaginary
   * parts alike.
   */
  struct GridConvolution::Plans
  {
    double       *real         = nullptr;
    fftw_complex *spectrum     = nullptr;
    fftw_plan     rows_forward = nullptr, columns_forward = nullptr,
              columns_backward = nullptr, rows_backward = nullptr;
    std::size_t n_real = 0, n_spectrum = 0;
    std::mutex  mutex; ///< the buffers serve one convolution at a time

    /** The buffers: @p reals doubles and @p complexes complex numbers
     *  (none: no spectrum). */
    void
    allocate(const std::size_t reals, const std::size_t complexes)
    {
      n_real     = reals;
      n_spectrum = complexes;
      real       = fftw_alloc_real(n_real);
      if (n_spectrum > 0)
        spectrum = fftw_alloc_complex(n_spectrum);
      AssertThrow(real && (spectrum || n_spectrum == 0),
                  ExcMessage("GridConvolution: out of memory for the FFT."));
    }

    /** The real FFTs of @p rows contiguous rows of @p length, forward
     *  from @p real and back to it (the spectrum's rows length / 2 + 1
     *  apart); under the planner's lock. */
    void
    make_row_ffts(int length, const int rows)
    {
      const int s   = length / 2 + 1;
      rows_forward  = fftw_plan_many_dft_r2c(1,
                                            &length,
                                            rows,
                                            real,
                                            nullptr,
                                            1,
                                            length,
                                            spectrum,
                                            nullptr,
                                            1,
                                            s,
                                            FFTW_ESTIMATE);
      rows_backward = fftw_plan_many_dft_c2r(1,
                                             &length,
                                             rows,
                                             spectrum,
                                             nullptr,
                                             1,
                                             s,
                                             real,
                                             nullptr,
                                             1,
                                             length,
                                             FFTW_ESTIMATE);
    }

    ~Plans()
    {
      const std::lock_guard<std::mutex> lock(planner_mutex());
      for (fftw_plan plan :
           {rows_forward, columns_forward, columns_backward, rows_backward})
        if (plan)
          fftw_destroy_plan(plan);
      fftw_free(real);
      fftw_free(spectrum);
    }
  };

  GridConvolution::GridConvolution(const Point<2>              &centre,
                                   const double                 spacing,
                                   const std::array<double, 2> &half_widths,
                                   const unsigned int           order,
                                   const std::function<double(double)> &kernel,
                                   const std::array<bool, 2> &mirror_images)
    : spline_order(order)
    , h(spacing)
    , mirrored(mirror_images)
    , plans(std::make_unique<Plans>())
  {
    AssertThrow(order >= 4 && order <= max_order && order % 2 == 0,
                ExcMessage("GridConvolution: the spline order must be even, "
                           "from 4 to " +
                           std::to_string(max_order) + "."));
    AssertThrow(spacing > 0 && std::isfinite(spacing),
                ExcMessage("GridConvolution: the spacing must be positive."));
    // The stencil's weights are evaluated in every product rather than
    // stored (136 bytes a Gauss point): weight j is the spline's piece
    // order - 1 - j.
    std::array<double, max_order * max_order> pieces{};
    cardinal_bspline_polynomials(order, pieces.data());
    for (unsigned int j = 0; j < order; ++j)
      for (unsigned int e = 0; e < max_order; ++e)
        weight_polynomials[e * max_order + j] =
          pieces[(order - 1 - j) * max_order + e];
    // Nodes centre + (i - (n-1)/2) h, enough that every stencil of a point
    // within the half widths lies on the grid.
    for (unsigned int d = 0; d < 2; ++d)
      {
        const double cells = 2. * half_widths[d] / h + order + 2;
        AssertThrow(cells < 1e8,
                    ExcMessage("GridConvolution: the grid is too large."));
        n[d] = static_cast<unsigned int>(std::ceil(cells)) + 1;
        // the cosine transforms' even sequences about the point between
        // the two middle nodes (REDFT10)
        if (mirrored[d] && n[d] % 2 == 1)
          ++n[d];
        origin[d] = centre[d] - 0.5 * (n[d] - 1) * h;
        // Hockney: offsets up to n - 1 either way without wrapping, and a
        // margin where the filter's tail would wrap. The cosine
        // transforms' period is twice their length.
        const unsigned int margin = filter_margin(order);
        padded[d]                 = mirrored[d] ? fast_fft_size(n[d] + margin) :
                                                  fast_fft_size(2 * (n[d] + margin));
      }
    if (mirrored[0] && mirrored[1])
      make_quarter_plans(kernel);
    else if (mirrored[0] || mirrored[1])
      make_half_plans(kernel);
    else
      make_whole_plans(kernel);
  }

  void
  GridConvolution::make_whole_plans(const std::function<double(double)> &kernel)
  {
    // FFTW's row-major 2D layout: y the slow index, x the fast one.
    const unsigned int px = padded[0], py = padded[1], sx = px / 2 + 1;
    plans->allocate(std::size_t(px) * py, std::size_t(sx) * py);
    // FFTW_ESTIMATE: the same plans, so the same rounding, on every run
    // with the same number of threads.
    {
      const std::lock_guard<std::mutex> lock(planner_mutex());
      plan_with_deal_ii_threads();
      int       length_y = py;
      const int columns  = sx;
      plans->make_row_ffts(px, n[1]);
      const auto columns_plan = [&](const int direction) {
        return fftw_plan_many_dft(1,
                                  &length_y,
                                  columns,
                                  plans->spectrum,
                                  nullptr,
                                  sx,
                                  1,
                                  plans->spectrum,
                                  nullptr,
                                  sx,
                                  1,
                                  direction,
                                  FFTW_ESTIMATE);
      };
      plans->columns_forward  = columns_plan(FFTW_FORWARD);
      plans->columns_backward = columns_plan(FFTW_BACKWARD);
      AssertThrow(plans->rows_forward && plans->columns_forward &&
                    plans->columns_backward && plans->rows_backward,
                  ExcMessage("GridConvolution: FFTW made no plan."));
    }

    // The kernel's samples at the circular offsets, transformed once over
    // all rows (the samples fill them).
    for (unsigned int j = 0; j < py; ++j)
      for (unsigned int i = 0; i < px; ++i)
        {
          const double dx = (i <= px / 2) ? double(i) : double(i) - px;
          const double dy = (j <= py / 2) ? double(j) : double(j) - py;
          plans->real[std::size_t(j) * px + i] = kernel(h * std::hypot(dx, dy));
        }
    execute_once([&]() {
      return fftw_plan_dft_r2c_2d(
        py, px, plans->real, plans->spectrum, FFTW_ESTIMATE);
    });
    kernel_transform.resize(plans->n_spectrum);
    const std::vector<double> bx = spline_symbols(sx, px),
                              by = spline_symbols(py, py);
    const double scale = 1. / (double(px) * py); // FFTW's unnormalised pair
    for (unsigned int j = 0; j < py; ++j)
      for (unsigned int i = 0; i < sx; ++i)
        {
          const std::size_t k = std::size_t(j) * sx + i;
          const double      b = bx[i] * by[j];
          kernel_transform[k] = scale * plans->spectrum[k][0] / (b * b);
        }
  }

  void
  GridConvolution::make_quarter_plans(
    const std::function<double(double)> &kernel)
  {
    // The quarter of nodes nx/2 + a, ny/2 + b, padded to the transforms'
    // lengths; y the slow index, x the fast one.
    const unsigned int mx = padded[0], my = padded[1];
    plans->allocate(std::size_t(mx) * my, 0);
    {
      const std::lock_guard<std::mutex> lock(planner_mutex());
      plan_with_deal_ii_threads();
      const fftw_r2r_kind even = FFTW_REDFT10, inverse = FFTW_REDFT01;
      // @p count transforms of @p length in place on the quarter, the
      // entries @p stride apart, the transforms @p distance apart
      const auto in_place = [&](int                  length,
                                const int            count,
                                const int            stride,
                                const int            distance,
                                const fftw_r2r_kind &kind) {
        return fftw_plan_many_r2r(1,
                                  &length,
                                  count,
                                  plans->real,
                                  nullptr,
                                  stride,
                                  distance,
                                  plans->real,
                                  nullptr,
                                  stride,
                                  distance,
                                  &kind,
                                  FFTW_ESTIMATE);
      };
      // the rows that hold the quarter's nodes; all columns
      const int rows          = n[1] / 2;
      plans->rows_forward     = in_place(mx, rows, 1, mx, even);
      plans->columns_forward  = in_place(my, mx, mx, 1, even);
      plans->columns_backward = in_place(my, mx, mx, 1, inverse);
      plans->rows_backward    = in_place(mx, rows, 1, mx, inverse);
      AssertThrow(plans->rows_forward && plans->columns_forward &&
                    plans->columns_backward && plans->rows_backward,
                  ExcMessage("GridConvolution: FFTW made no plan."));
    }

    // The DFT of the kernel's samples over the period 2 m is, the samples
    // being even, the type-I cosine transform (REDFT00) of offsets 0 … m.
    std::vector<double> samples(std::size_t(mx + 1) * (my + 1));
    for (unsigned int j = 0; j <= my; ++j)
      for (unsigned int i = 0; i <= mx; ++i)
        samples[std::size_t(j) * (mx + 1) + i] =
          kernel(h * std::hypot(double(i), double(j)));
    execute_once([&]() {
      return fftw_plan_r2r_2d(my + 1,
                              mx + 1,
                              samples.data(),
                              samples.data(),
                              FFTW_REDFT00,
                              FFTW_REDFT00,
                              FFTW_ESTIMATE);
    });
    kernel_transform.resize(plans->n_real);
    const std::vector<double> bx = spline_symbols(mx, 2 * mx),
                              by = spline_symbols(my, 2 * my);
    // REDFT10 then REDFT01 multiply by twice the length each way
    const double scale = 1. / (4. * double(mx) * my);
    for (unsigned int j = 0; j < my; ++j)
      for (unsigned int i = 0; i < mx; ++i)
        {
          const double b = bx[i] * by[j];
          kernel_transform[std::size_t(j) * mx + i] =
            scale * samples[std::size_t(j) * (mx + 1) + i] / (b * b);
        }
  }

  void
  GridConvolution::make_half_plans(const std::function<double(double)> &kernel)
  {
    // e the mirrored direction (cosine transforms of length m on its
    // half), f the free one (real FFT of length p, s complex entries).
    // The buffers' rows run along f whichever it is, so that the real
    // FFTs are contiguous: real rows x p, the spectrum m x s.
    const unsigned int e = mirrored[0] ? 0 : 1, f = 1 - e;
    const unsigned int m = padded[e], p = padded[f], s = p / 2 + 1;
    const int          rows = n[e] / 2;
    plans->allocate(std::size_t(rows) * p, std::size_t(m) * s);
    {
      const std::lock_guard<std::mutex> lock(planner_mutex());
      plan_with_deal_ii_threads();
      int           length_m = m;
      double *const parts    = &plans->spectrum[0][0];
      // rows: real FFTs of the half's rows; columns: cosine transforms of
      // the spectrum's real and imaginary parts (2 s sequences)
      plans->make_row_ffts(p, rows);
      const auto columns_plan = [&](const fftw_r2r_kind &kind) {
        return fftw_plan_many_r2r(1,
                                  &length_m,
                                  2 * s,
                                  parts,
                                  nullptr,
                                  2 * s,
                                  1,
                                  parts,
                                  nullptr,
                                  2 * s,
                                  1,
                                  &kind,
                                  FFTW_ESTIMATE);
      };
      plans->columns_forward  = columns_plan(FFTW_REDFT10);
      plans->columns_backward = columns_plan(FFTW_REDFT01);
      AssertThrow(plans->rows_forward && plans->columns_forward &&
                    plans->columns_backward && plans->rows_backward,
                  ExcMessage("GridConvolution: FFTW made no plan."));
    }

    // The kernel's samples at offsets 0 … m along e (their DFT over the
    // period 2 m is the type-I cosine transform) and at the circular
    // offsets along f (an even sequence: its DFT is real), rows along f.
    std::vector<double> samples(std::size_t(m + 1) * p);
    for (unsigned int a = 0; a <= m; ++a)
      for (unsigned int k = 0; k < p; ++k)
        {
          const double offset = (k <= p / 2) ? double(k) : double(k) - p;
          samples[std::size_t(a) * p + k] =
            kernel(h * std::hypot(double(a), offset));
        }
    execute_once([&]() {
      int                 length = m + 1;
      const fftw_r2r_kind kind   = FFTW_REDFT00;
      return fftw_plan_many_r2r(1,
                                &length,
                                p,
                                samples.data(),
                                nullptr,
                                p,
                                1,
                                samples.data(),
                                nullptr,
                                p,
                                1,
                                &kind,
                                FFTW_ESTIMATE);
    });
    // The real FFTs of the m rows used, into the plans' spectrum, which
    // the convolutions overwrite.
    execute_once([&]() {
      int length = p;
      return fftw_plan_many_dft_r2c(1,
                                    &length,
                                    m,
                                    samples.data(),
                                    nullptr,
                                    1,
                                    p,
                                    plans->spectrum,
                                    nullptr,
                                    1,
                                    s,
                                    FFTW_ESTIMATE);
    });
    kernel_transform.resize(plans->n_spectrum);
    const std::vector<double> b_e = spline_symbols(m, 2 * m),
                              b_f = spline_symbols(s, p);
    // REDFT10 then REDFT01 multiply by 2 m, the real FFT's pair by p
    const double scale = 1. / (2. * double(m) * p);
    for (unsigned int a = 0; a < m; ++a)
      for (unsigned int k = 0; k < s; ++k)
        {
          const std::size_t entry = std::size_t(a) * s + k;
          const double      b     = b_e[a] * b_f[k];
          kernel_transform[entry] = scale * plans->spectrum[entry][0] / (b * b);
        }
  }

  std::vector<double>
  GridConvolution::spline_symbols(const unsigned int count,
                                  const unsigned int period) const
  {
    // The B-splines' symbol B(w) = sum_m M(m) e^{-i w m} (real, positive
    // for an even order), from the samples at the integers M_n(k), k < n:
    // the pieces' constant terms (stored as weights order - 1 - k).
    std::array<double, max_order> samples;
    for (unsigned int k = 0; k < spline_order; ++k)
      samples[k] = weight_polynomials[spline_order - 1 - k];
    std::vector<double> symbols(count);
    for (unsigned int i = 0; i < count; ++i)
      {
        const double w = 2 * M_PI * i / period;
        // centred: offsets k - n/2
        double sum = 0;
        for (unsigned int k = 1; k < spline_order; ++k)
          sum += samples[k] * std::cos(w * (double(k) - 0.5 * spline_order));
        symbols[i] = sum;
      }
    return symbols;
  }

  GridConvolution::~GridConvolution() = default;

  namespace
  {
    /**
     * The @p P weights at offset @p u by Horner's rule, all weights at
     * once, power by power: independent lanes with a fixed count, which
     * the compiler unrolls and vectorises (coefficients as in
     * GridConvolution::weight_polynomials).
     */
    template <unsigned int P>
    void
    spline_weights(const double u, const double *coefficients, double *weights)
    {
      constexpr unsigned int m = GridConvolution::max_order;
      double                 w[P];
      for (unsigned int j = 0; j < P; ++j)
        w[j] = coefficients[(P - 1) * m + j];
      for (unsigned int e = P - 1; e-- > 0;)
        for (unsigned int j = 0; j < P; ++j)
          w[j] = w[j] * u + coefficients[e * m + j];
      for (unsigned int j = 0; j < P; ++j)
        weights[j] = w[j];
    }
  } // namespace

  int
  GridConvolution::stencil_1d(const double       x,
                              const unsigned int d,
                              double            *weights) const
  {
    // t > 0: every point lies inside the grid (constructor)
    const double t    = (x - origin[d]) / h;
    const int    cell = static_cast<int>(t);
    const double u    = t - cell;
    // node cell + n/2 - k has the weight M_n(u + k) (constructor)
    switch (spline_order)
      {
        case 4:
          spline_weights<4>(u, weight_polynomials.data(), weights);
          break;
        case 6:
          spline_weights<6>(u, weight_polynomials.data(), weights);
          break;
        default:
          Assert(spline_order == 8, ExcInternalError());
          spline_weights<8>(u, weight_polynomials.data(), weights);
      }
    const int first = cell - int(spline_order / 2) + 1;
    Assert(t > 0 && first >= 0 && first + spline_order <= n[d],
           ExcInternalError());
    return first;
  }

  GridConvolution::Stencil
  GridConvolution::stencil(const Point<2> &x) const
  {
    Stencil s;
    s.first_x = stencil_1d(x[0], 0, s.x.data());
    s.first_y = stencil_1d(x[1], 1, s.y.data());
    return s;
  }

  void
  GridConvolution::convolve(const Vector<double> &charges,
                            Vector<double>       &potentials) const
  {
    AssertDimension(charges.size(), n_grid_nodes());
    const std::lock_guard<std::mutex> lock(plans->mutex);
    const unsigned int                hx = n[0] / 2, hy = n[1] / 2;
    // The buffer's rows run along x, except on the half mirrored in x
    // (make_half_plans()): there along y. A grid node's place in it lies
    // on the half in a mirrored direction, where a charge meets its image.
    const bool         along_y    = mirrored[0] && !mirrored[1];
    const unsigned int row_length = padded[along_y ? 1 : 0];
    const unsigned int rows       = along_y ? hx : (mirrored[1] ? hy : n[1]);
    const auto         place = [&](const unsigned int i, const unsigned int j) {
      const unsigned int a = mirrored[0] ? half_index(i, hx) : i,
                         b = mirrored[1] ? half_index(j, hy) : j;
      return along_y ? std::size_t(a) * row_length + b :
                               std::size_t(b) * row_length + a;
    };
    std::fill(plans->real, plans->real + std::size_t(rows) * row_length, 0.);
    for (unsigned int j = 0; j < n[1]; ++j)
      for (unsigned int i = 0; i < n[0]; ++i)
        plans->real[place(i, j)] += charges[std::size_t(j) * n[0] + i];
    fftw_execute(plans->rows_forward);
    // The padding rows going into the columns' transforms are zero: the
    // spectrum's rows, or on the quarter the real rows.
    if (plans->spectrum)
      std::fill(&plans->spectrum[std::size_t(rows) * (row_length / 2 + 1)][0],
                &plans->spectrum[0][0] + 2 * plans->n_spectrum,
                0.);
    else
      std::fill(plans->real + std::size_t(rows) * row_length,
                plans->real + plans->n_real,
                0.);
    fftw_execute(plans->columns_forward);
    if (plans->spectrum)
      for (std::size_t k = 0; k < plans->n_spectrum; ++k)
        {
          plans->spectrum[k][0] *= kernel_transform[k];
          plans->spectrum[k][1] *= kernel_transform[k];
        }
    else
      for (std::size_t k = 0; k < plans->n_real; ++k)
        plans->real[k] *= kernel_transform[k];
    fftw_execute(plans->columns_backward);
    fftw_execute(plans->rows_backward);
    if (potentials.size() != n_grid_nodes())
      potentials.reinit(n_grid_nodes(), true);
    for (unsigned int j = 0; j < n[1]; ++j)
      for (unsigned int i = 0; i < n[0]; ++i)
        potentials[std::size_t(j) * n[0] + i] = plans->real[place(i, j)];
  }

  std::size_t
  GridConvolution::memory_consumption() const
  {
    return kernel_transform.size() * sizeof(double) +
           plans->n_real * sizeof(double) +
           plans->n_spectrum * sizeof(fftw_complex);
  }
} // namespace PlateOnHalfspace
