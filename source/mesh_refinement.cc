#include <deal.II/base/quadrature_lib.h>

#include <deal.II/grid/grid_refinement.h>

#include <deal.II/numerics/error_estimator.h>

#include <plate_on_halfspace/mesh_refinement.h>

#include <algorithm>

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
    // Cells on the plate edge and on the contact boundary (nodes in and out
    // of contact, or pressures of both signs) go first.
    const float            top   = indicators.linfty_norm();
    const FoundationSpace &space = plate.get_foundation_space();
    unsigned int           index = 0;
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      {
        bool in = false, out = false, positive = false, negative = false;
        for (const auto &terms : space.cells[index].expansion)
          for (const auto &t : terms)
            {
              (contact.in_contact[t.first] ? in : out)        = true;
              (contact.q[t.first] >= 0 ? positive : negative) = true;
            }
        if (cell->at_boundary() || (in && out) || (positive && negative))
          indicators[index] = std::max(indicators[index], top);
        ++index;
      }
    GridRefinement::refine_and_coarsen_fixed_number(triangulation,
                                                    indicators,
                                                    adaptivity.refine_fraction,
                                                    adaptivity.coarsen_fraction,
                                                    adaptivity.max_cells);
    return true;
  }
} // namespace PlateOnHalfspace
