/**
 * plate-on-halfspace: an elastic Mindlin plate on an elastic (tensionless)
 * half-space. Usage:
 *   plate-on-halfspace scene.prm
 *   plate-on-halfspace --print-parameters
 */
#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <plate_on_halfspace/plate_on_halfspace_problem.h>
#include <plate_on_halfspace/scene/input_checks.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <iostream>
#include <string>


int
main(int argc, char **argv)
{
  using namespace PlateOnHalfspace;
  dealii::deal_II_exceptions::disable_abort_on_exception();

  const std::string usage =
    "usage: plate-on-halfspace SCENE.prm | --print-parameters";
  if (argc != 2)
    {
      std::cerr << usage << std::endl;
      return 2;
    }
  const std::string argument = argv[1];
  try
    {
      if (argument == "--print-parameters")
        {
          dealii::ParameterHandler prm;
          SceneParameters::declare_parameters(prm);
          prm.print_parameters(
            std::cout,
            dealii::ParameterHandler::PRM |
              dealii::ParameterHandler::KeepDeclarationOrder);
          return 0;
        }
      if (argument == "--help" || argument == "-h")
        {
          std::cout << usage << std::endl;
          return 0;
        }
      SceneParameters parameters;
      parameters.read(argument);
      for (const std::string &warning : scene_warnings(parameters))
        std::cerr << "Warning: " << warning << std::endl;
      PlateOnHalfspaceProblem problem(parameters, std::cout);
      if (!problem.run())
        {
          std::cerr << "Error: a Verification/Checks value was not reproduced."
                    << std::endl;
          return 1;
        }
    }
  catch (const std::exception &e)
    {
      std::cout.flush();
      std::cerr << "Error: " << short_error_message(e) << std::endl;
      return 1;
    }
  return 0;
}
