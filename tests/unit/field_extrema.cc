// Peaks of the plate's fields (plate/field_extrema.h).
// (a) Known polynomial fields on a 6 x 4 mesh of the 12 m x 8 m plate
//     (serendipity element, cells 2 m), rectangular and sheared by
//     x -> x + 0.3 y (parallelograms), interpolated exactly:
//     - w = W - a (x-x0)^2 - b (y-y0)^2 - e (x-x0)(y-y0), concave, its
//       maximum W at (x0, y0) inside a cell and off its sampling lattice;
//       the minimum at a plate corner;
//     - on the rectangles, beta_x = x ((y-y0)^2 - c), beta_y = (x-x0)^2 y,
//       so that Mx = -D ((y-y0)^2 - c + nu (x-x0)^2): maximum D c at
//       (x0, y0);
//     the values to 1e-12 relative, the locations to 1e-6 m, plate_quantity()
//     against MindlinPlate::moments() at random points, and every peak (w,
//     Mx, My, Mxy, M1) against a 41 x 41 sampling of every cell.
// (b) The shipped example2-bonded.prm (whole plate, one cycle): the
//     summary's peaks of w, q, Mx, My (maximum and minimum) and the
//     principal moment bound the values at the plate centre, at the scene's
//     probe points, at the plate corner and at 200 random points, and the
//     samples the peaks were taken from before (w, q at the nodes, Mx at
//     the 2x2 Gauss points); the peaks of the continuous w and q are the
//     fields' values at their locations.

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <deal.II/numerics/vector_tools.h>

#include <plate_on_halfspace/plate/field_extrema.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/plate/plate_mesh.h>

#include <cmath>
#include <random>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

namespace
{
  const Point<2> peak(1.2345, -0.6789);
  const double   W = 0.01, a = 2e-4, b = 3e-4, e = 1e-4, c = 0.75;

  /** The polynomial fields (a). */
  class Fields : public Function<2>
  {
  public:
    Fields()
      : Function<2>(3)
    {}
    double
    value(const Point<2> &p, const unsigned int component) const override
    {
      const double dx = p[0] - peak[0], dy = p[1] - peak[1];
      switch (component)
        {
          case 0:
            return W - a * dx * dx - b * dy * dy - e * dx * dy;
          case 1:
            return 1e-3 * p[0] * (dy * dy - c);
          default:
            return 1e-3 * dx * dx * p[1];
        }
    }
  };

  const char *
  name(const PlateQuantity q)
  {
    switch (q)
      {
        case PlateQuantity::w:
          return "w";
        case PlateQuantity::mx:
          return "Mx";
        case PlateQuantity::my:
          return "My";
        case PlateQuantity::mxy:
          return "Mxy";
        default:
          return "M1";
      }
  }

  void
  report(const std::string &what, const bool ok, const std::string &detail)
  {
    deallog << what << ": " << (ok ? "OK" : "FAILED") << " " << detail
            << std::endl;
    AssertThrow(ok, ExcMessage(what));
  }

  std::string
  numbers(const double x, const double y)
  {
    // 6 digits: the values are checked to 1e-12 (rounded() of tests.h)
    std::ostringstream s;
    s << std::setprecision(6) << x << " vs " << y;
    return s.str();
  }

