// The active-set solver's safeguard against cycling. Full primal-dual
// active-set steps can cycle on a linear complementarity problem whose
// matrix is a P-matrix but not symmetric (as the paper's collocation
// operator is). This test builds such a problem in the contact solver's own
// terms: a small foundation operator with F = A - I/k, B = M = I and a
// plate K̄ = k I, so that the gap is g = A q - P̄/k with the 3x3 P-matrix A
// below
// (found by a random search; full steps from "all in contact" return to a
// set seen before after two steps), plus three anchor nodes that always
// stay in contact so that the plate is never a mechanism. The solver must
// detect the cycle, switch to single (least-index) pivots and reach the
// unique solution, which the test finds independently by enumerating all
// 2^3 contact sets.

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>

#include <plate_on_halfspace/contact/direct_solver.h>

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

  /** A dense operator F with M = B = I on the nodes of a FoundationSpace. */
  class MatrixFoundation : public FoundationOperator
  {
  public:
    void
    build(const FoundationSpace &space, const std::vector<bool> &) override
    {
      DynamicSparsityPattern dsp(n, n);
      for (unsigned int i = 0; i < n; ++i)
        dsp.add(i, i);
      mass_sparsity.copy_from(dsp);
      mass.reinit(mass_sparsity);
      for (unsigned int i = 0; i < n; ++i)
        mass.set(i, i, 1.);
      node_supported.assign(space.n_nodes(), true);
      in_contact = node_supported;
      flexibility.reinit(n);
      flexibility = 0.;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          flexibility(i, j) = A[i][j] - (i == j ? 1. / k : 0.);
      for (unsigned int i = 3; i < n; ++i)
        flexibility(i, i) = 1.;
      set_contact_nodes(node_supported);
    }
    void
    set_contact_nodes(const std::vector<bool> &requested) override
    {
      factorise_contact_block(requested, flexibility, false, "singular");
    }
    void
    apply(const Vector<double> &q, Vector<double> &s) const override
    {
      s.reinit(n);
      flexibility.vmult(s, q);
    }
    void
    plate_settlement(const Vector<double> &w, Vector<double> &s) const override
    {
      s = w;
    }
    void
    solve(const Vector<double> &w, Vector<double> &q) const override
    {
      solve_contact_block(w, q);
    }
    void
    add_stiffness(LAPACKFullMatrix<double> &matrix) const override
    {
      LAPACKFullMatrix<double> rows(contact_index.size(), n);
      rows = 0.;
      for (unsigned int i = 0; i < contact_index.size(); ++i)
        rows(i, contact_index[i]) = 1.;
      add_mass_times_contact_inverse(rows, matrix);
    }
    bool
    is_symmetric() const override
    {
      return false;
    }
    std::string
    storage_name() const override
    {
      return "test";
    }
    std::size_t
    memory_consumption() const override
    {
      return 0;
    }

  private:
    LAPACKFullMatrix<double> flexibility;
  };
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
  LAPACKFullMatrix<double> plate(n);
  plate = 0.;
  for (unsigned int i = 0; i < n; ++i)
    plate(i, i) = k;
  Vector<double> load(n);
  for (unsigned int i = 0; i < 3; ++i)
    load[i] = -k * b[i];
  for (unsigned int i = 3; i < n; ++i)
    load[i] = k;

  MatrixFoundation foundation;
  foundation.build(space, {});
  Parameters::Contact contact;
  contact.method         = Parameters::Contact::Method::active_set;
  contact.max_iterations = 50;
  contact.tolerance      = 1e-8;
  std::ostringstream  log;
  const ContactSolver solver(contact, true, 1, log);
  const ContactState  state = solver.solve(plate, load, foundation, space, {});
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
