// The quadrature of a layered soil's kernel alpha1/r + R(r) over separated
// cells (SurfaceKernel::separated_points(); doc/soil-models.md, "How the
// storages use it"), against an independent 14-point Gauss rule per
// direction of the same kernel:
//  - CellPairIntegrator::integrate_kernel()'s 9 x 9 block of the quadratic
//    shape functions of two cells, for cells 0.5, 0.7, 1 and 2 times as wide
//    as the top layer h1 (squares and a distorted quadrilateral), 3 to 60
//    cell diameters apart: every entry within 2e-5 of the block's largest
//    (of alpha1/r + |R|, the scale the kernel's accuracy is stated in);
//  - settlement_at_points() under a uniform pressure on one cell, seen from
//    points 3 to 60 diameters away: within 2e-5 on the same scale.
// The soils: the pavement of parameters/pavement-on-layers.prm (stiff base
// and subbase over a subgrade on rock, where R dominates and changes sign
// near the layers' depth) and the same layers over a half-space. R varies
// over h1 at any distance: the 2-point rule that suffices for 1/r beyond
// 20 diameters leaves it about 1e-4 wrong there; the 3-point rule leaves
// at most 2e-6 on cells up to 0.7 h1 wide and 1.6e-5 on cells 2 h1 wide
// (at 3 diameters; from 2.6 to 11.2 diameters 1/r's own accuracy asks 4
// points, which the pair takes).

#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>
#include <plate_on_halfspace/soil/layered_soil.h>
#include <plate_on_halfspace/soil/surface_settlement.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "../tests.h"

#include "../foundation_cells.h"

namespace
{
  using namespace PlateOnHalfspace;

  /** The vertices of a cell of width @p a at @p origin, in deal.II's order;
   *  distorted: a trapezoid with a sheared top. */
  std::array<Point<2>, 4>
  vertices(const Point<2> &origin, const double a, const bool distorted)
  {
    const Point<2> o = origin;
    if (!distorted)
      return {{o, o + Point<2>(a, 0), o + Point<2>(0, a), o + Point<2>(a, a)}};
    return {{o,
             o + Point<2>(a, 0.1 * a),
             o + Point<2>(0.3 * a, 0.8 * a),
             o + Point<2>(1.2 * a, 1.1 * a)}};
  }

  /**
   * int_K int_L phi_a(x) phi_b(y) K(|x - y|) by 14 x 14 points on each;
   * with @p magnitude, K replaced by alpha / r + |R|, the scale the
   * kernel's own accuracy is stated in (TabulatedLayeredRemainder).
   */
  FullMatrix<double>
  reference_block(const BilinearQuadrilateral &k,
                  const BilinearQuadrilateral &l,
                  const SurfaceKernel         &kernel,
                  const bool                   magnitude = false)
  {
    const QGauss<2>    rule(14);
    FullMatrix<double> block(9, 9);
    for (unsigned int p = 0; p < rule.size(); ++p)
      {
        const Point<2> x     = k.map(rule.point(p));
        const auto     phi_x = q2_shape_values(rule.point(p));
        const double   wx =
          rule.weight(p) * k.jacobian_determinant(rule.point(p));
        for (unsigned int q = 0; q < rule.size(); ++q)
          {
            const Point<2> y     = l.map(rule.point(q));
            const auto     phi_y = q2_shape_values(rule.point(q));
            const double   r     = x.distance(y);
            const double   w =
              wx * rule.weight(q) * l.jacobian_determinant(rule.point(q)) *
              (kernel.alpha / r + (magnitude ?
                                     std::abs(kernel.remainder->value(r)) :
                                     kernel.remainder->value(r)));
            for (unsigned int a = 0; a < 9; ++a)
              for (unsigned int b = 0; b < 9; ++b)
                block(a, b) += w * phi_x[a] * phi_y[b];
          }
      }
    return block;
  }

