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



    /**
     * Signed area of a polygon (shoelace formula), positive if CCW. Taken
     * about its first vertex, not the origin: a polygon much smaller than
     * its distance from the origin (a 1e-9 patch at x = 1.8) would
     * otherwise lose its area to the round-off of the coordinates'
     * products.
     */
    double
    signed_polygon_area(const std::vector<Point<2>> &polygon)
    {
      double area = 0.;
      for (unsigned int i = 1; i + 1 < polygon.size(); ++i)
        area += cross(polygon[i] - polygon[0], polygon[i + 1] - polygon[0]);
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

  double
  BilinearQuadrilateral::area() const
  {
    // the shoelace formula, vertices counterclockwise 0, 1, 3, 2, as half
    // the cross product of the diagonals: differences of coordinates only,
    // so that a plate far from the origin (a Gmsh mesh in survey
    // coordinates, 1e8 m off) keeps its digits
    const Point<2> &a = vertices[0], &b = vertices[1], &c = vertices[3],
                   &d     = vertices[2];
    const Tensor<1, 2> ac = c - a, bd = d - b;
    return 0.5 * (ac[0] * bd[1] - ac[1] * bd[0]);
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
  quadrature_on_cell(const BilinearQuadrilateral &cell,
                     const unsigned int           n_points_1d)
  {
    // the rules a load asks for (at most Pressure function points + 3),
    // made once: a Gauss rule's construction costs more than its use on a
    // cell
    static const std::vector<QGauss<2>> rules = [] {
      std::vector<QGauss<2>> made;
      for (unsigned int n = 0; n <= 40; ++n)
        made.emplace_back(std::max(n, 1u));
      return made;
    }();
    AssertThrow(n_points_1d < rules.size(),
                ExcMessage("quadrature_on_cell(): at most 40 points per "
                           "direction."));
    const QGauss<2>    &reference = rules[n_points_1d];
    std::vector<double> weights(reference.size());
    for (unsigned int q = 0; q < reference.size(); ++q)
      weights[q] =
        reference.weight(q) * cell.jacobian_determinant(reference.point(q));
    return Quadrature<2>(reference.get_points(), weights);
  }

  Quadrature<2>
  quadrature_on_rectangle_part(const BilinearQuadrilateral &cell,
                               const Point<2>              &lower,
                               const Point<2>              &upper,
                               const unsigned int           n_points_1d)
  {
    std::vector<Point<2>> polygon = ccw_polygon(cell);

    polygon = clip_polygon(polygon, 0, lower[0], true);
    polygon = clip_polygon(polygon, 0, upper[0], false);
    polygon = clip_polygon(polygon, 1, lower[1], true);
    polygon = clip_polygon(polygon, 1, upper[1], false);

    // Only a polygon of no area (the rectangle touching the cell along an
    // edge or at a point) is no overlap. The test is relative to the
    // clipped polygon's own bounding box, not to the cell: a patch much
    // smaller than the cell is on the plate and carries its whole load.
    if (polygon.size() < 3)
      return Quadrature<2>();
    {
      Point<2> lowest = polygon[0], highest = polygon[0];
      for (const Point<2> &p : polygon)
        for (unsigned int d = 0; d < 2; ++d)
          {
            lowest[d]  = std::min(lowest[d], p[d]);
            highest[d] = std::max(highest[d], p[d]);
          }
      if (!(signed_polygon_area(polygon) >
            1e-12 * (highest[0] - lowest[0]) * (highest[1] - lowest[1])))
        return Quadrature<2>();
    }

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
        if (!(twice_area > 0.))
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

    const std::vector<Point<2>> polygon = ccw_polygon(cell);
    const double                scale   = cell.diameter();
    // Lengths below this count as zero (tangency, a vertex on the circle,
    // coincident corners). Relative to the smaller of the cell and the
    // disk, never to the larger: a disk of radius 1e13 over a cell of 1 m
    // must not make the cell's own edges negligible (tests/unit/
    // huge_and_tiny_patches), nor a 1e-9 disk vanish in a 1 m cell.
    const double tolerance = 1e-13 * std::min(scale, radius);

    // Quick rejection by the bounding box.
    const auto box = cell.bounding_box();
    for (unsigned int d = 0; d < 2; ++d)
      if (centre[d] + radius <= box.first[d] ||
          centre[d] - radius >= box.second[d])
        return Quadrature<2>();

    const Quadrature<2>   triangle_rule = reference_triangle_rule(n_points_1d);
    std::vector<Point<2>> points;
    std::vector<double>   weights;
    // Exact Gauss rules on a fan of triangles of the convex polygon.
    const auto add_polygon = [&](const std::vector<Point<2>> &corners) {
      for (unsigned int i = 1; i + 1 < corners.size(); ++i)
        {
          const Tensor<1, 2> e1         = corners[i] - corners[0];
          const Tensor<1, 2> e2         = corners[i + 1] - corners[0];
          const double       twice_area = cross(e1, e2);
          if (!(twice_area > 0.))
            continue;
          for (unsigned int q = 0; q < triangle_rule.size(); ++q)
            {
              const Point<2> &xi = triangle_rule.point(q);
              points.push_back(
                cell.inverse_map(corners[0] + xi[0] * e1 + xi[1] * e2));
              weights.push_back(triangle_rule.weight(q) * twice_area);
            }
        }
    };

    // Every vertex in the disk: K is the whole (convex) cell, integrated
    // exactly. This also keeps a disk far larger than the cell away from
    // the arcs below, whose R^2-sized terms would swamp the cell.
    {
      bool inside = true;
      for (const Point<2> &v : polygon)
        inside = inside && (v - centre).norm() <= radius;
      if (inside)
        {
          add_polygon(polygon);
          return Quadrature<2>(points, weights);
        }
    }

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
        // The foot of the perpendicular from the centre and the half
        // chord about it, rather than the roots of a t^2 + 2 b t + c:
        // b^2 - a c cancels to nothing for a disk much smaller than its
        // distance from the edge's end points (tests/unit/
        // huge_and_tiny_patches).
        const double       t0       = -(f * e) / a;
        const Tensor<1, 2> foot     = f + t0 * e;
        const double       distance = foot.norm();
        if (!(distance < radius))
          continue;
        const double half =
          std::sqrt((radius - distance) * (radius + distance) / a);
        double t1 = t0 - half, t2 = t0 + half;
        t1 = std::max(t1, 0.);
        t2 = std::min(t2, 1.);
        if ((t2 - t1) * std::sqrt(a) <= tolerance)
          continue;
        pieces.emplace_back(p + t1 * e, p + t2 * e);
      }

    // Corners of the boundary of K in counterclockwise order, and the arcs
    // between them, each at most an eighth of the circle: its end points
    // and its opening angle.
    struct Arc
    {
      Point<2> start, end;
      double   opening;
    };
    std::vector<Point<2>> corners;
    std::vector<Arc>      arcs;
    const double          max_opening = 0.25 * numbers::PI;
    const auto            on_circle   = [&](const double angle) {
      return Point<2>(centre + radius * unit_vector(angle));
    };
    // by value: corners grows while an arc is added
    const auto add_arc = [&](const Point<2> start,
                             const Point<2> end,
                             const double   opening) {
      const unsigned int n_parts =
        std::max(1, static_cast<int>(std::ceil(opening / max_opening - 1e-10)));
      const double part = opening / n_parts;
      const double first =
        std::atan2(start[1] - centre[1], start[0] - centre[0]);
      Point<2> from = start;
      for (unsigned int k = 0; k < n_parts; ++k)
        {
          const Point<2> to =
            (k + 1 == n_parts ? end : on_circle(first + (k + 1) * part));
          arcs.push_back({from, to, part});
          if (k + 1 < n_parts)
            corners.push_back(to);
          from = to;
        }
    };

    if (pieces.empty())
      {
        // The circle does not cross the boundary: K is the whole disk if the
        // centre is in the cell, and empty otherwise. Without a tolerance:
        // a tiny disk just beside the edge must not count in both cells.
        for (unsigned int i = 0; i < polygon.size(); ++i)
          if (cross(polygon[(i + 1) % polygon.size()] - polygon[i],
                    centre - polygon[i]) < 0.)
            return Quadrature<2>();
        // The whole disk in polar coordinates about its centre: weights
        // exact whatever the disk's size against its distance from the
        // origin. For a polynomial of degree 2 n - 1 in x and y, r dr is
        // integrated exactly by n + 1 Gauss points and the trigonometric
        // polynomial in theta by 2 n + 2 equally spaced angles.
        const unsigned int n_r     = std::max(n_points_1d, 1u) + 1;
        const unsigned int n_theta = 2 * std::max(n_points_1d, 1u) + 2;
        const QGauss<1>    gauss_r(n_r);
        for (unsigned int i = 0; i < gauss_r.size(); ++i)
          for (unsigned int k = 0; k < n_theta; ++k)
            {
              const double r = radius * gauss_r.point(i)[0];
              points.push_back(cell.inverse_map(
                centre + r * unit_vector(2. * numbers::PI * k / n_theta)));
              weights.push_back(gauss_r.weight(i) * radius * r * 2. *
                                numbers::PI / n_theta);
            }
        return Quadrature<2>(points, weights);
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
              // follows the circle counterclockwise to the next piece. The
              // opening from the chord, not from a difference of angles
              // (which loses every digit for a large disk), and from the
              // centre's signed distance to the chord (positive left of
              // end -> next: the minor arc), not from the arc sine of the
              // half chord over the radius, which loses half the digits
              // near a half circle (an arc of pi + 4e-8 for a disk centred
              // on a cell's edge).
              const double chord = end.distance(next);
              const double signed_distance =
                cross(next - end, centre - end) / chord;
              add_arc(end, next, 2. * std::atan2(0.5 * chord, signed_distance));
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

    // The convex polygon Q: fan of triangles, exact for polynomials.
    if (corners.size() >= 3)
      add_polygon(corners);

    // The circular segments, each in the frame of its chord: with the
    // chord's midpoint m, its direction tau and the normal n towards the
    // arc, the half opening a and s = R sin(psi), the segment is
    //   x = m + t n + s tau,  |psi| <= a,
    //   0 <= t <= R (cos(psi) - cos(a)),   dx dy = R cos(psi) dpsi dt,
    // so for polynomial integrands the t integral is a polynomial and the psi
    // integrand a trigonometric polynomial: n Gauss points are exact in t,
    // and in psi Gauss rules converge very fast on |psi| <= pi/8. The arc is
    // the only inexact part, so it gets 4 extra points in psi: with them the
    // area of any disk part is exact to ~1e-13 relative already for n = 2
    // (with n points in psi and quarter-circle arcs: 6e-2 for n = 2, 1e-3
    // for n = 3, 2e-5 for n = 4). The chord's frame and the height as a
    // product of sines keep a segment of a huge disk (R = 1e13, a = 1e-13)
    // free of cancellation.
    const QGauss<1> gauss_t(std::max(n_points_1d, 1u));
    const QGauss<1> gauss_psi(std::max(n_points_1d, 1u) + 4);
    for (const Arc &arc : arcs)
      {
        const Tensor<1, 2> chord  = arc.end - arc.start;
        const double       length = chord.norm();
        if (!(length > 0.))
          continue;
        const double       a   = 0.5 * arc.opening;
        const Tensor<1, 2> tau = chord / length;
        Tensor<1, 2>       n;
        n[0]             = tau[1];
        n[1]             = -tau[0];
        const Point<2> m = arc.start + 0.5 * chord;
        for (unsigned int i = 0; i < gauss_psi.size(); ++i)
          {
            const double psi    = (2. * gauss_psi.point(i)[0] - 1.) * a;
            const double height = 2. * radius * std::sin(0.5 * (a + psi)) *
                                  std::sin(0.5 * (a - psi));
            if (!(height > 0.))
              continue;
            const double s = radius * std::sin(psi);
            for (unsigned int j = 0; j < gauss_t.size(); ++j)
              {
                const double t = gauss_t.point(j)[0] * height;
                points.push_back(cell.inverse_map(m + t * n + s * tau));
                weights.push_back(gauss_psi.weight(i) * 2. * a *
                                  gauss_t.weight(j) * height * radius *
                                  std::cos(psi));
              }
          }
      }

    double total = 0.;
    for (const double w : weights)
      total += w;
    if (!(total > 0.))
      return Quadrature<2>();
    return Quadrature<2>(points, weights);
  }
} // namespace PlateOnHalfspace
