#include <plate_on_halfspace/halfspace/collocation_operator.h>
#include <plate_on_halfspace/soil/boussinesq_kernel.h>
#include <plate_on_halfspace/soil/half_space.h>

#include <cmath>

namespace PlateOnHalfspace
{
  BoussinesqCollocationOperator::BoussinesqCollocationOperator(
    std::shared_ptr<const ElasticSoil> soil)
    : elastic(std::move(soil))
  {
    soil_model = elastic;
  }

  BoussinesqCollocationOperator::BoussinesqCollocationOperator(
    const double       alpha,
    const unsigned int singular_order)
    : BoussinesqCollocationOperator(
        std::make_shared<HomogeneousHalfSpace>(alpha, singular_order))
  {}

  void
  BoussinesqCollocationOperator::build(
    const FoundationSpace   &space,
    const std::vector<bool> &cell_in_foundation)
  {
    AssertThrow(dynamic_cast<const HomogeneousHalfSpace *>(elastic.get()),
                ExcMessage("Discretization/Flexibility = collocation is the "
                           "paper's closed-form operator of the homogeneous "
                           "half-space; with Foundation/Model = " +
                           elastic->name() + " use galerkin."));
    const SurfaceKernel kernel = elastic->kernel(maximal_distance(space));
    const double        alpha  = kernel.alpha;
    build_mass_matrix(space, cell_in_foundation);
    use_identity_test_coupling();
    const unsigned int n = space.n_nodes();
    flexibility.reinit(n);
    flexibility = 0.;

    // The paper's subdivision (Figure 2): 3x3 sub-rectangles around the
    // 3-point Gauss points; with the weights 5/9, 8/9, 5/9 their bounds in
    // xi are -1, -4/9, 4/9, 1, i.e. 0, 5/18, 13/18, 1 on [0,1].
    const double bounds[4]   = {0., 5. / 18., 13. / 18., 1.};
    const double g           = 0.5 * std::sqrt(3. / 5.);
    const auto   reflections = space.symmetry.reflections();
    const double gauss[3]    = {0.5 - g, 0.5, 0.5 + g};

    for (unsigned int c = 0; c < space.cells.size(); ++c)
      {
        if (!cell_in_foundation.empty() && !cell_in_foundation[c])
          continue;
        const FoundationSpace::Cell &cell = space.cells[c];
        AssertThrow(cell.geometry.is_axis_aligned_rectangle(),
                    ExcMessage(
                      "Discretization/Flexibility = collocation needs "
                      "axis-aligned rectangular cells (the paper's "
                      "closed-form integral (P5)); this mesh has another "
                      "cell shape: use Flexibility = galerkin."));
        // The reference x axis may run along -x for a mirrored cell: map the
        // reference bounds through the cell's own map.
        for (unsigned int kx = 0; kx < 3; ++kx)
          for (unsigned int ky = 0; ky < 3; ++ky)
            {
              const Point<2> lo =
                cell.geometry.map(Point<2>(bounds[kx], bounds[ky]));
              const Point<2> hi =
                cell.geometry.map(Point<2>(bounds[kx + 1], bounds[ky + 1]));
              const double x1 = std::min(lo[0], hi[0]),
                           x2 = std::max(lo[0], hi[0]),
                           y1 = std::min(lo[1], hi[1]),
                           y2 = std::max(lo[1], hi[1]);
              // q_Gk = sum_i N_i(xi_Gk) q_i (P6), expanded to the nodes.
              const auto phi = q2_shape_values(Point<2>(gauss[kx], gauss[ky]));
              std::vector<std::pair<unsigned int, double>> pressure_weights;
              for (unsigned int i = 0; i < 9; ++i)
                for (const auto &t : cell.expansion[i])
                  pressure_weights.emplace_back(t.first, t.second * phi[i]);
              // G_ji += alpha I_Gk(x_j) N_i(xi_Gk)  (P7)-(P9). A symmetric
              // scene (mirror_symmetry.h) adds the settlement under the
              // mirror images R of the sub-rectangle, I_{R Gk}(x_j) =
              // I_Gk(R x_j).
              for (unsigned int j = 0; j < n; ++j)
                {
                  const Point<2> &x = space.node_locations[j];
                  double          integral =
                    alpha * integral_of_inverse_distance_over_rectangle(
                              x, x1, x2, y1, y2);
                  for (const auto &signs : reflections)
                    integral +=
                      alpha * integral_of_inverse_distance_over_rectangle(
                                Point<2>(signs[0] * x[0], signs[1] * x[1]),
                                x1,
                                x2,
                                y1,
                                y2);
                  for (const auto &pw : pressure_weights)
                    flexibility(j, pw.first) += integral * pw.second;
                }
            }
      }
  }

  void
  BoussinesqCollocationOperator::apply(const Vector<double> &q,
                                       Vector<double>       &s) const
  {
    s.reinit(q.size());
    flexibility.vmult(s, q);
  }

  void
  BoussinesqCollocationOperator::copy_block(
    const std::vector<unsigned int> &nodes,
    LAPACKFullMatrix<double>        &block) const
  {
    copy_dense_block(flexibility, nodes, block);
  }

  std::size_t
  BoussinesqCollocationOperator::memory_consumption() const
  {
    return flexibility.memory_consumption() + coupling_memory_consumption();
  }
} // namespace PlateOnHalfspace
