// Loads/Pressure function (doc/loads.md, "Pressure function").
// 1. The applied load against exact integrals: a polynomial over the whole
//    plate, exp(x) cos(y) over a rectangle region that crosses cell edges
//    and x^2 + y^2 over a disk region; and the stated integration error
//    (load_integration_error) bounds the true one.
// 2. A near-rigid slab (l = 42 m against L = 4 m) on a tensionless dense
//    liquid under p = p0 ((x + L/2)/L)^2, uniform in y. Its resultant lies
//    at L/4 from the centre, outside the kern (L/6), so the slab lifts off;
//    a rigid slab's contact pressure is then linear, its resultant at a
//    third of the contact length c from the loaded edge: c = 3 L/4, the
//    peak pressure 2 F/(c B) = 8 p0/9 and the edge deflections q_max/k
//    and -q_max/(3 k). The contact ends on the node line x = -L/4.

#include <deal.II/base/numbers.h>

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  std::string
  loads(const std::string &function,
        const std::string &constants,
        const std::string &region)
  {
    return "subsection Loads\n set Pressure function = " + function +
           "\n set Function constants = " + constants +
           "\n set Pressure function region = " + region + "\nend\n";
  }
} // namespace

int
main()
{
  initlog();
  // 1. exact integrals on a 4 x 2 slab of 5 x 3 cells refined once (the
  //    regions' edges cross the cells)
  {
    const auto run = [](const std::string &extra) {
      return TestTools::run_scene_text(TestTools::slab_on_dense_liquid(
        4, 2, 0.2, 5e4, "bonded", 5, 3, 1, extra));
    };
    const auto whole = run(loads("p0*(y+1)^2", "p0=5", ""));
    check("whole plate, p0 (y+1)^2: load",
          whole->summaries().back().number("applied_load"),
          4. * 5. * 8. / 3.,
          1e-12);
    const double x1 = -1.3, x2 = 0.9, y1 = -0.55, y2 = 0.35;
    const auto   rectangle =
      run(loads("exp(x)*cos(y)", "", "-1.3,-0.55,0.9,0.35"));
    const double exact_rectangle =
      (std::exp(x2) - std::exp(x1)) * (std::sin(y2) - std::sin(y1));
    const auto &r = rectangle->summaries().back();
    check("rectangle region, exp(x) cos(y): load",
          r.number("applied_load"),
          exact_rectangle,
          1e-10);
    const double a = 0.6, xc = 0.3, yc = -0.2;
    const auto   disk       = run(loads("x^2 + y^2", "", "0.3,-0.2,0.6"));
    const double exact_disk = numbers::PI * std::pow(a, 4) / 2 +
                              numbers::PI * a * a * (xc * xc + yc * yc);
    const auto &d = disk->summaries().back();
    check("disk region, x^2 + y^2: load",
          d.number("applied_load"),
          exact_disk,
          1e-10);
    // a rule of 2 points on cells the disk cuts: the stated error bounds
    // the true one
    const auto coarse =
      run(loads("exp(3*x)", "", "0.3,-0.2,0.6") +
          "subsection Loads\n set Pressure function points = 2\nend\n");
    const double exact_exp = [&] {
      // Int over the disk of exp(3 x) = 2 pi a exp(3 xc) I1(3 a) / 3
      return 2 * numbers::PI * a * std::exp(3 * xc) *
             std::cyl_bessel_i(1., 3 * a) / 3.;
    }();
    const auto  &c = coarse->summaries().back();
    const double true_error =
      std::abs(c.number("applied_load") - exact_exp) / exact_exp;
    deallog << "2 points on a disk of exp(3x): the stated error "
            << (c.number("load_integration_error") >= 0.5 * true_error &&
                    c.number("load_integration_error") > 0 ?
                  "covers" :
                  "DOES NOT cover")
            << " the true error (within a factor 2)" << std::endl;
    AssertThrow(c.number("load_integration_error") >= 0.5 * true_error &&
                  c.number("load_integration_error") > 0,
                ExcMessage("the stated integration error misses the true "
                           "one"));
  }

  // 2. the near-rigid slab lifting off
  {
    const double L = 4, B = 2, k = 1e3, p0 = 9;
    const auto   problem =
      TestTools::run_scene_text(TestTools::slab_on_dense_liquid(
        L,
        B,
        0.5,
        k,
        "tensionless",
        8,
        4,
        1,
        loads("p0*((x+2)/4)^2", "p0=9", "") +
          "subsection Plate\n set Young's modulus = 3e11\nend\n"
          "subsection Output\n set Probe points = 2,0 ; -2,0 ; 1.5,0.5\nend\n"));
    const auto  &s     = problem->summaries().back();
    const double F     = p0 * L * B / 3;
    const double q_max = 8 * p0 / 9;
    check("applied load", s.number("applied_load"), F, 1e-12);
    check("contact force", s.number("contact_force"), F, 1e-8);
    check("peak pressure", s.number("max_q"), q_max, 1e-4);
    check("w at the loaded edge",
          s.items("probes")[0].number("w"),
          q_max / k,
          1e-4);
    check("w at the lifted edge",
          s.items("probes")[1].number("w"),
          -q_max / (3 * k),
          1e-4);
    // q(x) = q_max (x + L/4) / (3 L/4)
    check("q at (1.5, 0.5)",
          s.items("probes")[2].number("q"),
          q_max * (1.5 + L / 4) / (3 * L / 4),
          1e-4);
    // relative to the pressures and gaps (doc/outputs.md); the near-rigid
    // slab's solves leave about 1e-10
    deallog << "complementarity: "
            << (s.number("complementarity_violation") <= 1e-8 ? "within 1e-8" :
                                                                "VIOLATED")
            << std::endl;
    AssertThrow(s.number("complementarity_violation") <= 1e-8,
                ExcMessage("complementarity violated"));
  }
}
