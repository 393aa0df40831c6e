#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/halfspace/memory_guard.h>

#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

namespace PlateOnHalfspace
{
  namespace
  {
    std::string
    gigabytes(const std::size_t bytes)
    {
      std::ostringstream s;
      s << std::setprecision(3) << bytes / 1073741824. << " GiB";
      return s.str();
    }
  } // namespace

  std::size_t
  dense_foundation_bytes(const std::size_t n_foundation_nodes,
                         const bool        iterative)
  {
    return (iterative ? 3 : 7) * n_foundation_nodes * n_foundation_nodes *
           sizeof(double);
  }

  std::size_t
  available_memory_bytes()
  {
    std::size_t   available = 0;
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;)
      {
        std::size_t kilobytes = 0;
        meminfo >> kilobytes;
        if (key == "MemAvailable:")
          {
            available = kilobytes * 1024;
            break;
          }
        meminfo.ignore(256, '\n');
      }
    if (const char *limit = std::getenv("PLATE_ON_HALFSPACE_MEMORY_LIMIT"))
      {
        char             *end   = nullptr;
        const double      value = std::strtod(limit, &end);
        const std::string unit  = end;
        const double      scale = (unit == "K" ? 1024. :
                                   unit == "M" ? 1048576. :
                                   unit == "G" ? 1073741824. :
                                                 1.);
        const std::size_t bytes = static_cast<std::size_t>(value * scale);
        AssertThrow(value > 0 && (unit.empty() || scale > 1.),
                    dealii::ExcMessage(
                      "The environment variable PLATE_ON_HALFSPACE_MEMORY_"
                      "LIMIT = <" +
                      std::string(limit) +
                      "> must be a positive number of bytes, optionally with "
                      "a suffix K, M or G."));
        if (available == 0 || bytes < available)
          available = bytes;
      }
    return available;
  }

  MemoryOnMachine
  memory_on_machine(const std::size_t needed, const MPI_Comm communicator)
  {
    MemoryOnMachine memory;
    memory.needed    = needed;
    memory.available = available_memory_bytes();
    if (n_ranks(communicator) > 1)
      {
        MPI_Comm  machine;
        const int error = MPI_Comm_split_type(
          communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
        AssertThrowMPI(error);
        memory.needed = dealii::Utilities::MPI::sum(needed, machine);
        memory.available =
          dealii::Utilities::MPI::min(memory.available, machine);
        memory.ranks = n_ranks(machine);
        MPI_Comm_free(&machine);
      }
    const bool short_here =
      memory.available > 0 && memory.needed > memory.available;
    memory.fits =
      dealii::Utilities::MPI::max(short_here ? 1u : 0u, communicator) == 0u;
    return memory;
  }

  std::string
  machine_shortfall_text(const MemoryOnMachine &memory)
  {
    std::ostringstream text;
    text << std::setprecision(3);
    if (memory.ranks > 1)
      text << " on each process, " << memory.needed / 1073741824.
           << " GiB for the " << memory.ranks
           << " processes on its machine together";
    text << ", but only " << memory.available / 1073741824.
         << " GiB are available";
    if (memory.ranks > 1)
      text << " (on this or another of the run's machines)";
    text << ".";
    return text.str();
  }

  std::string
  dense_foundation_memory_shortfall(const std::size_t n_foundation_nodes,
                                    const bool        iterative,
                                    const bool        suggest_hierarchical)
  {
    const std::size_t needed =
      dense_foundation_bytes(n_foundation_nodes, iterative);
    const std::size_t available = available_memory_bytes();
    if (available == 0 || needed <= available)
      return {};
    return "The dense foundation block of " +
           std::to_string(n_foundation_nodes) + " nodes needs about " +
           std::to_string(needed) + " bytes (" + gigabytes(needed) +
           (iterative ? ", 3" : ", 7") + " n^2 doubles), but only " +
           std::to_string(available) + " bytes (" + gigabytes(available) +
           ") are available. Reduce the node count: Discretization/"
           "Subdivisions x and y, Discretization/Initial refinements, "
           "Adaptivity/Max cells or Adaptivity/Cycles (memory grows with the "
           "square of the nodes; Discretization/Symmetry, where available, "
           "quarters it)" +
           std::string(
             suggest_hierarchical ?
               ", or use Foundation operator/Storage = hierarchical." :
               "; the hierarchical storage's conjugate gradients "
               "failed on this scene (Contact/Solver = auto).");
  }

  void
  check_dense_foundation_memory(const std::size_t n_foundation_nodes,
                                const bool        iterative,
                                const bool        suggest_hierarchical)
  {
    const std::string shortfall =
      dense_foundation_memory_shortfall(n_foundation_nodes,
                                        iterative,
                                        suggest_hierarchical);
    AssertThrow(shortfall.empty(), dealii::ExcMessage(shortfall));
  }
} // namespace PlateOnHalfspace
