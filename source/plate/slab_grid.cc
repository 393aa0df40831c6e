#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>

#include <plate_on_halfspace/plate/slab_grid.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

namespace PlateOnHalfspace
{
  bool
  Joint::contains(const Point<2> &p, const double tolerance) const
  {
    const unsigned int along = 1 - axis;
    return std::abs(p[axis] - start[axis]) <= tolerance &&
           p[along] >= start[along] - tolerance &&
           p[along] <= end[along] + tolerance;
  }

  std::string
  Joint::name() const
  {
    std::ostringstream s;
    s << (axis == 0 ? "transverse joint x = " : "longitudinal joint y = ")
      << start[axis] << ", " << (axis == 0 ? "y" : "x") << " in ["
      << start[1 - axis] << ", " << end[1 - axis] << "]";
    return s.str();
  }

  SlabGrid::SlabGrid(const Parameters::Plate  &plate,
                     const Parameters::Joints &joint_parameters)
    : parameters(joint_parameters)
  {
    if (plate.shape != Parameters::Plate::Shape::slabs)
      {
        // one slab without joints: the whole plate
        const double extent = (plate.shape == Parameters::Plate::Shape::disk ?
                                 plate.radius :
                                 std::max(plate.length_x, plate.length_y));
        point_tolerance     = 1e-10 * extent;
        slabs.push_back({Point<2>(-extent, -extent), Point<2>(extent, extent)});
        return;
      }

    // slab boundaries along each axis, the grid centred at the origin
    std::array<std::vector<double>, 2> lines;
    for (const unsigned int axis : {0u, 1u})
      {
        const auto &lengths =
          (axis == 0 ? plate.slab_lengths_x : plate.slab_lengths_y);
        const double total =
          std::accumulate(lengths.begin(), lengths.end(), 0.);
        lines[axis].push_back(-total / 2);
        for (const double length : lengths)
          lines[axis].push_back(lines[axis].back() + length);
        lines[axis].back() = total / 2;
      }
    point_tolerance       = 1e-10 * std::max(lines[0].back() - lines[0].front(),
                                       lines[1].back() - lines[1].front());
    const unsigned int nx = lines[0].size() - 1, ny = lines[1].size() - 1;
    for (unsigned int j = 0; j < ny; ++j)
      for (unsigned int i = 0; i < nx; ++i)
        slabs.push_back({Point<2>(lines[0][i], lines[1][j]),
                         Point<2>(lines[0][i + 1], lines[1][j + 1])});

    const auto dowel_positions = [&](const Point<2>    &start,
                                     const Point<2>    &end,
                                     const unsigned int along) {
      // bars Dowel spacing apart, centred on the joint (EverFE's and
      // ISLAB2000's layout; a joint shorter than the spacing has one bar)
      const double       length = end[along] - start[along];
      const unsigned int n =
        std::max(1u,
                 static_cast<unsigned int>(
                   std::floor(length / parameters.dowel_spacing + 1e-9)));
      const double first =
        start[along] + (length - (n - 1) * parameters.dowel_spacing) / 2;
      std::vector<Point<2>> bars;
      for (unsigned int k = 0; k < n; ++k)
        {
          Point<2> p = start;
          p[along]   = first + k * parameters.dowel_spacing;
          bars.push_back(p);
        }
      return bars;
    };

    // transverse joints (x = const) between slabs i and i + 1 of a row
    for (unsigned int j = 0; j < ny; ++j)
      for (unsigned int i = 0; i + 1 < nx; ++i)
        {
          Joint joint;
          joint.axis      = 0;
          joint.start     = Point<2>(lines[0][i + 1], lines[1][j]);
          joint.end       = Point<2>(lines[0][i + 1], lines[1][j + 1]);
          joint.slab_low  = j * nx + i;
          joint.slab_high = j * nx + i + 1;
          joint.transfer  = parameters.transverse;
          joints.push_back(joint);
        }
    // longitudinal joints (y = const) between rows j and j + 1
    for (unsigned int j = 0; j + 1 < ny; ++j)
      for (unsigned int i = 0; i < nx; ++i)
        {
          Joint joint;
          joint.axis      = 1;
          joint.start     = Point<2>(lines[0][i], lines[1][j + 1]);
          joint.end       = Point<2>(lines[0][i + 1], lines[1][j + 1]);
          joint.slab_low  = j * nx + i;
          joint.slab_high = (j + 1) * nx + i;
          joint.transfer  = parameters.longitudinal;
          joints.push_back(joint);
        }
    for (Joint &joint : joints)
      if (joint.transfer == Parameters::Joints::LoadTransfer::dowels)
        joint.dowels = dowel_positions(joint.start, joint.end, 1 - joint.axis);
  }

