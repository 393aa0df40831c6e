#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/base/quadrilateral_geometry.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace PlateOnHalfspace
{
  namespace
  {
    /** z-component of the cross product of two plane vectors. */
    double
    cross(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
    {
      return a[0] * b[1] - a[1] * b[0];
    }



    /** The unit vector at angle @p theta. */
    Tensor<1, 2>
    unit_vector(const double theta)
    {
      Tensor<1, 2> direction;
      direction[0] = std::cos(theta);
      direction[1] = std::sin(theta);
      return direction;
    }



    /** Signed area of a polygon (shoelace formula), positive if CCW. */
    double
    signed_polygon_area(const std::vector<Point<2>> &polygon)
    {
      double area = 0.;
      for (unsigned int i = 0; i < polygon.size(); ++i)
        {
          const Point<2> &a = polygon[i];
          const Point<2> &b = polygon[(i + 1) % polygon.size()];
          area += a[0] * b[1] - a[1] * b[0];
        }
      return 0.5 * area;
    }



    /**
     * The cell as a polygon, walked counterclockwise. deal.II's vertex
     * numbering is lexicographic, so the boundary walk is v0, v1, v3, v2; we
     * reverse it should the cell be negatively oriented, so that all the
     * half-plane tests below can assume "inside = left of the edge".
     */
    std::vector<Point<2>>
    ccw_polygon(const BilinearQuadrilateral &cell)
    {
      const auto           &v       = cell.get_vertices();
      std::vector<Point<2>> polygon = {v[0], v[1], v[3], v[2]};
      if (signed_polygon_area(polygon) < 0)
        std::reverse(polygon.begin(), polygon.end());
      return polygon;
    }



    /**
     * One Sutherland-Hodgman step: the part of the polygon on the side
     * x[coordinate] >= value (if @p keep_greater) or <= value (otherwise).
     * Intersection points get the clipping coordinate exactly, so that the
     * clipped polygon lies exactly on the rectangle's edges.
     */
    std::vector<Point<2>>
    clip_polygon(const std::vector<Point<2>> &polygon,
                 const unsigned int           coordinate,
                 const double                 value,
                 const bool                   keep_greater)
    {
      const auto inside = [&](const Point<2> &p) {
        return keep_greater ? (p[coordinate] >= value) :
                              (p[coordinate] <= value);
      };
      const auto intersection = [&](const Point<2> &a, const Point<2> &b) {
        const double t =
          (value - a[coordinate]) / (b[coordinate] - a[coordinate]);
        Point<2> p    = a + t * (b - a);
        p[coordinate] = value;
        return p;
      };

      std::vector<Point<2>> result;
      result.reserve(polygon.size() + 2);
      for (unsigned int i = 0; i < polygon.size(); ++i)
        {
          const Point<2> &previous =
            polygon[(i + polygon.size() - 1) % polygon.size()];
          const Point<2> &current = polygon[i];
          if (inside(current))
            {
              if (!inside(previous))
                result.push_back(intersection(previous, current));
              result.push_back(current);
            }
          else if (inside(previous))
            result.push_back(intersection(previous, current));
        }
      return result;
    }



    /**
     * A rule on the reference triangle (0,0), (1,0), (0,1) that is exact for
     * polynomials of degree 2 n - 1, weights summing to 1/2. deal.II's
     * QGaussSimplex has exactly this property but exists for n <= 4 only;
     * beyond that we use the collapsed (Duffy) tensor product of Gauss rules
     * with n + 1 points in the collapsed direction, which absorbs the extra
     * degree the collapse's Jacobian adds.
     */
    Quadrature<2>
    reference_triangle_rule(const unsigned int n)
    {
      if (n <= 4)
        return QGaussSimplex<2>(std::max(n, 1u));

      const QGauss<1>       gauss_u(n + 1);
      const QGauss<1>       gauss_v(n);
      std::vector<Point<2>> points;
      std::vector<double>   weights;
      for (unsigned int i = 0; i < gauss_u.size(); ++i)
        for (unsigned int j = 0; j < gauss_v.size(); ++j)
          {
            const double u = gauss_u.point(i)[0];
            const double v = gauss_v.point(j)[0];
            points.emplace_back(u, v * (1. - u));
            weights.push_back(gauss_u.weight(i) * gauss_v.weight(j) * (1. - u));
          }
      return Quadrature<2>(points, weights);
    }
  } // namespace



  BilinearQuadrilateral::BilinearQuadrilateral(
    const std::array<Point<2>, 4> &vertices)
    : vertices(vertices)
  {}



  Point<2>
  BilinearQuadrilateral::map(const Point<2> &p) const
  {
    const double s = p[0], t = p[1];
    return Point<2>((1. - s) * (1. - t) * vertices[0] +
                    s * (1. - t) * vertices[1] + (1. - s) * t * vertices[2] +
                    s * t * vertices[3]);
  }



  Tensor<2, 2>
  BilinearQuadrilateral::jacobian(const Point<2> &p) const
  {
    const double       s = p[0], t = p[1];
    const Tensor<1, 2> d_ds =
      (1. - t) * (vertices[1] - vertices[0]) + t * (vertices[3] - vertices[2]);
    const Tensor<1, 2> d_dt =
      (1. - s) * (vertices[2] - vertices[0]) + s * (vertices[3] - vertices[1]);
    Tensor<2, 2> J;
    for (unsigned int i = 0; i < 2; ++i)
      {
        J[i][0] = d_ds[i];
        J[i][1] = d_dt[i];
      }
    return J;
  }



  double
  BilinearQuadrilateral::jacobian_determinant(const Point<2> &p) const
  {
    return determinant(jacobian(p));
  }



  /**
   * Newton's method from the cell centre. The map is bilinear, so for a
   * parallelogram the first step is exact; for other convex cells and points
   * inside or near the cell convergence is quadratic and takes a handful of
   * steps. Far outside a non-parallelogram Newton can wander (the inverse of
   * a bilinear map is not unique there), so a step that increases the
   * residual is halved a few times; the iteration count is capped.
   */
  Point<2>
  BilinearQuadrilateral::inverse_map(const Point<2> &x) const
  {
    const double scale         = diameter();
    Point<2>     p             = Point<2>(0.5, 0.5);
    double       residual_norm = (map(p) - x).norm();
    for (unsigned int iteration = 0; iteration < 50; ++iteration)
      {
        const Tensor<2, 2> J = jacobian(p);
        if (std::abs(determinant(J)) <= 1e-300)
          break;
        const Tensor<1, 2> step = invert(J) * (map(p) - x);

        double   factor         = 1.;
        Point<2> trial          = p - step;
        double   trial_residual = (map(trial) - x).norm();
        for (unsigned int halving = 0;
             halving < 10 && trial_residual > residual_norm &&
             trial_residual > 1e-15 * scale;
             ++halving)
          {
            factor *= 0.5;
            trial          = p - factor * step;
            trial_residual = (map(trial) - x).norm();
          }
        p             = trial;
        residual_norm = trial_residual;

        // Quadratic convergence: once the step is this small, the error left
        // is at round-off level.
        if (factor * step.norm() <= 1e-13 * (1. + p.norm()))
          break;
      }
    return p;
  }



  /**
   * The straight-sided cell is the convex polygon v0 v1 v3 v2, so the point
   * is inside iff it is on the inner side of all four edges. This is
   * equivalent to inverse_map() landing in [0,1]^2, but needs no iteration
   * and is robust for points far away. The tolerance is 1e-10 times the cell
   * diameter, so points on edges and vertices count as inside.
   */
  bool
  BilinearQuadrilateral::contains(const Point<2> &x) const
  {
    const std::vector<Point<2>> polygon   = ccw_polygon(*this);
    const double                tolerance = 1e-10 * diameter();
    for (unsigned int i = 0; i < 4; ++i)
      {
        const Tensor<1, 2> edge   = polygon[(i + 1) % 4] - polygon[i];
        const double       length = edge.norm();
        if (length == 0.)
          continue;
        if (cross(edge, x - polygon[i]) / length < -tolerance)
          return false;
      }
    return true;
  }



  bool
  BilinearQuadrilateral::is_axis_aligned_rectangle(
    const double relative_tolerance) const
  {
    const double tolerance = relative_tolerance * diameter();
    return std::abs(vertices[0][1] - vertices[1][1]) <= tolerance &&
           std::abs(vertices[2][1] - vertices[3][1]) <= tolerance &&
           std::abs(vertices[0][0] - vertices[2][0]) <= tolerance &&
           std::abs(vertices[1][0] - vertices[3][0]) <= tolerance;
  }



  std::pair<Point<2>, Point<2>>
  BilinearQuadrilateral::bounding_box() const
  {
    Point<2> lower = vertices[0], upper = vertices[0];
    for (const Point<2> &v : vertices)
      for (unsigned int d = 0; d < 2; ++d)
        {
          lower[d] = std::min(lower[d], v[d]);
          upper[d] = std::max(upper[d], v[d]);
        }
    return {lower, upper};
  }



  double
  BilinearQuadrilateral::diameter() const
  {
    return std::max(vertices[0].distance(vertices[3]),
                    vertices[1].distance(vertices[2]));
  }



  Quadrature<2>
  quadrature_on_rectangle_part(const BilinearQuadrilateral &cell,
                               const Point<2>              &lower,
                               const Point<2>              &upper,
                               const unsigned int           n_points_1d)
  {
    std::vector<Point<2>> polygon   = ccw_polygon(cell);
    const double          cell_area = signed_polygon_area(polygon);

    polygon = clip_polygon(polygon, 0, lower[0], true);
    polygon = clip_polygon(polygon, 0, upper[0], false);
    polygon = clip_polygon(polygon, 1, lower[1], true);
    polygon = clip_polygon(polygon, 1, upper[1], false);

    if (polygon.size() < 3 || signed_polygon_area(polygon) <= 1e-14 * cell_area)
      return Quadrature<2>();

    // The clipped polygon is convex (intersection of convex sets), so a fan
    // from its first vertex triangulates it. Each triangle gets the
    // reference-triangle rule mapped affinely, which keeps the rule exact for
    // polynomials in the physical coordinates.
    const Quadrature<2>   triangle_rule = reference_triangle_rule(n_points_1d);
    std::vector<Point<2>> points;
    std::vector<double>   weights;
    points.reserve((polygon.size() - 2) * triangle_rule.size());
    weights.reserve((polygon.size() - 2) * triangle_rule.size());
    for (unsigned int i = 1; i + 1 < polygon.size(); ++i)
      {
        const Tensor<1, 2> e1         = polygon[i] - polygon[0];
        const Tensor<1, 2> e2         = polygon[i + 1] - polygon[0];
        const double       twice_area = cross(e1, e2);
        if (twice_area <= 1e-16 * cell_area)
          continue; // degenerate sliver from coincident clip points
        for (unsigned int q = 0; q < triangle_rule.size(); ++q)
          {
            const Point<2> &xi = triangle_rule.point(q);
            const Point<2>  x  = polygon[0] + xi[0] * e1 + xi[1] * e2;
            points.push_back(cell.inverse_map(x));
            weights.push_back(triangle_rule.weight(q) * twice_area);
          }
      }
    return Quadrature<2>(points, weights);
  }



  /**
   * The region K = cell ∩ disk is convex. Its boundary consists of the parts
   * of the cell's edges inside the disk and of circular arcs joining them. We
   * split K into the convex polygon Q spanned by the corners of that
   * boundary (fan-triangulated, exact Gauss rules as for rectangles) and one
   * circular segment (between a chord and its arc) per arc, arcs being
   * subdivided to at most an eighth of the circle.
   *
   * Why not plain polar coordinates about the centre: where an edge bounds
   * the region, the radial limit is h / cos(theta - phi), whose pole comes
   * close to the theta interval when the centre lies outside the cell near
   * the edge's line, and Gauss rules in theta then converge slowly. Here Q
   * is integrated exactly and the segments' integrands are analytic
   * everywhere (see below), so the accuracy does not depend on where the
   * centre lies.
   */
  Quadrature<2>
  quadrature_on_disk_part(const BilinearQuadrilateral &cell,
                          const Point<2>              &centre,
                          const double                 radius,
                          const unsigned int           n_points_1d)
  {
    if (!(radius > 0.))
      return Quadrature<2>();

    const std::vector<Point<2>> polygon   = ccw_polygon(cell);
    const double                cell_area = signed_polygon_area(polygon);
    const double                scale     = cell.diameter();
    const double                tolerance = 1e-13 * std::max(scale, radius);

    // Quick rejection by the bounding box.
    const auto box = cell.bounding_box();
    for (unsigned int d = 0; d < 2; ++d)
      if (centre[d] + radius <= box.first[d] ||
          centre[d] - radius >= box.second[d])
        return Quadrature<2>();

    // The part of each edge p + t (q - p), t in [0,1], inside the disk, in
    // counterclockwise order; pieces of zero length (tangency, a vertex on the
    // circle) carry no boundary and are dropped.
    std::vector<std::pair<Point<2>, Point<2>>> pieces;
    for (unsigned int i = 0; i < polygon.size(); ++i)
      {
        const Point<2>    &p = polygon[i];
        const Tensor<1, 2> e = polygon[(i + 1) % polygon.size()] - p;
        const Tensor<1, 2> f = p - centre;
        const double       a = e * e;
        if (a == 0.)
          continue;
        const double b            = f * e; // half the linear coefficient
        const double c            = f * f - radius * radius;
        const double discriminant = b * b - a * c;
        if (discriminant <= 0.)
          continue;
        // Numerically stable roots of a t^2 + 2 b t + c = 0.
        const double q  = -(b + std::copysign(std::sqrt(discriminant), b));
        double       t1 = q / a, t2 = (q != 0. ? c / q : -t1);
        if (t1 > t2)
          std::swap(t1, t2);
        t1 = std::max(t1, 0.);
        t2 = std::min(t2, 1.);
        if ((t2 - t1) * std::sqrt(a) <= tolerance)
          continue;
        pieces.emplace_back(p + t1 * e, p + t2 * e);
      }

    // Corners of the boundary of K in counterclockwise order, and the arcs
    // (start angle, opening angle) between them.
    std::vector<Point<2>>                  corners;
    std::vector<std::pair<double, double>> arcs;
    const double                           quarter     = 0.5 * numbers::PI;
    const double                           max_opening = 0.25 * numbers::PI;
    const auto add_arc = [&](const double start, const double opening) {
      const unsigned int n_parts =
        std::max(1, static_cast<int>(std::ceil(opening / max_opening - 1e-10)));
      const double part = opening / n_parts;
      for (unsigned int k = 0; k < n_parts; ++k)
        {
          arcs.emplace_back(start + k * part, part);
          if (k > 0)
            corners.push_back(centre + radius * unit_vector(start + k * part));
        }
    };
    const auto angle_of = [&](const Point<2> &x) {
      return std::atan2(x[1] - centre[1], x[0] - centre[0]);
    };

    if (pieces.empty())
      {
        // The circle does not cross the boundary: K is the whole disk if the
        // centre is in the cell, and empty otherwise.
        if (!cell.contains(centre))
          return Quadrature<2>();
        corners.push_back(centre + radius * unit_vector(0.));
        add_arc(0., 2. * numbers::PI); // adds the other three corners
      }
    else
      for (unsigned int j = 0; j < pieces.size(); ++j)
        {
          const Point<2> &start = pieces[j].first;
          const Point<2> &end   = pieces[j].second;
          const Point<2> &next  = pieces[(j + 1) % pieces.size()].first;
          corners.push_back(start);
          corners.push_back(end);
          if (end.distance(next) > tolerance)
            {
              // The boundary leaves the edge at a point on the circle and
              // follows the circle counterclockwise to the next piece.
              const double start_angle = angle_of(end);
              double       opening     = angle_of(next) - start_angle;
              while (opening <= 0.)
                opening += 2. * numbers::PI;
              add_arc(start_angle, opening);
            }
        }

    // Remove coincident consecutive corners (shared vertices of pieces).
    {
      std::vector<Point<2>> distinct;
      for (const Point<2> &x : corners)
        if (distinct.empty() || distinct.back().distance(x) > tolerance)
          distinct.push_back(x);
      while (distinct.size() > 1 &&
             distinct.back().distance(distinct.front()) <= tolerance)
        distinct.pop_back();
      corners.swap(distinct);
    }

    std::vector<Point<2>> points;
    std::vector<double>   weights;

    // The convex polygon Q: fan of triangles, exact for polynomials.
    if (corners.size() >= 3)
      {
        const Quadrature<2> triangle_rule =
          reference_triangle_rule(n_points_1d);
        for (unsigned int i = 1; i + 1 < corners.size(); ++i)
          {
            const Tensor<1, 2> e1         = corners[i] - corners[0];
            const Tensor<1, 2> e2         = corners[i + 1] - corners[0];
            const double       twice_area = cross(e1, e2);
            if (twice_area <= 1e-16 * cell_area)
              continue;
            for (unsigned int q = 0; q < triangle_rule.size(); ++q)
              {
                const Point<2> &xi = triangle_rule.point(q);
                points.push_back(
                  cell.inverse_map(corners[0] + xi[0] * e1 + xi[1] * e2));
                weights.push_back(triangle_rule.weight(q) * twice_area);
              }
          }
      }

    // The circular segments. With the chord's midpoint normal n (towards the
    // arc), the tangent tau, the chord's distance h = R cos(opening/2) from
    // the centre and s = R sin(psi), the segment is
    //   x = centre + (h + t) n + s tau,  |psi| <= opening/2,
    //   0 <= t <= R cos(psi) - h,        dx dy = R cos(psi) dpsi dt,
    // so for polynomial integrands the t integral is a polynomial and the psi
    // integrand a trigonometric polynomial: n Gauss points are exact in t,
    // and in psi Gauss rules converge very fast on |psi| <= pi/8. The arc is
    // the only inexact part, so it gets 4 extra points in psi: with them the
    // area of any disk part is exact to ~1e-13 relative already for n = 2
    // (with n points in psi and quarter-circle arcs: 6e-2 for n = 2, 1e-3
    // for n = 3, 2e-5 for n = 4).
    const QGauss<1> gauss_t(std::max(n_points_1d, 1u));
    const QGauss<1> gauss_psi(std::max(n_points_1d, 1u) + 4);
    for (const auto &arc : arcs)
      {
        const double       half_opening = 0.5 * arc.second;
        const double       h            = radius * std::cos(half_opening);
        const Tensor<1, 2> n            = unit_vector(arc.first + half_opening);
        const Tensor<1, 2> tau =
          unit_vector(arc.first + half_opening + quarter);
        for (unsigned int i = 0; i < gauss_psi.size(); ++i)
          {
            const double psi = (2. * gauss_psi.point(i)[0] - 1.) * half_opening;
            const double height = radius * std::cos(psi) - h;
            if (!(height > 0.))
              continue;
            const double s = radius * std::sin(psi);
            for (unsigned int j = 0; j < gauss_t.size(); ++j)
              {
                const double t = gauss_t.point(j)[0] * height;
                points.push_back(
                  cell.inverse_map(centre + (h + t) * n + s * tau));
                weights.push_back(gauss_psi.weight(i) * 2. * half_opening *
                                  gauss_t.weight(j) * height * radius *
                                  std::cos(psi));
              }
          }
      }

    double total = 0.;
    for (const double w : weights)
      total += w;
    if (total <= 1e-14 * cell_area)
      return Quadrature<2>();
    return Quadrature<2>(points, weights);
  }
} // namespace PlateOnHalfspace
