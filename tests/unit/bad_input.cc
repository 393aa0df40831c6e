// Bad parameters and physically impossible scenes: each must stop with a
// short message that names the entry (section/entry) or the physical
// reason; never a crash, a NaN or a half-written result. The messages are
// the test's output.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <sstream>

#include "../tests.h"

using namespace PlateOnHalfspace;

void
check(const std::string &what, const std::string &text)
{
  try
    {
      SceneParameters parameters;
      parameters.read_from_string("set Output directory = results\n"
                                  "subsection Output\n set VTU = false\n"
                                  " set Verbosity = 0\nend\n" +
                                  text);
      std::ostringstream      log;
      PlateOnHalfspaceProblem problem(parameters, log);
      problem.run();
      deallog << what << ": accepted -- FAILED" << std::endl;
      AssertThrow(false, ExcMessage("bad input accepted: " + what));
    }
  catch (const std::exception &e)
    {
      const std::string message = short_error_message(e);
      AssertThrow(message.find("bad input accepted") == std::string::npos,
                  ExcMessage(message));
      deallog << what << ": " << message << std::endl;
    }
}

int
main()
{
  initlog();
  check("unknown entry", "subsection Plate\n set Thikness = 1\nend\n");
  check("Poisson's ratio out of range",
        "subsection Plate\n set Poisson's ratio = 0.6\nend\n");
  check("negative thickness", "subsection Plate\n set Thickness = -1\nend\n");
  check("zero soil modulus",
        "subsection Foundation\n set Young's modulus = 0\nend\n");
  check("not a number in a list",
        "subsection Loads\n set Point loads = 0,zero,10\nend\n");
  check("patch with x1 > x2",
        "subsection Loads\n set Rectangular patches = 1,0,0,1,10\nend\n");
  check("patch off the plate",
        "subsection Loads\n set Rectangular patches = 20,20,21,21,10\nend\n");
  check("point load off the plate",
        "subsection Loads\n set Point loads = 50,0,10\nend\n");
  check("probe off the plate",
        "subsection Loads\n set Uniform pressure = 1\nend\n"
        "subsection Output\n set Probe points = 0,40\nend\n");
  check("collocation on a disk",
        "subsection Plate\n set Shape = disk\nend\n"
        "subsection Discretization\n set Flexibility = collocation\nend\n");
  check("iterative solver with collocation",
        "subsection Loads\n set Uniform pressure = 1\nend\n"
        "subsection Discretization\n set Flexibility = collocation\nend\n"
        "subsection Contact\n set Solver = iterative\nend\n");
  check("iterative solver with element exclusion",
        "subsection Loads\n set Uniform pressure = 1\nend\n"
        "subsection Contact\n set Solver = iterative\n"
        " set Method = element exclusion\nend\n");
  check("missing mesh file",
        "subsection Plate\n set Shape = mesh file\n"
        " set Mesh file = no-such-file.msh\nend\n");
  check("compressed storage with the direct solver",
        "subsection Foundation operator\n set Storage = hierarchical\nend\n"
        "subsection Contact\n set Solver = direct\nend\n");
  check("unstable element",
        "subsection Discretization\n set Element = lagrange\n"
        " set Shear integration = reduced\nend\n");
  check("upward load on a tensionless foundation",
        "subsection Loads\n set Uniform pressure = -10\nend\n");
  check("unknown goal", "subsection Adaptivity\n set Goal = Qx at 0,0\nend\n");
  check("goal point with one coordinate",
        "subsection Adaptivity\n set Goal = w at 1\nend\n");
  check("goal point off the plate",
        "subsection Loads\n set Uniform pressure = 1\nend\n"
        "subsection Discretization\n set Initial refinements = 1\nend\n"
        "subsection Adaptivity\n set Goal = Mx at 40,0\nend\n");
  check("goal refinement without a goal",
        "subsection Adaptivity\n set Refinement = goal\nend\n");
  check("target error without a goal",
        "subsection Adaptivity\n set Target error = 0.01\nend\n");
  check("target error of 1 or more",
        "subsection Adaptivity\n set Goal = mean w\n"
        " set Target error = 1\nend\n");
  check("goal with the collocation operator",
        "subsection Discretization\n set Flexibility = collocation\n"
        " set Initial refinements = 1\nend\n"
        "subsection Adaptivity\n set Goal = mean w\nend\n");
  check("goal refinement for a pressure",
        "subsection Adaptivity\n set Goal = q at 0,0\n"
        " set Refinement = goal\nend\n");
  check("unknown summary key in a check",
        "subsection Verification\n set Checks = max_deflection,1,1\nend\n");
}
