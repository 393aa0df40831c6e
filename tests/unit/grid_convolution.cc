// The grid convolution with mirror images (halfspace/grid_convolution.h;
// doc/formulation.md, "Split-kernel FFT storage"), on the smooth kernel
// k(r) = erf(r / s) / r (s = 0.4, grid spacing 0.125, B-splines of order 6
// and 8), with 60 point charges in the quarter x, y > 0 of a 2.6 x 1.8
// plate, some within a stencil of the centre lines:
//  - read back at 40 other points with the same B-splines, the potentials
//    of the charges and their images in x = 0 (x), y = 0 (y), both (xy,
//    the cosine transforms on the quarter) or none equal the direct sums
//    of k over the charges and their images, to 2e-6 (order 6) and 1e-7
//    (order 8) of the largest: the spline interpolant's accuracy
//    (measured 7e-7 ... 1e-6 and 3e-8 ... 4e-8);
//  - the cosine transforms on the quarter give the potentials of the
//    whole padded grid's FFT with the images added by hand, on the same
//    nodes, to 1e-12 of the largest (measured 5e-14: the two padded
//    periods differ, but the filters' tails have decayed within them);
//  - the quarter's arrays take less than a third of the whole grid's;
//  - with images in one line (cosine transforms on the half in that
//    direction, the real FFT in the other) the potentials equal the whole
//    grid's convolution of the charges with that image added by hand, to
//    1e-12, in less than 60 % of the whole grid's memory;
//  - on the grid itself, the convolution of random grid charges (with
//    their images) equals the direct sums with the filtered kernel on the
//    infinite lattice (the samples k(h |m|) filtered by the coefficients
//    of 1 / B(w)^2, B the symbol of the B-spline's samples, both computed
//    here from the B-spline's closed form), to 1e-10 of the largest, for
//    orders 4, 6 and 8 on small grids (h = 0.1, s = 0.3): the padding
//    leaves none of the filter's tail to wrap (measured at most 4e-14,
//    8e-13 and 9e-12 for orders 4, 6 and 8, the filter amplifying the
//    FFT's rounding; with a margin of 2p + 8 nodes 9e-12, 3e-8 and 9e-7);
//  - at order 8 too, the half with one image line equals the whole
//    grid's convolution with the image added by hand to 1e-12;
//  - the xy potentials are mirror symmetric exactly, and the grid with
//    cosine transforms has an even number of nodes each way: where the
//    whole grid would have an odd number (33 in x, a second set of half
//    widths), one more, and the direct sums hold there too.
// The verdicts only are printed: the errors depend on the FFT's rounding.

#include <plate_on_halfspace/halfspace/grid_convolution.h>