  /** (a) on the mesh sheared by x -> x + shear y. */
  void
  polynomial_fields(const double shear)
  {
    // inputs and exact positions: 6 digits are all there is to see
    deallog << std::setprecision(6) << "mesh sheared by " << shear << std::endl;
    SceneParameters parameters;
    parameters.read_from_string(
      "include " SOURCE_DIR "/../../parameters/example2-bonded.prm\n"
      "set Output directory = results\n"
      "subsection Discretization\n set Symmetry = none\n"
      " set Subdivisions x = 6\n set Subdivisions y = 4\nend\n");
    Triangulation<2> mesh;
    make_plate_mesh(parameters.plate, parameters.discretization, mesh);
    GridTools::transform(
      [shear](const Point<2> &p) {
        return Point<2>(p[0] + shear * p[1], p[1]);
      },
      mesh);
    MindlinPlate plate(parameters.plate, parameters.discretization);
    plate.setup(mesh);
    Vector<double> solution(plate.get_dof_handler().n_dofs());
    VectorTools::interpolate(plate.get_dof_handler(), Fields(), solution);
    plate.get_constraints().distribute(solution);
    const double D = plate.flexural_rigidity(), nu = plate.poissons_ratio();

    // the peak is inside a cell, off its lattice points
    const auto located = plate.locate(peak);
    deallog << "peak at reference point " << located.second << std::endl;

    const FieldExtrema w = field_extrema(plate, solution, PlateQuantity::w);
    report("max w value",
           std::abs(w.maximum.value - W) <= 1e-12 * W,
           numbers(w.maximum.value, W));
    report("max w location",
           w.maximum.location.distance(peak) <= 1e-6,
           "(distance <= 1e-6)");
    // the minimum of a concave field: the lowest plate corner
    double corner_min = std::numeric_limits<double>::max();
    for (const double x : {-6., 6.})
      for (const double y : {-4., 4.})
        corner_min =
          std::min(corner_min, Fields().value(Point<2>(x + shear * y, y), 0));
    report("min w value",
           std::abs(w.minimum.value - corner_min) <= 1e-12 * W,
           numbers(w.minimum.value, corner_min));
    report("field_maximum, field_minimum = field_extrema()",
           field_maximum(plate, solution, PlateQuantity::w).value ==
               w.maximum.value &&
             field_minimum(plate, solution, PlateQuantity::w).value ==
               w.minimum.value,
           "");

    // the rotations are cubic: interpolated exactly on rectangles only
    const FieldExtremum mx = field_maximum(plate, solution, PlateQuantity::mx);
    const double        mx_peak = 1e-3 * D * c;
    if (shear == 0)
      {
        report("max Mx value",
               std::abs(mx.value - mx_peak) <= 1e-12 * mx_peak,
               numbers(mx.value, mx_peak));
        report("max Mx location",
               mx.location.distance(peak) <= 1e-6,
               "(distance <= 1e-6)");
      }
    report("max Mx = plate_quantity at its cell and reference point",
           mx.value ==
             plate_quantity(
               plate, solution, PlateQuantity::mx, mx.cell, mx.reference_point),
           "");

    // plate_quantity against MindlinPlate::moments and the exact moments
    std::mt19937                           random(20240607);
    std::uniform_real_distribution<double> unit(0., 1.);
    double                                 difference = 0, exact = 0;
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      for (unsigned int i = 0; i < 5; ++i)
        {
          const Point<2> p(unit(random), unit(random));
          const Moments  m = plate.moments(cell, p, solution);
          const double   mx_here =
            plate_quantity(plate, solution, PlateQuantity::mx, cell, p);
          difference = std::max(
            {difference,
             std::abs(mx_here - m.mx),
             std::abs(
               plate_quantity(plate, solution, PlateQuantity::my, cell, p) -
               m.my),
             std::abs(
               plate_quantity(plate, solution, PlateQuantity::mxy, cell, p) -
               m.mxy)});
          const Point<2> x = cell->vertex(0) +
                             p[0] * (cell->vertex(1) - cell->vertex(0)) +
                             p[1] * (cell->vertex(2) - cell->vertex(0));
          const double dx = x[0] - peak[0], dy = x[1] - peak[1];
          exact = std::max(exact,
                           std::abs(mx_here - (-1e-3 * D *
                                               (dy * dy - c + nu * dx * dx))));
        }
    report("plate_quantity = MindlinPlate::moments",
           difference <= 1e-12 * mx_peak,
           "(Mx, My, Mxy at 5 random points per cell, to 1e-12)");
    if (shear == 0)
      report("Mx = the exact field", exact <= 1e-12 * mx_peak, "(1e-12)");

    // huge fields (moments near the overflow of their squares): finite
    // peaks, scaled exactly
    {
      Vector<double> huge(solution);
      huge *= 1e290;
      const FieldExtremum m1 =
        field_maximum(plate, solution, PlateQuantity::principal_moment);
      const FieldExtremum m1_huge =
        field_maximum(plate, huge, PlateQuantity::principal_moment);
      report("M1 peak of the field times 1e290",
             std::isfinite(m1_huge.value) &&
               std::abs(m1_huge.value - 1e290 * m1.value) <=
                 1e-12 * std::abs(1e290 * m1.value),
             "(finite, = 1e290 x the peak to 1e-12)");
    }

    // every peak against a fine sampling of every cell
    for (const PlateQuantity q : {PlateQuantity::w,
                                  PlateQuantity::mx,
                                  PlateQuantity::my,
                                  PlateQuantity::mxy,
                                  PlateQuantity::principal_moment})
      {
        const FieldExtrema peaks      = field_extrema(plate, solution, q);
        double             sample_max = -std::numeric_limits<double>::max(),
               sample_min = std::numeric_limits<double>::max(), scale = 0;
        for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
          for (unsigned int i = 0; i <= 40; ++i)
            for (unsigned int j = 0; j <= 40; ++j)
              {
                const double v = plate_quantity(
                  plate, solution, q, cell, Point<2>(i / 40., j / 40.));
                sample_max = std::max(sample_max, v);
                sample_min = std::min(sample_min, v);
                scale      = std::max(scale, std::abs(v));
              }
        const bool ok = peaks.maximum.value >= sample_max - 1e-12 * scale &&
                        peaks.minimum.value <= sample_min + 1e-12 * scale &&
                        std::isfinite(peaks.maximum.value) &&
                        std::isfinite(peaks.minimum.value);
        std::ostringstream detail;
        detail << std::setprecision(6) << "max " << peaks.maximum.value
               << " >= sampled " << sample_max << ", min "
               << peaks.minimum.value << " <= sampled " << sample_min;
        report(std::string(name(q)) + " peaks bound a 41 x 41 sampling",
               ok,
               detail.str());
      }
  }

