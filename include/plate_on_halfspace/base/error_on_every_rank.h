/**
 * An error that every rank of a distributed run meets alike, because it is
 * decided from what all ranks hold the same (the mesh and its partition,
 * doc/parallel.md). Unlike a failure that one rank meets during the solve,
 * it needs no MPI_Abort: main.cc reports it once, in one "Error:" line like
 * a bad scene, and every rank ends with exit status 1.
 */
#ifndef plate_on_halfspace_base_error_on_every_rank_h
#define plate_on_halfspace_base_error_on_every_rank_h

#include <stdexcept>
#include <string>

namespace PlateOnHalfspace
{
  class ErrorOnEveryRank : public std::runtime_error
  {
  public:
    explicit ErrorOnEveryRank(const std::string &message)
      : std::runtime_error(message)
    {}
  };
} // namespace PlateOnHalfspace

#endif
