#include <deal.II/base/exceptions.h>

#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria_description.h>

#include <plate_on_halfspace/scene/mirror_symmetry.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

namespace PlateOnHalfspace
{
  std::string
  MirrorSymmetry::name() const
  {
    return x ? (y ? "xy" : "x") : (y ? "y" : "none");
  }

  std::vector<std::array<double, 2>>
  MirrorSymmetry::reflections() const
  {
    std::vector<std::array<double, 2>> result;
    if (x)
      result.push_back({{-1., 1.}});
    if (y)
      result.push_back({{1., -1.}});
    if (x && y)
      result.push_back({{-1., -1.}});
    return result;
  }

  Point<2>
  MirrorSymmetry::to_computed_part(const Point<2> &p) const
  {
    return Point<2>(x ? std::abs(p[0]) : p[0], y ? std::abs(p[1]) : p[1]);
  }

  Point<2>
  MirrorSymmetry::from_computed_part(const Point<2> &p,
                                     const Point<2> &reference) const
  {
    return Point<2>(x && reference[0] < 0 ? -p[0] : p[0],
                    y && reference[1] < 0 ? -p[1] : p[1]);
  }

  std::vector<Point<2>>
  MirrorSymmetry::images(const Point<2>    &p,
                         const unsigned int split_planes) const
  {
    std::vector<Point<2>> result = {p};
    for (const auto &signs : reflections())
      // a point on a plane is its own image across that plane, but for a
      // joint's two sides
      if ((signs[0] > 0 || std::abs(p[0]) > tolerance || (split_planes & 1)) &&
          (signs[1] > 0 || std::abs(p[1]) > tolerance || (split_planes & 2)))
        result.emplace_back(signs[0] * p[0], signs[1] * p[1]);
    return result;
  }

  namespace
  {
    /** The mirror image of @p p across the plane normal to @p axis. */
    Point<2>
    mirrored(const Point<2> &p, const unsigned int axis)
    {
      Point<2> image = p;
      image[axis]    = -image[axis];
      return image;
    }

    /**
     * Whether every point of @p points has its mirror image (across the
     * plane normal to @p axis) among them, to @p tolerance. Points are
     * binned on a grid of size 4 tolerance; an image is looked for in its
     * bin and the neighbouring ones.
     */
    bool
    mirror_closed(const std::vector<Point<2>> &points,
                  const unsigned int           axis,
                  const double                 tolerance)
    {
      const double h   = 4 * tolerance;
      const auto   bin = [h](const Point<2> &p) {
        return std::make_pair(std::llround(p[0] / h), std::llround(p[1] / h));
      };
      std::multimap<std::pair<long long, long long>, Point<2>> bins;
      for (const Point<2> &p : points)
        bins.emplace(bin(p), p);
      for (const Point<2> &p : points)
        {
          const Point<2> image = mirrored(p, axis);
          const auto     b     = bin(image);
          bool           found = false;
          for (long long i = -1; i <= 1 && !found; ++i)
            for (long long j = -1; j <= 1 && !found; ++j)
              {
                const auto range =
                  bins.equal_range(std::make_pair(b.first + i, b.second + j));
                for (auto it = range.first; it != range.second && !found; ++it)
                  found = it->second.distance(image) <= tolerance;
              }
          if (!found)
            return false;
        }
      return true;
    }

    /**
     * Why the scene is not symmetric about the plane normal to @p axis, or
     * an empty string if it is.
     */
    std::string
    reason_against_plane(
      const SceneParameters                                  &parameters,
      const Triangulation<2>                                 &mesh,
      const unsigned int                                      axis,
      const double                                            tolerance,
      const std::function<std::string(unsigned int, double)> &loads_reason)
    {
      const std::string plane = (axis == 0 ? "x = 0" : "y = 0");
      for (const auto &cell : mesh.active_cell_iterators())
        {
          double lowest = 0, highest = 0;
          for (const unsigned int v : cell->vertex_indices())
            {
              lowest  = std::min(lowest, cell->vertex(v)[axis]);
              highest = std::max(highest, cell->vertex(v)[axis]);
            }
          if (lowest < -tolerance && highest > tolerance)
            return "cells of the mesh straddle the plane " + plane +
                   (parameters.plate.shape ==
                        Parameters::Plate::Shape::rectangle ?
                      std::string(" (an odd Discretization/Subdivisions ") +
                        (axis == 0 ? "x" : "y") + ")" :
                      std::string());
        }
      std::vector<Point<2>> centres;
      for (const auto &cell : mesh.active_cell_iterators())
        centres.push_back(cell->center());
      if (!mirror_closed(mesh.get_vertices(), axis, tolerance) ||
          !mirror_closed(centres, axis, tolerance))
        return "the mesh is not mirror symmetric about " + plane;

      return loads_reason(axis, tolerance);
    }

    double
    mesh_extent(const Triangulation<2> &mesh)
    {
      double extent = 0;
      for (const Point<2> &v : mesh.get_vertices())
        extent = std::max(extent, v.norm());
      return extent;
    }
  } // namespace

