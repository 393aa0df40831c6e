/**
 * Fixed-fraction marking shared by the refinement strategies that rank
 * cells by an indicator (doc/formulation.md, "Adaptive refinement").
 */
#ifndef plate_on_halfspace_refinement_marking_h
#define plate_on_halfspace_refinement_marking_h

#include <deal.II/grid/tria.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/scene/parameters.h>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * Whether refining Adaptivity/Refine fraction of the whole plate's cells
   * (@p copies times the @p n_cells of the computed part) stays within
   * Adaptivity/Max cells.
   */
  bool
  can_refine_fraction(const Parameters::Adaptivity &adaptivity,
                      const unsigned int            copies,
                      const unsigned int            n_cells);

  /**
   * Flag the cells with the largest @p indicators (active cell order) for
   * refinement and those with the smallest for coarsening, in the numbers
   * Adaptivity/Refine and Coarsen fraction give for the whole plate. Cells
   * whose indicators tie with the last marked one (to 1e-5 relative:
   * rounding) are marked with it, so that a symmetric solution gets a
   * symmetric mesh and a symmetric scene's computed part is refined as the
   * whole plate would be. Unless @p refine_negligible, cells whose
   * indicator is within that tie of zero are not refined.
   */
  void
  mark_largest_fraction(const Vector<float>          &indicators,
                        const Parameters::Adaptivity &adaptivity,
                        const unsigned int            copies,
                        Triangulation<2>             &triangulation,
                        const bool                    refine_negligible = true);
} // namespace PlateOnHalfspace

#endif
