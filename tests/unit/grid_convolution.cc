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
  for (const std::array<bool, 2> mirror :
       {std::array<bool, 2>{{true, false}}, std::array<bool, 2>{{false, true}}})
    {
      const GridConvolution one_line(centre, h, half_widths, 6, kernel, mirror);
      const Vector<double>  field = spread(one_line, all);
      Vector<double>        by_grid, by_hand;
      one_line.convolve(field, by_grid);
      whole.convolve(with_images(whole, field, mirror), by_hand);
      const std::string name =
        std::string("image in ") + (mirror[0] ? "x" : "y") + " only";
      check_below(name + ": cosine transforms on the half against the "
                         "whole grid's FFT with the image added by hand",
                  relative_difference(by_grid, by_hand, Norm::max),
                  1e-12);
      require(name + ": the half's transforms in less than 60 % of the "
                     "whole grid's memory",
              one_line.memory_consumption() < 0.6 * whole.memory_consumption());
    }
}
