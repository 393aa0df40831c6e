#include <deal.II/base/quadrature_lib.h>

#include <deal.II/grid/grid_refinement.h>

#include <deal.II/numerics/error_estimator.h>

#include <plate_on_halfspace/mesh_refinement.h>

#include <algorithm>
#include <cmath>

namespace PlateOnHalfspace
{
  bool
  mark_cells_for_refinement(const Parameters::Adaptivity &adaptivity,
                            const MindlinPlate           &plate,
                            const Vector<double>         &solution,
                            const ContactState           &contact,
                            Triangulation<2>             &triangulation)
  {
    const unsigned int n_cells = triangulation.n_active_cells();
    if (!adaptivity.adaptive)
      {
        if (4 * n_cells > adaptivity.max_cells)
          return false;
        for (const auto &cell : triangulation.active_cell_iterators())
          cell->set_refine_flag();
        return true;
      }

    const unsigned int n_refined = static_cast<unsigned int>(
      std::max(1., adaptivity.refine_fraction * n_cells));
    if (n_cells + 3 * n_refined > adaptivity.max_cells)
      return false;

    Vector<float> indicators(n_cells);
    KellyErrorEstimator<2>::estimate(
      plate.get_dof_handler(), QGauss<1>(3), {}, solution, indicators);
    // The contact pressure is singular at the plate edge and changes sign
    // or vanishes non-smoothly at the contact boundary: on those cells add
    // an indicator sqrt(area) * max |q| (the pressure resolved at the
    // cell's scale), both indicators normalised to their maximum, so that
    // edges are refined where the pressure there matters.
    const FoundationSpace &space = plate.get_foundation_space();
    Vector<float>          pressure_indicators(n_cells);
    unsigned int           index = 0;
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      {
        bool   in = false, out = false, positive = false, negative = false;
        double largest = 0;
        for (const auto &terms : space.cells[index].expansion)
          for (const auto &t : terms)
            {
              (contact.in_contact[t.first] ? in : out)        = true;
              (contact.q[t.first] >= 0 ? positive : negative) = true;
              largest = std::max(largest, std::abs(contact.q[t.first]));
            }
        if (cell->at_boundary() || (in && out) || (positive && negative))
          pressure_indicators[index] = std::sqrt(cell->measure()) * largest;
        ++index;
      }
    const double kelly_max    = indicators.linfty_norm(),
                 pressure_max = pressure_indicators.linfty_norm();
    for (unsigned int c = 0; c < n_cells; ++c)
      indicators[c] =
        (kelly_max > 0 ? indicators[c] / kelly_max : 0.) +
        (pressure_max > 0 ? pressure_indicators[c] / pressure_max : 0.);
    GridRefinement::refine_and_coarsen_fixed_number(triangulation,
                                                    indicators,
                                                    adaptivity.refine_fraction,
                                                    adaptivity.coarsen_fraction,
                                                    adaptivity.max_cells);
    return true;
  }
} // namespace PlateOnHalfspace
