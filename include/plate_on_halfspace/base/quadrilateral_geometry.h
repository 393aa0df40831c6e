/**
 * Geometry of straight-sided (bilinear) quadrilateral cells in the plate's
 * x-y plane, and quadrature rules restricted to the part of such a cell that
 * a loaded region (axis-aligned rectangle or disk) covers.
 *
 * Why our own small class instead of deal.II's Mapping: the half-space
 * operators evaluate the bilinear map millions of times per cell pair, and
 * the load integration needs point-in-cell tests and clipped regions, which
 * deal.II does not offer. All plate cells are straight sided (MappingQ1), so
 * the bilinear map of the four vertices is exactly the geometry deal.II uses.
 */
#ifndef plate_on_halfspace_base_quadrilateral_geometry_h
#define plate_on_halfspace_base_quadrilateral_geometry_h

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <array>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * A bilinear quadrilateral given by its four vertices in deal.II's
   * lexicographic order: vertex 0 at reference (0,0), 1 at (1,0), 2 at (0,1),
   * 3 at (1,1).
   */
  class BilinearQuadrilateral
  {
  public:
    explicit BilinearQuadrilateral(const std::array<Point<2>, 4> &vertices);

    /** Physical point of the reference point @p p in [0,1]^2. */
    Point<2>
    map(const Point<2> &p) const;

    /** Jacobian d x / d p at the reference point @p p. */
    Tensor<2, 2>
    jacobian(const Point<2> &p) const;

    /** The area: the polygon of the four vertices. */
    double
    area() const;

    /** Determinant of the Jacobian (positive for a valid cell). */
    double
    jacobian_determinant(const Point<2> &p) const;

    /**
     * Reference coordinates of the physical point @p x (Newton iteration;
     * exact for parallelograms). Points outside the cell give reference
     * coordinates outside [0,1]^2.
     */
    Point<2>
    inverse_map(const Point<2> &x) const;

    /** Whether the physical point lies in the closed cell (tolerance relative
     * to the cell size). */
    bool
    contains(const Point<2> &x) const;

    /** Whether the cell is an axis-aligned rectangle (to a relative tolerance).
     */
    bool
    is_axis_aligned_rectangle(const double relative_tolerance = 1e-10) const;

    /** Lower-left and upper-right corner of the bounding box. */
    std::pair<Point<2>, Point<2>>
    bounding_box() const;

    /** Diameter (longest diagonal). */
    double
    diameter() const;

    /** The vertices, in deal.II's order. */
    const std::array<Point<2>, 4> &
    get_vertices() const
    {
      return vertices;
    }

  private:
    std::array<Point<2>, 4> vertices;
  };

  /**
   * Quadrature on the part of @p cell inside the axis-aligned rectangle
   * [lower, upper]. The points are in the cell's reference coordinates, the
   * weights are physical areas: sum_q w_q f(p_q) approximates the integral of
   * f over (cell ∩ rectangle) with respect to dx dy. The intersection polygon
   * is computed exactly (clipping) and triangulated; each triangle gets a
   * Gauss rule with @p n_points_1d points per direction, which is exact for
   * polynomials of degree 2 n_points_1d - 1 in physical coordinates (so the
   * biquadratic shape functions of an affine cell are integrated exactly for
   * n_points_1d >= 3). Returns an empty quadrature if the two do not overlap.
   */
  /**
   * The Gauss rule of @p n_points_1d (at most 40) points per direction on
   * the whole of @p cell: points in reference coordinates, weights
   * physical areas (as below).
   */
  Quadrature<2>
  quadrature_on_cell(const BilinearQuadrilateral &cell,
                     const unsigned int           n_points_1d);

  Quadrature<2>
  quadrature_on_rectangle_part(const BilinearQuadrilateral &cell,
                               const Point<2>              &lower,
                               const Point<2>              &upper,
                               const unsigned int           n_points_1d);

  /**
   * Quadrature on the part of @p cell inside the disk of @p radius around
   * @p centre, points in reference coordinates, weights physical areas (as
   * above). The convex region cell ∩ disk is split into the convex polygon
   * spanned by the corners of its boundary (triangulated, Gauss rules exact
   * as above) and circular segments of at most 45 degrees, each integrated
   * in coordinates in which the integrand of a polynomial is analytic, so
   * that the error decays exponentially whatever the position of the centre
   * (inside, outside, on an edge or vertex). Returns an empty quadrature if
   * there is no overlap.
   */
  Quadrature<2>
  quadrature_on_disk_part(const BilinearQuadrilateral &cell,
                          const Point<2>              &centre,
                          const double                 radius,
                          const unsigned int           n_points_1d);
} // namespace PlateOnHalfspace

#endif
