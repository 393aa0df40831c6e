// The active-set step's safeguard against cycling (ActiveSetUpdate, which
// both contact solvers use). Full primal-dual active-set steps can cycle on
// a linear complementarity problem whose matrix is a P-matrix but not
// symmetric (as the paper's collocation operator is). This test builds such
// a problem in the contact solvers' own terms: a flexibility F = A - I/k,
// B = M = I and a condensed plate K̄ = k I, so that the gap is
// g = A q - P̄/k with the 3x3 P-matrix A below (found by a random search;
// full steps from "all in contact" return to a set seen before after two
// steps), plus three anchor nodes that always stay in contact so that the
// plate is never a mechanism. Each set's coupled problem is solved here as
// the direct solver does it; the active-set step must detect the cycle,
// switch to single (least-index) pivots and reach the unique solution,
// which the test finds independently by enumerating all 2^3 contact sets.

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <plate_on_halfspace/contact/active_set.h>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  const double A[3][3] = {
    {0.7836008954477599, 1.3528566445878738, -0.5022178996752045},
    {1.957494649695339, 3.4156500142418778, -1.2922817448585844},
    {0.3106722886541444, 0.7044578626820348, 0.12607137155562642}};
  const double       b[3] = {2.732813549364325,
                             0.15911772800989699,
                             -1.3383831295833888};
  const unsigned int n    = 6;     // 3 cycling nodes, 3 anchors
  const double       k    = 1000.; // plate stiffness K̄ = k I

  /** F on all nodes: A - I/k on the cycling nodes, 1 on the anchors. */
  FullMatrix<double>
  flexibility()
  {
    FullMatrix<double> f(n, n);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        f(i, j) = A[i][j] - (i == j ? 1. / k : 0.);
    for (unsigned int i = 3; i < n; ++i)
      f(i, i) = 1.;
    return f;
  }

  /**
   * The coupled problem on @p set as the direct solver states it with
   * B = M = I: (K̄ + S) w = P̄ with S = I_{:,C} F_CC^{-1} I_{C,:}, then
   * q_C = F_CC^{-1} w_C and the gap g = F q - w.
   */
  void
  solve_on_set(const std::vector<bool>  &set,
               const FullMatrix<double> &f,
               const Vector<double>     &load,
               ContactState             &state)
  {
    std::vector<unsigned int> c;
    for (unsigned int i = 0; i < n; ++i)
      if (set[i])
        c.push_back(i);
    LAPACKFullMatrix<double> f_cc(c.size(), c.size());
    for (unsigned int i = 0; i < c.size(); ++i)
      for (unsigned int j = 0; j < c.size(); ++j)
        f_cc(i, j) = f(c[i], c[j]);
    f_cc.compute_lu_factorization();
    LAPACKFullMatrix<double> coupled(n);
    coupled = 0.;
    for (unsigned int i = 0; i < n; ++i)
      coupled(i, i) = k;
    for (unsigned int j = 0; j < c.size(); ++j)
      {
        Vector<double> column(c.size());
        column[j] = 1.;
        f_cc.solve(column);
        for (unsigned int i = 0; i < c.size(); ++i)
          coupled(c[i], c[j]) += column[i];
      }
    coupled.compute_lu_factorization();
    state.w = load;
    coupled.solve(state.w);
    Vector<double> q_c(c.size());
    for (unsigned int i = 0; i < c.size(); ++i)
      q_c[i] = state.w[c[i]];
    f_cc.solve(q_c);
    state.q.reinit(n);
    for (unsigned int i = 0; i < c.size(); ++i)
      state.q[c[i]] = q_c[i];
    state.gap.reinit(n);
    f.vmult(state.gap, state.q);
    state.gap -= state.w;
    state.in_contact = set;
  }
} // namespace

