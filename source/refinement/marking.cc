#include <plate_on_halfspace/refinement/marking.h>

#include <algorithm>
#include <functional>
#include <vector>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * The computed part's share of a number of the whole plate's cells:
     * the whole plate's n-th cell in the order of the indicators is the
     * part's ceil(n / copies)-th (a symmetric scene's cells come in groups
     * of copies).
     */
    unsigned int
    part_count(const double fraction_of_plate, const unsigned int copies)
    {
      const auto whole = static_cast<unsigned int>(fraction_of_plate);
      return (whole + copies - 1) / copies;
    }

    unsigned int
    n_to_refine(const Parameters::Adaptivity &adaptivity,
                const unsigned int            copies,
                const unsigned int            n_cells)
    {
      return std::max(1u,
                      part_count(adaptivity.refine_fraction * n_cells * copies,
                                 copies));
    }
  } // namespace

  bool
  can_refine_fraction(const Parameters::Adaptivity &adaptivity,
                      const unsigned int            copies,
                      const unsigned int            n_cells)
  {
    return n_cells + 3 * n_to_refine(adaptivity, copies, n_cells) <=
           adaptivity.max_cells;
  }

  void
  mark_largest_fraction(const Vector<float>          &indicators,
                        const Parameters::Adaptivity &adaptivity,
                        const unsigned int            copies,
                        Triangulation<2>             &triangulation,
                        const bool                    refine_negligible)
  {
    const unsigned int n_cells   = triangulation.n_active_cells();
    const unsigned int n_refined = n_to_refine(adaptivity, copies, n_cells);
    std::vector<float> sorted(indicators.begin(), indicators.end());
    std::sort(sorted.begin(), sorted.end(), std::greater<float>());
    const double       tie    = 1e-5 * sorted.front();
    const double       refine = refine_negligible ?
                                  sorted[n_refined - 1] - tie :
                                  std::max(sorted[n_refined - 1] - tie, 2. * tie);
    const unsigned int n_coarsened =
      part_count(adaptivity.coarsen_fraction * n_cells * copies, copies);
    const double coarsen =
      n_coarsened > 0 ? sorted[n_cells - n_coarsened] + tie : -1.;
    unsigned int index = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (indicators[index] >= refine)
          cell->set_refine_flag();
        else if (indicators[index] <= coarsen)
          cell->set_coarsen_flag();
        ++index;
      }
  }
} // namespace PlateOnHalfspace