#include <cmath>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  constexpr double s = 0.4;

  double
  kernel(const double r)
  {
    return r < 1e-8 ? 2. / (s * std::sqrt(M_PI)) : std::erf(r / s) / r;
  }

  struct Charge
  {
    Point<2> x;
    double   q;
  };

  /** Charges in the quarter [0, 1.3] x [0, 0.9], a few near the lines. */
  std::vector<Charge>
  charges()
  {
    std::vector<Charge> result;
    for (unsigned int k = 0; k < 60; ++k)
      {
        const double u = 0.5 + 0.5 * std::sin(1.7 * k + 0.3),
                     v = 0.5 + 0.5 * std::cos(2.3 * k + 1.1);
        Point<2> x(1.3 * u, 0.9 * v);
        if (k % 10 == 0)
          x[0] = 0.013 * k / 10.;
        if (k % 10 == 5)
          x[1] = 0.021 * k / 10.;
        result.push_back({x, 1. + 0.5 * std::sin(0.9 * k)});
      }
    return result;
  }

  std::vector<Point<2>>
  test_points()
  {
    std::vector<Point<2>> result;
    for (unsigned int k = 0; k < 40; ++k)
      result.emplace_back(1.3 * (0.5 + 0.5 * std::cos(1.3 * k)),
                          0.9 * (0.5 + 0.5 * std::sin(0.7 * k + 0.2)));
    return result;
  }

  /** The charges spread onto @p grid with its B-splines. */
  Vector<double>
  spread(const GridConvolution &grid, const std::vector<Charge> &all)
  {
    Vector<double>     field(grid.n_grid_nodes());
    const unsigned int nx = grid.grid_sizes()[0], p = grid.order();
    for (const Charge &c : all)
      {
        const GridConvolution::Stencil st = grid.stencil(c.x);
        for (unsigned int b = 0; b < p; ++b)
          for (unsigned int a = 0; a < p; ++a)
            field[std::size_t(st.first_y + b) * nx + st.first_x + a] +=
              c.q * st.x[a] * st.y[b];
      }
    return field;
  }

  double
  read_back(const GridConvolution &grid,
            const Vector<double>  &potentials,
            const Point<2>        &x)
  {
    const unsigned int             nx = grid.grid_sizes()[0], p = grid.order();
    const GridConvolution::Stencil st  = grid.stencil(x);
    double                         sum = 0;
    for (unsigned int b = 0; b < p; ++b)
      for (unsigned int a = 0; a < p; ++a)
        sum += potentials[std::size_t(st.first_y + b) * nx + st.first_x + a] *
               st.x[a] * st.y[b];
    return sum;
  }

  /** @p field plus its reflection in the grid's centre line(s). */
  Vector<double>
  with_images(const GridConvolution     &grid,
              const Vector<double>      &field,
              const std::array<bool, 2> &mirror)
  {
    const auto     n = grid.grid_sizes();
    Vector<double> result(field);
    for (unsigned int sy = 0; sy < 2; ++sy)
      for (unsigned int sx = 0; sx < 2; ++sx)
        if ((sx || sy) && (!sx || mirror[0]) && (!sy || mirror[1]))
          for (unsigned int j = 0; j < n[1]; ++j)
            for (unsigned int i = 0; i < n[0]; ++i)
              result[std::size_t(j) * n[0] + i] +=
                field[std::size_t(sy ? n[1] - 1 - j : j) * n[0] +
                      (sx ? n[0] - 1 - i : i)];
    return result;
  }

  /** The centred cardinal B-spline of order @p p at @p x (support
   *  [0, p]), by its closed form (de Boor's truncated powers). */
  double
  bspline(const unsigned int p, const double x)
  {
    double sum = 0, binomial = 1, factorial = 1;
    for (unsigned int i = 1; i < p; ++i)
      factorial *= i;
    for (unsigned int j = 0; j <= p; ++j)
      {
        if (j > 0)
          binomial = binomial * (p - j + 1) / j;
        if (x > j)
          sum += (j % 2 ? -1. : 1.) * binomial * std::pow(x - j, p - 1);
      }
    return sum / factorial;
  }

  /** The coefficients c_0 ... c_L of the filter 1 / B(w)^2, by the
   *  trapezoidal rule on 2^14 points (exact to rounding for a periodic
   *  analytic integrand). */
  std::vector<double>
  filter_coefficients(const unsigned int p, const unsigned int L)
  {
    const unsigned int  points = 1u << 14;
    std::vector<double> c(L + 1, 0.);
    for (unsigned int i = 0; i < points; ++i)
      {
        const double w = 2 * M_PI * i / points;
        double       b = 0;
        for (unsigned int k = 1; k < p; ++k)
          b += bspline(p, k) * std::cos(w * (k - 0.5 * p));
        for (unsigned int k = 0; k <= L; ++k)
          c[k] += std::cos(w * k) / (b * b) / points;
      }
    return c;
  }

  /**
   * The convolution of random charges on the grid of spacing 0.1 and
   * @p widths (with their images) against the direct sums with the
   * filtered kernel on the infinite lattice: G(m) = sum_a sum_b c_a c_b
   * k(h |m - (a, b)|), the sums to 100 nodes either way.
   */
  void
  against_the_lattice_interpolant(const unsigned int           order,
                                  const std::array<double, 2> &widths)
  {
    const double h_small = 0.1, s_small = 0.3;
    const auto   small_kernel = [=](const double r) {
      return r < 1e-8 ? 2. / (s_small * std::sqrt(M_PI)) :
                          std::erf(r / s_small) / r;
    };
    const int                 L = 100;
    const std::vector<double> c = filter_coefficients(order, L);
    for (const std::array<bool, 2> mirror :
         {std::array<bool, 2>{{false, false}},
          std::array<bool, 2>{{true, false}},
          std::array<bool, 2>{{false, true}},
          std::array<bool, 2>{{true, true}}})
      {
        const GridConvolution grid(
          Point<2>(0.37, -1.21), h_small, widths, order, small_kernel, mirror);
        const int nx = grid.grid_sizes()[0], ny = grid.grid_sizes()[1];
        // the kernel's samples at offsets -(n - 1) - L ... (n - 1) + L,
        // filtered along x, then along y
        const int           wx = 2 * nx - 1 + 2 * L, wy = 2 * ny - 1 + 2 * L;
        const int           ox = 2 * nx - 1, oy = 2 * ny - 1;
        std::vector<double> samples(std::size_t(wx) * wy),
          along_x(std::size_t(ox) * wy), lattice(ox * oy);
        for (int j = 0; j < wy; ++j)
          for (int i = 0; i < wx; ++i)
            samples[std::size_t(j) * wx + i] = small_kernel(
              h_small * std::hypot(i - (nx - 1) - L, j - (ny - 1) - L));
        for (int j = 0; j < wy; ++j)
          for (int i = 0; i < ox; ++i)
            {
              double sum = 0;
              for (int a = -L; a <= L; ++a)
                sum +=
                  c[std::abs(a)] * samples[std::size_t(j) * wx + i + L + a];
              along_x[std::size_t(j) * ox + i] = sum;
            }
        for (int j = 0; j < oy; ++j)
          for (int i = 0; i < ox; ++i)
            {
              double sum = 0;
              for (int b = -L; b <= L; ++b)
                sum +=
                  c[std::abs(b)] * along_x[std::size_t(j + L + b) * ox + i];
              lattice[std::size_t(j) * ox + i] = sum;
            }
        Vector<double> field(grid.n_grid_nodes());
        for (unsigned int k = 0; k < field.size(); ++k)
          field[k] = std::sin(12.9898 * k + 78.233 * order);
        const Vector<double> all = with_images(grid, field, mirror);
        Vector<double>       potentials, direct(field.size());
        grid.convolve(field, potentials);
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i)
            {
              double sum = 0;
              for (int b = 0; b < ny; ++b)
                for (int a = 0; a < nx; ++a)
                  sum +=
                    lattice[std::size_t(j - b + ny - 1) * ox + i - a + nx - 1] *
                    all[std::size_t(b) * nx + a];
              direct[std::size_t(j) * nx + i] = sum;
            }
        check_below(std::string("order ") + std::to_string(order) + ", " +
                      std::to_string(nx) + " x " + std::to_string(ny) +
                      " nodes, images in " +
                      (mirror[0] && mirror[1] ? "x and y" :
                       mirror[0]              ? "x" :
                       mirror[1]              ? "y" :
                                                "neither") +
                      ": grid potentials against the lattice interpolant",
                    relative_difference(potentials, direct, Norm::max),
                    1e-10);
      }
  }

  const Point<2>              centre(0., 0.);
  const double                h = 0.125;
  const std::array<double, 2> half_widths{{1.4375, 1.0625}};

  void
  against_direct_sums(const unsigned int           order,
                      const std::array<double, 2> &widths,
                      const double                 tolerance)
  {
    const std::vector<Charge> all = charges();
    for (const std::array<bool, 2> mirror :
         {std::array<bool, 2>{{false, false}},
          std::array<bool, 2>{{true, false}},
          std::array<bool, 2>{{false, true}},
          std::array<bool, 2>{{true, true}}})
      {
        const GridConvolution grid(centre, h, widths, order, kernel, mirror);
        Vector<double>        potentials;
        grid.convolve(spread(grid, all), potentials);
        double error = 0, largest = 0;
        for (const Point<2> &x : test_points())
          {
            double direct = 0;
            for (const Charge &c : all)
              for (const double fx : {1., -1.})
                for (const double fy : {1., -1.})
                  if ((fx > 0 || mirror[0]) && (fy > 0 || mirror[1]))
                    direct +=
                      c.q *
                      kernel(x.distance(Point<2>(fx * c.x[0], fy * c.x[1])));
            error   = std::max(error,
                             std::abs(read_back(grid, potentials, x) - direct));
            largest = std::max(largest, std::abs(direct));
          }
        const std::string name =
          std::string("order ") + std::to_string(order) + ", " +
          std::to_string(grid.grid_sizes()[0]) + " x " +
          std::to_string(grid.grid_sizes()[1]) + " nodes, images in " +
          (mirror[0] && mirror[1] ? "x and y" :
           mirror[0]              ? "x" :
           mirror[1]              ? "y" :
                                    "neither") +
          (mirror[0] || mirror[1] ? " (cosine transforms)" : "");
        check_below(name + ": potentials against the direct sums",
                    error / largest,
                    tolerance);
      }
  }
} // namespace