  /** int_K K(|x - y|) dy by 14 x 14 points (@p magnitude: as above). */
  double
  reference_settlement(const BilinearQuadrilateral &k,
                       const Point<2>              &x,
                       const SurfaceKernel         &kernel,
                       const bool                   magnitude = false)
  {
    const QGauss<2> rule(14);
    double          sum = 0;
    for (unsigned int q = 0; q < rule.size(); ++q)
      {
        const double r = x.distance(k.map(rule.point(q)));
        sum += rule.weight(q) * k.jacobian_determinant(rule.point(q)) *
               (kernel.alpha / r + (magnitude ?
                                      std::abs(kernel.remainder->value(r)) :
                                      kernel.remainder->value(r)));
      }
    return sum;
  }

  void
  check_soil(const std::string &name, const LayeredProfile &profile)
  {
    const double       h1        = profile.layers.front().thickness;
    const double       tolerance = 2e-5;
    const LayeredSoil  soil(profile, 8);
    const double       direction[2]   = {0.8, 0.6};
    const unsigned int separations[4] = {3, 8, 25, 60};
    for (const double width : {0.5, 0.7, 1., 2.})
      for (const bool distorted : {false, true})
        {
          const double                a = width * h1;
          const FoundationSpace::Cell first =
            cell_with_own_nodes(vertices(Point<2>(), a, distorted), 0);
          const double        diameter = first.geometry.diameter();
          const Point<2>      centre   = first.geometry.map(Point<2>(0.5, 0.5));
          const SurfaceKernel kernel   = soil.kernel(61 * diameter + 2 * a);
          for (const unsigned int s : separations)
            {
              const std::string pair = name + ", cells " +
                                       std::to_string(width).substr(0, 3) +
                                       " h1" + (distorted ? " distorted" : "") +
                                       ", " + std::to_string(s) + " diameters";
              // The second cell's centre s diameters from the first's.
              const Point<2> offset(s * diameter * direction[0],
                                    s * diameter * direction[1]);
              const std::vector<FoundationSpace::Cell> cells = {
                first, cell_with_own_nodes(vertices(offset, a, distorted), 9)};
              const CellPairIntegrator integrator(cells, 8);
              FullMatrix<double>       block;
              integrator.integrate_kernel(0, 1, kernel, block, {}, {});
              const FullMatrix<double> reference =
                reference_block(cells[0].geometry, cells[1].geometry, kernel);
              const FullMatrix<double> scale = reference_block(
                cells[0].geometry, cells[1].geometry, kernel, true);
              double largest = 0, deviation = 0;
              for (unsigned int i = 0; i < 9; ++i)
                for (unsigned int j = 0; j < 9; ++j)
                  {
                    largest = std::max(largest, std::abs(scale(i, j)));
                    deviation =
                      std::max(deviation,
                               std::abs(block(i, j) - reference(i, j)));
                  }
              check_below(pair + ", pair block",
                          deviation / largest,
                          tolerance);

              // The settlement under a unit pressure on the first cell, seen
              // from the second cell's centre.
              FoundationSpace space;
              space.cells = {first};
              space.node_locations.resize(9);
              Vector<double> pressure(9);
              pressure         = 1.;
              const Point<2> x = centre + offset;
              const double   computed =
                settlement_at_points(space, pressure, {x}, kernel, 8)[0];
              const double exact =
                reference_settlement(first.geometry, x, kernel);
              check_below(
                pair + ", settlement at a point",
                std::abs(computed - exact) /
                  reference_settlement(first.geometry, x, kernel, true),
                tolerance);
            }
        }
  }
} // namespace

int
main()
{
  initlog();
  LayeredProfile pavement;
  pavement.layers = {{0.15, 5e6, 0.2}, {0.3, 2e5, 0.35}, {2.55, 5e4, 0.4}};
  pavement.base   = LayeredProfile::Base::rigid;
  check_soil("pavement over rock", pavement);

  LayeredProfile over_half_space      = pavement;
  over_half_space.base                = LayeredProfile::Base::half_space;
  over_half_space.base_youngs_modulus = 5e4;
  over_half_space.base_poissons_ratio = 0.4;
  check_soil("pavement over a half-space", over_half_space);
}
