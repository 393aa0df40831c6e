#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <plate_on_halfspace/foundation_space.h>

#include <algorithm>

namespace PlateOnHalfspace
{
  std::array<double, 9>
  q2_shape_values(const Point<2> &p)
  {
    // 1D Lagrange polynomials on the nodes 0, 1/2, 1.
    const auto lagrange = [](const double s) {
      return std::array<double, 3>{
        {(1. - s) * (1. - 2. * s), 4. * s * (1. - s), s * (2. * s - 1.)}};
    };
    const std::array<double, 3> lx = lagrange(p[0]), ly = lagrange(p[1]);
    // FE_Q<2>(2) numbering: vertices, then the midpoints of the faces x=0,
    // x=1, y=0, y=1, then the centre.
    return {{lx[0] * ly[0],
             lx[2] * ly[0],
             lx[0] * ly[2],
             lx[2] * ly[2],
             lx[0] * ly[1],
             lx[2] * ly[1],
             lx[1] * ly[0],
             lx[1] * ly[2],
             lx[1] * ly[1]}};
  }

  std::vector<FoundationSpace::Cell>
  FoundationSpace::mirror_image_cells() const
  {
    // Local numbering of the reflections of the reference square: vertices
    // 0-3 and FE_Q(2)'s face midpoints 4-7 (faces x=0, x=1, y=0, y=1) and
    // centre 8. xi -> 1 - xi swaps 0<->1, 2<->3, 4<->5; eta -> 1 - eta
    // swaps 0<->2, 1<->3, 6<->7.
    constexpr std::array<unsigned int, 9> flip_x = {
      {1, 0, 3, 2, 5, 4, 6, 7, 8}};
    constexpr std::array<unsigned int, 9> flip_y = {
      {2, 3, 0, 1, 4, 5, 7, 6, 8}};
    std::vector<Cell> images;
    for (const auto &signs : symmetry.reflections())
      for (const Cell &cell : cells)
        {
          std::array<unsigned int, 9> from;
          for (unsigned int i = 0; i < 9; ++i)
            {
              from[i] = i;
              if (signs[0] < 0)
                from[i] = flip_x[from[i]];
              if (signs[1] < 0)
                from[i] = flip_y[from[i]];
            }
          // image vertex i = R (vertex from[i]), image function i = function
          // from[i]: psi'(xi) = psi(sigma xi) and x'(xi) = R x(sigma xi).
          std::array<Point<2>, 4> vertices;
          for (unsigned int v = 0; v < 4; ++v)
            {
              const Point<2> &p = cell.geometry.get_vertices()[from[v]];
              vertices[v]       = Point<2>(signs[0] * p[0], signs[1] * p[1]);
            }
          Cell image{BilinearQuadrilateral(vertices), {}};
          for (unsigned int i = 0; i < 9; ++i)
            image.expansion[i] = cell.expansion[from[i]];
          images.push_back(image);
        }
    return images;
  }

  void
  FoundationSpace::assemble_mass_matrix(
    const std::vector<bool> &cell_in_foundation,
    SparsityPattern         &sparsity,
    SparseMatrix<double>    &matrix) const
  {
    const auto included = [&](const unsigned int c) {
      return cell_in_foundation.empty() || cell_in_foundation[c];
    };

    DynamicSparsityPattern dsp(n_nodes(), n_nodes());
    for (unsigned int c = 0; c < cells.size(); ++c)
      if (included(c))
        for (const auto &terms_i : cells[c].expansion)
          for (const auto &ti : terms_i)
            for (const auto &terms_j : cells[c].expansion)
              for (const auto &tj : terms_j)
                dsp.add(ti.first, tj.first);
    // Every node keeps its diagonal, so that excluded nodes stay valid rows.
    for (unsigned int i = 0; i < n_nodes(); ++i)
      dsp.add(i, i);
    matrix.clear();
    sparsity.copy_from(dsp);
    matrix.reinit(sparsity);

    const QGauss<2> quadrature(3);
    for (unsigned int c = 0; c < cells.size(); ++c)
      if (included(c))
        {
          const Cell &cell        = cells[c];
          double      local[9][9] = {};
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Point<2> &p   = quadrature.point(q);
              const auto      phi = q2_shape_values(p);
              const double    JxW =
                quadrature.weight(q) * cell.geometry.jacobian_determinant(p);
              for (unsigned int i = 0; i < 9; ++i)
                for (unsigned int j = 0; j < 9; ++j)
                  local[i][j] += phi[i] * phi[j] * JxW;
            }
          for (unsigned int i = 0; i < 9; ++i)
            for (const auto &ti : cell.expansion[i])
              for (unsigned int j = 0; j < 9; ++j)
                for (const auto &tj : cell.expansion[j])
                  matrix.add(ti.first,
                             tj.first,
                             ti.second * tj.second * local[i][j]);
        }
  }

  std::vector<unsigned int>
  FoundationSpace::Cell::nodes() const
  {
    std::vector<unsigned int> result;
    for (const auto &terms : expansion)
      for (const auto &t : terms)
        if (std::find(result.begin(), result.end(), t.first) == result.end())
          result.push_back(t.first);
    return result;
  }
} // namespace PlateOnHalfspace
