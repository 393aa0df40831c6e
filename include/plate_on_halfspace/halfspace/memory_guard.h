/**
 * The memory guard of the dense foundation block: the coupled matrix
 * K̄ + S lives on the n foundation nodes and is dense (n² doubles, several
 * copies at once), so a fine mesh can ask for more memory than the machine
 * has. Before building it, the program estimates the bytes and stops with
 * a message naming them and the entries that reduce n, instead of being
 * killed by the operating system halfway through.
 */
#ifndef plate_on_halfspace_halfspace_memory_guard_h
#define plate_on_halfspace_halfspace_memory_guard_h

#include <mpi.h>

#include <cstddef>
#include <stdexcept>
#include <string>

namespace PlateOnHalfspace
{
  /**
   * A storage's build found that it would need more memory than
   * available_memory_bytes(), before allocating it; what() names the bytes
   * and what helps. Storage = auto takes another storage on it.
   */
  class StorageDoesNotFit : public std::runtime_error
  {
  public:
    StorageDoesNotFit(const std::string &shortfall, const std::string &advice)
      : std::runtime_error(shortfall + advice)
      , shortfall(shortfall)
    {}

    /** The bytes needed and available, without the advice. */
    const std::string shortfall;
  };

  /**
   * Peak bytes of the dense matrices for @p n_foundation_nodes nodes: the
   * half-space flexibility F, the factor of its contact block, the
   * condensed plate K̄, the coupled matrix K̄ + S and the right-hand sides
   * M_{C,:} of S (foundation_operator.h, contact_solver.h), plus the second
   * flexibility that element exclusion keeps: seven n x n doubles. With
   * the iterative contact solver (@p iterative) three: F, the factor of
   * F_CC of all nodes that build() makes, and the Cholesky factor that
   * preconditions the conjugate gradients.
   */
  std::size_t
  dense_foundation_bytes(const std::size_t n_foundation_nodes,
                         const bool        iterative = false);

  /**
   * Bytes the run may use: MemAvailable of /proc/meminfo, or the
   * environment variable PLATE_ON_HALFSPACE_MEMORY_LIMIT (bytes; a suffix
   * K, M or G multiplies by 2^10, 2^20, 2^30) if it is set and smaller.
   * 0 if neither can be read (then the guard does not stop the run).
   */
  std::size_t
  available_memory_bytes();

  /**
   * Whether each rank's @p needed bytes fit, decided by all ranks of
   * @p communicator alike: the ranks that share a machine add their needs
   * and compare them with the least available_memory_bytes() any of them
   * reads; the answer is no if any machine is short. On one process:
   * @p needed against available_memory_bytes(). Collective.
   */
  struct MemoryOnMachine
  {
    bool         fits      = true;
    std::size_t  needed    = 0; ///< this machine's ranks together
    std::size_t  available = 0; ///< on this machine (0: unknown)
    unsigned int ranks     = 1; ///< ranks on this machine
  };
  MemoryOnMachine
  memory_on_machine(const std::size_t needed, const MPI_Comm communicator);

  /**
   * The end of a shortfall message after the bytes one process needs:
   * the machine's processes together (if several), and the bytes
   * available, e.g. ", but only 1.5 GiB are available.".
   */
  std::string
  machine_shortfall_text(const MemoryOnMachine &memory);

  /**
   * "" if dense_foundation_bytes() fits available_memory_bytes(); otherwise
   * the message naming the bytes needed, the bytes available and the
   * entries that reduce the node count; with @p suggest_hierarchical, also
   * the hierarchical storage (not after its iterations failed).
   */
  std::string
  dense_foundation_memory_shortfall(const std::size_t n_foundation_nodes,
                                    const bool        iterative,
                                    const bool        suggest_hierarchical);

  /** Throw an ExcMessage with dense_foundation_memory_shortfall()'s
   *  message unless it is empty. */
  void
  check_dense_foundation_memory(const std::size_t n_foundation_nodes,
                                const bool        iterative            = false,
                                const bool        suggest_hierarchical = true);
} // namespace PlateOnHalfspace

#endif
