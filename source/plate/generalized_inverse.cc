#include <deal.II/base/exceptions.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <plate_on_halfspace/base/distributed_sparse_direct.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/plate/generalized_inverse.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace PlateOnHalfspace
{
  std::vector<Vector<double>>
  rigid_body_motions(const MindlinPlate &plate)
  {
    const auto                 &foundation_dofs = plate.get_foundation_dofs();
    const unsigned int          n_dofs = plate.get_dof_handler().n_dofs();
    std::vector<Vector<double>> motions;
    const DoFHandler<2>        &dof_handler      = plate.get_dof_handler();
    const AffineConstraints<double> &constraints = plate.get_constraints();
    const SparseMatrix<double>      &stiffness   = plate.get_stiffness_matrix();

    std::vector<Point<2>> points(n_dofs);
    DoFTools::map_dofs_to_support_points(MappingQ1<2>(), dof_handler, points);
    std::vector<unsigned int>            component(n_dofs, 0);
    std::vector<types::global_dof_index> dofs(
      dof_handler.get_fe().n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          component[dofs[i]] =
            dof_handler.get_fe().system_to_component_index(i).first;
      }

    // The candidates w = 1, (x - c_x)/L, (y - c_y)/L with beta = grad w,
    // scaled to O(1) over the plate so that the pinned rows are well
    // conditioned.
    Point<2>     centre;
    double       extent = 0;
    const double n_f    = foundation_dofs.size();
    for (const auto dof : foundation_dofs)
      centre += points[dof] / n_f;
    for (const auto dof : foundation_dofs)
      extent = std::max(extent, points[dof].distance(centre));
    extent = std::max(extent, 1e-300);

    // The body of each DoF: the cells joined by the DoFs they share (a
    // slab of a grid, whose joint faces have DoFs of their own, or a piece
    // of a Gmsh mesh). Each body moves on its own where its joints allow.
    std::vector<unsigned int> root(n_dofs);
    std::iota(root.begin(), root.end(), 0u);
    const auto find = [&](unsigned int i) {
      while (root[i] != i)
        i = root[i] = root[root[i]];
      return i;
    };
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (const auto dof : dofs)
          root[find(dof)] = find(dofs[0]);
      }
    std::vector<unsigned int> body_of(n_dofs);
    std::vector<unsigned int> body_of_root(n_dofs,
                                           numbers::invalid_unsigned_int);
    unsigned int              n_bodies = 0;
    for (unsigned int i = 0; i < n_dofs; ++i)
      {
        unsigned int &body = body_of_root[find(i)];
        if (body == numbers::invalid_unsigned_int)
          body = n_bodies++;
        body_of[i] = body;
      }

    const double stiffness_scale     = stiffness.linfty_norm();
    const auto   without_constrained = [&](Vector<double> motion) {
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (constraints.is_constrained(i))
          motion[i] = 0;
      return motion;
    };
    // How far a candidate is from a motion: the change distribute() makes
    // (the constraints do not allow it) and its image under K on the
    // unconstrained DoFs, relative to the stiffness.
    const auto defect = [&](const Vector<double> &candidate) {
      Vector<double> distributed(candidate);
      constraints.distribute(distributed);
      distributed -= candidate;
      Vector<double> image(n_dofs);
      stiffness.vmult(image, without_constrained(candidate));
      for (unsigned int i = 0; i < n_dofs; ++i)
        distributed[i] += constraints.is_constrained(i) ?
                            0. :
                            image[i] / std::max(stiffness_scale, 1e-300);
      return distributed;
    };

    std::vector<Vector<double>> failed, failed_defects;
    for (unsigned int body = 0; body < n_bodies; ++body)
      for (unsigned int mode = 0; mode < 3; ++mode)
        {
          Vector<double> motion(n_dofs);
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              if (body_of[i] != body)
                continue;
              if (component[i] == 0)
                motion[i] =
                  (mode == 0 ?
                     1. :
                     (points[i][mode - 1] - centre[mode - 1]) / extent);
              else if (mode > 0 && component[i] == mode)
                motion[i] = 1. / extent;
            }
          // Allowed by the constraints (hanging nodes and the serendipity
          // centres reproduce linear fields; supports, mirror planes and
          // tied joints may not) and in the kernel of the stiffness (the
          // constrained rows and columns of K only hold a diagonal entry;
          // joints' springs may hold a slab's motion). A motion in the
          // kernel leaves rounding, about 1e-16; a spring far softer than
          // the plate may still be far stiffer than the soil and must hold
          // its slab (doc/errors-and-limits.md, "Jointed slabs").
          Vector<double> d = defect(motion);
          if (d.linfty_norm() <= 1e-12 * motion.linfty_norm())
            motions.push_back(without_constrained(motion));
          else if (n_bodies > 1)
            {
              failed.push_back(motion);
              failed_defects.push_back(d);
            }
        }

    // Slabs joined by joints move together, or hinge about a joint held in
    // shear only: the combinations of the failed candidates without
    // defect, the kernel of their defects' Gram matrix.
    const unsigned int m = failed.size();
    if (m > 0)
      {
        LAPACKFullMatrix<double> gram(m, m);
        double                   trace = 0;
        for (unsigned int a = 0; a < m; ++a)
          for (unsigned int b = 0; b < m; ++b)
            gram(a, b) = failed_defects[a] * failed_defects[b];
        for (unsigned int a = 0; a < m; ++a)
          trace += gram(a, a);
        Vector<double>     eigenvalues;
        FullMatrix<double> eigenvectors;
        gram.compute_eigenvalues_symmetric(
          -1., std::max(1e-20, 1e-14 * trace), 0., eigenvalues, eigenvectors);
        for (unsigned int k = 0; k < eigenvalues.size(); ++k)
          {
            Vector<double> motion(n_dofs);
            for (unsigned int a = 0; a < m; ++a)
              motion.add(eigenvectors(a, k), failed[a]);
            motions.push_back(without_constrained(motion));
          }
      }
    return motions;
  }

  PlateGeneralizedInverse::PlateGeneralizedInverse(const MindlinPlate &plate)
    : plate(plate)
    , setup(plate.setup_id())
    // The plate's DoFs split over ranks; read without an MPI call, so
    // that this can run beside collective work on another thread.
    , distributed_factor(plate.locally_owned_dofs().n_elements() <
                         plate.get_dof_handler().n_dofs())
    , foundation_dofs(plate.get_foundation_dofs())
    , n_dofs(plate.get_dof_handler().n_dofs())
    , motions(rigid_body_motions(plate))
  {
    const AffineConstraints<double> &constraints = plate.get_constraints();
    const SparseMatrix<double>      &stiffness   = plate.get_stiffness_matrix();
    // Pin one foundation deflection per motion, chosen by Gaussian
    // elimination with row pivoting on R restricted to the foundation
    // nodes, so that R at the pinned nodes is well conditioned and K
    // without them is positive definite.
    const unsigned int               n_motions = motions.size();
    std::vector<std::vector<double>> rows(foundation_dofs.size(),
                                          std::vector<double>(n_motions));
    for (unsigned int i = 0; i < foundation_dofs.size(); ++i)
      for (unsigned int j = 0; j < n_motions; ++j)
        rows[i][j] = motions[j][foundation_dofs[i]];
    std::vector<bool> pinned(n_dofs, false);
    std::vector<bool> row_used(foundation_dofs.size(), false);
    for (unsigned int k = 0; k < n_motions; ++k)
      {
        unsigned int pivot   = foundation_dofs.size();
        double       largest = 0;
        for (unsigned int i = 0; i < rows.size(); ++i)
          if (!row_used[i] && std::abs(rows[i][k]) > largest)
            {
              largest = std::abs(rows[i][k]);
              pivot   = i;
            }
        AssertThrow(largest > 1e-8,
                    ExcMessage("The plate's rigid-body motions cannot be "
                               "pinned at its foundation nodes: fewer than "
                               "three non-collinear foundation nodes."));
        row_used[pivot]                = true;
        pinned[foundation_dofs[pivot]] = true;
        for (unsigned int i = 0; i < rows.size(); ++i)
          if (!row_used[i])
            {
              const double factor = rows[i][k] / rows[pivot][k];
              for (unsigned int j = k; j < n_motions; ++j)
                rows[i][j] -= factor * rows[pivot][j];
            }
      }

    for (types::global_dof_index i = 0; i < n_dofs; ++i)
      if (!constraints.is_constrained(i) && !pinned[i])
        solved_dofs.push_back(i);
    // The analysis fails only for want of memory, and says so; whether
    // the plate has a mechanism shows in factorize().
    if (distributed_factor)
      return;
    factor.analyze(stiffness, solved_dofs);
  }

  void
  PlateGeneralizedInverse::factorize()
  {
    if (factorized)
      return;
    const SparseMatrix<double> &stiffness    = plate.get_stiffness_matrix();
    const MPI_Comm              communicator = plate.get_communicator();
    try
      {
        if (distributed_factor)
          {
            std::vector<bool> solved(n_dofs, false);
            for (const auto i : solved_dofs)
              solved[i] = true;
            distributed = std::make_unique<DistributedSparseDirect>();
            distributed->factorize(stiffness,
                                   solved,
                                   plate.locally_owned_dofs(),
                                   communicator);
          }
        else
          factor.factorize(stiffness, solved_dofs);
      }
    catch (...)
      {
        AssertThrow(false,
                    ExcMessage("The plate stiffness with its rigid-body "
                               "motions pinned is not positive definite: "
                               "the plate has a mechanism of its own."));
      }
    factorized = true;
  }

  PlateGeneralizedInverse::~PlateGeneralizedInverse() = default;

  void
  PlateGeneralizedInverse::solve(const Vector<double> &f,
                                 Vector<double>       &u) const
  {
    Assert(factorized,
           ExcMessage("PlateGeneralizedInverse::factorize() first."));
    if (distributed)
      {
        distributed->solve(f, u);
        return;
      }
    std::vector<double> block(solved_dofs.size());
    for (unsigned int c = 0; c < solved_dofs.size(); ++c)
      block[c] = f[solved_dofs[c]];
    factor.solve(block, 1);
    u.reinit(n_dofs);
    for (unsigned int c = 0; c < solved_dofs.size(); ++c)
      u[solved_dofs[c]] = block[c];
  }

  void
  PlateGeneralizedInverse::foundation_flexibility(const Vector<double> &x,
                                                  Vector<double>       &y,
                                                  Vector<double>       &u) const
  {
    Vector<double> f(n_dofs);
    for (unsigned int i = 0; i < foundation_dofs.size(); ++i)
      f[foundation_dofs[i]] = x[i];
    solve(f, u);
    y.reinit(foundation_dofs.size());
    for (unsigned int i = 0; i < foundation_dofs.size(); ++i)
      y[i] = u[foundation_dofs[i]];
  }

  void
  PlateGeneralizedInverse::foundation_flexibility(const Vector<double> &x,
                                                  Vector<double>       &y) const
  {
    if (!distributed)
      {
        Vector<double> u;
        foundation_flexibility(x, y, u);
        return;
      }
    Assert(factorized,
           ExcMessage("PlateGeneralizedInverse::factorize() first."));
    Vector<double> f(n_dofs);
    for (unsigned int i = 0; i < foundation_dofs.size(); ++i)
      f[foundation_dofs[i]] = x[i];
    distributed->solve_at(f, foundation_dofs, y);
  }
} // namespace PlateOnHalfspace
