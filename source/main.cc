/**
 * plate-on-halfspace: an elastic Mindlin plate on an elastic (tensionless)
 * half-space. Usage:
 *   plate-on-halfspace scene.prm
 *   plate-on-halfspace --print-parameters
 *   plate-on-halfspace --print-results
 *   plate-on-halfspace --help
 *   mpirun -np P plate-on-halfspace scene.prm
 * Under MPI every rank runs the same program on a shared mesh; rank 0
 * writes the log, the messages and the results (doc/parallel.md).
 */
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <plate_on_halfspace/base/error_on_every_rank.h>
#include <plate_on_halfspace/base/interruption.h>
#include <plate_on_halfspace/base/mpi_singleton.h>
#include <plate_on_halfspace/base/result_record.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/plate_on_halfspace_problem.h>
#include <plate_on_halfspace/scene/input_checks.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <iostream>
#include <ostream>
#include <string>


int
main(int argc, char **argv)
{
  using namespace PlateOnHalfspace;
  // Before MPI_Init, and destroyed after MPI_Finalize: a run without
  // mpirun gets a private Open MPI session (doc/parallel.md, "Serial runs").
  const MpiSingletonEnvironment singleton;
  // Each rank takes its share of the cores for deal.II's threads.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv);
  dealii::deal_II_exceptions::disable_abort_on_exception();
  begin_failure_agreement();
  // SIGINT and SIGTERM stop the run at a safe point with its earlier
  // results restored (base/interruption.h, doc/outputs.md).
  Interruption::catch_signals();
  const bool is_root = rank_in(MPI_COMM_WORLD) == 0;
  // The other ranks compute the same scene; only rank 0 speaks.
  std::ostream  silent(nullptr);
  std::ostream &out = is_root ? std::cout : silent;
  std::ostream &err = is_root ? std::cerr : silent;

  const std::string usage =
    "usage: plate-on-halfspace SCENE.prm | --print-parameters | "
    "--print-results";
  if (argc != 2)
    {
      err << usage << std::endl;
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
            out,
            dealii::ParameterHandler::PRM |
              dealii::ParameterHandler::KeepDeclarationOrder);
          return 0;
        }
      // the keys of summary.json and the columns of convergence.txt, as
      // their producers declare them (base/result_record.h)
      if (argument == "--print-results")
        {
          out << results_help_text();
          return 0;
        }
      if (argument == "--help" || argument == "-h")
        {
          out << usage << std::endl;
          return 0;
        }
      // Any other argument that begins with '-' is an option this program
      // does not have (--help=1, --print-parameter): the usage, status 2,
      // as for a wrong number of arguments. A scene file whose name begins
      // with '-' is reached as ./-x.prm.
      if (argument.rfind('-', 0) == 0)
        {
          err << "Error: unknown option <" << printable(argument)
              << ">; a scene file whose name begins with - is given as ./"
              << printable(argument) << "." << std::endl
              << usage << std::endl;
          return 2;
        }
      // Every rank reads the same file and fails alike: a bad scene ends
      // every rank here with one message.
      SceneParameters parameters;
      parameters.read(argument);
      for (const std::string &warning : scene_warnings(parameters))
        err << "Warning: " << printable(warning) << std::endl;
      try
        {
          PlateOnHalfspaceProblem problem(parameters, out);
          if (!problem.run())
            {
              err << "Error: a Verification/Checks value was not reproduced."
                  << std::endl;
              return 1;
            }
        }
      catch (const Interrupted &e)
        {
          // Every rank stopped at the same safe point (check() agrees over
          // the ranks) and the earlier results are back: the conventional
          // status of a death by the signal, 128 + its number.
          out.flush();
          if (e.results_committed())
            {
              err << "Error: " << e.what()
                  << " after the results were written; they are whole in <"
                  << printable(parameters.output_directory)
                  << "> (doc/outputs.md)." << std::endl;
              return 128 + e.signal_number();
            }
          err << "Error: " << e.what() << "; the earlier results in <"
              << printable(parameters.output_directory)
              << "> are kept (doc/outputs.md)." << std::endl;
          return 128 + e.signal_number();
        }
      catch (const std::exception &e)
        {
          // During the run a rank may fail while the others wait for it in
          // a collective step: on several processes the failing rank says
          // why and stops them all (doc/parallel.md). Its earlier results
          // are already restored (ResultsOutput).
          out.flush();
          // An error all ranks meet alike (too many ranks for the mesh, a
          // load off the plate) is reported once, like a bad scene.
          if (every_rank_fails_alike(e, FailureSite::run))
            throw;
          std::cerr << "Error (rank " << rank_in(MPI_COMM_WORLD) << " of "
                    << n_ranks(MPI_COMM_WORLD)
                    << "): " << short_error_message(e) << std::endl;
          MPI_Abort(MPI_COMM_WORLD, 1);
        }
    }
  catch (const std::exception &e)
    {
      out.flush();
      err << "Error: " << short_error_message(e) << std::endl;
      return 1;
    }
  return 0;
}
