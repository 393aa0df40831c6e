// The extremes of the plate-to-soil stiffness ratio, on the rigid disk of
// parameters/rigid-disk.prm (E0 = 1e4): plate moduli from 1e3 (a plate far
// softer than the soil) to 5e10 (E/E0 = 5e6), 8e5 times stiffer than the
// soil at its size (D k^4 G(k), k = 1/(2 a)), near the 1e6 beyond which a
// run refuses the plate as rigid for the soil (doc/errors-and-limits.md,
// "Stiffness ratio"). Every run must finish with finite results,
// equilibrium to 1e-10 (the rigid-body correction of the contact solver
// keeps it at the soil's scale however stiff the plate), and the stiff
// runs must approach the rigid punch P(1-nu0^2)/(2 E0 a) = 0.0455 (within
// the disk mesh's discretisation error, 1%), E = 1e10 and 5e10 agreeing to
// 1e-6 (the rigid limit); tensionless contact with the eccentric load
// 0.4 a as well. E = 1e15 is refused, naming the entry.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>
#include <plate_on_halfspace/scene/input_checks.h>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

int
main()
{
  initlog();
  double previous = 0;
  for (const std::string contact : {"bonded", "tensionless"})
    for (const double E : {1e3, 1e9, 1e10, 5e10})
      {
        std::ostringstream extra;
        extra << "subsection Plate\n set Young's modulus = " << E << "\nend\n"
              << "subsection Foundation\n set Contact = " << contact
              << "\nend\nsubsection Adaptivity\n set Cycles = 1\nend\n";
        if (contact == "tensionless")
          extra << "subsection Loads\n set Point loads = 0.4,0,1000\nend\n";
        const auto   problem = solve_scene("rigid-disk.prm", extra.str());
        const auto  &s       = problem->summaries().back();
        const double w       = problem->values_at(Point<2>(0, 0.5)).w;
        // w for the record, 4 digits: the near-singular solves at large E
        // change later digits with the CPU (the checks follow)
        deallog << std::setprecision(6) << contact << ", E = " << E
                << ": w(0,0.5) = " << std::setprecision(4) << w
                << std::setprecision(10) << ", nodes in contact "
                << s.count("contact_nodes") << std::endl;
        AssertThrow(std::isfinite(w), ExcMessage("not finite"));
        check("  contact force",
              s.number("contact_force"),
              s.number("applied_load"),
              1e-10);
        if (E >= 1e9 && contact == "bonded")
          check("  rigid punch", w, 0.0455, 1e-2);
        if (E >= 5e10)
          check("  same as E = 1e10", w, previous, 1e-6);
        previous = w;
      }
  bool refused = false;
  try
    {
      solve_scene("rigid-disk.prm",
                  "subsection Plate\n set Young's modulus = 1e15\nend\n");
    }
  catch (const std::exception &error)
    {
      const std::string message = one_line_message(error);
      refused = message.find("The plate is 1.58e+10 times stiffer than the "
                             "half-space soil") != std::string::npos &&
                message.find("Plate/Young's modulus at most 6.32e+10") !=
                  std::string::npos;
    }
  require("E = 1e15: refused as rigid for the soil, naming Plate/Young's "
          "modulus",
          refused);
}