  void
  solved_scene()
  {
    const auto          problem = solve_scene("example2-bonded.prm",
                                     "subsection Adaptivity\n set Cycles = 1\n"
                                              "end\n");
    const ResultRecord &s       = problem->summaries().back();
    // The solved scene's values for the record, 4 digits: the solve
    // changes later digits with the CPU's BLAS kernel; the checks below
    // count points and compare with 1e-12 margins.
    deallog << std::setprecision(4) << "example2-bonded, whole plate, "
            << s.count("n_cells") << " cells: max_w " << s.number("max_w")
            << " max_q " << s.number("max_q") << " max_Mx "
            << s.number("max_Mx") << " max_My " << s.number("max_My")
            << " max_principal_moment " << s.number("max_principal_moment")
            << std::endl;
    const PointValues centre = problem->values_at(Point<2>(0, 0));
    deallog << "centre: w " << centre.w << " q " << centre.q << " Mx "
            << centre.mx << " My " << centre.my << std::endl;

    std::vector<Point<2>>                  points = {Point<2>(0, 0),
                                                     Point<2>(3, 0),
                                                     Point<2>(6, 0),
                                                     Point<2>(6, 4),
                                                     Point<2>(-6, -4),
                                                     Point<2>(2, 0),
                                                     Point<2>(0, 4)};
    std::mt19937                           random(12345);
    std::uniform_real_distribution<double> x(-6, 6), y(-4, 4);
    for (unsigned int i = 0; i < 200; ++i)
      points.emplace_back(x(random), y(random));
    double w_scale =
             std::max(std::abs(s.number("max_w")), std::abs(s.number("min_w"))),
           q_scale =
             std::max(std::abs(s.number("max_q")), std::abs(s.number("min_q"))),
           m_scale     = std::max({std::abs(s.number("max_Mx")),
                                   std::abs(s.number("min_Mx")),
                                   std::abs(s.number("max_My")),
                                   std::abs(s.number("min_My"))});
    unsigned int bad_w = 0, bad_q = 0, bad_mx = 0, bad_my = 0, bad_m1 = 0;
    const double tolerance = 1e-12;
    for (const Point<2> &p : points)
      {
        const PointValues v = problem->values_at(p);
        bad_w += (v.w > s.number("max_w") + tolerance * w_scale ||
                  v.w < s.number("min_w") - tolerance * w_scale);
        bad_q += (v.q > s.number("max_q") + tolerance * q_scale ||
                  v.q < s.number("min_q") - tolerance * q_scale);
        bad_mx += (v.mx > s.number("max_Mx") + tolerance * m_scale ||
                   v.mx < s.number("min_Mx") - tolerance * m_scale);
        bad_my += (v.my > s.number("max_My") + tolerance * m_scale ||
                   v.my < s.number("min_My") - tolerance * m_scale);
        // the principal moment at the point (in the cell values_at uses)
        const auto   located = problem->plate().locate(p);
        const double m1      = plate_quantity(problem->plate(),
                                         problem->solution(),
                                         PlateQuantity::principal_moment,
                                         located.first,
                                         located.second);
        bad_m1 += (m1 > s.number("max_principal_moment") + tolerance * m_scale);
      }
    const auto line = [&](const std::string &what,
                          const unsigned int bad,
                          const double       peak,
                          const double       at_centre) {
      std::ostringstream detail;
      detail << std::setprecision(4) << "(" << bad << " of " << points.size()
             << " points beyond; peak " << peak << ", centre " << at_centre
             << ")";
      report(what + " bounds the values at the points", bad == 0, detail.str());
    };
    line("max_w, min_w", bad_w, s.number("max_w"), centre.w);
    line("max_q, min_q", bad_q, s.number("max_q"), centre.q);
    line("max_Mx, min_Mx", bad_mx, s.number("max_Mx"), centre.mx);
    line("max_My, min_My", bad_my, s.number("max_My"), centre.my);
    const auto centre_cell = problem->plate().locate(Point<2>(0, 0));
    line("max_principal_moment",
         bad_m1,
         s.number("max_principal_moment"),
         plate_quantity(problem->plate(),
                        problem->solution(),
                        PlateQuantity::principal_moment,
                        centre_cell.first,
                        centre_cell.second));

    // the samples the peaks were taken from before: w and q at the nodes,
    // the moments at the 2x2 Gauss points of every cell
    const ContactState &state     = problem->contact_state();
    unsigned int        bad_nodes = 0;
    for (unsigned int i = 0; i < state.w.size(); ++i)
      bad_nodes += (state.w[i] > s.number("max_w") + tolerance * w_scale ||
                    state.w[i] < s.number("min_w") - tolerance * w_scale ||
                    state.q[i] > s.number("max_q") + tolerance * q_scale ||
                    state.q[i] < s.number("min_q") - tolerance * q_scale);
    report("peaks of w and q bound the nodal values",
           bad_nodes == 0,
           "(" + std::to_string(state.w.size()) + " nodes)");
    const QGauss<2> rule(2);
    FEValues<2>     values(problem->plate().get_fe(), rule, update_gradients);
    std::vector<Tensor<2, 2>> grad(rule.size());
    const double              D = problem->plate().flexural_rigidity(),
                 nu             = problem->plate().poissons_ratio();
    double gauss_max_mx         = -std::numeric_limits<double>::max(),
           gauss_min_mx         = std::numeric_limits<double>::max();
    for (const auto &cell :
         problem->plate().get_dof_handler().active_cell_iterators())
      {
        values.reinit(cell);
        values[FEValuesExtractors::Vector(1)].get_function_gradients(
          problem->solution(), grad);
        for (const auto &g : grad)
          {
            const double mx = -D * (g[0][0] + nu * g[1][1]);
            gauss_max_mx    = std::max(gauss_max_mx, mx);
            gauss_min_mx    = std::min(gauss_min_mx, mx);
          }
      }
    std::ostringstream gauss;
    gauss << std::setprecision(4) << "(Gauss points: Mx in [" << gauss_min_mx
          << ", " << gauss_max_mx << "])";
    report("peaks of Mx bound the 2x2 Gauss points",
           s.number("max_Mx") >= gauss_max_mx &&
             s.number("min_Mx") <= gauss_min_mx,
           gauss.str());

    // w and q are continuous: each peak is the field's value at its
    // location, whichever cell values_at() finds there
    double mismatch = 0;
    for (const auto &[value, at] :
         {std::make_pair(s.number("max_w"), s.point("max_w_at")),
          std::make_pair(s.number("min_w"), s.point("min_w_at"))})
      mismatch = std::max(mismatch,
                          std::abs(problem->values_at(at).w - value) / w_scale);
    for (const auto &[value, at] :
         {std::make_pair(s.number("max_q"), s.point("max_q_at")),
          std::make_pair(s.number("min_q"), s.point("min_q_at"))})
      mismatch = std::max(mismatch,
                          std::abs(problem->values_at(at).q - value) / q_scale);
    report("w and q peaks = the fields at their locations",
           mismatch <= 1e-10,
           "");
  }
} // namespace

int
main()
{
  initlog();
  polynomial_fields(0.);
  polynomial_fields(0.3);
  solved_scene();
}
