#include <deal.II/base/quadrature_lib.h>

#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>

#include <algorithm>
#include <cmath>

namespace PlateOnHalfspace
{
  BoussinesqGalerkinOperator::BoussinesqGalerkinOperator(
    const double       alpha,
    const unsigned int singular_order,
    const bool         positive_pressure_basis)
    : alpha(alpha)
    , singular_order(singular_order)
    , positive_pressure_basis(positive_pressure_basis)
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
    const auto add = [&](const unsigned int               a,
                         const unsigned int               b,
                         const FullMatrix<double>        &block,
                         const std::vector<unsigned int> &nodes_a,
                         const std::vector<unsigned int> &nodes_b) {
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
    };

    // A symmetric scene (mirror_symmetry.h): the pressure of the computed
    // part has mirror images, so cell b acts on cell a also through its
    // images R b: A_ij = alpha sum_R ∫_K ∫_{R L} psi_i(x) psi_j(R y) /
    // |x - y|. The image pair (b, R a) is the transpose of (a, R b) (R is an
    // isometry and an involution), so the loop over b >= a covers all.
    std::vector<FoundationSpace::Cell> cells = space.cells;
    {
      const auto images = space.mirror_image_cells();
      cells.insert(cells.end(), images.begin(), images.end());
    }
    const CellPairIntegrator integrator(cells, singular_order);
    const unsigned int       n_cells  = space.cells.size();
    const unsigned int       n_images = space.symmetry.reflections().size();
    FullMatrix<double>       block;
    for (unsigned int a = 0; a < n_cells; ++a)
      for (unsigned int b = a; b < n_cells; ++b)
        {
          if (!included(a) && !included(b))
            continue;
          // block(i,j) = ∫_K ∫_L psi_i(x) psi_j(y) / |x - y| over the node
          // shape functions psi of the two cells.
          integrator.integrate_inverse_distance(a, b, block);
          add(a, b, block, integrator.nodes(a), integrator.nodes(b));
          for (unsigned int r = 1; r <= n_images; ++r)
            {
              const unsigned int image = r * n_cells + b;
              integrator.integrate_inverse_distance(a, image, block);
              if (a == b)
                symmetrise_self_image_block(integrator.nodes(a),
                                            integrator.nodes(image),
                                            block);
              add(a, b, block, integrator.nodes(a), integrator.nodes(image));
            }
        }

    // The contact conditions in the positive pressure basis
    // (foundation_space.h): A <- T^T A T, M <- T^T M.
    set_pressure_basis(space, positive_pressure_basis);
    transform_flexibility(flexibility);
    if (partial_foundation)
      {
        transform_flexibility(system_flexibility);
        transform_tests(full_mass, full_tested_sparsity, full_tested_mass);
      }
  }

  void
  BoussinesqGalerkinOperator::copy_block(const std::vector<unsigned int> &nodes,
                                         LAPACKFullMatrix<double> &block) const
  {
    // The paper's exclusion removes a cell's contribution to A of the
    // contact conditions: both test and pressure over the foundation cells.
    copy_dense_block(partial_foundation ? system_flexibility : flexibility,
                     nodes,
                     block);
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
    (partial_foundation ? full_tested_mass : test_coupling()).vmult(b, w);
  }

  std::size_t
  BoussinesqGalerkinOperator::memory_consumption() const
  {
    return flexibility.memory_consumption() +
           system_flexibility.memory_consumption() +
           full_mass.memory_consumption() +
           full_tested_mass.memory_consumption() +
           coupling_memory_consumption();
  }
} // namespace PlateOnHalfspace
