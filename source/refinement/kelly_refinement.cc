#include <deal.II/base/bounding_box.h>
#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/grid/grid_refinement.h>
#include <deal.II/grid/grid_tools.h>

#include <deal.II/numerics/error_estimator.h>

#include <plate_on_halfspace/refinement/interface.h>
#include <plate_on_halfspace/refinement/marking.h>

#include <algorithm>
#include <cmath>

namespace PlateOnHalfspace
{
  namespace
  {
    /** The load that the loads' jumps put on @p cell (Load::jump_on()). */
    double
    load_edge_indicator(const Triangulation<2>::active_cell_iterator &cell,
                        const LoadList                               &loads)
    {
      const std::array<Point<2>, 4> vertices = {
        {cell->vertex(0), cell->vertex(1), cell->vertex(2), cell->vertex(3)}};
      const double area  = cell->measure();
      double       value = 0;
      for (const auto &load : loads)
        value += load->jump_on(vertices, area);
      return value;
    }
  } // namespace

  GlobalRefinement::GlobalRefinement(const Parameters::Adaptivity &adaptivity)
    : adaptivity(adaptivity)
  {}

  bool
  GlobalRefinement::mark(const MindlinPlate &,
                         const ContactState &,
                         const GoalErrorEstimate &,
                         Triangulation<2> &triangulation) const
  {
    if (4 * triangulation.n_active_cells() > adaptivity.max_cells)
      return false;
    for (const auto &cell : triangulation.active_cell_iterators())
      cell->set_refine_flag();
    return true;
  }

  KellyRefinement::KellyRefinement(const Parameters::Adaptivity &adaptivity,
                                   const LoadList               &loads)
    : adaptivity(adaptivity)
    , loads(loads)
  {}

