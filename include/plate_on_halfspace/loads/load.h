/**
 * The loads on the plate (doc/loads.md): one class per kind behind one
 * interface, so that the plate's load vector, the goal estimate's residual,
 * Kelly refinement, mirror symmetry, the load checks and the driver all ask
 * a load the same questions and never name its kind. Pressures and forces
 * are downward positive (doc/formulation.md, "Conventions").
 *
 * A kind that declares its own entries registers itself (LoadKind): a new
 * kind is one file in source/loads/ (doc/architecture.md, "A new load").
 * The family lies below the scene: it knows no parameter struct.
 */
#ifndef plate_on_halfspace_loads_load_h
#define plate_on_halfspace_loads_load_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  class BilinearQuadrilateral;

  /**
   * What a load puts on one cell: a quadrature over the part of the cell it
   * covers (points in the cell's reference coordinates [0,1]^2, weights
   * physical areas) and the pressure at each point, so that the load's work
   * on a field v is sum_q pressure[q] rule.weight(q) v(x_q).
   */
  struct CellLoad
  {
    Quadrature<2>       rule;
    std::vector<double> pressure;

    bool
    empty() const
    {
      return rule.size() == 0;
    }
  };

  class Load
  {
  public:
    virtual ~Load() = default;

    /** How messages name it, e.g. "Loads/Circular patches: patch 2". */
    virtual std::string
    label() const = 0;

    /**
     * The pressure on the part of @p cell this load covers (empty if it
     * covers none), by the load's own rule: every caller integrates the
     * load the same way. @p extra_points raises that rule by as many Gauss
     * points per direction, for the integration error's check.
     */
    virtual CellLoad
    on_cell(const BilinearQuadrilateral &cell,
            const unsigned int           extra_points = 0) const = 0;

    /**
     * Whether on_cell() integrates it to rounding on every cell (a
     * uniform pressure over a polygon or a disk): the integration check
     * (load_integration_error()) then skips it.
     */
    virtual bool
    integrated_exactly() const
    {
      return false;
    }

    /** A force at a point (location, force); none for a pressure. */
    virtual std::optional<std::pair<Point<2>, double>>
    concentrated_force() const
    {
      return {};
    }

    /**
     * The load that a jump of this load puts on a cell with vertices @p
     * vertices and area @p area (Kelly refinement's load indicator): |p|
     * times the area for a patch whose edge crosses the cell, |F| for a
     * point load in the cell's box, zero where the load is smooth.
     */
    virtual double
    jump_on(const std::array<Point<2>, 4> &vertices,
            const double                   area) const = 0;

    /**
     * The area of the region it covers when that region is its own (a
     * patch, a pressure function's region), for the warning about loads
     * partly off the plate; none for a load over the whole plate or at a
     * point.
     */
    virtual std::optional<double>
    region_area() const
    {
      return {};
    }

    /**
     * The smallest width of the region it covers when that region is its
     * own (a rectangle's shorter side, a disk's diameter), the length the
     * cells must resolve at its edge; none for a load over the whole
     * plate or at a point.
     */
    virtual std::optional<double>
    region_width() const
    {
      return {};
    }

    /** Its load as given when its pressure is uniform over its own
     *  region (a patch: pressure times area); none otherwise. */
    virtual std::optional<double>
    nominal_force() const
    {
      return {};
    }

    /**
     * Whether it stays on the plate while the axles move: the joints'
     * transfer efficiency is that of the deflection the other loads add
     * (doc/formulation.md, "Joints").
     */
    virtual bool
    standing() const
    {
      return false;
    }

    /**
     * Its mirror image across the plane normal to @p axis (x = 0 for 0),
     * or null for a load whose symmetry cannot be decided exactly: a scene
     * with such a load is solved whole.
     */
    virtual std::shared_ptr<const Load>
    mirror_image(const unsigned int axis) const = 0;

    /** Whether @p other is the same load: positions within @p tolerance,
     *  values to 1e-12. */
    virtual bool
    same_as(const Load &other, const double tolerance) const = 0;

    /**
     * What the computed part of a mirror-symmetric scene carries of it
     * (scene/mirror_symmetry.h): the part is x >= 0 if @p planes[0], y >= 0
     * if @p planes[1], a point within @p tolerance of a plane lies on it.
     * The load itself, none (null) if it lies wholly on the other side of a
     * plane, or the half of a point load on a plane.
     */
    virtual std::shared_ptr<const Load>
    on_computed_part(const std::array<bool, 2> &planes,
                     const double               tolerance) const = 0;
  };

  using LoadList = std::vector<std::shared_ptr<const Load>>;

  /**
   * A kind of load that declares its own entries in subsection Loads and
   * makes its loads from them (e.g. Loads/Pressure function). It registers
   * itself with register_load_kind() in its own file; the scene declares
   * and parses every registered kind (Parameters::Loads).
   */
  struct LoadKind
  {
    std::string                             name;
    std::function<void(ParameterHandler &)> declare_parameters;
    /** Inside subsection Loads; throws a message naming the entry. */
    std::function<LoadList(ParameterHandler &)> parse_parameters;
  };

  /** Adds @p kind to registered_load_kinds(); true, for a static
   *  initialiser. */
  bool
  register_load_kind(const LoadKind &kind);

  /** The registered kinds, in the order of their names. */
  const std::vector<LoadKind> &
  registered_load_kinds();

  /** The kinds the scene makes from its long-standing entries
   *  (Parameters::Loads; each in its own file of source/loads/). */
  std::shared_ptr<const Load>
  create_uniform_pressure(const double pressure, const std::string &label);
  std::shared_ptr<const Load>
  create_rectangular_patch(const Point<2>    &lower,
                           const Point<2>    &upper,
                           const double       pressure,
                           const std::string &label);
  std::shared_ptr<const Load>
  create_circular_patch(const Point<2>    &centre,
                        const double       radius,
                        const double       pressure,
                        const std::string &label);
  std::shared_ptr<const Load>
  create_point_load(const Point<2> &location, const double force);

  /** The loads of @p loads on the computed part (Load::on_computed_part()). */
  LoadList
  loads_on_computed_part(const LoadList            &loads,
                         const std::array<bool, 2> &planes,
                         const double               tolerance);

  /**
   * Why @p loads are not mirror symmetric across the plane normal to @p
   * axis (each load, or an equal one, must have its image among them as
   * often as itself), or an empty string if they are.
   */
  std::string
  reason_loads_not_symmetric(const LoadList    &loads,
                             const unsigned int axis,
                             const double       tolerance);

  /** Only the loads that stay while the axles move (Load::standing()). */
  LoadList
  standing_loads(const LoadList &loads);
} // namespace PlateOnHalfspace

#endif
