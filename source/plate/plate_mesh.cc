#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <deal.II/numerics/rtree.h>

#include <plate_on_halfspace/base/error_on_every_rank.h>
#include <plate_on_halfspace/base/number_list.h>
#include <plate_on_halfspace/base/quadrilateral_geometry.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/plate/plate_mesh.h>
#include <plate_on_halfspace/scene/input_checks.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * Refuse a cell whose bilinear map is not one-to-one: a zero-area cell,
     * a collapsed edge, a non-convex or self-intersecting (bow-tie) or
     * inverted quadrilateral. Its Jacobian vanishes or changes sign inside
     * the cell, so the plate's integrals divide by zero and the results
     * hold NaN (doc/errors-and-limits.md). The Jacobian determinant of a
     * bilinear map is linear in each reference coordinate, so it is
     * positive on the whole cell iff it is positive at the four vertices;
     * the bound is relative to the cell's size, as a determinant is an area.
     */
    void
    check_cells_are_valid(const Triangulation<2> &triangulation,
                          const std::string      &file_name)
    {
      const Point<2> corners[4] = {Point<2>(0, 0),
                                   Point<2>(1, 0),
                                   Point<2>(0, 1),
                                   Point<2>(1, 1)};
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          std::array<Point<2>, 4> vertices;
          for (unsigned int v = 0; v < 4; ++v)
            vertices[v] = cell->vertex(v);
          const BilinearQuadrilateral geometry(vertices);
          const double                size = geometry.diameter();
          double smallest = std::numeric_limits<double>::infinity();
          double largest  = -smallest;
          for (const Point<2> &corner : corners)
            {
              const double j = geometry.jacobian_determinant(corner);
              smallest       = std::min(smallest, j);
              largest        = std::max(largest, j);
            }
          if (smallest > 1e-12 * size * size)
            continue;
          std::ostringstream message;
          message << "Plate/Mesh file: cell " << cell->active_cell_index() + 1
                  << " of <" << file_name << "> with the vertices";
          for (const unsigned int v : {0u, 1u, 3u, 2u})
            message << (v == 0 ? " (" : ", (") << vertices[v][0] << ", "
                    << vertices[v][1] << ")";
          message << " is degenerate ("
                  << (!(size > 0) || largest <= 1e-12 * size * size ?
                        "zero or negative area, or inverted" :
                        "not convex, self-intersecting or with a collapsed "
                        "edge")
                  << ": the Jacobian of its map ranges from " << smallest
                  << " to " << largest
                  << " over its vertices, and must exceed 1e-12 of its "
                     "diameter squared, "
                  << 1e-12 * size * size
                  << ", at all of them). Mend the "
                     "cell in the mesh generator; every cell must be a "
                     "convex quadrilateral with its vertices in order "
                     "around it.";
          AssertThrow(false, ExcMessage(message.str()));
        }
    }

    /**
     * Refuse a Gmsh file whose $Nodes or $Elements section declares more
     * entries than the file could hold (each takes a line of at least six
     * bytes) or a negative number of them, before GridIn allocates for
     * that count: a count of 1e9 in a small file would otherwise ask for
     * tens of GB, and a negative one ends in std::bad_alloc. Format 2 gives
     * the count alone on the section's first line, format 4 as the second
     * of four numbers.
     */
    void
    check_msh_counts(const std::string &file_name)
    {
      std::ifstream file(file_name, std::ios::binary);
      file.seekg(0, std::ios::end);
      const double bytes = static_cast<double>(file.tellg());
      file.seekg(0);
      std::string line;
      while (std::getline(file, line))
        {
          if (!line.empty() && line.back() == '\r')
            line.pop_back();
          if (line != "$Nodes" && line != "$Elements")
            continue;
          const std::string section = line;
          if (!std::getline(file, line))
            return;
          std::istringstream  fields(line);
          std::vector<double> numbers;
          double              number;
          while (fields >> number)
            numbers.push_back(number);
          if (numbers.empty())
            continue; // GridIn says what it cannot read
          const double count = numbers.size() >= 4 ? numbers[1] : numbers[0];
          std::ostringstream message;
          message << "Plate/Mesh file: <" << file_name << "> declares " << count
                  << " entries in its " << section << " section, ";
          AssertThrow(count >= 0,
                      ExcMessage(message.str() + "a negative number."));
          message << "more than its " << bytes
                  << " bytes can hold (at least 6 bytes each): the file is "
                     "truncated or the count is wrong.";
          AssertThrow(6 * count <= bytes, ExcMessage(message.str()));
        }
    }

    /**
     * Where GridIn could not read @p file_name: the first field of its
     * $Nodes section that is not a finite decimal number ("line 7: <nan>"),
     * or "" if every field is one. GridIn itself then reports only that it
     * lost its place in the file ("<$Nodes> is not recognized").
     */
    std::string
    unreadable_node_field(const std::string &file_name)
    {
      std::ifstream file(file_name, std::ios::binary);
      std::string   line;
      bool          in_nodes = false;
      for (unsigned int number = 1; std::getline(file, line); ++number)
        {
          if (!line.empty() && line.back() == '\r')
            line.pop_back();
          if (line == "$Nodes" || line == "$EndNodes")
            {
              in_nodes = line == "$Nodes";
              continue;
            }
          if (!in_nodes)
            continue;
          std::istringstream fields(line);
          for (std::string field; fields >> field;)
            {
              // GridIn reads an underflow as 0
              double               value   = 0;
              const DecimalReading reading = read_decimal_number(field, value);
              if (reading != DecimalReading::number &&
                  reading != DecimalReading::underflow)
                return "line " + std::to_string(number) + ": <" + field + ">";
            }
        }
      return "";
    }

    /**
     * Refuse a Gmsh mesh with two vertices at one place: GridIn keeps them
     * apart, so the cells on either side share no degree of freedom and the
     * plate would be cut there without notice (a mesh made of surfaces
     * that Gmsh did not make coherent). Places within 1e-9 of the mesh's
     * size count as one.
     */
    void
    check_vertices_are_merged(const Triangulation<2> &triangulation,
                              const std::string      &file_name)
    {
      const std::vector<Point<2>> &vertices = triangulation.get_vertices();
      const std::vector<bool>     &used     = triangulation.get_used_vertices();
      std::vector<unsigned int>    order;
      for (unsigned int v = 0; v < vertices.size(); ++v)
        if (used[v])
          order.push_back(v);
      std::sort(order.begin(), order.end(), [&](const auto a, const auto b) {
        return vertices[a][0] < vertices[b][0] ||
               (vertices[a][0] == vertices[b][0] &&
                vertices[a][1] < vertices[b][1]);
      });
      // the end of each run of equal x, so that a column of a structured
      // mesh is not scanned past the y within reach
      std::vector<std::size_t> run_end(order.size());
      for (std::size_t i = order.size(); i-- > 0;)
        run_end[i] = i + 1 < order.size() &&
                         vertices[order[i + 1]][0] == vertices[order[i]][0] ?
                       run_end[i + 1] :
                       i + 1;
      const auto corners =
        GridTools::compute_bounding_box(triangulation).get_boundary_points();
      const double tolerance = 1e-9 * corners.first.distance(corners.second);
      std::size_t  pairs     = 0;
      Point<2>     first;
      for (std::size_t i = 0; i < order.size(); ++i)
        for (std::size_t j = i + 1;
             j < order.size() &&
             vertices[order[j]][0] - vertices[order[i]][0] <= tolerance;
             ++j)
          {
            const double dy = vertices[order[j]][1] - vertices[order[i]][1];
            if (std::abs(dy) <= tolerance)
              {
                if (pairs == 0)
                  first = vertices[order[i]];
                ++pairs;
              }
            else if (dy > tolerance && j < run_end[i])
              j = run_end[i] - 1; // the rest of this column lies higher
          }
      if (pairs == 0)
        return;
      std::ostringstream message;
      message << "Plate/Mesh file: <" << file_name << "> has " << pairs
              << (pairs == 1 ? " pair" : " pairs")
              << " of distinct vertices at the same place (the first at ("
              << first[0] << ", " << first[1]
              << ")): the cells on either side would not be connected, and "
                 "the plate would be cut there. Merge them (in Gmsh: "
                 "Geometry.AutoCoherence = 1, or Coherence Mesh before "
                 "saving); a joint is modelled by Plate/Shape = slabs.";
      AssertThrow(false, ExcMessage(message.str()));
    }

    /**
     * Refuse a Gmsh mesh whose vertices do not lie in one plane z = const:
     * GridIn reads a 2d mesh's x and y and drops z, which would flatten a
     * tilted or curved surface without notice. The file is read again as a
     * surface in 3d for its z; a file that this reading refuses (it does
     * not reorient cells as the 2d reading does) was read in 2d already.
     */
    void
    check_mesh_is_plane(const std::string      &file_name,
                        const Triangulation<2> &plane)
    {
      Triangulation<2, 3> surface;
      try
        {
          std::ifstream file(file_name);
          GridIn<2, 3>  grid_in(surface);
          grid_in.read_msh(file);
        }
      catch (const std::exception &)
        {
          return;
        }
      double lowest  = std::numeric_limits<double>::infinity(),
             highest = -lowest;
      for (const Point<3> &vertex : surface.get_vertices())
        {
          lowest  = std::min(lowest, vertex[2]);
          highest = std::max(highest, vertex[2]);
        }
      const auto corners =
        GridTools::compute_bounding_box(plane).get_boundary_points();
      const double size = corners.first.distance(corners.second);
      // A tilt of dz over the diameter shortens the plan by (dz/size)^2 / 2:
      // 5e-9 at this bound, below what the results resolve, while CAD
      // noise and coordinates far from the origin stay well inside it.
      if (!(highest - lowest > 1e-4 * size))
        return;
      std::ostringstream message;
      message
        << std::setprecision(12) << "Plate/Mesh file: <" << file_name
        << "> is not plane: its vertices' z differ by " << highest - lowest
        << " (from " << lowest << " to " << highest
        << ") over a plate of diameter " << size
        << ", more than 1e-4 of it. The plate lies in the plane z = const "
           "and only x and y are read; mesh the plate in one plane (a "
           "constant z is allowed).";
      AssertThrow(false, ExcMessage(message.str()));
    }

    /**
     * Refuse a Gmsh mesh with a hanging node (a T-junction): a vertex that
     * lies inside an edge of a cell without being one of that cell's
     * vertices. That edge is then a boundary face of its cell, the cells on
     * the other side share no degree of freedom with it, and the plate
     * would be cut along it without notice. Every boundary face is checked
     * against the vertices near it (an R-tree of the vertices, so that a
     * mesh of 1e5 cells takes O(n log n)); a vertex within 1e-10 of the
     * face's length of its line and farther than that from both of its end
     * points lies inside it. Overlapping cells are refused before
     * (check_cells_do_not_overlap()): a vertex inside a face that two cells
     * share, or of a cell folded over its neighbour, is one of them.
     */
    void
    check_mesh_is_conforming(const Triangulation<2> &triangulation,
                             const std::string      &file_name)
    {
      namespace bgi                         = boost::geometry::index;
      const std::vector<Point<2>> &vertices = triangulation.get_vertices();
      const std::vector<bool>     &used     = triangulation.get_used_vertices();
      std::vector<Point<2>>        points;
      std::vector<unsigned int>    index_of_point;
      for (unsigned int v = 0; v < vertices.size(); ++v)
        if (used[v])
          {
            points.push_back(vertices[v]);
            index_of_point.push_back(v);
          }
      const auto          tree = pack_rtree_of_indices(points);
      std::vector<bool>   hanging(points.size(), false);
      std::size_t         count = 0;
      std::ostringstream  first;
      std::vector<size_t> near;
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->face(f)->at_boundary())
              continue;
            const unsigned int ends[2] = {
              cell->vertex_index(GeometryInfo<2>::face_to_cell_vertices(f, 0)),
              cell->vertex_index(GeometryInfo<2>::face_to_cell_vertices(f, 1))};
            const Point<2>    &a      = vertices[ends[0]];
            const Point<2>    &b      = vertices[ends[1]];
            const Tensor<1, 2> edge   = b - a;
            const double       length = edge.norm();
            // relative to the face, and no finer than the coordinates'
            // own digits (a mesh in survey coordinates, 4.5e6 m off)
            const double tolerance =
              std::max(1e-10 * length,
                       16 * std::numeric_limits<double>::epsilon() *
                         std::max({std::abs(a[0]),
                                   std::abs(a[1]),
                                   std::abs(b[0]),
                                   std::abs(b[1])}));
            const Point<2> lower(std::min(a[0], b[0]) - tolerance,
                                 std::min(a[1], b[1]) - tolerance);
            const Point<2> upper(std::max(a[0], b[0]) + tolerance,
                                 std::max(a[1], b[1]) + tolerance);
            near.clear();
            tree.query(bgi::intersects(BoundingBox<2>({lower, upper})),
                       std::back_inserter(near));
            for (const size_t i : near)
              {
                if (index_of_point[i] == ends[0] ||
                    index_of_point[i] == ends[1] || hanging[i])
                  continue;
                const Tensor<1, 2> d = points[i] - a;
                // the distance along the face from a, and from its line
                const double along = d * edge / length;
                const double across =
                  (edge[0] * d[1] - edge[1] * d[0]) / length;
                if (!(std::abs(across) <= tolerance && along > tolerance &&
                      along < length - tolerance))
                  continue;
                hanging[i] = true;
                if (count++ > 0)
                  continue;
                // the end points in a fixed order, whatever the cell's
                const bool a_first =
                  a[0] < b[0] || (a[0] == b[0] && a[1] <= b[1]);
                const Point<2> &p = a_first ? a : b;
                const Point<2> &q = a_first ? b : a;
                first << std::setprecision(12) << "the first at ("
                      << points[i][0] << ", " << points[i][1]
                      << "), inside the edge from (" << p[0] << ", " << p[1]
                      << ") to (" << q[0] << ", " << q[1] << ") of cell "
                      << cell->active_cell_index() + 1;
              }
          }
      if (count == 0)
        return;
      std::ostringstream message;
      message << "Plate/Mesh file: <" << file_name
              << "> is not conforming: " << count
              << (count == 1 ? " vertex lies" : " vertices lie")
              << " inside an edge of a cell without being a vertex of that "
                 "cell (a hanging node; "
              << first.str()
              << "): the cells on either side of that edge would not be "
                 "connected, and the plate would be cut there. Cells must "
                 "share whole edges: mesh the plate conforming, without "
                 "hanging nodes (in Gmsh: adjoining surfaces on shared "
                 "curves, Geometry.AutoCoherence = 1).";
      AssertThrow(false, ExcMessage(message.str()));
    }

    /**
     * How far two convex quadrilaterals, their vertices in order around
     * each, overlap: the least, over the normals of the edges of both, of
     * the overlap of their projections onto it. Two convex polygons whose
     * interiors are disjoint have a separating line along one of their
     * edges, so this is <= 0 (up to rounding) for cells that only touch
     * (share an edge or a vertex), and the depth of the overlap otherwise.
     * The coordinates are taken relative to a vertex of @p p, so that a mesh
     * far from the origin keeps its digits.
     */
    double
    overlap_depth(const std::array<Point<2>, 4> &p,
                  const std::array<Point<2>, 4> &q)
    {
      const Point<2> origin = p[0];
      double         depth  = std::numeric_limits<double>::infinity();
      for (const auto *polygon : {&p, &q})
        for (unsigned int e = 0; e < 4; ++e)
          {
            const Tensor<1, 2> edge   = (*polygon)[(e + 1) % 4] - (*polygon)[e];
            const double       length = edge.norm();
            if (!(length > 0))
              continue;
            double low[2]  = {std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::infinity()};
            double high[2] = {-low[0], -low[1]};
            for (unsigned int k = 0; k < 2; ++k)
              for (const Point<2> &vertex : (k == 0 ? p : q))
                {
                  const Tensor<1, 2> d = vertex - origin;
                  const double s = (edge[1] * d[0] - edge[0] * d[1]) / length;
                  low[k]         = std::min(low[k], s);
                  high[k]        = std::max(high[k], s);
                }
            depth =
              std::min(depth,
                       std::min(high[0], high[1]) - std::max(low[0], low[1]));
          }
      return depth;
    }

    /**
     * Refuse a Gmsh mesh whose cells overlap: two cells covering the same
     * area, or a cell folded back over its neighbour (both on the same side
     * of the edge they share). GridIn accepts either, and the area covered
     * twice carries its load and its soil twice. Convex cells are assumed
     * (check_cells_are_valid()); the candidates are the cells whose
     * bounding boxes meet (an R-tree, O(n log n)), and two cells overlap
     * when they do by more than 1e-10 of the smaller one's diameter.
     */
    void
    check_cells_do_not_overlap(const Triangulation<2> &triangulation,
                               const std::string      &file_name)
    {
      namespace bgi                          = boost::geometry::index;
      const unsigned int                   n = triangulation.n_active_cells();
      std::vector<std::array<Point<2>, 4>> polygons(n);
      std::vector<BoundingBox<2>>          boxes(n);
      std::vector<double>                  diameters(n);
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          const unsigned int i = cell->active_cell_index();
          // around the cell (deal.II numbers the vertices lexicographically)
          polygons[i]  = {{cell->vertex(0),
                           cell->vertex(1),
                           cell->vertex(3),
                           cell->vertex(2)}};
          boxes[i]     = cell->bounding_box();
          diameters[i] = std::max(cell->vertex(0).distance(cell->vertex(3)),
                                  cell->vertex(1).distance(cell->vertex(2)));
        }
      const auto          tree     = pack_rtree_of_indices(boxes);
      std::size_t         pairs    = 0;
      unsigned int        first[2] = {0, 0};
      std::vector<size_t> near;
      for (unsigned int i = 0; i < n; ++i)
        {
          near.clear();
          tree.query(bgi::intersects(boxes[i]), std::back_inserter(near));
          for (const size_t j : near)
            if (j > i && overlap_depth(polygons[i], polygons[j]) >
                           1e-10 * std::min(diameters[i], diameters[j]))
              {
                if (pairs == 0)
                  {
                    first[0] = i;
                    first[1] = j;
                  }
                ++pairs;
              }
        }
      if (pairs == 0)
        return;
      std::ostringstream message;
      message << std::setprecision(12) << "Plate/Mesh file: cells "
              << first[0] + 1 << " and " << first[1] + 1 << " of <" << file_name
              << "> overlap (";
      for (unsigned int k = 0; k < 2; ++k)
        {
          message << (k == 0 ? "cell " : "; cell ") << first[k] + 1
                  << " with the vertices";
          for (unsigned int v = 0; v < 4; ++v)
            message << (v == 0 ? " (" : ", (") << polygons[first[k]][v][0]
                    << ", " << polygons[first[k]][v][1] << ")";
        }
      message
        << "; " << pairs << (pairs == 1 ? " pair" : " pairs")
        << " of cells in all): cells that overlap or fold over each "
           "other cover part of the plate twice, and the loads and the "
           "soil there would be counted twice. Mend the mesh in the mesh generator; the "
           "cells must cover the plate once, sharing whole edges.";
      AssertThrow(false, ExcMessage(message.str()));
    }

  } // namespace

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
            check_msh_counts(plate.mesh_file);
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
                const std::string field =
                  unreadable_node_field(plate.mesh_file);
                if (!field.empty())
                  reason = " its $Nodes section, " + field +
                           ", is not a finite decimal number (each node is a "
                           "number and its coordinates x y z).";
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
            check_cells_are_valid(triangulation, plate.mesh_file);
            check_vertices_are_merged(triangulation, plate.mesh_file);
            check_mesh_is_plane(plate.mesh_file, triangulation);
            check_cells_do_not_overlap(triangulation, plate.mesh_file);
            check_mesh_is_conforming(triangulation, plate.mesh_file);
            const auto corners = GridTools::compute_bounding_box(triangulation)
                                   .get_boundary_points();
            const std::string problem = plate_width_problem(
              std::min(corners.second[0] - corners.first[0],
                       corners.second[1] - corners.first[1]),
              plate.thickness,
              "Plate/Mesh file: the plate of <" + plate.mesh_file + ">",
              "the mesh's coordinates");
            AssertThrow(problem.empty(), ExcMessage(problem));
            break;
          }
      }
  }

  void
  partition_plate_mesh(Triangulation<2> &triangulation,
                       const MPI_Comm    communicator)
  {
    const unsigned int n_parts = n_ranks(communicator);
    if (n_parts <= 1)
      return;
    // METIS cannot give every rank a cell of a mesh with fewer cells than
    // ranks (it fails inside with std::bad_array_new_length), and it may
    // leave a part empty even with more. Every rank computes the same
    // partition, so every rank stops here alike (doc/parallel.md).
    const unsigned int n_cells = triangulation.n_active_cells();
    if (n_cells >= n_parts)
      GridTools::partition_triangulation(n_parts,
                                         triangulation,
                                         SparsityTools::Partitioner::metis);
    std::vector<unsigned int> cells_of_rank(n_parts, 0);
    if (n_cells >= n_parts)
      for (const auto &cell : triangulation.active_cell_iterators())
        ++cells_of_rank[std::min(cell->subdomain_id(), n_parts - 1)];
    if (std::count(cells_of_rank.begin(), cells_of_rank.end(), 0u) > 0)
      throw ErrorOnEveryRank(too_many_ranks_message(n_parts, n_cells));
  }

  std::string
  too_many_ranks_message(const unsigned int n_processes,
                         const unsigned int n_cells)
  {
    return "More MPI processes than the mesh can share: " +
           std::to_string(n_processes) + " processes for " +
           std::to_string(n_cells) + (n_cells == 1 ? " cell" : " cells") +
           " (of the part computed: Discretization/Symmetry cuts a "
           "symmetric scene to a half or a quarter), and each process needs "
           "cells with a foundation node of its own. Run on fewer processes "
           "or refine the mesh (Discretization/Subdivisions x and y, "
           "Discretization/Initial refinements).";
  }
} // namespace PlateOnHalfspace
