// Foundation-space cells for the quadrature tests, whose integrals are
// checked per cell pair without a mesh.
#ifndef plate_on_halfspace_tests_foundation_cells_h
#define plate_on_halfspace_tests_foundation_cells_h

#include <plate_on_halfspace/plate/foundation_space.h>

#include <array>

/** A cell whose 9 local functions are the nodes first, first + 1, ... */
inline PlateOnHalfspace::FoundationSpace::Cell
cell_with_own_nodes(const std::array<dealii::Point<2>, 4> &vertices,
                    const unsigned int                     first)
{
  PlateOnHalfspace::FoundationSpace::Cell cell{
    PlateOnHalfspace::BilinearQuadrilateral(vertices), {}};
  for (unsigned int i = 0; i < 9; ++i)
    cell.expansion[i] = {{first + i, 1.}};
  return cell;
}

#endif
