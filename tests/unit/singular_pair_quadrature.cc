// The Galerkin integrals of 1/r over singular cell pairs (a cell with
// itself, and cells that touch; doc/formulation.md, "Singular pairs"),
// against the closed form of the double integral of 1/|x - y| over two
// axis-parallel rectangles (the sum over their 16 corner differences of
// G(u, v) = u v^2/2 asinh(u/v) + u^2 v/2 asinh(v/u) - (u^2 + v^2)^(3/2)/6,
// whose derivative d^4 G / du^2 dv^2 is 1/sqrt(u^2 + v^2)). The nine
// quadratic shape functions of a cell sum to 1, so the sum of a pair's
// 9 x 9 block is that integral. At the default Singular quadrature
// order (8):
// - a square with itself, a 2 : 1 rectangle with itself, squares sharing
//   an edge, squares sharing a vertex: within 1e-5, and each entry within
//   1e-4 (a cell with itself: measured 2.7e-5 and 7.0e-5) or 2e-5 of the
//   largest of the same rules at order 30;
// - cells beside a hanging node, where a vertex of one cell lies inside
//   an edge of the other (a square with one twice as wide on top, a half
//   square at its edge or in the middle of its edge, squares offset by
//   half an edge): within 1e-5, each entry within 2e-5. The outer rule
//   graded on the whole cell left 3e-4 in the sum and 1e-3 in the entries
//   here; it is now graded on the pieces cut through that vertex.
// Also: the singular pairs are the ones these are (singular_pair()).
// Only verdicts are printed.

#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "../tests.h"

#include "../foundation_cells.h"

namespace
{
  using namespace PlateOnHalfspace;

  struct Rectangle
  {
    double x0, y0, width, height;
  };

  std::array<Point<2>, 4>
  vertices(const Rectangle &r)
  {
    return {{Point<2>(r.x0, r.y0),
             Point<2>(r.x0 + r.width, r.y0),
             Point<2>(r.x0, r.y0 + r.height),
             Point<2>(r.x0 + r.width, r.y0 + r.height)}};
  }

  /** G(u, v) above, even in u and v. */
  double
  corner_function(double u, double v)
  {
    u        = std::abs(u);
    v        = std::abs(v);
    double g = -std::pow(u * u + v * v, 1.5) / 6.;
    if (u > 0 && v > 0)
      g += 0.5 * u * v * v * std::asinh(u / v) +
           0.5 * u * u * v * std::asinh(v / u);
    return g;
  }

  /** The double integral of 1/|x - y| over x in @p k and y in @p l. */
  double
  closed_form(const Rectangle &k, const Rectangle &l)
  {
    const std::array<double, 2> a = {{k.x0, k.x0 + k.width}},
                                b = {{k.y0, k.y0 + k.height}},
                                c = {{l.x0, l.x0 + l.width}},
                                d = {{l.y0, l.y0 + l.height}};
    double sum                    = 0;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        for (unsigned int m = 0; m < 2; ++m)
          for (unsigned int n = 0; n < 2; ++n)
            sum += ((i + j + m + n) % 2 == 0 ? 1. : -1.) *
                   corner_function(a[i] - c[j], b[m] - d[n]);
    return sum;
  }

  /** The largest difference of two blocks' entries over the largest
   *  entry of @p reference. */
  double
  entry_difference(const FullMatrix<double> &block,
                   const FullMatrix<double> &reference)
  {
    double largest = 0, deviation = 0;
    for (unsigned int i = 0; i < reference.m(); ++i)
      for (unsigned int j = 0; j < reference.n(); ++j)
        {
          largest = std::max(largest, std::abs(reference(i, j)));
          deviation =
            std::max(deviation, std::abs(block(i, j) - reference(i, j)));
        }
    return deviation / largest;
  }

  void
  check_pair(const std::string &name,
             const Rectangle   &k,
             const Rectangle   &l,
             const double       bound,
             const double       entry_bound)
  {
    const std::vector<FoundationSpace::Cell> cells = {
      cell_with_own_nodes(vertices(k), 0), cell_with_own_nodes(vertices(l), 9)};
    const bool same = k.x0 == l.x0 && k.y0 == l.y0 && k.width == l.width &&
                      k.height == l.height;
    const CellPairIntegrator integrator(cells, 8);
    const unsigned int       second = same ? 0 : 1;
    AssertThrow(integrator.singular_pair(0, second),
                ExcMessage(name + ": not a singular pair"));
    FullMatrix<double> block;
    integrator.integrate_inverse_distance(0, second, block);
    double sum = 0;
    for (unsigned int i = 0; i < block.m(); ++i)
      for (unsigned int j = 0; j < block.n(); ++j)
        sum += block(i, j);
    const double exact = closed_form(k, l);
    check_below(name + ": |sum of the block - integral| / integral",
                std::abs(sum - exact) / exact,
                bound);
    // each entry against the same rules at order 30 (the sum above can
    // hide errors of opposite signs)
    const CellPairIntegrator fine(cells, 30);
    FullMatrix<double>       reference;
    fine.integrate_inverse_distance(0, second, reference);
    check_below(name + ": entries against order 30",
                entry_difference(block, reference),
                entry_bound);
  }
} // namespace

int
main()
{
  initlog();
  // the closed form itself: a unit square with itself,
  // 4 ln(1 + sqrt 2) - 4 (sqrt 2 - 1) / 3
  check("closed form, unit square with itself",
        closed_form({0, 0, 1, 1}, {0, 0, 1, 1}),
        4. * std::log(1. + std::sqrt(2.)) - 4. * (std::sqrt(2.) - 1.) / 3.,
        1e-14);

  const Rectangle square{0, 0, 1, 1};
  check_pair("a square with itself", square, square, 1e-5, 1e-4);
  check_pair("a 2 : 1 rectangle with itself",
             {0, 0, 1, 0.5},
             {0, 0, 1, 0.5},
             1e-5,
             1e-4);
  check_pair("squares sharing an edge", square, {1, 0, 1, 1}, 1e-5, 2e-5);
  check_pair("squares sharing a vertex", square, {1, 1, 1, 1}, 1e-5, 2e-5);
  check_pair("a square under one twice as wide (hanging node)",
             square,
             {0, 1, 2, 1},
             1e-5,
             2e-5);
  check_pair("a half square at a square's edge (hanging node)",
             square,
             {1, 0, 0.5, 0.5},
             1e-5,
             2e-5);
  check_pair("a half square in the middle of a square's edge",
             square,
             {1, 0.25, 0.5, 0.5},
             1e-5,
             2e-5);
  check_pair(
    "squares offset by half an edge", square, {1, 0.5, 1, 1}, 1e-5, 2e-5);
}
