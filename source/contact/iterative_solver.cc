#include <deal.II/base/exceptions.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/full_matrix.h>

#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/contact/iterative_solver.h>
#include <plate_on_halfspace/base/sparse_cholesky.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    const std::string mechanism_message =
      "The plate is a mechanism: the nodes left in contact cannot carry it "
      "(fewer than three non-collinear supporting nodes).";

    /**
     * The plate's flexibility at the foundation nodes without condensing
     * it: K^+ (a generalised inverse of the sparse stiffness on the
     * unconstrained DoFs) from one CHOLMOD factorisation with one
     * deflection per rigid-body motion pinned, and the rigid-body motions R
     * that span the kernel of K (doc/formulation.md, "Plate"; the free plate's
     * w = 1, x, y with the matching rotations, those of them that the
     * plate's constraints allow: a mirror plane's beta_n = 0 removes the
     * tilt about that plane, supports remove all).
     */
    class PlateGeneralizedInverse
    {
    public:
      explicit PlateGeneralizedInverse(const MindlinPlate &plate);

      /** u = K^+ f (full DoF vectors; zero at constrained and pinned DoFs). */
      void
      solve(const Vector<double> &f, Vector<double> &u) const;

      /** y = N K^+ N^T x: deflections at the foundation nodes from nodal
       *  forces there. */
      void
      foundation_flexibility(const Vector<double> &x, Vector<double> &y) const;

      /** The rigid-body motions in the kernel of K (full DoF vectors, zero
       *  at constrained DoFs). */
      const std::vector<Vector<double>> &
      rigid_motions() const
      {
        return motions;
      }

    private:
      const std::vector<types::global_dof_index> &foundation_dofs;
      const unsigned int                          n_dofs;
      std::vector<types::global_dof_index>        solved_dofs;
      SparseCholesky                              factor;
      std::vector<Vector<double>>                 motions;
    };

    PlateGeneralizedInverse::PlateGeneralizedInverse(const MindlinPlate &plate)
      : foundation_dofs(plate.get_foundation_dofs())
      , n_dofs(plate.get_dof_handler().n_dofs())
    {
      const DoFHandler<2>             &dof_handler = plate.get_dof_handler();
      const AffineConstraints<double> &constraints = plate.get_constraints();
      const SparseMatrix<double>      &stiffness = plate.get_stiffness_matrix();

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

      const double stiffness_scale = stiffness.linfty_norm();
      for (unsigned int mode = 0; mode < 3; ++mode)
        {
          Vector<double> motion(n_dofs);
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              if (component[i] == 0)
                motion[i] =
                  (mode == 0 ?
                     1. :
                     (points[i][mode - 1] - centre[mode - 1]) / extent);
              else if (mode > 0 && component[i] == mode)
                motion[i] = 1. / extent;
            }
          // Allowed by the constraints (hanging nodes and the serendipity
          // centres reproduce linear fields; supports and mirror planes
          // may not): distribute() from the unconstrained values gives it
          // back.
          Vector<double> distributed(motion);
          constraints.distribute(distributed);
          distributed -= motion;
          if (distributed.linfty_norm() > 1e-10 * motion.linfty_norm())
            continue;
          // In the kernel of the stiffness on the unconstrained DoFs (the
          // constrained rows and columns of K only hold a diagonal entry).
          for (unsigned int i = 0; i < n_dofs; ++i)
            if (constraints.is_constrained(i))
              motion[i] = 0;
          Vector<double> image(n_dofs);
          stiffness.vmult(image, motion);
          double largest = 0;
          for (unsigned int i = 0; i < n_dofs; ++i)
            if (!constraints.is_constrained(i))
              largest = std::max(largest, std::abs(image[i]));
          if (largest <= 1e-8 * stiffness_scale * motion.linfty_norm())
            motions.push_back(motion);
        }

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
          AssertThrow(largest > 1e-8, ExcMessage(mechanism_message));
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
      try
        {
          factor.factorize(stiffness, solved_dofs);
        }
      catch (...)
        {
          AssertThrow(false,
                      ExcMessage("The plate stiffness with its rigid-body "
                                 "motions pinned is not positive definite: "
                                 "the plate has a mechanism of its own."));
        }
    }

    void
    PlateGeneralizedInverse::solve(const Vector<double> &f,
                                   Vector<double>       &u) const
    {
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
                                                    Vector<double> &y) const
    {
      Vector<double> f(n_dofs), u;
      for (unsigned int i = 0; i < foundation_dofs.size(); ++i)
        f[foundation_dofs[i]] = x[i];
      solve(f, u);
      y.reinit(foundation_dofs.size());
      for (unsigned int i = 0; i < foundation_dofs.size(); ++i)
        y[i] = u[foundation_dofs[i]];
    }

    /**
     * The reduced problem of one contact set C (see the header): H, d, G,
     * the projector onto ker G^T and the equilibrium start, all as vectors
     * on C of the pressure coefficients (the contact basis). B = T^T M
     * (@p test_coupling) tests deflections, M T (@p force_coupling, its
     * transpose) gives the nodal forces of coefficients; both are M
     * without the positive basis.
     */
    class ContactSetProblem
    {
    public:
      ContactSetProblem(const std::vector<bool>           &in_contact,
                        const SparseMatrix<double>        &test_coupling,
                        const SparseMatrix<double>        &force_coupling,
                        const PlateGeneralizedInverse     &plate,
                        const PreconditionedFlexibility   &flexibility,
                        const Vector<double>              &tested_plate_load,
                        const std::vector<Vector<double>> &tested_motions,
                        const Vector<double>              &motion_loads);

      unsigned int
      size() const
      {
        return nodes.size();
      }

      /** y = H x and @p soil = (F x)_C, the soil's part of it. */
      void
      vmult(Vector<double>       &y,
            const Vector<double> &x,
            Vector<double>       &soil) const;

      /** y = (F̃^{-1})_CC x. */
      void
      precondition(Vector<double> &y, const Vector<double> &x) const;

      /** x -= G (G^T G)^{-1} G^T x. */
      void
      project(Vector<double> &x) const;

      /** The q of the affine space G^T q = R^T P nearest to @p q. */
      void
      make_equilibrated(Vector<double> &q) const;

      /** alpha = (G^T G)^{-1} G^T (H q - d). */
      Vector<double>
      rigid_motion_amplitudes(const Vector<double> &q) const;

      /** r = Pi (d - H q) and @p soil = (F q)_C. */
      void
      projected_residual(const Vector<double> &q,
                         Vector<double>       &r,
                         Vector<double>       &soil) const;

      /** Zero extension of a vector on C to all nodes. */
      Vector<double>
      extend_by_zero(const Vector<double> &x) const;

      /** Restriction to C of a vector on all nodes. */
      Vector<double>
      restrict_to_contact_set(const Vector<double> &x) const;

    private:
      /** G^T x. */
      Vector<double>
      constraint_values(const Vector<double> &x) const;

      const SparseMatrix<double>      &test_coupling;
      const SparseMatrix<double>      &force_coupling;
      const PlateGeneralizedInverse   &plate;
      const PreconditionedFlexibility &flexibility;
      std::vector<unsigned int>        nodes;
      Vector<double>                   d;
      std::vector<Vector<double>>      g; ///< the columns of G
      FullMatrix<double>               gram_inverse;
      Vector<double>                   motion_loads;
    };

    ContactSetProblem::ContactSetProblem(
      const std::vector<bool>           &in_contact,
      const SparseMatrix<double>        &test_coupling,
      const SparseMatrix<double>        &force_coupling,
      const PlateGeneralizedInverse     &plate,
      const PreconditionedFlexibility   &flexibility,
      const Vector<double>              &tested_plate_load,
      const std::vector<Vector<double>> &tested_motions,
      const Vector<double>              &motion_loads)
      : test_coupling(test_coupling)
      , force_coupling(force_coupling)
      , plate(plate)
      , flexibility(flexibility)
      , motion_loads(motion_loads)
    {
      for (unsigned int i = 0; i < in_contact.size(); ++i)
        if (in_contact[i])
          nodes.push_back(i);
      d = restrict_to_contact_set(tested_plate_load);
      for (const auto &column : tested_motions)
        g.push_back(restrict_to_contact_set(column));
      const unsigned int n_motions = g.size();
      FullMatrix<double> gram(n_motions, n_motions);
      for (unsigned int i = 0; i < n_motions; ++i)
        for (unsigned int j = 0; j < n_motions; ++j)
          gram(i, j) = g[i] * g[j];
      gram_inverse = gram;
      if (n_motions > 0)
        {
          // The contact set must carry the rigid motions: G^T G regular.
          // Its diagonal scaling first, so the test is scale free.
          Vector<double> scale(n_motions);
          for (unsigned int i = 0; i < n_motions; ++i)
            {
              AssertThrow(gram(i, i) > 0, ExcMessage(mechanism_message));
              scale[i] = 1. / std::sqrt(gram(i, i));
            }
          FullMatrix<double> scaled(n_motions, n_motions);
          for (unsigned int i = 0; i < n_motions; ++i)
            for (unsigned int j = 0; j < n_motions; ++j)
              scaled(i, j) = gram(i, j) * scale[i] * scale[j];
          // The determinant of this correlation matrix is 1 for orthogonal
          // columns and 0 for dependent ones (a line of nodes, one node).
          AssertThrow(scaled.determinant() > 1e-10,
                      ExcMessage(mechanism_message));
          gram_inverse.gauss_jordan();
        }
    }

    Vector<double>
    ContactSetProblem::extend_by_zero(const Vector<double> &x) const
    {
      Vector<double> all(test_coupling.m());
      for (unsigned int i = 0; i < nodes.size(); ++i)
        all[nodes[i]] = x[i];
      return all;
    }

    Vector<double>
    ContactSetProblem::restrict_to_contact_set(const Vector<double> &x) const
    {
      Vector<double> part(nodes.size());
      for (unsigned int i = 0; i < nodes.size(); ++i)
        part[i] = x[nodes[i]];
      return part;
    }

    void
    ContactSetProblem::vmult(Vector<double>       &y,
                             const Vector<double> &x,
                             Vector<double>       &soil) const
    {
      // H x = (F q)_C + (B N K^+ N^T M T q)_C with q the zero extension of
      // x (F = T^T A T, B = T^T M in the positive basis).
      const Vector<double> q = extend_by_zero(x);
      Vector<double>       settlement(q.size()), forces(q.size()), plate_w,
        plate_settlement(q.size());
      flexibility.vmult(settlement, q);
      force_coupling.vmult(forces, q);
      plate.foundation_flexibility(forces, plate_w);
      test_coupling.vmult(plate_settlement, plate_w);
      soil = restrict_to_contact_set(settlement);
      settlement += plate_settlement;
      y = restrict_to_contact_set(settlement);
    }

    void
    ContactSetProblem::precondition(Vector<double>       &y,
                                    const Vector<double> &x) const
    {
      Vector<double> q(test_coupling.m());
      flexibility.precondition(q, extend_by_zero(x));
      y = restrict_to_contact_set(q);
    }

    Vector<double>
    ContactSetProblem::constraint_values(const Vector<double> &x) const
    {
      Vector<double> values(g.size());
      for (unsigned int j = 0; j < g.size(); ++j)
        values[j] = g[j] * x;
      return values;
    }

    void
    ContactSetProblem::project(Vector<double> &x) const
    {
      if (g.empty())
        return;
      Vector<double> coefficients(g.size());
      gram_inverse.vmult(coefficients, constraint_values(x));
      for (unsigned int j = 0; j < g.size(); ++j)
        x.add(-coefficients[j], g[j]);
    }

    void
    ContactSetProblem::make_equilibrated(Vector<double> &q) const
    {
      if (g.empty())
        return;
      Vector<double> defect(motion_loads), coefficients(g.size());
      defect -= constraint_values(q);
      gram_inverse.vmult(coefficients, defect);
      for (unsigned int j = 0; j < g.size(); ++j)
        q.add(coefficients[j], g[j]);
    }

    Vector<double>
    ContactSetProblem::rigid_motion_amplitudes(const Vector<double> &q) const
    {
      Vector<double> hq(q.size()), amplitudes(g.size()), soil;
      vmult(hq, q, soil);
      hq -= d;
      if (!g.empty())
        gram_inverse.vmult(amplitudes, constraint_values(hq));
      return amplitudes;
    }

    void
    ContactSetProblem::projected_residual(const Vector<double> &q,
                                          Vector<double>       &r,
                                          Vector<double>       &soil) const
    {
      r.reinit(q.size());
      vmult(r, q, soil);
      r.sadd(-1., 1., d);
      project(r);
    }

    /** Outcome of one projected conjugate gradient solve. */
    struct ConjugateGradientResult
    {
      unsigned int iterations        = 0;
      double       relative_residual = 0;
      bool         converged         = false;
    };

    /**
     * Projected preconditioned conjugate gradients (FETI's PCPG) for
     * H q = d + G alpha on the affine space G^T q = R^T P, from @p q (made
     * equilibrated first). Every search direction lies in ker G^T, so every
     * iterate keeps equilibrium.
     *
     * The residual Pi (d - H q) is minus the projected gap on C, so it is
     * measured against the soil's settlement there, |(F q)_C|: the scale
     * of the gap in the contact conditions (evaluate_contact_conditions).
     * A residual relative to |d| would not do: for a plate much more
     * flexible than the soil, d and H q are dominated by the plate's
     * flexibility and w = K^+ (P - N^T M q) + R alpha amplifies their
     * difference, so a small |r|/|d| can hide a wrong w; with the
     * settlement scale such a problem fails with an error instead.
     * The stopping test on the recursive residual is confirmed with the
     * recomputed one (restarting from the iterate if rounding made them
     * differ).
     */
    ConjugateGradientResult
    projected_conjugate_gradients(const ContactSetProblem        &problem,
                                  const ConjugateGradientControl &control,
                                  Vector<double>                 &q)
    {
      ConjugateGradientResult result;
      const unsigned int      m = problem.size();
      Vector<double>          r(m), soil(m), z(m), p(m), hp(m), soil_p(m);
      problem.make_equilibrated(q);
      while (true)
        {
          problem.projected_residual(q, r, soil);
          result.relative_residual =
            r.l2_norm() / std::max(soil.l2_norm(), 1e-300);
          if (r.l2_norm() <= control.tolerance * soil.l2_norm() ||
              r.l2_norm() == 0.)
            {
              result.converged = true;
              return result;
            }
          if (result.iterations >= control.max_iterations)
            return result;
          // (Re)start.
          problem.precondition(z, r);
          problem.project(z);
          p         = z;
          double rz = r * z;
          while (result.iterations < control.max_iterations)
            {
              problem.vmult(hp, p, soil_p);
              const double curvature = p * hp;
              AssertThrow(curvature > 0 && rz > 0,
                          ExcMessage("The conjugate gradients on the contact "
                                     "pressures met a direction of "
                                     "non-positive curvature: the "
                                     "preconditioner or the contact problem "
                                     "is not positive definite."));
              const double step = rz / curvature;
              q.add(step, p);
              soil.add(step, soil_p);
              problem.project(hp);
              r.add(-step, hp);
              ++result.iterations;
              if (r.l2_norm() <= control.tolerance * soil.l2_norm())
                break;
              problem.precondition(z, r);
              problem.project(z);
              const double rz_next = r * z;
              p.sadd(rz_next / rz, 1., z);
              rz = rz_next;
            }
        }
    }

    double
    max_abs(const Vector<double> &v)
    {
      return v.size() > 0 ? v.linfty_norm() : 0.;
    }
  } // namespace

  DenseGalerkinFlexibility::DenseGalerkinFlexibility(
    const FoundationOperator &foundation)
    : foundation(foundation)
  {
    const auto *galerkin =
      dynamic_cast<const BoussinesqGalerkinOperator *>(&foundation);
    AssertThrow(galerkin != nullptr,
                ExcMessage("The iterative contact solver needs the symmetric "
                           "Galerkin half-space operator (Discretization/"
                           "Flexibility = galerkin); the collocation operator "
                           "stays on the direct solver."));
    cholesky_factor = galerkin->flexibility_matrix();
    try
      {
        cholesky_factor.compute_cholesky_factorization();
      }
    catch (...)
      {
        AssertThrow(false,
                    ExcMessage("The Galerkin half-space matrix A is not "
                               "positive definite; the singular quadrature "
                               "is too coarse for this mesh (raise "
                               "Discretization/Singular quadrature order)."));
      }
  }

  unsigned int
  DenseGalerkinFlexibility::size() const
  {
    return foundation.test_coupling().m();
  }

  void
  DenseGalerkinFlexibility::vmult(Vector<double>       &s,
                                  const Vector<double> &q) const
  {
    foundation.apply(q, s);
  }

  void
  DenseGalerkinFlexibility::precondition(Vector<double>       &q,
                                         const Vector<double> &s) const
  {
    q = s;
    cholesky_factor.solve(q);
  }

  IterativeContactSolver::IterativeContactSolver(
    const Parameters::Contact      &contact,
    const bool                      tensionless,
    const ConjugateGradientControl &control,
    const unsigned int              verbosity,
    std::ostream                   &log)
    : contact(contact)
    , tensionless(tensionless)
    , control(control)
    , verbosity(verbosity)
    , log(log)
  {}

  ContactState
  IterativeContactSolver::solve(const MindlinPlate              &plate,
                                const FoundationOperator        &foundation,
                                const PreconditionedFlexibility &flexibility,
                                const std::vector<bool> &initial_contact,
                                Vector<double>          *plate_solution) const
  {
    // As ContactSolver::solve: the coefficients, their nodal values, the
    // active set, and the reported contact where the pressure acts.
    ContactState state = solve_in_contact_basis(
      plate, foundation, flexibility, initial_contact, plate_solution);
    express_in_nodal_values(foundation, state);
    return state;
  }

  ContactState
  IterativeContactSolver::solve_in_contact_basis(
    const MindlinPlate              &plate,
    const FoundationOperator        &foundation,
    const PreconditionedFlexibility &flexibility,
    const std::vector<bool>         &initial_contact,
    Vector<double>                  *plate_solution) const
  {
    const FoundationSpace &space = plate.get_foundation_space();
    const unsigned int     n     = space.n_nodes();
    AssertThrow(foundation.is_symmetric() && flexibility.size() == n &&
                  foundation.test_coupling().m() == n,
                ExcMessage("The iterative contact solver needs the Galerkin "
                           "half-space operator built on the plate's "
                           "foundation nodes."));
    AssertThrow(!tensionless ||
                  contact.method == Parameters::Contact::Method::active_set,
                ExcMessage("Contact/Method: element exclusion rebuilds the "
                           "half-space operator and stays on the direct "
                           "solver; the iterative solver uses the active "
                           "set."));

    ContactState state;
    state.cell_in_foundation.assign(space.cells.size(), true);
    AssertThrow(plate.get_load_vector().linfty_norm() > 0,
                ExcMessage("Loads: the total load is zero (Loads/Uniform "
                           "pressure, Rectangular patches, Circular patches, "
                           "Point loads and Plate/Unit weight give no load); "
                           "set at least one non-zero load."));
    AssertThrow(!tensionless || plate.applied_load() > 0,
                ExcMessage("The loads lift the plate off a tensionless "
                           "foundation: their resultant is not downward."));

    // Once per cycle: K^+ and R, and the contact-set independent parts
    // B N K^+ P (for d), B N R (for G) and R^T P, with B = T^T M the test
    // coupling of the contact basis (foundation_operator.h). G is B N R
    // because equilibrium R^T (P - N^T M T q) = 0 reads (B N R)^T q = R^T P
    // (M T = B^T): the same G that the gap equation H q - G alpha = d has.
    const PlateGeneralizedInverse inverse(plate);
    const SparseMatrix<double>   &test_coupling   = foundation.test_coupling();
    const SparseMatrix<double>   &force_coupling  = foundation.force_coupling();
    const auto                   &foundation_dofs = plate.get_foundation_dofs();
    const Vector<double>         &load            = plate.get_load_vector();
    const auto                    to_foundation = [&](const Vector<double> &u) {
      Vector<double> w(n);
      for (unsigned int i = 0; i < n; ++i)
        w[i] = u[foundation_dofs[i]];
      return w;
    };
    Vector<double> plate_response, tested_plate_load(n);
    inverse.solve(load, plate_response);
    test_coupling.vmult(tested_plate_load, to_foundation(plate_response));
    const auto                 &motions = inverse.rigid_motions();
    std::vector<Vector<double>> tested_motions;
    Vector<double>              motion_loads(motions.size());
    for (unsigned int j = 0; j < motions.size(); ++j)
      {
        Vector<double> column(n);
        test_coupling.vmult(column, to_foundation(motions[j]));
        tested_motions.push_back(column);
        motion_loads[j] = motions[j] * load;
      }

    // One coupled solve on a contact set to the relative residual
    // @p tolerance, warm started from state.q.
    const auto solve_on = [&](const std::vector<bool> &in_contact,
                              const double             tolerance) {
      AssertThrow(contact_set_supports_plate(space, in_contact),
                  ExcMessage(mechanism_message));
      const ContactSetProblem  problem(in_contact,
                                      test_coupling,
                                      force_coupling,
                                      inverse,
                                      flexibility,
                                      tested_plate_load,
                                      tested_motions,
                                      motion_loads);
      Vector<double>           q             = state.q.size() == n ?
                                                 problem.restrict_to_contact_set(state.q) :
                                                 Vector<double>(problem.size());
      ConjugateGradientControl solve_control = control;
      solve_control.tolerance                = tolerance;
      const ConjugateGradientResult cg =
        projected_conjugate_gradients(problem, solve_control, q);
      ContactState::LinearSolve record;
      record.contact_iteration = state.linear_solves.size() + 1;
      record.contact_nodes     = problem.size();
      record.iterations        = cg.iterations;
      record.relative_residual = cg.relative_residual;
      state.linear_solves.push_back(record);
      if (verbosity > 0)
        log << "   contact iteration " << record.contact_iteration
            << ": conjugate gradients " << cg.iterations
            << " iterations, relative residual " << std::scientific
            << std::setprecision(1) << cg.relative_residual << std::defaultfloat
            << std::endl;
      if (!cg.converged)
        {
          std::ostringstream message;
          message
            << "The conjugate gradients on the contact pressures did "
               "not converge: relative residual "
            << std::scientific << std::setprecision(2) << cg.relative_residual
            << " after " << cg.iterations << " iterations (tolerance "
            << tolerance
            << "). A plate far more flexible than the soil (characteristic "
               "length well below the element size) needs Contact/"
               "Solver = direct.";
          AssertThrow(false, ExcMessage(message.str()));
        }

      // u = K^+ (P - N^T M T q) + R alpha, w = N u.
      state.q                    = problem.extend_by_zero(q);
      const Vector<double> alpha = problem.rigid_motion_amplitudes(q);
      Vector<double>       forces(n), f(load), u;
      force_coupling.vmult(forces, state.q);
      for (unsigned int i = 0; i < n; ++i)
        f[foundation_dofs[i]] -= forces[i];
      inverse.solve(f, u);
      for (unsigned int j = 0; j < motions.size(); ++j)
        u.add(alpha[j], motions[j]);
      if (plate_solution != nullptr)
        {
          *plate_solution = u;
          plate.get_constraints().distribute(*plate_solution);
        }
      state.w = to_foundation(u);
      for (const double v : state.w)
        AssertThrow(std::isfinite(v), ExcMessage(mechanism_message));

      // gap = F q - B w (foundation_operator.h; B w = T^T M w).
      Vector<double> plate_settlement;
      flexibility.vmult(state.gap, state.q);
      foundation.plate_settlement(state.w, plate_settlement);
      state.gap -= plate_settlement;
      state.in_contact = in_contact;
      return plate_settlement;
    };

    if (!tensionless)
      {
        const Vector<double> plate_settlement =
          solve_on(foundation.supported_nodes(), control.tolerance);
        state.iterations = 1;
        state.converged  = true;
        evaluate_contact_conditions(plate_settlement,
                                    foundation.supported_nodes(),
                                    state);
        return state;
      }

    // Primal-dual active set, the same steps as ContactSolver's, with
    // inexact solves while the set changes (as inexact Newton methods
    // do): a set that is about to change needs only the signs of q and of
    // the gap away from the contact boundary, which a loose solve gets
    // right. Once a loose solve leaves nothing to change, the same set is
    // solved to the full tolerance and checked again; only that check
    // converges.
    ActiveSetUpdate active_set(space,
                               foundation.supported_nodes(),
                               initial_contact);
    Vector<double>  plate_settlement;
    double          tolerance =
      std::max(control.tolerance, control.changing_set_tolerance);
    for (state.iterations = 1; state.iterations <= contact.max_iterations;
         ++state.iterations)
      {
        plate_settlement = solve_on(active_set.contact_set(), tolerance);
        // A sign below the solve's accuracy is rounding, not a violation.
        const double accuracy  = std::max(1e-12, tolerance);
        const double q_scale   = std::max(max_abs(state.q), 1e-300);
        const double gap_scale = std::max(max_abs(plate_settlement), 1e-300);
        if (active_set.step(state.q,
                            state.gap,
                            accuracy * q_scale,
                            accuracy * gap_scale,
                            state.iterations,
                            verbosity,
                            log))
          {
            if (tolerance <= control.tolerance)
              {
                state.converged = true;
                break;
              }
            tolerance = control.tolerance;
          }
      }
    state.iterations = std::min(state.iterations, contact.max_iterations);
    evaluate_contact_conditions(plate_settlement,
                                foundation.supported_nodes(),
                                state);
    return state;
  }
} // namespace PlateOnHalfspace