  MirrorSymmetry
  choose_mirror_symmetry(
    const SceneParameters                                  &parameters,
    const Triangulation<2>                                 &coarse_mesh,
    const std::function<std::string(unsigned int, double)> &loads_reason)
  {
    const std::string &requested = parameters.discretization.symmetry;
    MirrorSymmetry     symmetry;
    symmetry.tolerance = 1e-10 * mesh_extent(coarse_mesh);
    if (requested == "none")
      return symmetry;
    // a sweep moves the axles off any plane of the first position
    if (parameters.loads.sweep_steps > 0)
      {
        AssertThrow(requested == "auto",
                    ExcMessage("Discretization/Symmetry = " + requested +
                               ": Loads/Sweep moves the axles, so the scene "
                               "is not symmetric at every position. Use "
                               "auto or none."));
        return symmetry;
      }
    const double tolerance = symmetry.tolerance;
    for (const unsigned int axis : {0u, 1u})
      {
        const bool wanted =
          requested.find(axis == 0 ? 'x' : 'y') != std::string::npos;
        if (requested != "auto" && !wanted)
          continue;
        const std::string reason = reason_against_plane(
          parameters, coarse_mesh, axis, tolerance, loads_reason);
        AssertThrow(reason.empty() || requested == "auto",
                    ExcMessage("Discretization/Symmetry = " + requested +
                               ": the scene is not symmetric, " + reason +
                               ". Use auto (the planes the scene has) or "
                               "none."));
        (axis == 0 ? symmetry.x : symmetry.y) = reason.empty();
      }
    return symmetry;
  }

  void
  cut_to_computed_part(const MirrorSymmetry &symmetry,
                       Triangulation<2>     &triangulation)
  {
    if (!symmetry.x && !symmetry.y)
      return;
    AssertThrow(triangulation.n_levels() == 1,
                ExcInternalError("The mesh is cut before it is refined."));
    const double tolerance = symmetry.tolerance;
    const auto   kept      = [&](const Triangulation<2>::cell_iterator &cell) {
      const Point<2> c = cell->center();
      return (!symmetry.x || c[0] > 0) && (!symmetry.y || c[1] > 0);
    };

    std::map<unsigned int, unsigned int> new_index;
    std::vector<Point<2>>                vertices;
    const auto vertex = [&](const unsigned int old_index) {
      const auto [it, inserted] =
        new_index.emplace(old_index,
                          static_cast<unsigned int>(vertices.size()));
      if (inserted)
        vertices.push_back(triangulation.get_vertices()[old_index]);
      return it->second;
    };
    std::vector<CellData<2>> cells;
    SubCellData              faces;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (!kept(cell))
          continue;
        CellData<2> data;
        for (const unsigned int v : cell->vertex_indices())
          data.vertices[v] = vertex(cell->vertex_index(v));
        data.material_id = cell->material_id();
        data.manifold_id = cell->manifold_id();
        cells.push_back(data);
        // Curved faces keep their manifold (a disk's rim).
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->manifold_id() != numbers::flat_manifold_id)
            {
              CellData<1> line;
              line.vertices    = {vertex(cell->face(f)->vertex_index(0)),
                                  vertex(cell->face(f)->vertex_index(1))};
              line.manifold_id = cell->face(f)->manifold_id();
              line.boundary_id =
                (cell->at_boundary(f) || !kept(cell->neighbor(f))) ?
                  0 :
                  numbers::internal_face_boundary_id;
              faces.boundary_lines.push_back(line);
            }
      }

    std::map<types::manifold_id, std::unique_ptr<Manifold<2>>> manifolds;
    for (const types::manifold_id id : triangulation.get_manifold_ids())
      if (id != numbers::flat_manifold_id)
        manifolds[id] = triangulation.get_manifold(id).clone();
    triangulation.clear();
    triangulation.reset_all_manifolds();
    triangulation.create_triangulation(vertices, cells, faces);
    for (auto &[id, manifold] : manifolds)
      if (dynamic_cast<TransfiniteInterpolationManifold<2> *>(manifold.get()))
        {
          // built on the cells it interpolates: build it anew on these
          TransfiniteInterpolationManifold<2> transfinite;
          transfinite.initialize(triangulation);
          triangulation.set_manifold(id, transfinite);
        }
      else
        triangulation.set_manifold(id, *manifold);

    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->at_boundary(f))
          {
            const auto face     = cell->face(f);
            const auto on_plane = [&](const unsigned int axis) {
              return std::abs(face->vertex(0)[axis]) <= tolerance &&
                     std::abs(face->vertex(1)[axis]) <= tolerance;
            };
            face->set_boundary_id(
              symmetry.x && on_plane(0) ? mirror_plane_x_boundary_id :
              symmetry.y && on_plane(1) ? mirror_plane_y_boundary_id :
                                          0);
          }
  }

} // namespace PlateOnHalfspace
