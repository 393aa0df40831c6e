/**
 * The plate's initial mesh from the scene: a rectangle or a disk from
 * deal.II's GridGenerator, or a Gmsh file.
 */
#ifndef plate_on_halfspace_plate_plate_mesh_h
#define plate_on_halfspace_plate_plate_mesh_h

#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria.h>

#include <plate_on_halfspace/scene/parameters.h>

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
   */
  void
  partition_plate_mesh(Triangulation<2> &triangulation,
                       const MPI_Comm    communicator);
} // namespace PlateOnHalfspace

#endif