  namespace
  {
    /** The dowel bar of @p joints as a beam on the concrete's support:
     *  E I and beta = (K d / (4 E I))^(1/4). */
    std::pair<double, double>
    dowel_beam(const Parameters::Joints &joints)
    {
      const double d = joints.dowel_diameter;
      const double EI =
        joints.dowel_modulus * numbers::PI * std::pow(d, 4) / 64.;
      return {EI, std::pow(joints.dowel_support_modulus * d / (4. * EI), 0.25)};
    }
  } // namespace

  double
  SlabGrid::dowel_stiffness() const
  {
    // doc/formulation.md, "Joints": the bar as a semi-infinite beam on the
    // concrete's support K d per length on either side (Friberg), loaded at
    // the face by the shear P and the moment P z / 2: each side deflects
    // y0 = P (2 + beta z) / (4 beta^3 E I) and turns
    // theta0 = P (1 + beta z) / (2 beta^2 E I); across the opening the bar
    // bends as two cantilevers of z/2 and shears (steel, nu = 0.3, shear
    // factor 10/9 of a circle).
    const auto [EI, beta] = dowel_beam(parameters);
    const double d        = parameters.dowel_diameter;
    const double z        = parameters.joint_opening;
    const double GA =
      parameters.dowel_modulus / (2. * (1. + 0.3)) * numbers::PI * d * d / 4.;
    const double compliance = (2. + beta * z) / (2. * std::pow(beta, 3) * EI) +
                              (1. + beta * z) * z / (2. * beta * beta * EI) +
                              std::pow(z, 3) / (12. * EI) + 10. / 9. * z / GA;
    return 1. / compliance;
  }

  double
  SlabGrid::dowel_bearing_stress(const double force) const
  {
    // K y0, y0 the deflection at the joint face
    const auto [EI, beta] = dowel_beam(parameters);
    return parameters.dowel_support_modulus * force *
           (2. + beta * parameters.joint_opening) /
           (4. * std::pow(beta, 3) * EI);
  }

  unsigned int
  SlabGrid::joint_at(const Point<2> &p) const
  {
    for (unsigned int j = 0; j < joints.size(); ++j)
      if (joints[j].contains(p, point_tolerance))
        return j;
    return joints.size();
  }

  void
  SlabGrid::mark_joint_faces(Triangulation<2> &triangulation) const
  {
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->at_boundary(f))
          {
            const auto         face  = cell->face(f);
            const unsigned int joint = joint_at(face->center());
            if (joint == joints.size())
              continue;
            const bool on_mirror_plane =
              face->boundary_id() == mirror_plane_x_boundary_id ||
              face->boundary_id() == mirror_plane_y_boundary_id;
            if (on_mirror_plane && joints[joint].transfer ==
                                     Parameters::Joints::LoadTransfer::tied)
              continue;
            face->set_boundary_id(joint_boundary_id);
          }
  }

  void
  SlabGrid::match_refinement(Triangulation<2> &triangulation) const
  {
    if (joints.empty())
      return;
    // The cells on the two sides of a joint face, found by the face's
    // centre (face_key()).
    bool changed = true;
    while (changed)
      {
        triangulation.prepare_coarsening_and_refinement();
        changed = false;
        std::map<std::pair<long long, long long>,
                 std::vector<Triangulation<2>::active_cell_iterator>>
          facing;
        for (const auto &cell : triangulation.active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            if (cell->at_boundary(f) &&
                cell->face(f)->boundary_id() == joint_boundary_id)
              facing[face_key(cell->face(f)->center())].push_back(cell);
        for (auto &[centre, cells] : facing)
          {
            (void)centre;
            const bool refine =
              std::any_of(cells.begin(), cells.end(), [](const auto &c) {
                return c->refine_flag_set();
              });
            const bool keep =
              std::any_of(cells.begin(), cells.end(), [](const auto &c) {
                return !c->coarsen_flag_set();
              });
            for (auto &cell : cells)
              {
                if (refine && !cell->refine_flag_set())
                  {
                    cell->clear_coarsen_flag();
                    cell->set_refine_flag();
                    changed = true;
                  }
                if (keep && cell->coarsen_flag_set())
                  {
                    cell->clear_coarsen_flag();
                    changed = true;
                  }
              }
          }
      }
  }
} // namespace PlateOnHalfspace
