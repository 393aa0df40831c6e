// Load patches far larger or far smaller than the cells
// (doc/errors-and-limits.md, "Geometry and contact"): the tolerances of the
// patch-cell overlap (base/quadrilateral_geometry.h) scale with the cell,
// never with the patch.
// - A disk of radius 1e13 or 3e14 covering a 4 m x 3 m plate of 8 x 6 cells
//   covers exactly its area (the sum of the cells' rules' weights is 12 to
//   1e-12; it was 2.9e66 / 0 when the tolerance grew with the radius).
// - A huge disk whose circle crosses the plate: the covered area is finite
//   and right to the precision of its centre's coordinates (1e-3 here).
// - Disks centred on a cell's edge or vertex cover exactly their area.
// - A 1e-9 square and disks of radius 1e-8 inside a cell and across an
//   edge (to the precision of the centre's coordinates, 1e-6), and of
//   radius 1e-12 1e-11 beside an edge are covered exactly once (they were
//   dropped as slivers of the cell, or counted in both cells).
// - The same plate on a dense liquid, bonded, under the huge patch:
//   applied_load = pressure x area to 1e-12 and contact_force =
//   applied_load to 1e-10, on one thread and on two.
// Only verdicts are printed.

#include <deal.II/base/multithread_info.h>

#include <plate_on_halfspace/base/quadrilateral_geometry.h>
#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <sstream>
#include <string>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  /** The 8 x 6 cells of the plate [-2, 2] x [-1.5, 1.5]. */
  std::vector<BilinearQuadrilateral>
  plate_cells()
  {
    std::vector<BilinearQuadrilateral> cells;
    for (unsigned int j = 0; j < 6; ++j)
      for (unsigned int i = 0; i < 8; ++i)
        {
          const double x0 = -2 + 0.5 * i, y0 = -1.5 + 0.5 * j;
          cells.emplace_back(
            std::array<Point<2>, 4>{{Point<2>(x0, y0),
                                     Point<2>(x0 + 0.5, y0),
                                     Point<2>(x0, y0 + 0.5),
                                     Point<2>(x0 + 0.5, y0 + 0.5)}});
        }
    return cells;
  }

  /** The area of the disk on @p cells: the sum of every rule's weights. */
  double
  disk_area_on(const std::vector<BilinearQuadrilateral> &cells,
               const Point<2>                           &centre,
               const double                              radius)
  {
    double area = 0;
    for (const auto &cell : cells)
      {
        const Quadrature<2> rule =
          quadrature_on_disk_part(cell, centre, radius, 8);
        for (unsigned int q = 0; q < rule.size(); ++q)
          area += rule.weight(q);
      }
    return area;
  }

  void
  verdict(const std::string &name,
          const double       computed,
          const double       reference,
          const double       tolerance)
  {
    const bool ok = std::isfinite(computed) &&
                    std::abs(computed - reference) <= tolerance * reference;
    std::ostringstream bound; // the tolerance as written, not in 10 digits
    bound << tolerance;
    deallog << name << ": relative error <= " << bound.str() << ": "
            << (ok ? "ok" : "FAILED") << std::endl;
    if (!ok)
      deallog << "  computed " << computed << ", reference " << reference
              << std::endl;
    AssertThrow(ok, ExcMessage(name + " failed"));
  }
} // namespace

int
main()
{
  initlog();
  const auto cells = plate_cells();

  for (const double radius : {1e13, 3e14})
    {
      std::ostringstream name;
      name << "disk of radius " << radius << " over the plate, covered area";
      verdict(name.str(),
              disk_area_on(cells, Point<2>(0.3, -0.2), radius),
              12,
              1e-12);
    }
  // Disks centred on a cell's edge or vertex, whose arcs in a cell are
  // half or quarter circles: the covered area is exact (it was 1.3e-9 to
  // 2.6e-9 too large where the arc's opening came out as pi + 4e-8).
  for (const auto &[x, y, radius] :
       std::vector<std::array<double, 3>>{{0.5, 0.4, 0.05},
                                          {0.5, 0.5, 0.1},
                                          {0, 0.3, 0.2},
                                          {-1, -0.5, 0.45},
                                          {0.5 + 1e-7, 0.4, 0.15}})
    {
      std::ostringstream name;
      name << "disk of radius " << radius << " centred at (" << x << ", " << y
           << "), covered area";
      verdict(name.str(),
              disk_area_on(cells, Point<2>(x, y), radius),
              numbers::PI * radius * radius,
              1e-13);
    }
  {
    // the circle crosses the plate near x = 0.5; the centre's last digit
    // (an ulp of 1e13 is 2e-3) decides where
    const double   radius = 1e13;
    const Point<2> centre(0.5 - radius, 0.1);
    verdict("huge disk whose circle crosses the plate, covered area",
            disk_area_on(cells, centre, radius),
            (centre[0] + radius + 2) * 3,
            1e-3);
  }

  {
    const BilinearQuadrilateral cell = cells[0];
    const Point<2>      lower(-1.8, -1.3), upper(-1.8 + 1e-9, -1.3 + 1e-9);
    const Quadrature<2> rule =
      quadrature_on_rectangle_part(cell, lower, upper, 4);
    double area = 0;
    for (unsigned int q = 0; q < rule.size(); ++q)
      area += rule.weight(q);
    // the square's sides as the doubles hold them (1e-9 to 1e-7)
    verdict("1e-9 square inside a cell, covered area",
            area,
            (upper[0] - lower[0]) * (upper[1] - lower[1]),
            1e-9);
  }
  const double tiny = 1e-8;
  verdict("disk of radius 1e-8 inside a cell, covered area",
          disk_area_on(cells, Point<2>(-1.8, -1.3), tiny),
          numbers::PI * tiny * tiny,
          1e-9);
  // where the circle crosses the edge is known to an ulp of the centre's
  // coordinates (2e-16 x 1.5), 3e-8 of the radius
  verdict("disk of radius 1e-8 across an edge, covered area",
          disk_area_on(cells, Point<2>(-1.5 + 0.3 * tiny, -1.3), tiny),
          numbers::PI * tiny * tiny,
          1e-6);
  verdict("disk of radius 1e-12 1e-11 beside an edge, covered once",
          disk_area_on(cells, Point<2>(-1.5 + 1e-11, -1.3), 1e-12),
          numbers::PI * 1e-24,
          1e-9);

  for (const unsigned int threads : {1u, 2u})
    {
      MultithreadInfo::set_thread_limit(threads);
      for (const std::string radius : {"1e13", "3e14"})
        {
          const auto problem =
            TestTools::run_scene_text(TestTools::slab_on_dense_liquid(
              4,
              3,
              0.25,
              5e4,
              "bonded",
              8,
              6,
              0,
              "subsection Loads\n set Circular patches = 0, 0, " + radius +
                ", 100\nend\n"));
          const ResultRecord &s = problem->summaries().back();
          const std::string   scene =
            "radius " + radius + ", " + std::to_string(threads) + " thread(s)";
          verdict(scene + ": applied_load = 100 x 12",
                  s.number("applied_load"),
                  1200,
                  1e-12);
          verdict(scene + ": contact_force = applied_load",
                  s.number("contact_force"),
                  s.number("applied_load"),
                  1e-10);
        }
    }
}