int
main()
{
  initlog();
  against_direct_sums(6, half_widths, 2e-6);
  against_direct_sums(8, half_widths, 1e-7);
  // 2 * 1.5 / 0.125 + 6 + 2 = 32 cells, 33 nodes in x: the cosine
  // transforms' grid takes one more
  against_direct_sums(6, {{1.5, 1.0625}}, 2e-6);
  // 36 x 11 and 22 x 21 nodes at order 8: small grids, where the far
  // offsets' kernel is largest against its peak
  for (const unsigned int order : {4u, 6u, 8u})
    for (const std::array<double, 2> widths :
         {std::array<double, 2>{{1.25, 0.}}, std::array<double, 2>{{0.5, 0.5}}})
      against_the_lattice_interpolant(order, widths);
  {
    const GridConvolution odd(
      centre, h, {{1.5, 1.0625}}, 6, kernel, {{false, false}});
    const GridConvolution even(
      centre, h, {{1.5, 1.0625}}, 6, kernel, {{true, true}});
    require("an odd node count made even for the cosine transforms",
            odd.grid_sizes()[0] % 2 == 1 &&
              even.grid_sizes()[0] == odd.grid_sizes()[0] + 1 &&
              even.grid_sizes()[1] == odd.grid_sizes()[1]);
  }

  const std::vector<Charge> all = charges();
  // 2 * 1.4375 / 0.125 + 6 + 2 = 31 cells, 32 nodes in x; 26 in y.
  const GridConvolution quarter(
    centre, h, half_widths, 6, kernel, {{true, true}});
  const GridConvolution whole(centre, h, half_widths, 6, kernel);
  require("cosine transforms: an even number of nodes each way",
          quarter.cosine_transform_directions()[0] &&
            quarter.cosine_transform_directions()[1] &&
            quarter.grid_sizes()[0] % 2 == 0 &&
            quarter.grid_sizes()[1] % 2 == 0);
  require("the same nodes as the whole grid's",
          quarter.grid_sizes() == whole.grid_sizes() &&
            !whole.cosine_transform_directions()[0] &&
            !whole.cosine_transform_directions()[1]);
  require("cosine transforms: less than a third of the whole grid's memory",
          3 * quarter.memory_consumption() < whole.memory_consumption());
  {
    const Vector<double> field = spread(quarter, all);
    Vector<double>       by_cosines, by_fft;
    quarter.convolve(field, by_cosines);
    whole.convolve(with_images(whole, field, {{true, true}}), by_fft);
    check_below("cosine transforms against the whole grid's FFT",
                relative_difference(by_cosines, by_fft, Norm::max),
                1e-12);
    const auto n         = quarter.grid_sizes();
    bool       symmetric = true;
    for (unsigned int j = 0; j < n[1]; ++j)
      for (unsigned int i = 0; i < n[0]; ++i)
        {
          const double v = by_cosines[std::size_t(j) * n[0] + i];
          symmetric      = symmetric &&
                      v == by_cosines[std::size_t(j) * n[0] + n[0] - 1 - i] &&
                      v == by_cosines[std::size_t(n[1] - 1 - j) * n[0] + i];
        }
    require("cosine transforms: potentials mirror symmetric", symmetric);
  }
  const GridConvolution whole_8(centre, h, half_widths, 8, kernel);
  for (const unsigned int order : {6u, 8u})
    for (const std::array<bool, 2> mirror :
         {std::array<bool, 2>{{true, false}},
          std::array<bool, 2>{{false, true}}})
      {
        const GridConvolution &whole_p = order == 6 ? whole : whole_8;
        const GridConvolution  one_line(
          centre, h, half_widths, order, kernel, mirror);
        const Vector<double> field = spread(one_line, all);
        Vector<double>       by_grid, by_hand;
        one_line.convolve(field, by_grid);
        whole_p.convolve(with_images(whole_p, field, mirror), by_hand);
        const std::string name = std::string("order ") + std::to_string(order) +
                                 ", image in " + (mirror[0] ? "x" : "y") +
                                 " only";
        check_below(name + ": cosine transforms on the half against the "
                           "whole grid's FFT with the image added by hand",
                    relative_difference(by_grid, by_hand, Norm::max),
                    1e-12);
        require(name + ": the half's transforms in less than 60 % of the "
                       "whole grid's memory",
                one_line.memory_consumption() <
                  0.6 * whole_p.memory_consumption());
      }
}
