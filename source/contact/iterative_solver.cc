#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <plate_on_halfspace/base/interruption.h>
#include <plate_on_halfspace/base/single_threaded_blas.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/base/tasks.h>
#include <plate_on_halfspace/contact/active_set.h>
#include <plate_on_halfspace/contact/iterative_solver.h>
#include <plate_on_halfspace/contact/pressure_preconditioner.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/plate/generalized_inverse.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    /** OpenBLAS on one thread for a solve on @p foundation, except where
     *  its product gains from the threads: nullptr then. */
    std::unique_ptr<SingleThreadedBlas>
    blas_on_one_thread(const FoundationOperator &foundation)
    {
      if (foundation.product_uses_blas_threads())
        return nullptr;
      return std::make_unique<SingleThreadedBlas>();
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
                        const FoundationOperator          &foundation,
                        const PressurePreconditioner      &preconditioner,
                        const Vector<double>              &tested_plate_load,
                        const std::vector<Vector<double>> &tested_motions,
                        const Vector<double>              &motion_loads);

      unsigned int
      size() const
      {
        return nodes.size();
      }

      /** The columns of G: the rigid motions the set must hold. */
      unsigned int
      n_motions() const
      {
        return g.size();
      }

      /** y = H x and @p soil = (F x)_C, the soil's part of it. */
      void
      vmult(Vector<double>       &y,
            const Vector<double> &x,
            Vector<double>       &soil) const;

      /**
       * The same product on every node, not only on C: y = (F + B N K^+
       * N^T M T) q and @p soil = F q with q the zero extension of @p x.
       * Off C, y - d - G alpha is the gap of the nodes out of contact.
       * With @p plate_response, the plate's whole response K^+ N^T M T q
       * to the pressures as well.
       */
      void
      vmult_on_all_nodes(Vector<double>       &y,
                         const Vector<double> &x,
                         Vector<double>       &soil,
                         Vector<double>       *plate_response = nullptr) const;

      /** y = (P^{-1})_CC x (pressure_preconditioner.h). */
      void
      precondition(Vector<double> &y, const Vector<double> &x) const;

      /** x -= G (G^T G)^{-1} G^T x. */
      void
      project(Vector<double> &x) const;

      /** The q of the affine space G^T q = R^T P nearest to @p q. */
      void
      make_equilibrated(Vector<double> &q) const;

      /** alpha = (G^T G)^{-1} G^T (H q - d), given @p hq = H q. */
      Vector<double>
      rigid_motion_amplitudes(const Vector<double> &hq) const;

      /**
       * r = Pi (d - H q) and @p soil = (F q)_C; @p product_on_all_nodes,
       * @p soil_on_all_nodes and @p plate_response receive
       * vmult_on_all_nodes() of q.
       */
      void
      projected_residual(const Vector<double> &q,
                         Vector<double>       &r,
                         Vector<double>       &soil,
                         Vector<double>       &product_on_all_nodes,
                         Vector<double>       &soil_on_all_nodes,
                         Vector<double>       &plate_response) const;

      /** Zero extension of a vector on C to all nodes. */
      Vector<double>
      extend_by_zero(const Vector<double> &x) const;

      /** Restriction to C of a vector on all nodes. */
      Vector<double>
      restrict_to_contact_set(const Vector<double> &x) const;

      /** SoilModel::definiteness_advice() of the foundation's soil. */
      std::string
      definiteness_advice() const
      {
        return foundation.soil().definiteness_advice();
      }

    private:
      /** G^T x. */
      Vector<double>
      constraint_values(const Vector<double> &x) const;

      const SparseMatrix<double>    &test_coupling;
      const SparseMatrix<double>    &force_coupling;
      const PlateGeneralizedInverse &plate;
      const FoundationOperator      &foundation;
      const PressurePreconditioner  &preconditioner;
      std::vector<unsigned int>      nodes;
      Vector<double>                 d;
      std::vector<Vector<double>>    g; ///< the columns of G
      FullMatrix<double>             gram_inverse;
      Vector<double>                 motion_loads;
    };

    ContactSetProblem::ContactSetProblem(
      const std::vector<bool>           &in_contact,
      const SparseMatrix<double>        &test_coupling,
      const SparseMatrix<double>        &force_coupling,
      const PlateGeneralizedInverse     &plate,
      const FoundationOperator          &foundation,
      const PressurePreconditioner      &preconditioner,
      const Vector<double>              &tested_plate_load,
      const std::vector<Vector<double>> &tested_motions,
      const Vector<double>              &motion_loads)
      : test_coupling(test_coupling)
      , force_coupling(force_coupling)
      , plate(plate)
      , foundation(foundation)
      , preconditioner(preconditioner)
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
              AssertThrow(gram(i, i) > 0,
                          ExcMessage(plate_is_mechanism_message()));
              scale[i] = 1. / std::sqrt(gram(i, i));
            }
          LAPACKFullMatrix<double> scaled(n_motions, n_motions);
          for (unsigned int i = 0; i < n_motions; ++i)
            for (unsigned int j = 0; j < n_motions; ++j)
              scaled(i, j) = gram(i, j) * scale[i] * scale[j];
          // The smallest eigenvalue of this correlation matrix is 1 for
          // orthogonal columns and 0 for dependent ones (a line of nodes,
          // one node). Its determinant would shrink with the number of
          // slabs of a grid with free joints (each slab's three motions
          // are correlated) and call a carried grid a mechanism.
          Vector<double>     below;
          FullMatrix<double> directions;
          scaled.compute_eigenvalues_symmetric(
            -1., 1e-10, 0., below, directions);
          AssertThrow(below.size() == 0,
                      ExcMessage(plate_is_mechanism_message()));
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
    ContactSetProblem::vmult_on_all_nodes(Vector<double>       &y,
                                          const Vector<double> &x,
                                          Vector<double>       &soil,
                                          Vector<double> *plate_response) const
    {
      // F q + B N K^+ N^T M T q with q the zero extension of x (F = T^T A
      // T, B = T^T M in the positive basis).
      const Vector<double> q = extend_by_zero(x);
      Vector<double> forces(q.size()), plate_w, plate_settlement(q.size());
      soil.reinit(q.size());
      const auto plate_part = [&]() {
        force_coupling.vmult(forces, q);
        if (plate_response)
          plate.foundation_flexibility(forces, plate_w, *plate_response);
        else
          plate.foundation_flexibility(forces, plate_w);
        test_coupling.vmult(plate_settlement, plate_w);
      };
      // The soil's product and the plate's triangular solves are
      // independent: on one process they run side by side, each on its
      // own data, so the sum is the same bits either way
      // (doc/performance.md, "BLAS threads in the contact solve"). Only
      // with OpenBLAS on one thread: a BLAS guard inside the product
      // (hmat-oss's) then changes nothing while the plate's solves are in
      // the BLAS. Not where the product wants the BLAS threads, and not on
      // several processes, where each half may be collective.
      if (n_ranks(MPI_COMM_WORLD) == 1 &&
          !foundation.product_uses_blas_threads() &&
          SingleThreadedBlas::in_effect())
        {
          run_tasks(2, [&](const unsigned int part) {
            if (part == 0)
              foundation.apply(q, soil);
            else
              plate_part();
          });
        }
      else
        {
          foundation.apply(q, soil);
          plate_part();
        }
      y = soil;
      y += plate_settlement;
    }

    void
    ContactSetProblem::vmult(Vector<double>       &y,
                             const Vector<double> &x,
                             Vector<double>       &soil) const
    {
      Vector<double> y_all, soil_all;
      vmult_on_all_nodes(y_all, x, soil_all);
      soil = restrict_to_contact_set(soil_all);
      y    = restrict_to_contact_set(y_all);
    }

    void
    ContactSetProblem::precondition(Vector<double>       &y,
                                    const Vector<double> &x) const
    {
      Vector<double> q(test_coupling.m());
      preconditioner.vmult(q, extend_by_zero(x));
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
    ContactSetProblem::rigid_motion_amplitudes(const Vector<double> &hq) const
    {
      Vector<double> defect(hq), amplitudes(g.size());
      defect -= d;
      if (!g.empty())
        gram_inverse.vmult(amplitudes, constraint_values(defect));
      return amplitudes;
    }

    void
    ContactSetProblem::projected_residual(const Vector<double> &q,
                                          Vector<double>       &r,
                                          Vector<double>       &soil,
                                          Vector<double> &product_on_all_nodes,
                                          Vector<double> &soil_on_all_nodes,
                                          Vector<double> &plate_response) const
    {
      vmult_on_all_nodes(product_on_all_nodes,
                         q,
                         soil_on_all_nodes,
                         &plate_response);
      soil = restrict_to_contact_set(soil_on_all_nodes);
      r    = restrict_to_contact_set(product_on_all_nodes);
      r.sadd(-1., 1., d);
      project(r);
    }

    /** The rounding floor of the residual in units of eps |H q|: 50 was
     *  measured on a plate with l = h/10 (doc/performance.md,
     *  "Preconditioning the contact pressures"). */
    constexpr double rounding_floor_factor = 100;
    /** Growth of the residual over the start's at which a deflated solve
     *  is taken to diverge (projected_conjugate_gradients()). */
    constexpr double divergence_factor = 1e4;
    /** Largest Deflation::disagreement() of a deflated solve: rounding
     *  leaves about 1e-14 (measured up to 7e-14 on flexible plates). */
    constexpr double largest_disagreement = 1e-11;
    /** Relative accuracy of solve_adjoint(), unless the fields' is
     *  coarser: the goal estimate moves by about 1e-4 of itself
     *  (doc/formulation.md, "Goal-oriented refinement"). */
    constexpr double adjoint_accuracy = 1e-6;

    /**
     * The space spanned by conjugate directions W of an earlier solve on
     * the same contact set, with their products H W: deflated conjugate
     * gradients (doc/formulation.md, "Recycled directions") start from the
     * H-projection of the residual onto W and keep every direction
     * H-orthogonal to W, in the well-conditioned part of the Gram matrix
     * W^T H W. Inactive if no part of it is.
     */
    class Deflation
    {
    public:
      Deflation(const std::vector<Vector<double>> &w,
                const std::vector<Vector<double>> &hw)
        : w(w)
        , hw(hw)
      {
        const unsigned int k = w.size();
        if (k == 0)
          return;
        LAPACKFullMatrix<double> gram(k, k);
        double                   trace = 0;
        for (unsigned int i = 0; i < k; ++i)
          for (unsigned int j = 0; j <= i; ++j)
            {
              const double g = 0.5 * (w[i] * hw[j] + w[j] * hw[i]);
              gram(i, j)     = g;
              gram(j, i)     = g;
              trace += i == j ? g : 0.;
            }
        if (!std::isfinite(trace) || !(trace > 0))
          return;
        // W^T H W = V Lambda V^T; the eigenvectors with eigenvalues below
        // 1e-6 of the trace are dropped: directions that rounding made
        // nearly dependent (a long solve's lost conjugacy), or that H
        // does not curve.
        gram.set_property(LAPACKSupport::symmetric);
        try
          {
            gram.compute_eigenvalues_symmetric(
              1e-6 * trace, 2 * trace, 0., eigenvalues, eigenvectors);
          }
        catch (...)
          {
            eigenvalues.reinit(0);
          }
        if (!std::all_of(eigenvalues.begin(),
                         eigenvalues.end(),
                         [](const double lambda) {
                           return std::isfinite(lambda);
                         }))
          eigenvalues.reinit(0);
      }

      bool
      active() const
      {
        return eigenvalues.size() > 0;
      }

      /**
       * How far the recorded products disagree with H on a direction p
       * and its product H p (projected): H is symmetric, so w_i . H p =
       * (H w_i) . p exactly; the largest difference over the directions,
       * relative to sqrt(p . H p) (each w_i has w_i . H w_i = 1).
       */
      double
      disagreement(const Vector<double> &p,
                   const Vector<double> &hp,
                   const double          curvature) const
      {
        double largest = 0;
        for (unsigned int i = 0; i < w.size(); ++i)
          largest = std::max(largest, std::abs(w[i] * hp - hw[i] * p));
        return largest / std::sqrt(curvature);
      }

      /** The recycled directions kept: the eigenvectors not dropped. */
      unsigned int
      rank() const
      {
        return eigenvalues.size();
      }

      /** x += sign W V Lambda^{-1} V^T V_b^T v, V_b = W or H W. */
      void
      add_projection(Vector<double>                    &x,
                     const std::vector<Vector<double>> &v_basis,
                     const Vector<double>              &v,
                     const double                       sign) const
      {
        Vector<double> wv(w.size()), c(eigenvalues.size()), mu(w.size());
        for (unsigned int i = 0; i < w.size(); ++i)
          wv[i] = v_basis[i] * v;
        eigenvectors.Tvmult(c, wv);
        for (unsigned int j = 0; j < c.size(); ++j)
          c[j] /= eigenvalues[j];
        eigenvectors.vmult(mu, c);
        for (unsigned int i = 0; i < w.size(); ++i)
          x.add(sign * mu[i], w[i]);
      }

      /** q += W (W^T H W)^+ W^T r: the residual r becomes orthogonal
       *  to W. */
      void
      correct(Vector<double> &q, const Vector<double> &r) const
      {
        add_projection(q, w, r, 1.);
      }

      /** d -= W (W^T H W)^+ (H W)^T z, with @p d = z on entry: the part
       *  of z H-orthogonal to W. */
      void
      make_conjugate(Vector<double> &d, const Vector<double> &z) const
      {
        add_projection(d, hw, z, -1.);
      }

    private:
      const std::vector<Vector<double>> &w, &hw;
      Vector<double>                     eigenvalues;
      FullMatrix<double>                 eigenvectors;
    };

    /**
     * Where projected_conjugate_gradients() puts the directions of its
     * solve (each scaled to p^T H p = 1, with H p projected), at most
     * @p room of them.
     */
    struct DirectionSink
    {
      std::vector<Vector<double>> p, hp;
      unsigned int                room = 0;
    };

    /** Outcome of one projected conjugate gradient solve. */
    struct ConjugateGradientResult
    {
      unsigned int iterations        = 0;
      double       relative_residual = 0;
      bool         converged         = false;
      /** The residual that rounding allows, relative like
       *  relative_residual (see projected_conjugate_gradients()). */
      double rounding_floor = 0;
      /** The recycled directions were dropped during the solve (a
       *  direction of non-positive curvature with them). */
      bool deflation_abandoned = false;
      /** vmult_on_all_nodes() of the final q: H q, F q and the plate's
       *  response K^+ N^T M T q. */
      Vector<double> product_on_all_nodes, soil_on_all_nodes, plate_response;
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
                                  Vector<double>                 &q,
                                  const Deflation                &deflation,
                                  DirectionSink                  &sink)
    {
      ConjugateGradientResult result;
      const unsigned int      m = problem.size();
      Vector<double>          r(m), soil(m), z(m), p(m), hp(m), soil_p(m), d(m);
      problem.make_equilibrated(q);
      unsigned int restarts_after_convergence = 0;
      bool         deflate = deflation.active(), corrected = false;
      // the start, to return to if the recycled directions make the
      // iteration diverge
      const Vector<double> start          = deflate ? q : Vector<double>();
      double               start_residual = 0;
      unsigned int         limit          = control.max_iterations;
      while (true)
        {
          problem.projected_residual(q,
                                     r,
                                     soil,
                                     result.product_on_all_nodes,
                                     result.soil_on_all_nodes,
                                     result.plate_response);
          result.relative_residual =
            r.l2_norm() / std::max(soil.l2_norm(), 1e-300);
          // A set of no more nodes than the rigid motions it holds (three
          // for a free plate; G^T G is regular on it) leaves ker G^T = {0}:
          // equilibrium alone fixes q, and what is left of the residual is
          // rounding, with no direction to search (a right-hand side with no
          // resultant, as an adjoint's, leaves q = 0 and no soil scale).
          if (m <= problem.n_motions())
            {
              result.relative_residual = 0;
              result.converged         = true;
              return result;
            }
          // The residual is a difference of deflections of size |H q|, so
          // rounding bounds it below by some eps |H q|: where the plate's
          // deflections dwarf the soil's settlement (a plate far more
          // flexible than the soil) that floor lies above the tolerance,
          // and reaching it is convergence (doc/formulation.md,
          // "Preconditioning the contact pressures").
          result.rounding_floor =
            rounding_floor_factor * std::numeric_limits<double>::epsilon() *
            problem.restrict_to_contact_set(result.product_on_all_nodes)
              .l2_norm() /
            std::max(soil.l2_norm(), 1e-300);
          if (r.l2_norm() <= control.tolerance * soil.l2_norm() ||
              r.l2_norm() == 0.)
            {
              result.converged = true;
              return result;
            }
          // Only once restarts have shown that the recursive residual's
          // convergence does not carry over to the recomputed one.
          if (restarts_after_convergence >= 2 &&
              result.relative_residual <= result.rounding_floor)
            {
              result.converged =
                result.relative_residual <= accepted_rounding_floor;
              return result;
            }
          if (result.iterations >= limit)
            return result;
          // The start's component in the recycled directions, solved
          // exactly; its residual is recomputed (once per solve).
          if (deflate && !corrected)
            {
              start_residual = r.l2_norm();
              deflation.correct(q, r);
              corrected = true;
              continue;
            }
          // (Re)start.
          problem.precondition(z, r);
          problem.project(z);
          p = z;
          if (deflate)
            deflation.make_conjugate(p, z);
          double rz = r * z;
          while (result.iterations < limit)
            {
              // a safe point, reached by every rank alike
              // (base/interruption.h)
              Interruption::check();
              problem.vmult(hp, p, soil_p);
              const double curvature = p * hp;
              // A residual already at the rounding floor has no digits
              // left for the curvature: recompute it instead (as a restart
              // after convergence, since the recursive residual has gone as
              // far as rounding lets it).
              if (!(curvature > 0 && rz > 0) &&
                  r.l2_norm() <= result.rounding_floor * soil.l2_norm())
                {
                  ++restarts_after_convergence;
                  break;
                }
              // The recycled directions, not H, may have lost their
              // conjugacy to rounding: go on without them.
              if (!(curvature > 0 && rz > 0) && deflate)
                {
                  deflate                    = false;
                  result.deflation_abandoned = true;
                  break;
                }
              if (!(curvature > 0 && rz > 0))
                throw ConjugateGradientsFailed(
                  "The conjugate gradients on the contact pressures met a "
                  "direction of non-positive curvature: in floating point "
                  "the contact problem is not positive definite. The "
                  "stiffnesses of the scene differ by too many orders of "
                  "magnitude: compare Foundation/Modulus of subgrade "
                  "reaction (dense liquid) or Foundation/Young's modulus "
                  "with Plate/Young's modulus and Plate/Thickness, and "
                  "Joints/Shear stiffness, Dowel modulus and Dowel support "
                  "modulus with the slabs; for a joint far stiffer than the "
                  "slabs use Joints/Load transfer = tied. " +
                  problem.definiteness_advice());
              const double step = rz / curvature;
              q.add(step, p);
              soil.add(step, soil_p);
              problem.project(hp);
              r.add(-step, hp);
              ++result.iterations;
              // The recorded products must agree with H on the directions
              // the iteration reaches: where rounding took their digits,
              // the disagreement grows from about 1e-14 until the deflated
              // iteration diverges. Exact conjugate gradients also bound
              // the residual by sqrt(cond H) times the start's. Past either
              // limit: start again from the start, without W, with a whole
              // budget of iterations.
              if (deflate &&
                  (!(deflation.disagreement(p, hp, curvature) <=
                     largest_disagreement) ||
                   !(r.l2_norm() <= divergence_factor * start_residual)))
                {
                  deflate                    = false;
                  result.deflation_abandoned = true;
                  q                          = start;
                  sink.p.clear();
                  sink.hp.clear();
                  limit = result.iterations + control.max_iterations;
                  break;
                }
              if (sink.p.size() < sink.room)
                {
                  const double scale = 1. / std::sqrt(curvature);
                  sink.p.emplace_back(p);
                  sink.p.back() *= scale;
                  sink.hp.emplace_back(hp);
                  sink.hp.back() *= scale;
                }
              if (r.l2_norm() <= control.tolerance * soil.l2_norm())
                {
                  ++restarts_after_convergence;
                  break;
                }
              problem.precondition(z, r);
              problem.project(z);
              const double rz_next = r * z;
              d                    = z;
              if (deflate)
                deflation.make_conjugate(d, z);
              p.sadd(rz_next / rz, 1., d);
              rz = rz_next;
            }
        }
    }
  } // namespace

  struct IterativeContactSolver::RecordedDirections
  {
    std::vector<bool>           contact_set;
    std::vector<Vector<double>> p, hp;
    /** The largest rounding floor of the solves that made p and hp. */
    double floor = 0;
    /** A deflated solve on this set gave the record up. */
    bool refused = false;

    /** Drops the directions (the set and refused stay). */
    void
    forget()
    {
      p.clear();
      hp.clear();
      floor = 0;
    }
  };

  IterativeContactSolver::IterativeContactSolver(
    const Parameters::Contact      &contact,
    const bool                      tensionless,
    const ConjugateGradientControl &control,
    const unsigned int              verbosity,
    std::ostream                   &log)
    : ContactIteration(contact, tensionless, verbosity, log)
    , control(control)
  {
    AssertThrow(!tensionless ||
                  contact.method == Parameters::Contact::Method::active_set,
                ExcMessage("Contact/Method: element exclusion rebuilds the "
                           "half-space operator and stays on the direct "
                           "solver; the iterative solver uses the active "
                           "set."));
  }

  IterativeContactSolver::~IterativeContactSolver() = default;

  void
  IterativeContactSolver::use_plate_inverse(
    std::unique_ptr<PlateGeneralizedInverse> analysed)
  {
    given_inverse = std::move(analysed);
  }

  void
  IterativeContactSolver::prepare(MindlinPlate       &plate,
                                  FoundationOperator &foundation,
                                  ContactState       &state)
  {
    // a new plate, operator or load: before the factorisations, whose
    // memory the record would add to
    recorded             = std::make_unique<RecordedDirections>();
    const unsigned int n = plate.get_foundation_space().n_nodes();
    AssertThrow(foundation.is_symmetric() && foundation.n_nodes() == n,
                ExcMessage("The iterative contact solver needs the symmetric "
                           "half-space operator (Discretization/Flexibility "
                           "= galerkin) built on the plate's foundation "
                           "nodes; the collocation operator stays on the "
                           "direct solver."));
    // Once per cycle: K^+ and R, and the contact-set independent parts
    // B N K^+ P (for d), B N R (for G) and R^T P, with B = T^T M the test
    // coupling of the contact basis. G is B N R because equilibrium
    // R^T (P - N^T M T q) = 0 reads (B N R)^T q = R^T P (M T = B^T): the
    // same G that the gap equation H q - G alpha = d has.
    // K^+ comes before the preconditioner: the transient copies of K in
    // its factorisation then do not meet the soil inverse's factors, which
    // lowers the run's peak memory, and the soil inverse's check of the
    // memory left counts K^+ (doc/performance.md, "Where the resident
    // memory goes").
    AssertThrow(!given_inverse || given_inverse->is_of(plate),
                ExcInternalError("IterativeContactSolver: the plate inverse "
                                 "given is of another plate."));
    // K^+ holds while the plate keeps its setup: a load sweep's later
    // solves reuse it.
    if (given_inverse)
      inverse = std::move(given_inverse);
    else if (!inverse || !inverse->is_of(plate))
      inverse = std::make_unique<PlateGeneralizedInverse>(plate);
    inverse->factorize();
    const SparseMatrix<double> &test_coupling = foundation.test_coupling();
    const auto                 &motions       = inverse->rigid_motions();
    tested_motions.clear();
    for (unsigned int j = 0; j < motions.size(); ++j)
      {
        Vector<double> column(n);
        test_coupling.vmult(column, plate.restrict_to_foundation(motions[j]));
        tested_motions.push_back(column);
      }
    {
      using Choice  = Parameters::Contact::Preconditioner;
      Choice choice = control.preconditioner;
      if (choice == Choice::automatic)
        {
          const PreconditionerEstimate estimate =
            estimate_preconditioners(plate, foundation.soil());
          choice = estimate.plate_on_springs < estimate.soil_inverse ?
                     Choice::plate_on_springs :
                     Choice::soil_inverse;
          if (verbosity > 0)
            log << "   pressure preconditioner: estimated condition "
                << std::setprecision(2) << estimate.soil_inverse
                << " (soil inverse), " << estimate.plate_on_springs
                << " (plate on springs)" << std::setprecision(6) << std::endl;
        }
      // Only the plate on springs reads K after K^+; without it K leaves
      // the solve's memory before the soil inverse's factors come.
      if (choice == Choice::soil_inverse)
        plate.release_stiffness();
      preconditioner =
        choice == Choice::plate_on_springs ?
          make_plate_on_springs_preconditioner(plate, foundation) :
          make_soil_inverse_preconditioner(foundation);
      state.factorization_time_s = preconditioner->factorization_time();
      state.factor_memory_bytes  = preconditioner->memory_consumption();
      if (verbosity > 0)
        log << "   pressure preconditioner: " << preconditioner->name()
            << std::endl;
    }
  }

  void
  IterativeContactSolver::prepare_load(const Vector<double> &load)
  {
    // B N K^+ P and R^T P: the parts of the contact-set problem that
    // depend on the load.
    inverse->solve(load, plate_load_response);
    tested_plate_load.reinit(foundation->n_nodes());
    foundation->test_coupling().vmult(
      tested_plate_load, plate->restrict_to_foundation(plate_load_response));
    const auto &motions = inverse->rigid_motions();
    motion_loads.reinit(motions.size());
    for (unsigned int j = 0; j < motions.size(); ++j)
      motion_loads[j] = motions[j] * load;
  }

  std::vector<bool>
  IterativeContactSolver::predict_contact_set(const ContactSeed &seed,
                                              ContactState      &state)
  {
    if (!control.constrained_start)
      return seed.contact_set;
    const FoundationSpace   &space     = plate->get_foundation_space();
    const std::vector<bool> &supported = foundation->supported_nodes();
    const unsigned int       n         = supported.size();
    std::vector<bool>        contact_set =
      initial_contact_set(space, supported, seed.contact_set);
    if (!contact_set_supports_plate(space, contact_set))
      return seed.contact_set;
    const double tolerance    = changing_set_tolerance();
    const auto   make_problem = [&](const std::vector<bool> &set) {
      return std::make_unique<ContactSetProblem>(set,
                                                 foundation->test_coupling(),
                                                 foundation->force_coupling(),
                                                 *inverse,
                                                 *foundation,
                                                 *preconditioner,
                                                 tested_plate_load,
                                                 tested_motions,
                                                 motion_loads);
    };

    // q on the set (equilibrated), and H q and F q on every node, kept
    // up to date by the steps and recomputed when the set loses nodes.
    // The preconditioner of the first set serves the whole estimate.
    preconditioner->use_contact_set(contact_set);
    state.factorization_time_s = preconditioner->factorization_time();
    state.factor_memory_bytes  = preconditioner->memory_consumption();
    // after the preconditioner's factorisation, which gains from the
    // BLAS threads
    const auto single_threaded_blas = blas_on_one_thread(*foundation);
    std::unique_ptr<ContactSetProblem> problem = make_problem(contact_set);
    Vector<double>                     q(problem->size()), y_all, soil_all;
    if (seed.pressure.size() == n)
      {
        // the seed's pressure (a coarser cycle's, interpolated) without its
        // tension: most of the pressure field is already there
        Vector<double> coefficients;
        foundation->pressure_coefficients(seed.pressure, coefficients);
        for (double &c : coefficients)
          c = std::max(c, 0.);
        q = problem->restrict_to_contact_set(coefficients);
      }
    problem->make_equilibrated(q);
    problem->vmult_on_all_nodes(y_all, q, soil_all);

    unsigned int   iterations = 0, set_changes = 0;
    bool           restart = true, converged = false;
    double         rz = 0;
    Vector<double> r, z, p, hp, hp_all, soil_p_all;
    // An estimate only: where the conjugate gradients converge slowly (a
    // plate far more flexible than the soil) the active set's own solves
    // decide, so the estimate stops early rather than double their cost.
    const unsigned int max_iterations = std::min(control.max_iterations, 200u);
    while (iterations < max_iterations)
      {
        // a safe point (base/interruption.h)
        Interruption::check();
        // The gap on every node: y - d - G alpha, alpha fitted on C; on C
        // it is minus the projected residual.
        const Vector<double> alpha = problem->rigid_motion_amplitudes(
          problem->restrict_to_contact_set(y_all));
        Vector<double> gap(y_all);
        gap -= tested_plate_load;
        for (unsigned int j = 0; j < alpha.size(); ++j)
          gap.add(-alpha[j], tested_motions[j]);
        r = problem->restrict_to_contact_set(gap);
        r *= -1.;
        problem->project(r);

        // A node off the set whose gap is closed beyond the solve's
        // accuracy joins it, with no pressure yet (the equilibrium holds).
        double settlement_scale = 0;
        for (unsigned int i = 0; i < n; ++i)
          settlement_scale =
            std::max(settlement_scale, std::abs(soil_all[i] - gap[i]));
        std::vector<bool> next(contact_set);
        bool              joined = false;
        for (unsigned int i = 0; i < n; ++i)
          if (supported[i] && !contact_set[i] &&
              gap[i] < -tolerance * settlement_scale)
            next[i] = joined = true;
        const double soil_norm =
          problem->restrict_to_contact_set(soil_all).l2_norm();
        if (!joined && r.l2_norm() <= tolerance * soil_norm)
          {
            converged = true;
            break;
          }
        if (joined)
          {
            const Vector<double> q_all = problem->extend_by_zero(q);
            contact_set                = next;
            problem                    = make_problem(contact_set);
            q       = problem->restrict_to_contact_set(q_all);
            restart = true;
            ++set_changes;
            continue;
          }

        problem->precondition(z, r);
        problem->project(z);
        const double rz_next = r * z;
        if (restart)
          p = z;
        else
          p.sadd(rz_next / rz, 1., z);
        rz      = rz_next;
        restart = false;
        problem->vmult_on_all_nodes(hp_all, p, soil_p_all);
        hp = problem->restrict_to_contact_set(hp_all);
        problem->project(hp);
        const double curvature = p * hp;
        if (!(curvature > 0 && rz > 0))
          break; // the active set's own solves report this
        const double step = rz / curvature;
        q.add(step, p);
        y_all.add(step, hp_all);
        soil_all.add(step, soil_p_all);
        ++iterations;

        // A node whose pressure turned tensile leaves the set with none;
        // re-equilibrate. A set that would no longer carry the plate ends
        // the prediction: the active set's own steps handle such a set.
        Vector<double> q_all = problem->extend_by_zero(q);
        next                 = contact_set;
        bool left            = false;
        for (unsigned int i = 0; i < n; ++i)
          if (contact_set[i] && q_all[i] < 0)
            {
              next[i]  = false;
              q_all[i] = 0;
              left     = true;
            }
        if (left)
          {
            if (!contact_set_supports_plate(space, next))
              break;
            contact_set = next;
            problem     = make_problem(contact_set);
            q           = problem->restrict_to_contact_set(q_all);
            problem->make_equilibrated(q);
            problem->vmult_on_all_nodes(y_all, q, soil_all);
            restart = true;
            ++set_changes;
          }
      }
    state.q                     = problem->extend_by_zero(q);
    state.prediction_iterations = iterations;
    if (verbosity > 0)
      log << "   contact set prediction: constrained conjugate gradients "
          << iterations << " iterations, " << set_changes
          << " set changes, nodes in contact "
          << std::count(contact_set.begin(), contact_set.end(), true)
          << (converged ? "" : " (not converged)") << std::endl;
    return contact_set;
  }

  Vector<double>
  IterativeContactSolver::solve_on_set(const std::vector<bool> &contact_set,
                                       const double             tolerance,
                                       ContactState            &state)
  {
    const unsigned int n = foundation->n_nodes();
    // the guard after a factorisation that the set may need
    preconditioner->use_contact_set(contact_set);
    const auto single_threaded_blas = blas_on_one_thread(*foundation);
    state.factorization_time_s      = preconditioner->factorization_time();
    state.factor_memory_bytes       = preconditioner->memory_consumption();
    const ContactSetProblem  problem(contact_set,
                                    foundation->test_coupling(),
                                    foundation->force_coupling(),
                                    *inverse,
                                    *foundation,
                                    *preconditioner,
                                    tested_plate_load,
                                    tested_motions,
                                    motion_loads);
    Vector<double>           q             = state.q.size() == n ?
                                               problem.restrict_to_contact_set(state.q) :
                                               Vector<double>(problem.size());
    ConjugateGradientControl solve_control = control;
    solve_control.tolerance                = tolerance;
    // Directions are recycled on one set only (H is the set's); at most
    // 32 of them, and at most 256 MiB with their products.
    if (recorded->contact_set != contact_set)
      {
        *recorded             = RecordedDirections();
        recorded->contact_set = contact_set;
      }
    // Near the rounding floor the products H p have their last digits
    // from rounding, too few for (W^T H W)^+ (doc/formulation.md,
    // "Recycled directions"). The floor's estimate holds a factor
    // rounding_floor_factor = 100, so a record serves a solve whose
    // tolerance lies at least a digit above the true floor of the solves
    // that made it (a final stage after a loose one may not).
    if (!(recorded->floor <= 10 * tolerance))
      recorded->forget();
    const std::size_t  offered = recorded->p.size();
    const Deflation    deflation(recorded->p, recorded->hp);
    DirectionSink      sink;
    const unsigned int capacity =
      std::min<std::size_t>(32,
                            (std::size_t(256) << 20) /
                              (2 * sizeof(double) * (problem.size() + 1)));
    // a record that serves no longer starts again with this solve's
    const std::size_t kept = deflation.active() ? offered : 0;
    sink.room              = capacity - std::min<std::size_t>(capacity, kept);
    const ConjugateGradientResult cg =
      projected_conjugate_gradients(problem, solve_control, q, deflation, sink);
    if (!deflation.active() || cg.deflation_abandoned)
      recorded->forget();
    // A record given up once on this set is not tried again on it; a solve
    // that ended at its rounding floor leaves none.
    recorded->refused = recorded->refused || cg.deflation_abandoned;
    if (recorded->refused || !(cg.relative_residual <= tolerance))
      {
        recorded->forget();
        sink.p.clear();
        sink.hp.clear();
      }
    if (!sink.p.empty())
      recorded->floor = std::max(recorded->floor, cg.rounding_floor);
    for (unsigned int i = 0; i < sink.p.size(); ++i)
      {
        recorded->p.push_back(std::move(sink.p[i]));
        recorded->hp.push_back(std::move(sink.hp[i]));
      }
    state.factor_memory_bytes +=
      2 * recorded->p.size() * problem.size() * sizeof(double);
    ContactState::LinearSolve record;
    record.contact_iteration = state.linear_solves.size() + 1;
    record.contact_nodes     = problem.size();
    record.iterations        = cg.iterations;
    record.relative_residual = cg.relative_residual;
    state.linear_solves.push_back(record);
    const bool at_floor = cg.converged && cg.relative_residual > tolerance;
    state.rounding_limited_residual = at_floor ? cg.relative_residual : 0.;
    if (verbosity > 0)
      log << "   contact iteration " << record.contact_iteration
          << ": conjugate gradients " << cg.iterations
          << " iterations, relative residual " << std::scientific
          << std::setprecision(1) << cg.relative_residual << std::defaultfloat
          << (at_floor ? " (the rounding floor)" : "")
          << (offered > 0 ? ", recycled " + std::to_string(deflation.rank()) +
                              " of " + std::to_string(offered) + " directions" :
                            std::string())
          << (cg.deflation_abandoned ? " (abandoned)" : "") << std::endl;
    if (!cg.converged && cg.relative_residual <= cg.rounding_floor &&
        cg.relative_residual > accepted_rounding_floor)
      {
        std::ostringstream message;
        message
          << "The contact pressures cannot be solved to better than "
          << std::scientific << std::setprecision(2) << cg.relative_residual
          << " of the soil's settlement: the plate's deflections "
             "exceed the settlement so far that rounding leaves no "
             "more digits (at most "
          << accepted_rounding_floor
          << " is accepted). The plate is far more flexible than the soil "
             "over its size (the floor grows like (L/l)^3 with the plate's "
             "diameter L over its radius of relative stiffness l, not with "
             "the mesh): ";
        if (std::string(foundation->storage_name()) == "sparse")
          message << "the dense liquid has only the iterative solver; check "
                     "Foundation/Modulus of subgrade reaction against "
                     "Plate/Thickness and Plate/Young's modulus.";
        else
          message << "use Contact/Solver = direct with Foundation "
                     "operator/Storage = dense (or both auto), which has no "
                     "such floor.";
        throw ConjugateGradientsFailed(message.str());
      }
    if (!cg.converged)
      {
        std::ostringstream message;
        message << "The conjugate gradients on the contact pressures did "
                   "not converge: relative residual "
                << std::scientific << std::setprecision(2)
                << cg.relative_residual << " after " << cg.iterations
                << " iterations (tolerance " << tolerance
                << ") with Contact/Preconditioner = " << preconditioner->name()
                << ". ";
        // Each preconditioner fails at the other end of the stiffness
        // ratio (doc/formulation.md, "Preconditioning the contact
        // pressures").
        if (preconditioner->name() == "soil inverse")
          message << "The plate is far more flexible than the soil over "
                     "the cells: use Contact/Preconditioner = plate on "
                     "springs (or auto).";
        else
          message << "The plate is far stiffer than the soil over the "
                     "cells: use Contact/Preconditioner = soil inverse (or "
                     "auto).";
        if (std::string(foundation->storage_name()) != "sparse")
          message << " Contact/Solver = direct (with Foundation "
                     "operator/Storage = auto or dense) solves without "
                     "iterations.";
        throw ConjugateGradientsFailed(message.str());
      }

    // u = K^+ P - K^+ N^T M T q + R alpha, w = N u: alpha, F q and the
    // plate's response to q from the product the last stopping test made
    // at q, so that no solve with K^+ is left for u.
    const auto          &motions = inverse->rigid_motions();
    const Vector<double> alpha   = problem.rigid_motion_amplitudes(
      problem.restrict_to_contact_set(cg.product_on_all_nodes));
    state.q          = problem.extend_by_zero(q);
    Vector<double> u = plate_load_response;
    u -= cg.plate_response;
    for (unsigned int j = 0; j < motions.size(); ++j)
      u.add(alpha[j], motions[j]);
    state.plate_solution = u;
    plate->get_constraints().distribute(state.plate_solution);
    state.w = plate->restrict_to_foundation(u);
    for (const double v : state.w)
      AssertThrow(std::isfinite(v), ExcMessage(plate_is_mechanism_message()));

    // gap = F q - B w (B w = T^T M w).
    Vector<double> plate_settlement;
    state.gap = cg.soil_on_all_nodes;
    foundation->plate_settlement(state.w, plate_settlement);
    state.gap -= plate_settlement;
    state.in_contact = contact_set;
    return plate_settlement;
  }

  double
  IterativeContactSolver::changing_set_tolerance() const
  {
    return control.changing_set_tolerance;
  }

  double
  IterativeContactSolver::final_tolerance() const
  {
    return last_solve_tolerance(control.tolerance, *foundation);
  }

  double
  IterativeContactSolver::adjoint_tolerance() const
  {
    return std::max(final_tolerance(), adjoint_accuracy);
  }

  double
  last_solve_tolerance(const double              tolerance,
                       const FoundationOperator &foundation)
  {
    return std::max(tolerance, 1e-2 * foundation.relative_accuracy());
  }
} // namespace PlateOnHalfspace