int
main()
{
  initlog();
  // Nodes: the cycling ones and three non-collinear anchors.
  FoundationSpace space;
  space.node_locations = {Point<2>(0.3, 0.3),
                          Point<2>(0.6, 0.3),
                          Point<2>(0.3, 0.6),
                          Point<2>(0, 0),
                          Point<2>(1, 0),
                          Point<2>(0, 1)};
  // K̄ = k I, P̄ = -k b for the cycling nodes, k for the anchors (there
  // F = 1 and q = k/(k+1) > 0).
  Vector<double> load(n);
  for (unsigned int i = 0; i < 3; ++i)
    load[i] = -k * b[i];
  for (unsigned int i = 3; i < n; ++i)
    load[i] = k;

  const FullMatrix<double> f = flexibility();
  const std::vector<bool>  supported(n, true);
  SparsityPattern          diagonal(n, n, 1);
  for (unsigned int i = 0; i < n; ++i)
    diagonal.add(i, i);
  diagonal.compress();
  SparseMatrix<double> identity(diagonal); // B = I
  for (unsigned int i = 0; i < n; ++i)
    identity.set(i, i, 1.);
  ActiveSetUpdate    active_set(space, supported, {}, identity);
  std::ostringstream log;
  ContactState       state;
  for (state.iterations = 1; state.iterations <= 50; ++state.iterations)
    {
      solve_on_set(active_set.contact_set(), f, load, state);
      const double q_scale   = std::max(state.q.linfty_norm(), 1e-300);
      const double gap_scale = std::max(state.w.linfty_norm(), 1e-300);
      if (active_set.step(state.q,
                          state.gap,
                          1e-12 * q_scale,
                          1e-12 * gap_scale,
                          state.iterations,
                          1,
                          log))
        {
          state.converged = true;
          break;
        }
    }
  evaluate_contact_conditions(state.w, supported, state);
  deallog << log.str();
  const bool cycle_seen = log.str().find("cycle detected") != std::string::npos;
  deallog << "cycle detected and handled: " << (cycle_seen ? "ok" : "FAILED")
          << std::endl;
  AssertThrow(cycle_seen && state.converged, ExcMessage("no cycle handling"));

  // Independent solution: the contact set C with z_C = -A_CC^{-1} b_C >= 0
  // and y = A z + b >= 0 off C (unique for a P-matrix).
  unsigned int found = 0;
  for (unsigned int set = 0; set < 8; ++set)
    {
      std::vector<unsigned int> c;
      for (unsigned int i = 0; i < 3; ++i)
        if (set & (1u << i))
          c.push_back(i);
      FullMatrix<double> acc(c.size(), c.size());
      Vector<double>     rhs(c.size()), z_c(c.size()), z(3);
      for (unsigned int i = 0; i < c.size(); ++i)
        {
          rhs[i] = -b[c[i]];
          for (unsigned int j = 0; j < c.size(); ++j)
            acc(i, j) = A[c[i]][c[j]];
        }
      if (!c.empty())
        {
          acc.gauss_jordan();
          acc.vmult(z_c, rhs);
        }
      for (unsigned int i = 0; i < c.size(); ++i)
        z[c[i]] = z_c[i];
      bool feasible = true;
      for (unsigned int i = 0; i < 3; ++i)
        {
          double y = b[i];
          for (unsigned int j = 0; j < 3; ++j)
            y += A[i][j] * z[j];
          feasible = feasible && z[i] >= -1e-12 && y >= -1e-12;
        }
      if (!feasible)
        continue;
      ++found;
      for (unsigned int i = 0; i < 3; ++i)
        {
          deallog << "node " << i << ": in contact " << state.in_contact[i]
                  << " (exact " << (z[i] > 0) << ")" << std::endl;
          AssertThrow(state.in_contact[i] == (z[i] > 0),
                      ExcMessage("contact set"));
          check("  pressure", state.q[i] + 1., z[i] + 1., 1e-12);
        }
    }
  AssertThrow(found == 1, ExcMessage("the LCP solution is not unique"));
  check("complementarity violation + 1",
        state.complementarity_violation + 1.,
        1.,
        1e-12);
}