  bool
  KellyRefinement::mark(const MindlinPlate &plate,
                        const ContactState &contact,
                        const GoalErrorEstimate &,
                        Triangulation<2> &triangulation) const
  {
    const Vector<double> &solution = contact.plate_solution;
    const unsigned int    n_cells  = triangulation.n_active_cells();
    const unsigned int    copies =
      plate.get_foundation_space().symmetry.n_copies();
    if (!can_refine_fraction(adaptivity, copies, n_cells))
      return false;

    Vector<float> indicators(n_cells);
    KellyErrorEstimator<2>::estimate(
      plate.get_dof_handler(), QGauss<1>(3), {}, solution, indicators);
    const MirrorSymmetry &symmetry = plate.get_foundation_space().symmetry;
    if (symmetry.x || symmetry.y)
      {
        // On the whole plate a face on a mirror plane is interior. A field
        // that is even across the plane (w; beta_y across x = 0; beta_x
        // across y = 0) has a jump of the normal derivative twice its
        // one-sided derivative there: the Kelly term 4 h/24 ∫ (du/dn)^2. An
        // odd field (beta_x across x = 0, beta_y across y = 0) has no jump.
        // Kelly of one component with zero Neumann data on its even planes
        // gives the term once (N^2 = R^2 + term, R without it), so eta^2 =
        // sum over components of 4 N^2 - 3 R^2, and the computed part is
        // marked as the whole plate would be.
        const Functions::ZeroFunction<2> zero(3);
        Vector<double>                   squares(n_cells);
        for (unsigned int component = 0; component < 3; ++component)
          {
            std::map<types::boundary_id, const Function<2> *> even_planes;
            if (symmetry.x && component != 1)
              even_planes[mirror_plane_x_boundary_id] = &zero;
            if (symmetry.y && component != 2)
              even_planes[mirror_plane_y_boundary_id] = &zero;
            ComponentMask mask(3, false);
            mask.set(component, true);
            Vector<float> raw(n_cells), with_planes(n_cells);
            KellyErrorEstimator<2>::estimate(
              plate.get_dof_handler(), QGauss<1>(3), {}, solution, raw, mask);
            KellyErrorEstimator<2>::estimate(plate.get_dof_handler(),
                                             QGauss<1>(3),
                                             even_planes,
                                             solution,
                                             with_planes,
                                             mask);
            for (unsigned int c = 0; c < n_cells; ++c)
              squares[c] += 4. * with_planes[c] * with_planes[c] -
                            3. * double(raw[c]) * raw[c];
          }
        for (unsigned int c = 0; c < n_cells; ++c)
          indicators[c] = std::sqrt(std::max(0., squares[c]));
      }
    // The contact pressure is singular at the plate edge and changes sign
    // or vanishes non-smoothly at the contact boundary: on those cells add
    // an indicator sqrt(area) * (max q - min q) over the cell's nodes (the
    // variation of the pressure at the cell's scale: large where q is
    // singular, small where it is smooth, e.g. under a flexible plate). The
    // edges of load patches and point loads make the shear force jump: there
    // add the load of the discontinuity. Each family is normalised to its
    // maximum, so that every kind of singular place is refined where it matters
    // most. Faces on a mirror plane (boundary id != 0) are not plate edges.
    const FoundationSpace &space = plate.get_foundation_space();
    Vector<float> pressure_indicators(n_cells), load_indicators(n_cells);
    unsigned int  index = 0;
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      {
        bool   in = false, out = false, positive = false, negative = false;
        double q_min = std::numeric_limits<double>::max(),
               q_max = -std::numeric_limits<double>::max();
        for (const auto &terms : space.cells[index].expansion)
          for (const auto &t : terms)
            {
              (contact.in_contact[t.first] ? in : out)        = true;
              (contact.q[t.first] >= 0 ? positive : negative) = true;
              q_min = std::min(q_min, contact.q[t.first]);
              q_max = std::max(q_max, contact.q[t.first]);
            }
        bool on_plate_edge = false;
        for (const unsigned int f : cell->face_indices())
          on_plate_edge = on_plate_edge || (cell->at_boundary(f) &&
                                            cell->face(f)->boundary_id() == 0);
        if (on_plate_edge || (in && out) || (positive && negative))
          pressure_indicators[index] =
            std::sqrt(cell->measure()) * (q_max - q_min);
        load_indicators[index] = load_edge_indicator(cell, loads);
        ++index;
      }
    // A family that only sees rounding (q uniform under a flexible plate)
    // is left out.
    const double kelly_max = indicators.linfty_norm(),
                 pressure_max =
                   pressure_indicators.linfty_norm() >
                       1e-8 * contact.q.linfty_norm() *
                         std::sqrt(GridTools::volume(triangulation)) ?
                     pressure_indicators.linfty_norm() :
                     0.,
                 load_max = load_indicators.linfty_norm();
    for (unsigned int c = 0; c < n_cells; ++c)
      indicators[c] =
        (kelly_max > 0 ? indicators[c] / kelly_max : 0.) +
        (pressure_max > 0 ? pressure_indicators[c] / pressure_max : 0.) +
        (load_max > 0 ? load_indicators[c] / load_max : 0.);
    mark_largest_fraction(indicators, adaptivity, copies, triangulation);
    return true;
  }

  std::unique_ptr<RefinementStrategy>
  create_refinement_strategy(const SceneParameters &parameters)
  {
    switch (parameters.adaptivity.refinement)
      {
        case Parameters::Adaptivity::Refinement::adaptive:
          // the plate's weight is uniform: it has no jump
          return std::make_unique<KellyRefinement>(parameters.adaptivity,
                                                   make_loads(parameters.loads,
                                                              0.));
        case Parameters::Adaptivity::Refinement::goal:
          return std::make_unique<GoalOrientedRefinement>(
            parameters.adaptivity);
        case Parameters::Adaptivity::Refinement::global:
          break;
      }
    return std::make_unique<GlobalRefinement>(parameters.adaptivity);
  }
} // namespace PlateOnHalfspace
