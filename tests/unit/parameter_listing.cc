// The full parameter listing with documentation and defaults (what
// `plate-on-halfspace --print-parameters` prints), so that a silent change
// of a default or an entry shows up in review.

#include <deal.II/base/parameter_handler.h>

#include <plate_on_halfspace/scene/parameters.h>

#include "../tests.h"

using namespace PlateOnHalfspace;

int
main()
{
  initlog();
  ParameterHandler prm;
  SceneParameters::declare_parameters(prm);
  prm.print_parameters(logfile,
                       ParameterHandler::PRM |
                         ParameterHandler::KeepDeclarationOrder);
  // The defaults form a valid scene.
  SceneParameters parameters;
  parameters.read_from_string("");
  deallog << "defaults parse: ok" << std::endl;
}
