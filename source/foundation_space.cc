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
