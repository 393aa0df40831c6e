#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/full_matrix.h>

#include <plate_on_halfspace/base/condition_estimate.h>
#include <plate_on_halfspace/contact/active_set.h>
#include <plate_on_halfspace/contact/direct_solver.h>
#include <plate_on_halfspace/contact/pressure_preconditioner.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/plate/generalized_inverse.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    /**
     * Factorise @p matrix in place (Cholesky if @p symmetric, else LU) and
     * return LAPACK's estimate of 1/κ₁; throw ExcMessage(@p failure()) if
     * it cannot be factorised (the message is composed only then).
     */
    double
    factorise(LAPACKFullMatrix<double>           &matrix,
              const bool                          symmetric,
              const std::function<std::string()> &failure)
    {
      const double l1_norm = matrix.l1_norm();
      try
        {
          if (symmetric)
            matrix.compute_cholesky_factorization();
          else
            matrix.compute_lu_factorization();
        }
      catch (...)
        {
          AssertThrow(false, ExcMessage(failure()));
        }
      return reciprocal_condition_number(matrix, l1_norm, symmetric);
    }
  } // namespace

  DirectContactSolver::DirectContactSolver(const Parameters::Contact &contact,
                                           const bool         tensionless,
                                           const unsigned int verbosity,
                                           std::ostream      &log)
    : ContactIteration(contact, tensionless, verbosity, log)
  {}

  void
  DirectContactSolver::prepare(MindlinPlate &plate,
                               FoundationOperator &,
                               ContactState &)
  {
    plate.condense(plate_stiffness);
    plate_rigid_motions = rigid_body_motions(plate);
    rigid_motions.clear();
    for (const Vector<double> &motion : plate_rigid_motions)
      rigid_motions.push_back(plate.restrict_to_foundation(motion));
    const unsigned int n_modes = rigid_motions.size();
    rigid_gram_inverse.reinit(n_modes, n_modes);
    for (unsigned int i = 0; i < n_modes; ++i)
      for (unsigned int j = 0; j < n_modes; ++j)
        rigid_gram_inverse(i, j) = rigid_motions[i] * rigid_motions[j];
    if (n_modes > 0)
      rigid_gram_inverse.gauss_jordan();
    factorised_once = false;
    factorised_set.clear();
  }

  void
  DirectContactSolver::prepare_load(const Vector<double> &new_load)
  {
    load       = new_load;
    plate_load = plate->condensed_load(load);
  }

  void
  DirectContactSolver::factorise_contact_block(
    const std::vector<bool> &contact_set,
    ContactState            &state)
  {
    const Timer              timer;
    const std::vector<bool> &supported = foundation->supported_nodes();
    contact_index.clear();
    for (unsigned int i = 0; i < contact_set.size(); ++i)
      if (contact_set[i] && supported[i])
        contact_index.push_back(i);
    foundation->copy_block(contact_index, contact_factor);
    state.contact_block_rcond = 1.;
    if (contact_index.empty())
      return;
    const bool symmetric       = foundation->is_symmetric();
    const auto failure_message = [&]() -> std::string {
      if (!symmetric)
        return "The collocation flexibility matrix G of the contact set is "
               "singular.";
      // Cells far more elongated than the cell-pair rules hold (about
      // 300 : 1, doc/formulation.md, "Graded and elongated pairs") make A
      // indefinite whatever the singular order: say so instead.
      double elongation = 1;
      for (const auto &cell : plate->get_foundation_space().cells)
        {
          const double d = cell.geometry.diameter();
          elongation     = std::max(elongation, d * d / cell.geometry.area());
        }
      std::ostringstream cause;
      if (elongation > 300)
        cause << "the cells are up to " << std::setprecision(3) << elongation
              << " times longer than wide, beyond the about 300 : 1 that "
                 "its cell-pair quadrature holds: make them nearer square "
                 "(Discretization/Subdivisions x and y against Plate/Length "
                 "x and y, or Slab lengths x and y).";
      else
        cause << "the singular quadrature is too coarse for this mesh (raise "
                 "Discretization/Singular quadrature order).";
      const std::string advice = foundation->soil().definiteness_advice();
      return "The Galerkin half-space matrix A of the contact set is not "
             "positive definite; " +
             cause.str() + (advice.empty() ? std::string() : " " + advice);
    };
    state.contact_block_rcond =
      factorise(contact_factor, symmetric, failure_message);
    if (!factorised_once)
      {
        state.factorization_time_s = timer.wall_time();
        state.factor_memory_bytes  = contact_factor.memory_consumption();
        factorised_once            = true;
      }
  }

  void
  DirectContactSolver::pressures(const Vector<double> &w,
                                 Vector<double>       &q) const
  {
    Vector<double> b(w.size());
    foundation->test_coupling().vmult(b, w);
    Vector<double> b_contact(contact_index.size());
    for (unsigned int i = 0; i < contact_index.size(); ++i)
      b_contact[i] = b[contact_index[i]];
    if (!contact_index.empty())
      contact_factor.solve(b_contact);
    q.reinit(b.size());
    for (unsigned int i = 0; i < contact_index.size(); ++i)
      q[contact_index[i]] = b_contact[i];
  }

  void
  DirectContactSolver::add_foundation_stiffness(
    LAPACKFullMatrix<double> &matrix) const
  {
    // S = (M T)_{:,C} F_CC^{-1} B_{C,:} (doc/formulation.md, "Half-space":
    // the foundation stiffness restricted to the contact set).
    if (contact_index.empty())
      return;
    const SparseMatrix<double> &tests  = foundation->test_coupling();
    const SparseMatrix<double> &forces = foundation->force_coupling();
    const unsigned int          n      = forces.m();
    LAPACKFullMatrix<double>    rows(contact_index.size(), n);
    rows = 0.;
    for (unsigned int i = 0; i < contact_index.size(); ++i)
      for (auto entry = tests.begin(contact_index[i]);
           entry != tests.end(contact_index[i]);
           ++entry)
        rows(i, entry->column()) = entry->value();
    contact_factor.solve(rows);
    // (M T)_{:,C} restricted to the contact columns, row by row.
    std::vector<int> position(n, -1);
    for (unsigned int i = 0; i < contact_index.size(); ++i)
      position[contact_index[i]] = i;
    std::vector<std::vector<std::pair<unsigned int, double>>> force_rows(n);
    for (unsigned int r = 0; r < n; ++r)
      for (auto entry = forces.begin(r); entry != forces.end(r); ++entry)
        if (position[entry->column()] >= 0)
          force_rows[r].emplace_back(position[entry->column()], entry->value());
    // matrix(:, c) += (M T)_{:,C} rows(:, c): both columns are contiguous
    // in LAPACK's column-major storage; the columns are independent, so
    // they are split over the threads.
    const auto add_columns = [&](const unsigned int begin,
                                 const unsigned int end) {
      for (unsigned int c = begin; c < end; ++c)
        for (unsigned int r = 0; r < n; ++r)
          {
            double sum = 0;
            for (const auto &kv : force_rows[r])
              sum += kv.second * rows(kv.first, c);
            matrix(r, c) += sum;
          }
    };
    Threads::TaskGroup<void> tasks;
    const unsigned int       n_chunks = MultithreadInfo::n_threads();
    for (unsigned int t = 0; t < n_chunks; ++t)
      tasks += Threads::new_task(
        [&, t]() { add_columns(n * t / n_chunks, n * (t + 1) / n_chunks); });
    tasks.join_all();
  }

  Vector<double>
  DirectContactSolver::solve_on_set(const std::vector<bool> &contact_set,
                                    const double,
                                    ContactState &state)
  {
    // A set solved before (the adjoint problem of solve_linearised()
    // shares the last set of solve()) reuses both factors.
    if (contact_set != factorised_set)
      {
        factorise_contact_block(contact_set, state);
        // (K̄ + S) w = P̄ (P21), S the foundation stiffness on the contact
        // set.
        coupled = plate_stiffness;
        add_foundation_stiffness(coupled);
        coupled_rcond  = factorise(coupled,
                                  foundation->is_symmetric(),
                                  plate_is_mechanism_message);
        block_rcond    = state.contact_block_rcond;
        factorised_set = contact_set;
      }
    state.coupled_rcond       = coupled_rcond;
    state.contact_block_rcond = block_rcond;
    state.w                   = plate_load;
    coupled.solve(state.w);
    for (const double v : state.w)
      AssertThrow(std::isfinite(v), ExcMessage(plate_is_mechanism_message()));
    pressures(state.w, state.q);
    correct_rigid_body_equilibrium(state);
    Vector<double> amplitudes, bending;
    split(state.w, amplitudes, bending);
    refine_bending(amplitudes, bending, state);

    state.in_contact.assign(contact_set.size(), false);
    for (const unsigned int i : contact_index)
      state.in_contact[i] = true;
    foundation->gap(state.w, state.q, state.gap);
    expand(amplitudes, bending, state.plate_solution);
    Vector<double> plate_settlement;
    foundation->plate_settlement(state.w, plate_settlement);
    return plate_settlement;
  }

  void
  DirectContactSolver::correct_rigid_body_equilibrium(ContactState &state) const
  {
    // The rigid-body motions r of the free plate are exactly in the kernel
    // of K̄, so the equations r^T (K̄ + S) w = r^T P̄ read r^T S w = r^T P̄:
    // vertical force and moment equilibrium. In floating point K̄ r is only
    // zero to rounding times |K̄|, which for a plate much stiffer than the
    // soil (E/E0 >= 1e8) spoils equilibrium. A correction w += R da within
    // that kernel restores these equations at the soil's scale without
    // touching the others. A plate with supports has no such motions and is
    // left as solved.
    if (state.w.size() < 3 || rigid_motions.empty())
      return;
    state.w += rigid_correction(state.w, plate_load);
    pressures(state.w, state.q);
  }

  void
  DirectContactSolver::split(const Vector<double> &w,
                             Vector<double>       &amplitudes,
                             Vector<double>       &bending) const
  {
    const unsigned int n_modes = rigid_motions.size();
    Vector<double>     projections(n_modes);
    for (unsigned int j = 0; j < n_modes; ++j)
      projections[j] = rigid_motions[j] * w;
    amplitudes.reinit(n_modes);
    if (n_modes > 0)
      rigid_gram_inverse.vmult(amplitudes, projections);
    bending = w;
    for (unsigned int j = 0; j < n_modes; ++j)
      bending.add(-amplitudes[j], rigid_motions[j]);
  }

  Vector<double>
  DirectContactSolver::refinement_step(const Vector<double> &bending,
                                       const Vector<double> &q) const
  {
    // The residual P̄ - K̄ w - S w, its soil part the forces of the
    // pressures @p q and K̄ applied to the bending part alone: K̄ maps the
    // rigid part to rounding times |K̄| |w|, so this residual is accurate
    // to eps |P̄|, and the correction solved from it is the solve's error.
    // Its rigid-body part is equilibrated as the answer's is
    // (correct_rigid_body_equilibrium()).
    Vector<double> forces, stiffness_w(bending.size());
    foundation->nodal_forces(q, forces);
    plate_stiffness.vmult(stiffness_w, bending);
    Vector<double> correction = plate_load;
    correction -= stiffness_w;
    correction -= forces;
    coupled.solve(correction);
    if (!rigid_motions.empty())
      correction += rigid_correction(correction, Vector<double>(q.size()));
    return correction;
  }

  void
  DirectContactSolver::refine_bending(Vector<double> &amplitudes,
                                      Vector<double> &bending,
                                      ContactState   &state) const
  {
    // For a plate much stiffer than the soil, w is a rigid-body motion
    // plus a bending part about E t^3/(E0 L^3) times smaller, and the
    // bending alone makes the moments and stresses. As one vector w keeps
    // only the digits of the bending part that its rigid part leaves, and
    // the solve loses more (its rounding grows with the condition of
    // K̄ + S): moments 1e-5 off at E t^3/(E0 L^3) = 1e7 and wrong in the
    // first digit at 1e11 (doc/errors-and-limits.md, "Stiffness ratio").
    // Held apart, as amplitudes of the rigid motions and a bending part,
    // iterative refinement recovers the bending to rounding of its own
    // size. It stops once a step no longer halves the bending's
    // correction. A plate with supports has no rigid motions and is left
    // as solved.
    if (contact_index.empty() || rigid_motions.empty())
      return;
    double last = bending.linfty_norm();
    for (unsigned int step = 0; step < max_refinement_steps && last > 0; ++step)
      {
        Vector<double> step_amplitudes, step_bending;
        split(refinement_step(bending, state.q), step_amplitudes, step_bending);
        const double size = step_bending.linfty_norm();
        if (!(size < 0.5 * last))
          break;
        amplitudes += step_amplitudes;
        bending += step_bending;
        state.w = bending;
        for (unsigned int j = 0; j < rigid_motions.size(); ++j)
          state.w.add(amplitudes[j], rigid_motions[j]);
        pressures(state.w, state.q);
        last = size;
        if (size <= 1e-15 * bending.linfty_norm())
          break;
      }
  }

  void
  DirectContactSolver::expand(const Vector<double> &amplitudes,
                              const Vector<double> &bending,
                              Vector<double>       &solution) const
  {
    // The rotations are K_rr^{-1} (P_r - K_rf w_f). K maps a rigid-body
    // motion to rounding times |K| |w| alone, which for a plate much
    // stiffer than the soil would swamp the bending's rotations: only the
    // bending part goes through K, and the rigid part is added as the
    // exact motions.
    plate->expand(bending, load, solution);
    for (unsigned int j = 0; j < amplitudes.size(); ++j)
      solution.add(amplitudes[j], plate_rigid_motions[j]);
    plate->get_constraints().distribute(solution);
  }

  Vector<double>
  DirectContactSolver::rigid_correction(const Vector<double> &w,
                                        const Vector<double> &f) const
  {
    const unsigned int n_modes = rigid_motions.size();
    FullMatrix<double> rigid_stiffness(n_modes, n_modes); // R^T S R
    Vector<double>     residual(n_modes), amplitudes(n_modes), forces, q;
    pressures(w, q);
    foundation->nodal_forces(q, forces);
    for (unsigned int j = 0; j < n_modes; ++j)
      {
        residual[j] = rigid_motions[j] * f - rigid_motions[j] * forces;
        Vector<double> s_mode;
        pressures(rigid_motions[j], q);
        foundation->nodal_forces(q, s_mode);
        for (unsigned int i = 0; i < n_modes; ++i)
          rigid_stiffness(i, j) = rigid_motions[i] * s_mode;
      }
    rigid_stiffness.gauss_jordan();
    rigid_stiffness.vmult(amplitudes, residual);
    Vector<double> correction(w.size());
    for (unsigned int j = 0; j < n_modes; ++j)
      correction.add(amplitudes[j], rigid_motions[j]);
    return correction;
  }

  void
  DirectContactSolver::check_accepted_solution(const ContactState &state) const
  {
    // Where the soil is far stiffer than the plate over a cell, the
    // settlement (B w)_C on the contact set is a small difference of the
    // plate's nodal deflections, and q = F^-1 (B w)_C keeps only what their
    // rounding leaves (doc/errors-and-limits.md, "Stiffness ratio"). One
    // step of iterative refinement measures it (refinement_step()).
    if (contact_index.empty() || state.w.size() < 3)
      return;
    Vector<double> amplitudes, bending;
    split(state.w, amplitudes, bending);
    const Vector<double> correction = refinement_step(bending, state.q);
    Vector<double>       pressure_correction;
    pressures(correction, pressure_correction);
    const double scale = state.q.linfty_norm();
    const double error = pressure_correction.linfty_norm() / scale;
    if (!(scale > 0) || !(error > accepted_rounding_floor))
      return;
    std::ostringstream message;
    message << "The contact pressures cannot be solved to better than "
            << std::scientific << std::setprecision(2) << error
            << " of their scale: the soil is so much stiffer than the plate "
               "over a cell that the settlement on the contact set is a "
               "small difference of the plate's deflections, and rounding "
               "leaves no more digits (at most "
            << accepted_rounding_floor
            << " is accepted). For the plate such a soil is rigid: one "
            << std::defaultfloat << std::setprecision(2)
            << error / (0.1 * accepted_rounding_floor)
            << " times softer is as rigid and keeps the digits; compare "
               "Foundation/Young's modulus (or the layers') with "
               "Plate/Young's modulus and Plate/Thickness, and check the "
               "units of the moduli.";
    AssertThrow(false, ExcMessage(message.str()));
  }
} // namespace PlateOnHalfspace
