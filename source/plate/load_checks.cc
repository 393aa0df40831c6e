#include <deal.II/base/exceptions.h>

#include <boost/accumulators/accumulators.hpp>
#include <boost/accumulators/statistics/stats.hpp>
#include <boost/accumulators/statistics/sum_kahan.hpp>

#include <plate_on_halfspace/plate/load_checks.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/plate/slab_grid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    /** The covered area of a region on the whole plate. */
    /** The four cells into which the midpoints of its edges and its
     *  centre cut @p cell. */
    std::array<BilinearQuadrilateral, 4>
    quarters(const BilinearQuadrilateral &cell)
    {
      const auto at = [&](const double s, const double t) {
        return cell.map(Point<2>(s, t));
      };
      const auto quarter = [&](const double s, const double t) {
        return BilinearQuadrilateral(std::array<Point<2>, 4>{
          {at(s, t), at(s + 0.5, t), at(s, t + 0.5), at(s + 0.5, t + 0.5)}});
      };
      return {{quarter(0., 0.),
               quarter(0.5, 0.),
               quarter(0., 0.5),
               quarter(0.5, 0.5)}};
    }

    double
    cross(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
    {
      return a[0] * b[1] - a[1] * b[0];
    }

    /** The convex hull of @p points, counterclockwise (monotone chain). */
    std::vector<Point<2>>
    convex_hull(std::vector<Point<2>> points)
    {
      std::sort(points.begin(),
                points.end(),
                [](const Point<2> &a, const Point<2> &b) {
                  return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]);
                });
      points.erase(std::unique(points.begin(), points.end()), points.end());
      if (points.size() < 3)
        return points;
      std::vector<Point<2>> hull(2 * points.size());
      unsigned int          k = 0;
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          while (k >= 2 &&
                 cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0)
            --k;
          hull[k++] = points[i];
        }
      for (int i = static_cast<int>(points.size()) - 2, lower = k + 1; i >= 0;
           --i)
        {
          while (k >= static_cast<unsigned int>(lower) &&
                 cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0)
            --k;
          hull[k++] = points[i];
        }
      hull.resize(k - 1);
      return hull;
    }

    /** The distance of @p x from the outline of the convex @p hull,
     *  negative outside. */
    double
    depth_in(const std::vector<Point<2>> &hull, const Point<2> &x)
    {
      double depth = std::numeric_limits<double>::infinity();
      for (unsigned int i = 0; i < hull.size(); ++i)
        {
          const Tensor<1, 2> edge = hull[(i + 1) % hull.size()] - hull[i];
          if (edge.norm() > 0)
            depth = std::min(depth, cross(edge, x - hull[i]) / edge.norm());
        }
      return depth;
    }

    /**
     * The smallest distance of @p x from an edge of the convex @p hull
     * among the edges that @p x lies outside the middle third of the width
     * across (the hull's largest distance from that edge's line): where a
     * linear pressure q >= 0 with its resultant at @p x cannot cover the
     * whole width, and carries it on a region three such distances wide.
     * Infinity where @p x lies within the middle third across every edge.
     */
    double
    depth_outside_middle_third(const std::vector<Point<2>> &hull,
                               const Point<2>              &x)
    {
      double depth = std::numeric_limits<double>::infinity();
      for (unsigned int i = 0; i < hull.size(); ++i)
        {
          const Tensor<1, 2> edge = hull[(i + 1) % hull.size()] - hull[i];
          if (!(edge.norm() > 0))
            continue;
          const double distance = cross(edge, x - hull[i]) / edge.norm();
          double       width    = 0;
          for (const Point<2> &y : hull)
            width = std::max(width, cross(edge, y - hull[i]) / edge.norm());
          if (3 * distance < width)
            depth = std::min(depth, distance);
        }
      return depth;
    }

    std::string
    number(const double value)
    {
      std::ostringstream s;
      s << std::setprecision(4) << value;
      return s.str();
    }

    std::string
    point(const Point<2> &x)
    {
      return "(" + number(x[0]) + ", " + number(x[1]) + ")";
    }
  } // namespace

  std::vector<LoadOnPlate>
  loads_on_plate(const FoundationSpace &space, const LoadList &loads)
  {
    std::vector<FoundationSpace::Cell> cells = space.cells;
    for (auto &image : space.mirror_image_cells())
      cells.push_back(std::move(image));
    std::vector<LoadOnPlate> result;
    for (const auto &load : loads)
      if (const auto area = load->region_area())
        {
          double applied = 0, covered = 0;
          for (const auto &cell : cells)
            {
              const CellLoad on_cell = load->on_cell(cell.geometry);
              for (unsigned int q = 0; q < on_cell.rule.size(); ++q)
                {
                  applied += on_cell.pressure[q] * on_cell.rule.weight(q);
                  covered += on_cell.rule.weight(q);
                }
            }
          const auto nominal = load->nominal_force();
          // the cells' pieces add up to the region to rounding
          result.push_back(
            {load->label(),
             *area,
             std::min(covered, *area),
             nominal ? *nominal : std::numeric_limits<double>::quiet_NaN(),
             applied});
        }
    return result;
  }

  double
  load_integration_error(const FoundationSpace &space, const LoadList &loads)
  {
    double largest = 0;
    for (const auto &load : loads)
      if (!load->integrated_exactly())
        {
          double force = 0, finer = 0, magnitude = 0;
          for (const auto &cell : space.cells)
            {
              const CellLoad given = load->on_cell(cell.geometry);
              for (unsigned int q = 0; q < given.rule.size(); ++q)
                force += given.pressure[q] * given.rule.weight(q);
              // each quarter of the cell (a bilinear cell of its own) by a
              // rule of 3 more points: a jump or a peak inside the cell,
              // which a higher order alone can miss, changes the sum
              for (const auto &quarter : quarters(cell.geometry))
                {
                  const CellLoad fine = load->on_cell(quarter, 3);
                  for (unsigned int q = 0; q < fine.rule.size(); ++q)
                    {
                      finer += fine.pressure[q] * fine.rule.weight(q);
                      magnitude +=
                        std::abs(fine.pressure[q]) * fine.rule.weight(q);
                    }
                }
            }
          if (magnitude > 0)
            largest = std::max(largest, std::abs(force - finer) / magnitude);
        }
    return largest;
  }

  std::vector<std::string>
  partly_off_plate_warnings(const std::vector<LoadOnPlate> &loads,
                            const std::string              &where)
  {
    std::vector<std::string> warnings;
    for (const LoadOnPlate &l : loads)
      {
        // The overlap's quadrature of a disk's arcs is exact to about 1e-9
        // of its area (a tyre tangent to the edge measured 1.1e-9 off);
        // less than 1e-6 off the plate is a patch that ends on the edge.
        const double share_off = l.area > 0 ? 1 - l.covered_area / l.area : 0;
        if (!(share_off > 1e-6) || l.covered_area == 0)
          continue;
        std::ostringstream w;
        w << where << l.entry
          << " lies partly off the plate: " << std::setprecision(3)
          << 100 * share_off;
        if (std::isfinite(l.load))
          w << " % of its load is off the plate, so only "
            << std::setprecision(6) << l.applied << " of its " << l.load
            << " is applied";
        else
          w << " % of its region is off the plate, so only the part on the "
               "plate, "
            << std::setprecision(6) << l.applied << ", is applied";
        w << " (applied_load in summary.json and sweep.csv).";
        warnings.push_back(w.str());
      }
    return warnings;
  }

  ResultantVerdict
  check_load_resultant(const MindlinPlate &plate,
                       const LoadList     &loads,
                       const bool          has_weight,
                       const bool          soil_couples_nodes)
  {
    ResultantVerdict       verdict;
    const FoundationSpace &space = plate.get_foundation_space();
    const auto            &dofs  = plate.get_foundation_dofs();
    const Vector<double>  &load  = plate.get_load_vector();
    const unsigned int     n     = space.n_nodes();
    if (n == 0 || load.size() == 0)
      return verdict;

    // The bodies that move on their own: the cells joined by a node they
    // share, and the slabs (the material id of their cells; one slab
    // unless Shape = slabs) joined by joints that keep them from
    // separating vertically (every joint but a free one). A Gmsh mesh in
    // several pieces is several bodies, as free slabs are.
    const SlabGrid           *grid    = plate.get_slab_grid();
    const unsigned int        n_slabs = grid ? grid->n_slabs() : 1;
    const bool                slabs   = n_slabs > 1;
    const unsigned int        n_cells = space.cells.size();
    std::vector<unsigned int> parent(n_cells + n_slabs);
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](unsigned int s) {
      while (parent[s] != s)
        s = parent[s] = parent[parent[s]];
      return s;
    };
    const auto join = [&](const unsigned int a, const unsigned int b) {
      parent[find(a)] = find(b);
    };
    // entries n_cells + s stand for slab s
    if (grid)
      for (const Joint &joint : grid->get_joints())
        if (joint.transfer != Parameters::Joints::LoadTransfer::free &&
            joint.slab_low < n_slabs && joint.slab_high < n_slabs)
          join(n_cells + joint.slab_low, n_cells + joint.slab_high);
    {
      std::vector<unsigned int> first_cell_of_node(
        n, numbers::invalid_unsigned_int);
      unsigned int c = 0;
      for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
        {
          if (slabs)
            join(c,
                 n_cells +
                   std::min<unsigned int>(cell->material_id(), n_slabs - 1));
          for (const unsigned int i : space.cells[c].nodes())
            {
              if (first_cell_of_node[i] == numbers::invalid_unsigned_int)
                first_cell_of_node[i] = c;
              else
                join(c, first_cell_of_node[i]);
            }
          ++c;
        }
    }
    // the bodies numbered in the order of their first cells
    std::vector<unsigned int> body_of_root(n_cells + n_slabs,
                                           numbers::invalid_unsigned_int);
    std::vector<unsigned int> body_of_cell(n_cells);
    unsigned int              n_bodies = 0;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        unsigned int &b = body_of_root[find(c)];
        if (b == numbers::invalid_unsigned_int)
          b = n_bodies++;
        body_of_cell[c] = b;
      }
    std::vector<unsigned int> body_of_node(n, 0);
    std::vector<double>       cell_size_of_node(n, 0);
    for (unsigned int c = 0; c < n_cells; ++c)
      for (const unsigned int i : space.cells[c].nodes())
        {
          body_of_node[i] = body_of_cell[c];
          cell_size_of_node[i] =
            std::max(cell_size_of_node[i], space.cells[c].geometry.diameter());
        }

    // The reflections that make the whole plate of the computed part's
    // bodies. A mirror plane on a joint that is not tied is two free
    // edges (SlabGrid::mark_joint_faces()): the image across it is a
    // body of its own, with the same loads, so it is not joined.
    bool separate[2] = {false, false};
    if (grid)
      for (const Joint &joint : grid->get_joints())
        if (joint.transfer != Parameters::Joints::LoadTransfer::tied &&
            std::abs(joint.start[joint.axis]) <= space.symmetry.tolerance)
          separate[joint.axis] = true;
    std::vector<std::array<double, 2>> reflections = {{{1., 1.}}};
    for (const auto &signs : space.symmetry.reflections())
      if (!(separate[0] && signs[0] < 0) && !(separate[1] && signs[1] < 0))
        reflections.push_back(signs);

    // Compensated sums: a body's force is tested against 1e-12 of its
    // magnitude, below a plain sum's drift over 10^6 nodes (the same reason
    // as MindlinPlate::resultant()).
    namespace acc = boost::accumulators;
    using CompensatedSum =
      acc::accumulator_set<double, acc::stats<acc::tag::sum_kahan>>;
    struct Body
    {
      CompensatedSum        force_sum, magnitude_sum, moment_sum[2];
      double                force = 0, magnitude = 0;
      Tensor<1, 2>          moment;
      std::vector<Point<2>> points;
      /** node locations with their cell sizes, for the size near x */
      std::vector<std::pair<Point<2>, double>> sizes;
    };
    std::vector<Body> bodies(n_bodies);
    CompensatedSum    total_sum;
    // A body's image across a mirror plane is the same body only where
    // the body reaches that plane; otherwise it is a body of its own with
    // the same loads (a Gmsh piece away from the plane), checked alike.
    std::vector<std::array<bool, 2>> reaches_plane(n_bodies, {{false, false}});
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 2; ++d)
        if (std::abs(space.node_locations[i][d]) <= space.symmetry.tolerance)
          reaches_plane[body_of_node[i]][d] = true;
    for (unsigned int i = 0; i < n; ++i)
      {
        Body        &b = bodies[body_of_node[i]];
        const double p = load[dofs[i]];
        // The whole plate: each mirror image carries the same load. A node
        // on a mirror plane is its own image there and carries only the
        // computed part's share, so the images of a node share the copies.
        const Point<2>       &node    = space.node_locations[i];
        const auto           &reaches = reaches_plane[body_of_node[i]];
        std::vector<Point<2>> images;
        unsigned int          copies = 0;
        for (const auto &signs : reflections)
          {
            if ((signs[0] < 0 && !reaches[0]) || (signs[1] < 0 && !reaches[1]))
              continue;
            ++copies;
            const Point<2> x(signs[0] * node[0], signs[1] * node[1]);
            if (std::none_of(images.begin(),
                             images.end(),
                             [&](const Point<2> &y) {
                               return y.distance(x) <= space.symmetry.tolerance;
                             }))
              images.push_back(x);
          }
        const double share = double(copies) / images.size();
        for (const Point<2> &x : images)
          {
            b.force_sum(share * p);
            b.magnitude_sum(share * std::abs(p));
            b.moment_sum[0](share * p * x[0]);
            b.moment_sum[1](share * p * x[1]);
            b.points.push_back(x);
            b.sizes.emplace_back(x, cell_size_of_node[i]);
            total_sum(share * p);
          }
      }
    for (Body &b : bodies)
      {
        b.force     = acc::sum_kahan(b.force_sum);
        b.magnitude = acc::sum_kahan(b.magnitude_sum);
        for (unsigned int d = 0; d < 2; ++d)
          b.moment[d] = acc::sum_kahan(b.moment_sum[d]);
      }
    // An upward or zero resultant has its own message (contact/interface.h).
    if (!(acc::sum_kahan(total_sum) > 0))
      return verdict;

    // a body whose mirror image is a body of its own
    bool imaged_apart = false;
    for (unsigned int b = 0; b < n_bodies; ++b)
      for (const auto &signs : reflections)
        imaged_apart = imaged_apart || (signs[0] < 0 && !reaches_plane[b][0]) ||
                       (signs[1] < 0 && !reaches_plane[b][1]);
    const bool several =
      separate[0] || separate[1] || imaged_apart ||
      std::count_if(bodies.begin(), bodies.end(), [](const Body &b) {
        return !b.points.empty();
      }) > 1;
    const auto name_of = [&](const unsigned int s) {
      std::string        whose = "the plate";
      const unsigned int first =
        std::find(body_of_cell.begin(), body_of_cell.end(), s) -
        body_of_cell.begin();
      if (several && !slabs)
        // a piece of a Gmsh mesh: named by a point of it
        whose = "the piece of the plate (the mesh's cells connected to "
                "each other) around " +
                point(space.cells[first].geometry.map(Point<2>(0.5, 0.5)));
      else if (several)
        {
          std::vector<unsigned int> members;
          for (unsigned int t = 0; t < n_slabs; ++t)
            if (find(n_cells + t) == find(first))
              members.push_back(t + 1);
          whose = members.size() == 1 ? "slab " : "slabs ";
          for (unsigned int k = 0; k < members.size(); ++k)
            whose += (k > 0 ? ", " : "") + std::to_string(members[k]);
          whose += members.size() == 1 ?
                     " (as summary.json's slabs, counted from 1)" :
                     " (as summary.json's slabs, counted from 1; joined "
                     "by joints that are not free)";
        }
      return whose;
    };
    std::string unloaded;
    for (unsigned int s = 0; s < n_bodies; ++s)
      {
        const Body &b = bodies[s];
        if (b.points.empty())
          continue;
        // A body without load on a weightless plate (a thermal load adds
        // none: its resultant and moment vanish) rests where it is only
        // if nothing moves it: on a dense liquid and without curling its
        // answer is w = 0, the limit of a vanishing weight. A half-space
        // settles under it with the loaded bodies and a temperature
        // difference curls it: then nothing holds it down, any lifted
        // position is an answer, and the contact iteration picked one by
        // its path (doc/errors-and-limits.md). Refused after the loaded
        // bodies' verdicts, which name the loads to move.
        if (b.magnitude == 0)
          {
            if (unloaded.empty() &&
                (soil_couples_nodes || plate.get_thermal_load().moment != 0))
              unloaded = name_of(s);
            continue;
          }
        const std::vector<Point<2>> hull = convex_hull(b.points);
        if (hull.size() < 3)
          continue;
        double diameter = 0;
        for (const Point<2> &x : hull)
          for (const Point<2> &y : hull)
            diameter = std::max(diameter, x.distance(y));
        const std::string whose = name_of(s);
        const std::string weight_advice =
          has_weight ? "" : "give the plate its weight (Plate/Unit weight), ";
        const std::string remedy =
          " Move the load inward, " + weight_advice +
          "or spread the load as a patch (Loads/Rectangular patches, "
          "Circular patches).";
        if (!(b.force > 1e-12 * b.magnitude))
          {
            verdict.error =
              "The loads on " + whose + " have no downward resultant (" +
              number(b.force) + "), so a tensionless foundation cannot hold " +
              (several ? "them" : "it") +
              " down and the scene has no determinate answer." + remedy;
            return verdict;
          }
        const Point<2> resultant(b.moment / b.force);
        const double   depth = depth_in(hull, resultant);
        if (depth <= 1e-9 * diameter)
          {
            // name the point loads on or beyond the outline
            std::string named;
            for (const auto &load : loads)
              if (const auto force = load->concentrated_force())
                if (depth_in(hull, force->first) <= 1e-9 * diameter)
                  named += std::string(named.empty() ? "" : ", ") +
                           point(force->first);
            verdict.error =
              "The loads on a tensionless foundation have no determinate "
              "answer: the resultant of the loads on " +
              whose + ", " + number(b.force) + " at " + point(resultant) +
              ", lies " + (depth < -1e-9 * diameter ? "outside" : "on") +
              " the outline of " +
              (!several ? "the plate" :
               slabs    ? "those slabs" :
                          "that piece") +
              (named.empty() ? std::string(" (Loads)") :
                               " (Loads/Point loads at " + named + ")") +
              ". A soil that cannot pull would have to carry the plate on "
              "that point or edge alone: the contact region shrinks with "
              "every refinement and the peak pressure grows without bound "
              "(doc/errors-and-limits.md, \"A resultant on the outline\")." +
              remedy;
            return verdict;
          }
        // The resultant inside: determinate. A linear pressure q >= 0 with
        // its resultant at the depth d from an edge, outside the middle
        // third of the width across it, needs a contact region 3 d wide (a
        // triangle); cells larger than that cannot resolve it. Within the
        // middle third across every edge (a narrow strip under a central
        // load) the whole plate carries it.
        const double eccentric_depth =
          depth_outside_middle_third(hull, resultant);
        double size = 0, nearest = std::numeric_limits<double>::infinity();
        for (const auto &[x, h] : b.sizes)
          if (x.distance(resultant) < nearest)
            {
              nearest = x.distance(resultant);
              size    = h;
            }
        if (3 * eccentric_depth < size && verdict.warning.empty())
          verdict.warning =
            "The resultant of the loads on " + whose + ", " + number(b.force) +
            " at " + point(resultant) + ", lies " + number(eccentric_depth) +
            " from the outline, less than a third of the cells there (" +
            number(size) +
            "): on a tensionless foundation the plate is then carried on a "
            "region about three times that wide, which these cells cannot "
            "resolve, so "
            "the answer changes with the mesh until they are much smaller. "
            "Refine there (Adaptivity), move the load inward, " +
            weight_advice + "or spread the load as a patch.";
      }
    if (!unloaded.empty())
      verdict.error =
        "The loads leave " + unloaded +
        " without any load, and the plate has no weight: on a tensionless " +
        (soil_couples_nodes ?
           std::string("half-space, which settles under it with the loaded ") +
             (slabs ? "slabs," : "pieces,") :
           "foundation, with the temperature difference "
           "curling it,") +
        " nothing holds it down, so its position and every result on it (its "
        "deflections" +
        (slabs ? std::string(", the load transfer of its joints") : "") +
        ") are not determined. Give the plate its weight (Plate/Unit "
        "weight), " +
        (slabs ? std::string("load that slab, or join it to a loaded one "
                             "(Joints/Load transfer other than free).") :
                 std::string("load that piece, or join it to a loaded one "
                             "in the mesh (Plate/Mesh file)."));
    return verdict;
  }
} // namespace PlateOnHalfspace
