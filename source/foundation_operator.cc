#include <plate_on_halfspace/boussinesq_collocation_operator.h>
#include <plate_on_halfspace/boussinesq_galerkin_operator.h>
#include <plate_on_halfspace/boussinesq_kernel.h>
#include <plate_on_halfspace/foundation_operator.h>

namespace PlateOnHalfspace
{
  void
  FoundationOperator::nodal_forces(const Vector<double> &q,
                                   Vector<double>       &forces) const
  {
    forces.reinit(q.size());
    mass.vmult(forces, q);
  }

  void
  FoundationOperator::gap(const Vector<double> &w,
                          const Vector<double> &q,
                          Vector<double>       &g) const
  {
    Vector<double> plate(w.size());
    apply(q, g);
    plate_settlement(w, plate);
    g -= plate;
  }

  void
  FoundationOperator::build_mass_matrix(
    const FoundationSpace   &space,
    const std::vector<bool> &cell_in_foundation)
  {
    space.assemble_mass_matrix(cell_in_foundation, mass_sparsity, mass);
    node_supported.assign(space.n_nodes(), false);
    for (unsigned int c = 0; c < space.cells.size(); ++c)
      if (cell_in_foundation.empty() || cell_in_foundation[c])
        for (const auto &terms : space.cells[c].expansion)
          for (const auto &t : terms)
            node_supported[t.first] = true;
    in_contact = node_supported;
  }

  std::vector<unsigned int>
  FoundationOperator::store_contact_nodes(const std::vector<bool> &requested)
  {
    AssertDimension(requested.size(), node_supported.size());
    std::vector<unsigned int> index;
    for (unsigned int i = 0; i < requested.size(); ++i)
      {
        in_contact[i] = requested[i] && node_supported[i];
        if (in_contact[i])
          index.push_back(i);
      }
    return index;
  }

  std::unique_ptr<FoundationOperator>
  create_foundation_operator(const SceneParameters &parameters)
  {
    const double alpha =
      boussinesq_flexibility_constant(parameters.foundation.youngs_modulus,
                                      parameters.foundation.poissons_ratio);
    // Storage = auto and dense both mean the dense LAPACK operators; the
    // parameter parser rejects the compressed storage this version lacks.
    if (parameters.discretization.flexibility ==
        Parameters::Discretization::Flexibility::galerkin)
      return std::make_unique<BoussinesqGalerkinOperator>(
        alpha, parameters.discretization.singular_quadrature_order);
    return std::make_unique<BoussinesqCollocationOperator>(alpha);
  }
} // namespace PlateOnHalfspace
