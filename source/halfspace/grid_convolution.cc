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
  } // namespace

  /**
   * The transforms of convolve(), pruned to the rows that hold data: the
   * rows' real transforms over the grid's n[1] rows only (the padding
   * rows are zero going in and not wanted coming out), the columns'
   * complex ones over all padded rows.
   */
  struct GridConvolution::Plans
  {
    double       *real         = nullptr;
    fftw_complex *spectrum     = nullptr;
    fftw_plan     rows_forward = nullptr, columns_forward = nullptr,
              columns_backward = nullptr, rows_backward = nullptr;
    std::size_t n_real = 0, n_spectrum = 0;
    std::mutex  mutex; ///< the buffers serve one convolution at a time

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
                                   const std::function<double(double)> &kernel)
    : spline_order(order)
    , h(spacing)
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
        n[d]      = static_cast<unsigned int>(std::ceil(cells)) + 1;
        origin[d] = centre[d] - 0.5 * (n[d] - 1) * h;
        // Hockney: offsets up to n - 1 either way without wrapping, and a
        // margin where the filter's tail wraps.
        padded[d] = fast_fft_size(2 * n[d] + 4 * order + 16);
      }

    // FFTW's row-major 2D layout: y the slow index, x the fast one.
    const unsigned int px = padded[0], py = padded[1], sx = px / 2 + 1;
    plans->n_real     = std::size_t(px) * py;
    plans->n_spectrum = std::size_t(sx) * py;
    plans->real       = fftw_alloc_real(plans->n_real);
    plans->spectrum   = fftw_alloc_complex(plans->n_spectrum);
    AssertThrow(plans->real && plans->spectrum,
                ExcMessage("GridConvolution: out of memory for the FFT."));
    // FFTW_ESTIMATE: the same plans, so the same rounding, on every run
    // with the same number of threads.
    {
      const std::lock_guard<std::mutex> lock(planner_mutex());
      plan_with_deal_ii_threads();
      int       length_x = px, length_y = py;
      const int rows = n[1], columns = sx;
      plans->rows_forward     = fftw_plan_many_dft_r2c(1,
                                                   &length_x,
                                                   rows,
                                                   plans->real,
                                                   nullptr,
                                                   1,
                                                   px,
                                                   plans->spectrum,
                                                   nullptr,
                                                   1,
                                                   sx,
                                                   FFTW_ESTIMATE);
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
      plans->rows_backward    = fftw_plan_many_dft_c2r(1,
                                                    &length_x,
                                                    rows,
                                                    plans->spectrum,
                                                    nullptr,
                                                    1,
                                                    sx,
                                                    plans->real,
                                                    nullptr,
                                                    1,
                                                    px,
                                                    FFTW_ESTIMATE);
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
    {
      fftw_plan whole;
      {
        const std::lock_guard<std::mutex> lock(planner_mutex());
        plan_with_deal_ii_threads();
        whole = fftw_plan_dft_r2c_2d(
          py, px, plans->real, plans->spectrum, FFTW_ESTIMATE);
      }
      AssertThrow(whole, ExcMessage("GridConvolution: FFTW made no plan."));
      fftw_execute(whole);
      const std::lock_guard<std::mutex> lock(planner_mutex());
      fftw_destroy_plan(whole);
    }

    // The B-splines' symbol B(w) = sum_m M(m) e^{-i w m} (real, positive
    // for an even order), from the samples at the integers.
    // M_n(k), k < n: the pieces' constant terms (stored as weights
    // order - 1 - k)
    std::array<double, max_order> samples;
    for (unsigned int k = 0; k < order; ++k)
      samples[k] = weight_polynomials[order - 1 - k];
    const auto symbol = [&](const double w) {
      // centred: offsets k - n/2
      double sum = 0;
      for (unsigned int k = 1; k < order; ++k)
        sum += samples[k] * std::cos(w * (double(k) - 0.5 * order));
      return sum;
    };
    std::vector<double> bx(sx), by(py);
    for (unsigned int i = 0; i < sx; ++i)
      bx[i] = symbol(2 * M_PI * i / px);
    for (unsigned int j = 0; j < py; ++j)
      by[j] = symbol(2 * M_PI * j / py);
    kernel_transform.resize(plans->n_spectrum);
    const double scale = 1. / (double(px) * py); // FFTW's unnormalised pair
    for (unsigned int j = 0; j < py; ++j)
      for (unsigned int i = 0; i < sx; ++i)
        {
          const std::size_t k = std::size_t(j) * sx + i;
          const double      b = bx[i] * by[j];
          kernel_transform[k] = scale * plans->spectrum[k][0] / (b * b);
        }
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
  GridConvolution::add_reflections(
    Vector<double>                           &field,
    const std::vector<std::array<double, 2>> &reflections) const
  {
    AssertDimension(field.size(), n_grid_nodes());
    if (reflections.empty())
      return;
    const Vector<double> original = field;
    for (const auto &sign : reflections)
      for (unsigned int j = 0; j < n[1]; ++j)
        {
          const unsigned int from_j = sign[1] < 0 ? n[1] - 1 - j : j;
          for (unsigned int i = 0; i < n[0]; ++i)
            {
              const unsigned int from_i = sign[0] < 0 ? n[0] - 1 - i : i;
              field[std::size_t(j) * n[0] + i] +=
                original[std::size_t(from_j) * n[0] + from_i];
            }
        }
  }

  void
  GridConvolution::convolve(const Vector<double> &charges,
                            Vector<double>       &potentials) const
  {
    AssertDimension(charges.size(), n_grid_nodes());
    const std::lock_guard<std::mutex> lock(plans->mutex);
    const unsigned int                px = padded[0], sx = px / 2 + 1;
    // The grid's rows, zero-padded in x; the padding rows are not read.
    for (unsigned int j = 0; j < n[1]; ++j)
      {
        double *row = plans->real + std::size_t(j) * px;
        std::copy(charges.begin() + std::size_t(j) * n[0],
                  charges.begin() + std::size_t(j + 1) * n[0],
                  row);
        std::fill(row + n[0], row + px, 0.);
      }
    fftw_execute(plans->rows_forward);
    // The padding rows' spectra are those of zero rows.
    std::fill(plans->spectrum[std::size_t(n[1]) * sx],
              plans->spectrum[0] + 2 * plans->n_spectrum,
              0.);
    fftw_execute(plans->columns_forward);
    for (std::size_t k = 0; k < plans->n_spectrum; ++k)
      {
        plans->spectrum[k][0] *= kernel_transform[k];
        plans->spectrum[k][1] *= kernel_transform[k];
      }
    fftw_execute(plans->columns_backward);
    fftw_execute(plans->rows_backward);
    if (potentials.size() != n_grid_nodes())
      potentials.reinit(n_grid_nodes(), true);
    for (unsigned int j = 0; j < n[1]; ++j)
      std::copy(plans->real + std::size_t(j) * px,
                plans->real + std::size_t(j) * px + n[0],
                potentials.begin() + std::size_t(j) * n[0]);
  }

  std::size_t
  GridConvolution::memory_consumption() const
  {
    return kernel_transform.size() * sizeof(double) +
           plans->n_real * sizeof(double) +
           plans->n_spectrum * sizeof(fftw_complex);
  }
} // namespace PlateOnHalfspace
