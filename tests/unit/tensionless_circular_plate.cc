// Lift-off of a weightless circular plate under a central point load on a
// tensionless half-space, against the computed reference of doc/verification.md
// ("Tensionless circular plate, weightless, central point load"): with
// K = (l/a)^3, l^3 = 2 D (1 - nu0^2) / E0, the plate keeps full contact
// for K >= about 0.069 and otherwise touches the soil on a disk of radius
// c: c/a = 0.408 at K = 0.003 and 0.587 at K = 0.01.
//
// The disk of parameters/rigid-disk.prm (a = 1 m, E0 = 1e4, nu0 = 0.3) is
// made a thin plate (t = 0.01 m, so l/t >= 14: nearly Kirchhoff) of the
// bending stiffness that gives K, solved on a quarter with 4 adaptive
// cycles (the indicator refines along the contact boundary). The contact
// radius is read two ways: from the contact area fraction, c/a =
// sqrt(fraction), and as the bracket between the outermost node in contact
// and the innermost lifted node. Before the contact conditions were stated
// in the positive pressure basis (foundation_space.h), a nodal condition
// q_i >= 0 on serendipity functions let the plate keep contact far beyond
// c.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

int
main()
{
  initlog();
  deallog << std::setprecision(4);
  const double a = 1, E0 = 1e4, nu0 = 0.3, t = 0.01, nu = 0.2;
  struct Case
  {
    double K, reference; // c/a; 1: full contact
  };
  for (const Case &c : {Case{0.003, 0.408}, Case{0.01, 0.587}, Case{0.1, 1.}})
    {
      const double       D = c.K * a * a * a * E0 / (2. * (1. - nu0 * nu0));
      const double       E = 12. * D * (1. - nu * nu) / (t * t * t);
      std::ostringstream extra;
      extra << std::setprecision(17)
            << "subsection Plate\n set Thickness = " << t
            << "\n set Young's modulus = " << E << "\nend\n"
            << "subsection Foundation\n set Contact = tensionless\nend\n"
            << "subsection Discretization\n set Symmetry = xy\nend\n"
            << "subsection Adaptivity\n set Cycles = 4\nend\n";
      const auto          problem = solve_scene("rigid-disk.prm", extra.str());
      const ResultRecord &s       = problem->summaries().back();
      const ContactState &state   = problem->contact_state();
      const auto         &nodes =
        problem->plate().get_foundation_space().node_locations;
      double outermost_in = 0, innermost_out = a;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        (state.in_contact[i] ? outermost_in : innermost_out) =
          state.in_contact[i] ? std::max(outermost_in, nodes[i].norm()) :
                                std::min(innermost_out, nodes[i].norm());
      const double from_area = std::sqrt(s.number("contact_area_fraction"));
      deallog << "K = " << c.K << ": contact radius c/a = " << from_area
              << " from the area, nodes in contact up to " << outermost_in
              << ", lifted from " << innermost_out << "; reference "
              << c.reference << " (" << s.count("n_foundation_dofs")
              << " foundation nodes, " << s.count("contact_iterations")
              << " contact iterations)" << std::endl;
      AssertThrow(s.flag("converged") &&
                    std::abs(s.number("contact_force") -
                             s.number("applied_load")) <=
                      1e-10 * s.number("applied_load") &&
                    s.number("complementarity_violation") <= 1e-10,
                  ExcMessage("contact conditions"));
      if (c.reference == 1.)
        {
          AssertThrow(s.number("contact_area_fraction") == 1.,
                      ExcMessage("lift-off above K = 0.069"));
          deallog << "  full contact: ok" << std::endl;
        }
      else
        {
          // 2 % of the radius: the reference's digits and the mesh size
          // at the contact boundary
          const bool area_ok    = std::abs(from_area - c.reference) <= 0.02;
          const bool bracket_ok = innermost_out - 0.02 <= c.reference &&
                                  c.reference <= outermost_in + 0.02;
          deallog << "  |c/a - reference| <= 0.02: "
                  << (area_ok ? "ok" : "FAILED")
                  << "; reference within the node bracket (+-0.02): "
                  << (bracket_ok ? "ok" : "FAILED") << std::endl;
          AssertThrow(area_ok && bracket_ok,
                      ExcMessage(
                        "contact radius differs from doc/verification.md"));
        }
    }
}
