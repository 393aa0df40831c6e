#include <deal.II/base/exceptions.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/partitioner.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/halfspace/grid_convolution.h>

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <tuple>

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

    /** An FFTW buffer of @p n entries of type T, freed with its owner
     *  (fftw_malloc's alignment: the kernel's transforms are planned on
     *  such buffers on one process as on several). */
    template <typename T>
    std::unique_ptr<T[], void (*)(void *)>
    fftw_buffer(const std::size_t n)
    {
      std::unique_ptr<T[], void (*)(void *)> buffer(
        static_cast<T *>(fftw_malloc(n * sizeof(T))), fftw_free);
      AssertThrow(buffer,
                  ExcMessage("GridConvolution: out of memory for the FFT."));
      return buffer;
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
   * rows. @p real holds the folded charges in rows along x (row_length to
   * a row), except on the half mirrored in x: there along y. The whole
   * grid's are real-to-complex ones (real rows, complex columns); the
   * quarter's cosine transforms in place; the half's a real FFT along its
   * rows (the free direction) and cosine transforms along the columns (the
   * mirrored one) on the spectrum's real and imaginary parts alike.
   *
   * On one rank the rows' transforms write into the first rows of the
   * columns' buffer. On several, rank r transforms the data rows
   * row_starts[r] … row_starts[r + 1] - 1 and the spectrum's columns
   * column_starts[r] … column_starts[r + 1] - 1, and two all-to-all
   * exchanges move the rows' spectra to the columns' owners and back.
   */
  struct GridConvolution::Plans
  {
    /** Rows that hold data, reals to a row, spectrum entries to a row
     *  (the columns), doubles to an entry (2: complex), and the columns'
     *  transform length. */
    unsigned int rows = 0, row_length = 0, columns = 0, width = 1,
                 column_length     = 0;
    unsigned int              rank = 0, n_ranks = 1;
    std::vector<unsigned int> row_starts, column_starts;

    /** This rank's rows × row_length reals. */
    double *real = nullptr;
    /** This rank's rows of the spectrum (columns × width doubles each);
     *  on one rank the first rows of @p column_data, in the quarter
     *  @p real itself. */
    double *row_spectrum = nullptr;
    /** column_length rows of this rank's columns × width doubles. */
    double   *column_data  = nullptr;
    fftw_plan rows_forward = nullptr, columns_forward = nullptr,
              columns_backward = nullptr, rows_backward = nullptr;
    std::size_t n_real = 0, n_row_spectrum = 0, n_column_data = 0;
    /** The transposes' counts and offsets (doubles), per rank: rows to
     *  columns (send, receive), the way back swaps them. */
    std::vector<int> to_columns_send_counts, to_columns_send_offsets,
      to_columns_receive_counts, to_columns_receive_offsets;
    std::vector<double> exchange;
    /** The footprint's places in @p folded (its local indices), whose
     *  owned part is this rank's data rows. */
    std::vector<unsigned int>                          footprint;
    bool                                               footprint_set = false;
    std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
    LinearAlgebra::distributed::Vector<double>         folded;
    std::mutex mutex; ///< the buffers serve one convolution at a time

    unsigned int
    my_rows() const
    {
      return row_starts[rank + 1] - row_starts[rank];
    }

    unsigned int
    my_columns() const
    {
      return column_starts[rank + 1] - column_starts[rank];
    }

    bool
    split() const
    {
      return n_ranks > 1;
    }

    /** The layout and this rank's share of it. */
    void
    set_layout(const MPI_Comm     communicator,
               const unsigned int data_rows,
               const unsigned int length,
               const unsigned int spectrum_columns,
               const unsigned int entry_width,
               const unsigned int transform_length)
    {
      rows          = data_rows;
      row_length    = length;
      columns       = spectrum_columns;
      width         = entry_width;
      column_length = transform_length;
      n_ranks       = PlateOnHalfspace::n_ranks(communicator);
      rank          = rank_in(communicator);
      row_starts.resize(n_ranks + 1);
      column_starts.resize(n_ranks + 1);
      for (unsigned int r = 0; r <= n_ranks; ++r)
        {
          row_starts[r]    = (std::uint64_t(rows) * r) / n_ranks;
          column_starts[r] = (std::uint64_t(columns) * r) / n_ranks;
        }
    }

    /** The buffers of set_layout()'s share. */
    void
    allocate()
    {
      n_column_data = std::size_t(column_length) * my_columns() * width;
      column_data   = fftw_alloc_real(std::max<std::size_t>(n_column_data, 1));
      if (!split())
        {
          row_spectrum = column_data;
          n_real       = std::size_t(rows) * row_length;
          real         = width == 1 ? column_data :
                                      fftw_alloc_real(std::max<std::size_t>(n_real, 1));
        }
      else
        {
          n_real         = std::size_t(my_rows()) * row_length;
          real           = fftw_alloc_real(std::max<std::size_t>(n_real, 1));
          n_row_spectrum = std::size_t(my_rows()) * columns * width;
          row_spectrum =
            width == 1 ?
              real :
              fftw_alloc_real(std::max<std::size_t>(n_row_spectrum, 1));
          make_exchange_layout();
        }
      AssertThrow(column_data && real && row_spectrum,
                  ExcMessage("GridConvolution: out of memory for the FFT."));
    }

    /** The transposes' counts: my rows × each rank's columns out, each
     *  rank's rows × my columns in, straight into column_data's rows. */
    void
    make_exchange_layout()
    {
      const auto as_int = [](const std::size_t n) {
        AssertThrow(n <= std::size_t(std::numeric_limits<int>::max()),
                    ExcMessage("GridConvolution: a slab exchange larger "
                               "than one MPI message holds; run on more "
                               "processes."));
        return static_cast<int>(n);
      };
      to_columns_send_counts.resize(n_ranks);
      to_columns_send_offsets.resize(n_ranks);
      to_columns_receive_counts.resize(n_ranks);
      to_columns_receive_offsets.resize(n_ranks);
      std::size_t at = 0;
      for (unsigned int t = 0; t < n_ranks; ++t)
        {
          const std::size_t n = std::size_t(my_rows()) *
                                (column_starts[t + 1] - column_starts[t]) *
                                width;
          to_columns_send_offsets[t] = as_int(at);
          to_columns_send_counts[t]  = as_int(n);
          at += n;
          to_columns_receive_offsets[t] =
            as_int(std::size_t(row_starts[t]) * my_columns() * width);
          to_columns_receive_counts[t] =
            as_int(std::size_t(row_starts[t + 1] - row_starts[t]) *
                   my_columns() * width);
        }
      exchange.resize(at);
    }

    /** The rows' spectra to the columns' owners (data rows only; the
     *  padding rows are zeroed by the caller). */
    void
    transpose_to_columns(const MPI_Comm communicator)
    {
      const std::size_t stride = std::size_t(columns) * width;
      for (unsigned int t = 0; t < n_ranks; ++t)
        {
          const std::size_t n =
            std::size_t(column_starts[t + 1] - column_starts[t]) * width;
          double *out = exchange.data() + to_columns_send_offsets[t];
          for (unsigned int r = 0; r < my_rows(); ++r, out += n)
            std::copy_n(row_spectrum + r * stride +
                          std::size_t(column_starts[t]) * width,
                        n,
                        out);
        }
      const int error = MPI_Alltoallv(exchange.data(),
                                      to_columns_send_counts.data(),
                                      to_columns_send_offsets.data(),
                                      MPI_DOUBLE,
                                      column_data,
                                      to_columns_receive_counts.data(),
                                      to_columns_receive_offsets.data(),
                                      MPI_DOUBLE,
                                      communicator);
      AssertThrowMPI(error);
    }

    /** The data rows of this rank's columns back to the rows' owners. */
    void
    transpose_to_rows(const MPI_Comm communicator)
    {
      const int error = MPI_Alltoallv(column_data,
                                      to_columns_receive_counts.data(),
                                      to_columns_receive_offsets.data(),
                                      MPI_DOUBLE,
                                      exchange.data(),
                                      to_columns_send_counts.data(),
                                      to_columns_send_offsets.data(),
                                      MPI_DOUBLE,
                                      communicator);
      AssertThrowMPI(error);
      const std::size_t stride = std::size_t(columns) * width;
      for (unsigned int t = 0; t < n_ranks; ++t)
        {
          const std::size_t n =
            std::size_t(column_starts[t + 1] - column_starts[t]) * width;
          const double *in = exchange.data() + to_columns_send_offsets[t];
          for (unsigned int r = 0; r < my_rows(); ++r, in += n)
            std::copy_n(in,
                        n,
                        row_spectrum + r * stride +
                          std::size_t(column_starts[t]) * width);
        }
    }

    /** The real FFTs of this rank's rows of @p length, forward from
     *  @p real into @p row_spectrum and back; under the planner's lock. */
    void
    make_row_ffts(int length)
    {
      if (my_rows() == 0)
        return;
      const int s   = length / 2 + 1;
      auto     *out = reinterpret_cast<fftw_complex *>(row_spectrum);
      rows_forward  = fftw_plan_many_dft_r2c(1,
                                            &length,
                                            my_rows(),
                                            real,
                                            nullptr,
                                            1,
                                            length,
                                            out,
                                            nullptr,
                                            1,
                                            s,
                                            FFTW_ESTIMATE);
      rows_backward = fftw_plan_many_dft_c2r(1,
                                             &length,
                                             my_rows(),
                                             out,
                                             nullptr,
                                             1,
                                             s,
                                             real,
                                             nullptr,
                                             1,
                                             length,
                                             FFTW_ESTIMATE);
    }

    /** @p count in-place cosine transforms of @p length on @p data, the
     *  entries @p stride apart, the transforms @p distance apart, each
     *  way; under the planner's lock. */
    static std::pair<fftw_plan, fftw_plan>
    cosine_pair(double   *data,
                int       length,
                const int count,
                const int stride,
                const int distance)
    {
      if (count == 0)
        return {nullptr, nullptr};
      const auto in_place = [&](const fftw_r2r_kind kind) {
        return fftw_plan_many_r2r(1,
                                  &length,
                                  count,
                                  data,
                                  nullptr,
                                  stride,
                                  distance,
                                  data,
                                  nullptr,
                                  stride,
                                  distance,
                                  &kind,
                                  FFTW_ESTIMATE);
      };
      return {in_place(FFTW_REDFT10), in_place(FFTW_REDFT01)};
    }

    /** Every plan that this rank's share needs was made. */
    void
    check_plans() const
    {
      AssertThrow((my_rows() == 0 || (rows_forward && rows_backward)) &&
                    (my_columns() == 0 ||
                     (columns_forward && columns_backward)),
                  ExcMessage("GridConvolution: FFTW made no plan."));
    }

    ~Plans()
    {
      const std::lock_guard<std::mutex> lock(planner_mutex());
      for (fftw_plan plan :
           {rows_forward, columns_forward, columns_backward, rows_backward})
        if (plan)
          fftw_destroy_plan(plan);
      if (row_spectrum != column_data && row_spectrum != real)
        fftw_free(row_spectrum);
      if (real != column_data)
        fftw_free(real);
      fftw_free(column_data);
    }
  };

  GridConvolution::GridConvolution(const Point<2>              &centre,
                                   const double                 spacing,
                                   const std::array<double, 2> &half_widths,
                                   const unsigned int           order,
                                   const std::function<double(double)> &kernel,
                                   const std::array<bool, 2> &mirror_images,
                                   const MPI_Comm             communicator)
    : spline_order(order)
    , h(spacing)
    , mirrored(mirror_images)
    , communicator(communicator)
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
    plans->set_layout(communicator, n[1], px, sx, 2, py);
    const unsigned int columns = plans->my_columns(),
                       first   = plans->column_starts[plans->rank];

    // The kernel's samples at the circular offsets, transformed once over
    // all rows (the samples fill them); every rank transforms them whole
    // and keeps its columns. Before the convolutions' buffers exist, so
    // that the two do not add up.
    {
      const auto samples  = fftw_buffer<double>(std::size_t(px) * py);
      const auto spectrum = fftw_buffer<fftw_complex>(std::size_t(sx) * py);
      for (unsigned int j = 0; j < py; ++j)
        for (unsigned int i = 0; i < px; ++i)
          {
            const double dx = (i <= px / 2) ? double(i) : double(i) - px;
            const double dy = (j <= py / 2) ? double(j) : double(j) - py;
            samples[std::size_t(j) * px + i] = kernel(h * std::hypot(dx, dy));
          }
      execute_once([&]() {
        return fftw_plan_dft_r2c_2d(
          py, px, samples.get(), spectrum.get(), FFTW_ESTIMATE);
      });
      const std::vector<double> bx = spline_symbols(sx, px),
                                by = spline_symbols(py, py);
      const double scale = 1. / (double(px) * py); // FFTW's unnormalised pair
      kernel_transform.resize(std::size_t(py) * columns);
      for (unsigned int j = 0; j < py; ++j)
        for (unsigned int c = 0; c < columns; ++c)
          {
            const unsigned int i = first + c;
            const double       b = bx[i] * by[j];
            kernel_transform[std::size_t(j) * columns + c] =
              scale * spectrum[std::size_t(j) * sx + i][0] / (b * b);
          }
    }

    plans->allocate();
    // FFTW_ESTIMATE: the same plans, so the same rounding, on every run
    // with the same number of threads.
    const std::lock_guard<std::mutex> lock(planner_mutex());
    plan_with_deal_ii_threads();
    int length_y = py;
    plans->make_row_ffts(px);
    auto *const data = reinterpret_cast<fftw_complex *>(plans->column_data);
    const auto  columns_plan = [&](const int direction) {
      return fftw_plan_many_dft(1,
                                &length_y,
                                columns,
                                data,
                                nullptr,
                                columns,
                                1,
                                data,
                                nullptr,
                                columns,
                                1,
                                direction,
                                FFTW_ESTIMATE);
    };
    if (columns > 0)
      {
        plans->columns_forward  = columns_plan(FFTW_FORWARD);
        plans->columns_backward = columns_plan(FFTW_BACKWARD);
      }
    plans->check_plans();
  }

  void
  GridConvolution::make_quarter_plans(
    const std::function<double(double)> &kernel)
  {
    // The quarter of nodes nx/2 + a, ny/2 + b, padded to the transforms'
    // lengths; y the slow index, x the fast one.
    const unsigned int mx = padded[0], my = padded[1];
    plans->set_layout(communicator, n[1] / 2, mx, mx, 1, my);
    const unsigned int columns = plans->my_columns(),
                       first   = plans->column_starts[plans->rank];

    // The DFT of the kernel's samples over the period 2 m is, the samples
    // being even, the type-I cosine transform (REDFT00) of offsets 0 … m.
    {
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
      const std::vector<double> bx = spline_symbols(mx, 2 * mx),
                                by = spline_symbols(my, 2 * my);
      // REDFT10 then REDFT01 multiply by twice the length each way
      const double scale = 1. / (4. * double(mx) * my);
      kernel_transform.resize(std::size_t(my) * columns);
      for (unsigned int j = 0; j < my; ++j)
        for (unsigned int c = 0; c < columns; ++c)
          {
            const unsigned int i = first + c;
            const double       b = bx[i] * by[j];
            kernel_transform[std::size_t(j) * columns + c] =
              scale * samples[std::size_t(j) * (mx + 1) + i] / (b * b);
          }
    }

    plans->allocate();
    const std::lock_guard<std::mutex> lock(planner_mutex());
    plan_with_deal_ii_threads();
    // the rows that hold the quarter's nodes; all columns
    std::tie(plans->rows_forward, plans->rows_backward) =
      Plans::cosine_pair(plans->real, mx, plans->my_rows(), 1, mx);
    std::tie(plans->columns_forward, plans->columns_backward) =
      Plans::cosine_pair(plans->column_data, my, columns, columns, 1);
    plans->check_plans();
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
    plans->set_layout(communicator, n[e] / 2, p, s, 2, m);
    const unsigned int columns = plans->my_columns(),
                       first   = plans->column_starts[plans->rank];

    // The kernel's samples at offsets 0 … m along e (their DFT over the
    // period 2 m is the type-I cosine transform) and at the circular
    // offsets along f (an even sequence: its DFT is real), rows along f.
    {
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
      // The real FFTs of the m rows used.
      const auto spectrum = fftw_buffer<fftw_complex>(std::size_t(m) * s);
      execute_once([&]() {
        int length = p;
        return fftw_plan_many_dft_r2c(1,
                                      &length,
                                      m,
                                      samples.data(),
                                      nullptr,
                                      1,
                                      p,
                                      spectrum.get(),
                                      nullptr,
                                      1,
                                      s,
                                      FFTW_ESTIMATE);
      });
      const std::vector<double> b_e = spline_symbols(m, 2 * m),
                                b_f = spline_symbols(s, p);
      // REDFT10 then REDFT01 multiply by 2 m, the real FFT's pair by p
      const double scale = 1. / (2. * double(m) * p);
      kernel_transform.resize(std::size_t(m) * columns);
      for (unsigned int a = 0; a < m; ++a)
        for (unsigned int c = 0; c < columns; ++c)
          {
            const unsigned int k = first + c;
            const double       b = b_e[a] * b_f[k];
            kernel_transform[std::size_t(a) * columns + c] =
              scale * spectrum[std::size_t(a) * s + k][0] / (b * b);
          }
    }

    plans->allocate();
    const std::lock_guard<std::mutex> lock(planner_mutex());
    plan_with_deal_ii_threads();
    // rows: real FFTs of the half's rows; columns: cosine transforms of
    // the spectrum's real and imaginary parts (2 s sequences)
    plans->make_row_ffts(p);
    std::tie(plans->columns_forward, plans->columns_backward) =
      Plans::cosine_pair(plans->column_data, m, 2 * columns, 2 * columns, 1);
    plans->check_plans();
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

  bool
  GridConvolution::covers(const Point<2> &x) const
  {
    for (unsigned int d = 0; d < 2; ++d)
      {
        const double t = (x[d] - origin[d]) / h;
        if (!(t > 0) || t >= n[d])
          return false;
        const int first = static_cast<int>(t) - int(spline_order / 2) + 1;
        if (first < 0 || first + spline_order > n[d])
          return false;
      }
    return true;
  }

  GridConvolution::Stencil
  GridConvolution::stencil(const Point<2> &x) const
  {
    Stencil s;
    s.first_x = stencil_1d(x[0], 0, s.x.data());
    s.first_y = stencil_1d(x[1], 1, s.y.data());
    return s;
  }

  bool
  GridConvolution::split() const
  {
    return plans->split();
  }

  std::size_t
  GridConvolution::place(const unsigned int i, const unsigned int j) const
  {
    // The buffer's rows run along x, except on the half mirrored in x
    // (make_half_plans()): there along y. A grid node's place in it lies
    // on the half in a mirrored direction, where a charge meets its image.
    const unsigned int hx = n[0] / 2, hy = n[1] / 2;
    const unsigned int a = mirrored[0] ? half_index(i, hx) : i,
                       b = mirrored[1] ? half_index(j, hy) : j;
    return mirrored[0] && !mirrored[1] ?
             std::size_t(a) * plans->row_length + b :
             std::size_t(b) * plans->row_length + a;
  }

  std::array<unsigned int, 2>
  GridConvolution::slab_sizes() const
  {
    return {{plans->my_rows(), plans->my_columns()}};
  }

  void
  GridConvolution::set_footprint(const std::vector<unsigned int> &grid_nodes)
  {
    AssertThrow(!plans->footprint_set,
                ExcMessage("GridConvolution: the footprint is set once."));
    AssertThrow(std::adjacent_find(grid_nodes.begin(),
                                   grid_nodes.end(),
                                   std::greater_equal<unsigned int>()) ==
                    grid_nodes.end() &&
                  (grid_nodes.empty() || grid_nodes.back() < n_grid_nodes()),
                ExcMessage("GridConvolution: a footprint lists distinct grid "
                           "nodes in increasing order."));
    plans->footprint_set = true;
    if (!split())
      return;
    const std::size_t             row_length = plans->row_length;
    const types::global_dof_index size = static_cast<types::global_dof_index>(
      std::size_t(plans->rows) * row_length);
    AssertThrow(std::size_t(size) == std::size_t(plans->rows) * row_length,
                ExcMessage("GridConvolution: the grid has more nodes than "
                           "deal.II's indices count."));
    IndexSet owned(size);
    owned.add_range(plans->row_starts[plans->rank] * row_length,
                    plans->row_starts[plans->rank + 1] * row_length);
    std::vector<types::global_dof_index> places;
    places.reserve(grid_nodes.size());
    for (const unsigned int g : grid_nodes)
      places.push_back(place(g % n[0], g / n[0]));
    std::vector<types::global_dof_index> ghosts(places);
    std::sort(ghosts.begin(), ghosts.end());
    ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
    ghosts.erase(std::remove_if(ghosts.begin(),
                                ghosts.end(),
                                [&](const types::global_dof_index k) {
                                  return owned.is_element(k);
                                }),
                 ghosts.end());
    IndexSet ghost_set(size);
    ghost_set.add_indices(ghosts.begin(), ghosts.end());
    plans->partitioner =
      std::make_shared<Utilities::MPI::Partitioner>(owned,
                                                    ghost_set,
                                                    communicator);
    plans->folded.reinit(plans->partitioner);
    plans->footprint.resize(grid_nodes.size());
    for (std::size_t k = 0; k < grid_nodes.size(); ++k)
      plans->footprint[k] = plans->partitioner->global_to_local(places[k]);
  }

  void
  GridConvolution::convolve(const Vector<double> &charges,
                            Vector<double>       &potentials) const
  {
    const std::lock_guard<std::mutex> lock(plans->mutex);
    Plans                            &p          = *plans;
    const std::size_t                 row_length = p.row_length;
    const std::size_t my_reals = std::size_t(p.my_rows()) * row_length;
    if (!p.split())
      {
        AssertDimension(charges.size(), n_grid_nodes());
        std::fill(p.real, p.real + my_reals, 0.);
        for (unsigned int j = 0; j < n[1]; ++j)
          for (unsigned int i = 0; i < n[0]; ++i)
            p.real[place(i, j)] += charges[std::size_t(j) * n[0] + i];
      }
    else
      {
        // Every rank must take part, so that none waits in the exchanges.
        AssertThrow(p.footprint_set,
                    ExcMessage("GridConvolution: a split grid convolves "
                               "only after set_footprint()."));
        AssertDimension(charges.size(), p.footprint.size());
        // each rank's charges to the owners of their rows, summed there
        p.folded = 0.;
        for (std::size_t k = 0; k < p.footprint.size(); ++k)
          p.folded.local_element(p.footprint[k]) += charges[k];
        p.folded.compress(VectorOperation::add);
        std::copy_n(p.folded.begin(), my_reals, p.real);
      }
    if (p.rows_forward)
      fftw_execute(p.rows_forward);
    // The padding rows going into the columns' transforms are zero.
    const std::size_t column_row = std::size_t(p.my_columns()) * p.width;
    if (p.split())
      p.transpose_to_columns(communicator);
    std::fill(p.column_data + std::size_t(p.rows) * column_row,
              p.column_data + p.n_column_data,
              0.);
    if (p.columns_forward)
      {
        fftw_execute(p.columns_forward);
        if (p.width == 2)
          for (std::size_t k = 0; k < kernel_transform.size(); ++k)
            {
              p.column_data[2 * k] *= kernel_transform[k];
              p.column_data[2 * k + 1] *= kernel_transform[k];
            }
        else
          for (std::size_t k = 0; k < kernel_transform.size(); ++k)
            p.column_data[k] *= kernel_transform[k];
        fftw_execute(p.columns_backward);
      }
    if (p.split())
      p.transpose_to_rows(communicator);
    if (p.rows_backward)
      fftw_execute(p.rows_backward);
    if (!p.split())
      {
        if (potentials.size() != n_grid_nodes())
          potentials.reinit(n_grid_nodes(), true);
        for (unsigned int j = 0; j < n[1]; ++j)
          for (unsigned int i = 0; i < n[0]; ++i)
            potentials[std::size_t(j) * n[0] + i] = p.real[place(i, j)];
      }
    else
      {
        // the rows' owners' potentials to the footprints that read them
        std::copy_n(p.real, my_reals, p.folded.begin());
        p.folded.update_ghost_values();
        if (potentials.size() != p.footprint.size())
          potentials.reinit(p.footprint.size(), true);
        for (std::size_t k = 0; k < p.footprint.size(); ++k)
          potentials[k] = p.folded.local_element(p.footprint[k]);
        p.folded.zero_out_ghost_values();
      }
  }

  std::size_t
  GridConvolution::memory_consumption() const
  {
    const Plans &p = *plans;
    return kernel_transform.size() * sizeof(double) +
           ((p.real != p.column_data ? p.n_real : 0) +
            (p.row_spectrum != p.column_data && p.row_spectrum != p.real ?
               p.n_row_spectrum :
               0) +
            p.n_column_data + p.exchange.size()) *
             sizeof(double) +
           p.folded.memory_consumption() +
           p.footprint.size() * sizeof(unsigned int);
  }
} // namespace PlateOnHalfspace
