#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/plate/plate_mesh.h>

#include <filesystem>
#include <fstream>
#include <numeric>

namespace PlateOnHalfspace
{
  void
  make_plate_mesh(const Parameters::Plate          &plate,
                  const Parameters::Discretization &discretization,
                  Triangulation<2>                 &triangulation)
  {
    make_coarse_plate_mesh(plate, discretization, triangulation);
    triangulation.refine_global(discretization.initial_refinements);
  }

  void
  make_coarse_plate_mesh(const Parameters::Plate          &plate,
                         const Parameters::Discretization &discretization,
                         Triangulation<2>                 &triangulation)
  {
    triangulation.clear();
    switch (plate.shape)
      {
        case Parameters::Plate::Shape::rectangle:
          GridGenerator::subdivided_hyper_rectangle(
            triangulation,
            {discretization.subdivisions_x, discretization.subdivisions_y},
            Point<2>(-plate.length_x / 2, -plate.length_y / 2),
            Point<2>(plate.length_x / 2, plate.length_y / 2));
          break;
        case Parameters::Plate::Shape::disk:
          // Twelve cells, mirror symmetric about x = 0 and y = 0; refinement
          // moves new boundary vertices onto the circle (the cells stay
          // straight sided, MappingQ1).
          GridGenerator::hyper_ball_balanced(triangulation,
                                             Point<2>(),
                                             plate.radius);
          break;
        case Parameters::Plate::Shape::slabs:
          {
            // Each slab its own vertices (plate/slab_grid.h): the faces of a
            // joint lie on each other but are not shared, so each slab has
            // its own unknowns. Subdivisions x/y are per slab.
            std::vector<Point<2>>    vertices;
            std::vector<CellData<2>> cells;
            const unsigned int       nx = discretization.subdivisions_x;
            const unsigned int       ny = discretization.subdivisions_y;
            double y0 = -std::accumulate(plate.slab_lengths_y.begin(),
                                         plate.slab_lengths_y.end(),
                                         0.) /
                        2;
            types::material_id slab = 0;
            for (const double ly : plate.slab_lengths_y)
              {
                double x0 = -std::accumulate(plate.slab_lengths_x.begin(),
                                             plate.slab_lengths_x.end(),
                                             0.) /
                            2;
                for (const double lx : plate.slab_lengths_x)
                  {
                    const unsigned int first = vertices.size();
                    for (unsigned int j = 0; j <= ny; ++j)
                      for (unsigned int i = 0; i <= nx; ++i)
                        vertices.emplace_back(
                          (i == nx ? x0 + lx : x0 + lx * i / nx),
                          (j == ny ? y0 + ly : y0 + ly * j / ny));
                    for (unsigned int j = 0; j < ny; ++j)
                      for (unsigned int i = 0; i < nx; ++i)
                        {
                          CellData<2>        cell;
                          const unsigned int v = first + j * (nx + 1) + i;
                          cell.vertices    = {v, v + 1, v + nx + 1, v + nx + 2};
                          cell.material_id = slab;
                          cells.push_back(cell);
                        }
                    ++slab;
                    x0 += lx;
                  }
                y0 += ly;
              }
            triangulation.create_triangulation(vertices, cells, SubCellData());
            break;
          }
        case Parameters::Plate::Shape::mesh_file:
          {
            std::ifstream file(plate.mesh_file);
            AssertThrow(file && !std::filesystem::is_directory(plate.mesh_file),
                        ExcMessage("Plate/Mesh file: cannot open <" +
                                   plate.mesh_file + ">."));
            GridIn<2> grid_in(triangulation);
            try
              {
                grid_in.read_msh(file);
              }
            catch (const std::exception &e)
              {
                // GridIn's own reason, without deal.II's source location
                std::string       reason = e.what();
                const std::string marker = "Additional information:";
                if (reason.find(marker) != std::string::npos)
                  reason = reason.substr(reason.find(marker) + marker.size());
                AssertThrow(false,
                            ExcMessage("Plate/Mesh file: <" + plate.mesh_file +
                                       "> is not a readable Gmsh mesh of "
                                       "quadrilaterals: " +
                                       reason));
              }
            AssertThrow(triangulation.n_active_cells() > 0,
                        ExcMessage("Plate/Mesh file: <" + plate.mesh_file +
                                   "> holds no quadrilaterals."));
            // The plate elements are quadrilaterals (doc/formulation.md); Gmsh
            // triangles would reach FE_Q as simplices.
            AssertThrow(triangulation.all_reference_cells_are_hyper_cube(),
                        ExcMessage("Plate/Mesh file: <" + plate.mesh_file +
                                   "> contains triangles; only "
                                   "quadrilaterals are allowed (in Gmsh: "
                                   "Mesh.RecombineAll = 1)."));
            break;
          }
      }
  }

  void
  partition_plate_mesh(Triangulation<2> &triangulation,
                       const MPI_Comm    communicator)
  {
    const unsigned int n_parts = n_ranks(communicator);
    if (n_parts > 1)
      GridTools::partition_triangulation(n_parts,
                                         triangulation,
                                         SparsityTools::Partitioner::metis);
  }
} // namespace PlateOnHalfspace
