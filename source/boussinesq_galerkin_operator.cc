#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/boussinesq_galerkin_operator.h>
#include <plate_on_halfspace/cell_pair_quadrature.h>

#include <algorithm>
#include <cmath>

namespace PlateOnHalfspace
{
  BoussinesqGalerkinOperator::BoussinesqGalerkinOperator(
    const double       alpha,
    const unsigned int singular_order)
    : alpha(alpha)
    , singular_order(singular_order)
  {}

  void
  BoussinesqGalerkinOperator::build(const FoundationSpace   &space,
                                    const std::vector<bool> &cell_in_foundation)
  {
    build_mass_matrix(space, cell_in_foundation);
    const auto included = [&](const unsigned int c) {
      return cell_in_foundation.empty() || cell_in_foundation[c];
    };
    partial_foundation =
      std::find(cell_in_foundation.begin(), cell_in_foundation.end(), false) !=
      cell_in_foundation.end();
    if (partial_foundation)
      // The gap is reported on the whole plate, also under excluded cells:
      // it tests with every w-shape function.
      space.assemble_mass_matrix({}, full_mass_sparsity, full_mass);

    const unsigned int n = space.n_nodes();
    flexibility.reinit(n);
    flexibility = 0.;
    system_flexibility.reinit(partial_foundation ? n : 0);
    if (partial_foundation)
      system_flexibility = 0.;

    // flexibility(i,j): test functions over the whole plate, pressures over
    // the foundation cells (the settlement everywhere); system_flexibility:
    // both over the foundation cells (the paper's exclusion removes a cell's
    // contribution to A). They coincide when every cell is in.
    const CellPairIntegrator integrator(space, singular_order);
    FullMatrix<double>       block;
    const unsigned int       n_cells = space.cells.size();
    for (unsigned int a = 0; a < n_cells; ++a)
      for (unsigned int b = a; b < n_cells; ++b)
        {
          if (!included(a) && !included(b))
            continue;
          // block(i,j) = ∫_K ∫_L psi_i(x) psi_j(y) / |x - y| over the node
          // shape functions psi of the two cells.
          integrator.integrate_inverse_distance(a, b, block);
          const auto &nodes_a = integrator.nodes(a);
          const auto &nodes_b = integrator.nodes(b);
          for (unsigned int i = 0; i < nodes_a.size(); ++i)
            for (unsigned int j = 0; j < nodes_b.size(); ++j)
              {
                const double value = alpha * block(i, j);
                if (included(b))
                  flexibility(nodes_a[i], nodes_b[j]) += value;
                if (a != b && included(a))
                  flexibility(nodes_b[j], nodes_a[i]) += value;
                if (partial_foundation && included(a) && included(b))
                  {
                    system_flexibility(nodes_a[i], nodes_b[j]) += value;
                    if (a != b)
                      system_flexibility(nodes_b[j], nodes_a[i]) += value;
                  }
              }
        }
    set_contact_nodes(node_supported);
  }

  void
  BoussinesqGalerkinOperator::set_contact_nodes(
    const std::vector<bool> &requested)
  {
    contact_index        = store_contact_nodes(requested);
    const unsigned int m = contact_index.size();
    contact_factor.reinit(m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        contact_factor(i, j) =
          (partial_foundation ?
             system_flexibility :
             flexibility)(contact_index[i], contact_index[j]);
    if (m == 0)
      return;
    try
      {
        contact_factor.compute_cholesky_factorization();
      }
    catch (...)
      {
        AssertThrow(false,
                    ExcMessage("The Galerkin half-space matrix A of the "
                               "contact set is not positive definite; the "
                               "singular quadrature is too coarse for this "
                               "mesh (raise Discretization/Singular "
                               "quadrature order)."));
      }
  }

  void
  BoussinesqGalerkinOperator::apply(const Vector<double> &q,
                                    Vector<double>       &s) const
  {
    s.reinit(q.size());
    flexibility.vmult(s, q);
  }

  void
  BoussinesqGalerkinOperator::plate_settlement(const Vector<double> &w,
                                               Vector<double>       &b) const
  {
    b.reinit(w.size());
    (partial_foundation ? full_mass : mass).vmult(b, w);
  }

  void
  BoussinesqGalerkinOperator::solve(const Vector<double> &w,
                                    Vector<double>       &q) const
  {
    // (B w)_C with the system's M (over the foundation cells).
    Vector<double> b(w.size());
    mass.vmult(b, w);
    Vector<double> b_contact(contact_index.size());
    for (unsigned int i = 0; i < contact_index.size(); ++i)
      b_contact[i] = b[contact_index[i]];
    if (!contact_index.empty())
      contact_factor.solve(b_contact);
    q.reinit(w.size());
    for (unsigned int i = 0; i < contact_index.size(); ++i)
      q[contact_index[i]] = b_contact[i];
  }

  void
  BoussinesqGalerkinOperator::add_stiffness(
    LAPACKFullMatrix<double> &matrix) const
  {
    const unsigned int n = mass.m(), m = contact_index.size();
    if (m == 0)
      return;
    // X = A_CC^{-1} M_{C,:}, then S = M_{:,C} X (formulation.md: the
    // foundation stiffness M A^{-1} M restricted to the contact set).
    LAPACKFullMatrix<double> x(m, n);
    x = 0.;
    std::vector<int> position(n, -1);
    for (unsigned int i = 0; i < m; ++i)
      {
        position[contact_index[i]] = i;
        for (auto entry = mass.begin(contact_index[i]);
             entry != mass.end(contact_index[i]);
             ++entry)
          x(i, entry->column()) = entry->value();
      }
    contact_factor.solve(x);
    for (unsigned int r = 0; r < n; ++r)
      for (auto entry = mass.begin(r); entry != mass.end(r); ++entry)
        if (position[entry->column()] >= 0)
          {
            const unsigned int k = position[entry->column()];
            const double       v = entry->value();
            for (unsigned int c = 0; c < n; ++c)
              matrix(r, c) += v * x(k, c);
          }
  }

  std::size_t
  BoussinesqGalerkinOperator::memory_consumption() const
  {
    return flexibility.memory_consumption() +
           system_flexibility.memory_consumption() +
           full_mass.memory_consumption() +
           contact_factor.memory_consumption() + mass.memory_consumption() +
           mass_sparsity.memory_consumption();
  }
} // namespace PlateOnHalfspace
