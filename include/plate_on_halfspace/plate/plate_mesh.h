/**
 * The plate's initial mesh from the scene: a rectangle or a disk from
 * deal.II's GridGenerator, or a Gmsh file.
 */
#ifndef plate_on_halfspace_plate_plate_mesh_h
#define plate_on_halfspace_plate_plate_mesh_h

#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria.h>

#include <plate_on_halfspace/scene/parameters.h>

#include <string>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * Create the initial mesh of the plate (Plate/Shape, Discretization/
   * Subdivisions and Initial refinements). Throws with a message naming
   * Plate/Mesh file if a file cannot be read or holds other than
   * quadrilaterals.
   */
  void
  make_plate_mesh(const Parameters::Plate          &plate,
                  const Parameters::Discretization &discretization,
                  Triangulation<2>                 &triangulation);

  /** The same without the Initial refinements (the mesh before a
   *  symmetric scene is cut to its computed part). */
  void
  make_coarse_plate_mesh(const Parameters::Plate          &plate,
                         const Parameters::Discretization &discretization,
                         Triangulation<2>                 &triangulation);

  /**
   * Split the cells of @p triangulation among the ranks of
   * @p communicator with METIS (GridTools::partition_triangulation): each
   * cell's subdomain id is its rank (doc/parallel.md). Nothing on one
   * process. Every rank computes the same partition of the same mesh.
   * Throws ErrorOnEveryRank (base/error_on_every_rank.h) with
   * too_many_ranks_message() if a rank would own no cell.
   */
  void
  partition_plate_mesh(Triangulation<2> &triangulation,
                       const MPI_Comm    communicator);

  /**
   * The refusal of a distributed run with more processes than the mesh of
   * @p n_cells cells can share (doc/parallel.md): it names
   * Discretization/Subdivisions x and y.
   */
  std::string
  too_many_ranks_message(const unsigned int n_processes,
                         const unsigned int n_cells);
} // namespace PlateOnHalfspace

#endif
