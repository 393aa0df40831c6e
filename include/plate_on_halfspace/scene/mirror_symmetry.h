/**
 * Mirror symmetry of a scene about the planes x = 0 and/or y = 0
 * (doc/formulation.md, "Symmetry"): a scene whose plate, mesh and loads are
 * mirror symmetric is solved on the half (x >= 0 or y >= 0) or the quarter
 * (x, y >= 0) of the plate. The solution is symmetric, so on a mirror plane
 * the rotation about the plane's normal vanishes (beta_x = 0 on x = 0,
 * beta_y = 0 on y = 0), and the half-space kernel of the computed part adds
 * the mirror images of the pressure: 1/|x - y| + 1/|x - R y| (+ ...), so
 * that the answer equals the whole plate's.
 *
 * Only scenes that are exactly symmetric are reduced (Discretization/
 * Symmetry = auto finds the planes; x, y or xy insist on them and say why
 * not if the scene is not symmetric).
 */
#ifndef plate_on_halfspace_scene_mirror_symmetry_h
#define plate_on_halfspace_scene_mirror_symmetry_h

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/grid/tria.h>

#include <plate_on_halfspace/scene/parameters.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** Boundary ids of the mirror planes on the computed part's mesh. */
  constexpr types::boundary_id mirror_plane_x_boundary_id = 1;
  constexpr types::boundary_id mirror_plane_y_boundary_id = 2;

  /** The mirror planes a scene is solved with (see file doc). */
  struct MirrorSymmetry
  {
    /** Plane x = 0: the computed part is x >= 0. */
    bool x = false;
    /** Plane y = 0: the computed part is y >= 0. */
    bool y = false;
    /** Distance from a plane below which a point counts as on it (1e-10
     *  of the plate's extent, set by choose_mirror_symmetry()). */
    double tolerance = 0;

    /** "none", "x", "y" or "xy" (summary.json's "symmetry"). */
    std::string
    name() const;

    /** Copies of the computed part that make up the plate: 1, 2 or 4. */
    unsigned int
    n_copies() const
    {
      return (x ? 2 : 1) * (y ? 2 : 1);
    }

    /**
     * The reflections other than the identity as sign pairs: the image of
     * (x, y) is (s[0] x, s[1] y). None, one or three of them.
     */
    std::vector<std::array<double, 2>>
    reflections() const;

    /** The point of the computed part that mirrors @p p (p itself if it is
     *  in that part). */
    Point<2>
    to_computed_part(const Point<2> &p) const;

    /**
     * The sign a field odd across each mirror plane (Mxy, sxy) takes at
     * the whole-plate point @p p against its image to_computed_part(p):
     * -1 where @p p is reflected in one plane, 1 in none or both.
     */
    double
    odd_field_sign(const Point<2> &p) const
    {
      return (x && p[0] < 0 ? -1. : 1.) * (y && p[1] < 0 ? -1. : 1.);
    }

    /**
     * The point of the whole plate that @p p of the computed part stands
     * for on the side of @p reference: @p p reflected in each plane in
     * which to_computed_part() reflects @p reference.
     */
    Point<2>
    from_computed_part(const Point<2> &p, const Point<2> &reference) const;

    /**
     * The points of the whole plate that @p p of the computed part stands
     * for: p itself and its distinct mirror images (1, 2 or 4 points; a
     * point on a mirror plane is its own image there, unless bit 0 (plane
     * x = 0) or bit 1 (y = 0) of @p split_planes is set: a node on a joint
     * in that plane, whose image is the other slab's node at the same
     * place).
     */
    std::vector<Point<2>>
    images(const Point<2> &p, const unsigned int split_planes = 0) const;
  };

  /**
   * The mirror planes to use for a scene (Discretization/Symmetry) on its
   * coarse, whole-plate mesh: a plane is used if the mesh's vertices and
   * cells are mirror images of each other across it, no cell straddles it,
   * and @p loads_reason(axis, tolerance), why the loads are not mirror
   * symmetric across the plane normal to axis, is empty (the load family's
   * reason_loads_not_symmetric(), which lies below this family). With
   * Symmetry = x, y or xy, a plane that fails throws a message naming the
   * reason.
   */
  MirrorSymmetry
  choose_mirror_symmetry(
    const SceneParameters                                  &parameters,
    const Triangulation<2>                                 &coarse_mesh,
    const std::function<std::string(unsigned int, double)> &loads_reason);

  /**
   * Replace the coarse (unrefined) @p triangulation by its cells in the
   * computed part, keeping manifolds, and mark the faces on the mirror
   * planes with mirror_plane_x/y_boundary_id (all other boundary faces get
   * id 0).
   */
  void
  cut_to_computed_part(const MirrorSymmetry &symmetry,
                       Triangulation<2>     &triangulation);

} // namespace PlateOnHalfspace

#endif
