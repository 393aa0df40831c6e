#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <plate_on_halfspace/plate/foundation_space.h>

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

  std::array<Tensor<1, 2>, 9>
  q2_shape_gradients(const Point<2> &p)
  {
    const auto lagrange = [](const double s) {
      return std::array<double, 3>{
        {(1. - s) * (1. - 2. * s), 4. * s * (1. - s), s * (2. * s - 1.)}};
    };
    const auto derivative = [](const double s) {
      return std::array<double, 3>{{4. * s - 3., 4. - 8. * s, 4. * s - 1.}};
    };
    const std::array<double, 3> lx = lagrange(p[0]), ly = lagrange(p[1]),
                                dx = derivative(p[0]), dy = derivative(p[1]);
    // the (x, y) factors of each function, in q2_shape_values' order
    constexpr std::array<std::array<unsigned int, 2>, 9> factors = {{{{0, 0}},
                                                                     {{2, 0}},
                                                                     {{0, 2}},
                                                                     {{2, 2}},
                                                                     {{0, 1}},
                                                                     {{2, 1}},
                                                                     {{1, 0}},
                                                                     {{1, 2}},
                                                                     {{1, 1}}}};
    std::array<Tensor<1, 2>, 9>                          gradients;
    for (unsigned int i = 0; i < 9; ++i)
      {
        gradients[i][0] = dx[factors[i][0]] * ly[factors[i][1]];
        gradients[i][1] = lx[factors[i][0]] * dy[factors[i][1]];
      }
    return gradients;
  }

  namespace
  {
    using LocalMatrix = std::array<std::array<double, 9>, 9>;

    /** Add a cell's matrix on its nine Q2 functions through their
     *  expansion into foundation nodes. */
    void
    add_local_matrix(const FoundationSpace::Cell &cell,
                     const LocalMatrix           &local,
                     SparseMatrix<double>        &matrix)
    {
      for (unsigned int i = 0; i < 9; ++i)
        for (const auto &ti : cell.expansion[i])
          for (unsigned int j = 0; j < 9; ++j)
            for (const auto &tj : cell.expansion[j])
              matrix.add(ti.first,
                         tj.first,
                         ti.second * tj.second * local[i][j]);
    }
  } // namespace

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
          const Cell &cell = cells[c];
          LocalMatrix local{};
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
          add_local_matrix(cell, local, matrix);
        }
  }

  void
  FoundationSpace::assemble_laplace_matrix(const SparsityPattern &sparsity,
                                           SparseMatrix<double>  &matrix) const
  {
    matrix.reinit(sparsity);
    const QGauss<2> quadrature(3);
    for (const Cell &cell : cells)
      {
        LocalMatrix local{};
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            const Point<2>    &p       = quadrature.point(q);
            const Tensor<2, 2> J       = cell.geometry.jacobian(p);
            const Tensor<2, 2> to_real = transpose(invert(J));
            const double       JxW     = quadrature.weight(q) * determinant(J);
            const auto         reference = q2_shape_gradients(p);
            std::array<Tensor<1, 2>, 9> gradients;
            for (unsigned int i = 0; i < 9; ++i)
              gradients[i] = to_real * reference[i];
            for (unsigned int i = 0; i < 9; ++i)
              for (unsigned int j = 0; j < 9; ++j)
                local[i][j] += gradients[i] * gradients[j] * JxW;
          }
        add_local_matrix(cell, local, matrix);
      }
  }

  bool
  FoundationSpace::positive_pressure_transform(
    SparsityPattern      &sparsity,
    SparseMatrix<double> &transform) const
  {
    constexpr double alpha = 0.2;
    // The end points (FE_Q numbering) of the edge of local mid-side node
    // 4 + e: the faces x = 0, x = 1, y = 0, y = 1.
    constexpr std::array<std::array<unsigned int, 2>, 4> edge_ends = {
      {{{0, 2}}, {{1, 3}}, {{0, 1}}, {{2, 3}}}};
    const auto single_node = [](const std::vector<Term> &terms) {
      return terms.size() == 1 && std::abs(terms[0].second - 1.) < 1e-12 ?
               static_cast<int>(terms[0].first) :
               -1;
    };

    // A cell whose centre function is not a node of its own is serendipity
    // (the centre is constrained to the vertices and mid-sides).
    bool serendipity = false;
    for (const Cell &cell : cells)
      serendipity = serendipity || single_node(cell.expansion[8]) < 0;
    transform.clear();
    if (!serendipity)
      return false;

    // The end nodes of each mid-side node, from the cells in which the
    // mid-side and both ends are nodes of their own (on a hanging edge:
    // the coarse cell; the fine side's nodes there are constrained).
    std::vector<std::array<int, 2>> ends(n_nodes(), {{-1, -1}});
    for (const Cell &cell : cells)
      for (unsigned int e = 0; e < 4; ++e)
        {
          const int m  = single_node(cell.expansion[4 + e]);
          const int c0 = single_node(cell.expansion[edge_ends[e][0]]);
          const int c1 = single_node(cell.expansion[edge_ends[e][1]]);
          if (m >= 0 && c0 >= 0 && c1 >= 0 && ends[m][0] < 0)
            ends[m] = {{c0, c1}};
        }

    DynamicSparsityPattern dsp(n_nodes(), n_nodes());
    for (unsigned int i = 0; i < n_nodes(); ++i)
      {
        dsp.add(i, i);
        if (ends[i][0] >= 0)
          {
            dsp.add(i, ends[i][0]);
            dsp.add(i, ends[i][1]);
          }
      }
    sparsity.copy_from(dsp);
    transform.reinit(sparsity);
    // q_m = (1 - 2 alpha) qt_m + alpha (qt_c0 + qt_c1), q_c = qt_c
    for (unsigned int i = 0; i < n_nodes(); ++i)
      if (ends[i][0] >= 0)
        {
          transform.set(i, i, 1. - 2. * alpha);
          transform.add(i, ends[i][0], alpha);
          transform.add(i, ends[i][1], alpha);
        }
      else
        transform.set(i, i, 1.);
    return true;
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

  std::array<double, 9>
  FoundationSpace::Cell::local_values(const Vector<double> &nodal_values) const
  {
    std::array<double, 9> values{};
    for (unsigned int i = 0; i < 9; ++i)
      for (const auto &term : expansion[i])
        values[i] += term.second * nodal_values[term.first];
    return values;
  }

  double
  FoundationSpace::area() const
  {
    double area = 0;
    for (const auto &cell : cells)
      area += cell.geometry.area();
    return area;
  }
} // namespace PlateOnHalfspace
