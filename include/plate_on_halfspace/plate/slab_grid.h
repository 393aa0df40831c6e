/**
 * The plan of a jointed pavement (Plate/Shape = slabs; doc/formulation.md,
 * "Joints"): a grid of rectangular slabs centred at the origin, the joints
 * between neighbouring slabs with their load transfer, and the dowel bars
 * along dowelled joints. Any other Plate/Shape is one slab without joints,
 * so the driver holds a SlabGrid whatever the scene.
 *
 * The mesh of a grid (plate_mesh.h) is one triangulation whose slabs share
 * no vertex, each slab's index the material id of its cells: the two faces of a
 * joint are boundary faces that lie on each other, each slab has its own plate
 * unknowns, and the joint model (plate/joints.h) couples the facing faces.
 * match_refinement() keeps the faces facing each other through refinement.
 */
#ifndef plate_on_halfspace_plate_slab_grid_h
#define plate_on_halfspace_plate_slab_grid_h

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/grid/tria.h>

#include <plate_on_halfspace/scene/mirror_symmetry.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** Boundary id of the faces on a joint (next to the mirror planes'). */
  constexpr types::boundary_id joint_boundary_id = 3;

  /** One slab: [lower, upper], its cells carry its index as material id. */
  struct Slab
  {
    Point<2> lower, upper;
  };

  /**
   * The joint between two neighbouring slabs: a segment of the line
   * x = const (transverse, axis 0) or y = const (longitudinal, axis 1).
   */
  struct Joint
  {
    /** 0: transverse (x = const), 1: longitudinal (y = const). */
    unsigned int axis;
    Point<2>     start, end;
    /** The slabs on its lower and its upper side along the axis. */
    unsigned int                     slab_low, slab_high;
    Parameters::Joints::LoadTransfer transfer;
    /** Dowels: the bars' positions, spaced Dowel spacing, centred. */
    std::vector<Point<2>> dowels;

    /** Whether @p p lies on the segment (within @p tolerance). */
    bool
    contains(const Point<2> &p, const double tolerance) const;

    /** "transverse joint x = 2.25, y in [-3.6, 0]" for messages. */
    std::string
    name() const;
  };

  class SlabGrid
  {
  public:
    /** The grid of @p plate (one slab unless Shape = slabs). */
    SlabGrid(const Parameters::Plate &plate, const Parameters::Joints &joints);

    unsigned int
    n_slabs() const
    {
      return slabs.size();
    }
    const std::vector<Slab> &
    get_slabs() const
    {
      return slabs;
    }
    const std::vector<Joint> &
    get_joints() const
    {
      return joints;
    }
    const Parameters::Joints &
    get_joint_parameters() const
    {
      return parameters;
    }

    /**
     * The shear stiffness of one dowel bar [force/length] (doc/
     * formulation.md, "Joints": the bar as a beam on the concrete's elastic
     * support on either side, bent across the joint opening).
     */
    double
    dowel_stiffness() const;

    /** The concrete's bearing stress under a bar that carries @p force
     *  (the support's reaction at the joint face). */
    double
    dowel_bearing_stress(const double force) const;

    /**
     * Mark the boundary faces of @p triangulation on a joint with
     * joint_boundary_id. A joint on a mirror plane (a face marked by
     * cut_to_computed_part()) stays a mirror plane if it is tied (the slab is
     * continuous there) and becomes two free edges otherwise: a symmetric
     * solution moves both sides alike, so the joint carries no force.
     */
    void
    mark_joint_faces(Triangulation<2> &triangulation) const;

    /**
     * Make the refinement and coarsening flags of @p triangulation equal on
     * the two sides of every joint (after a strategy flagged the cells, and
     * with the triangulation's own smoothing), so that the refined mesh's
     * joint faces still face each other.
     */
    void
    match_refinement(Triangulation<2> &triangulation) const;

    /** A key of the centre @p p of a joint face: facing faces, whose
     *  centres are the same, have the same key. */
    std::pair<long long, long long>
    face_key(const Point<2> &p) const
    {
      return {std::llround(p[0] / point_tolerance / 16),
              std::llround(p[1] / point_tolerance / 16)};
    }

    /** The joint whose segment holds @p p, or n_joints if none. */
    unsigned int
    joint_at(const Point<2> &p) const;

    /** Distance below which points count as equal (1e-10 of the extent). */
    double
    tolerance() const
    {
      return point_tolerance;
    }

  private:
    Parameters::Joints parameters;
    std::vector<Slab>  slabs;
    std::vector<Joint> joints;
    double             point_tolerance;
  };
} // namespace PlateOnHalfspace

#endif
