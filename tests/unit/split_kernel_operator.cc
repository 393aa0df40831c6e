// The split-kernel FFT storage (Foundation operator/Storage = fft,
// split_kernel_operator.h; doc/formulation.md, "Split-kernel FFT storage")
// against the dense Galerkin flexibility A, assembled entry by entry with
// the whole kernel alpha / r (the independent reference):
//  - the paper's 12 m x 8 m rectangle (24 x 16 cells, whole), the disk of
//    rigid-disk.prm (3 refinements, general quadrilaterals), the flexible
//    square as a quarter (mirror images in the kernel: the cosine
//    transforms on the quarter), the rectangle's half below y = 0's
//    mirror plane (the image in one line), the distorted
//    Gmsh square (tests/data/distorted-square.msh), a graded mesh (the
//    rectangle refined twice towards a corner, hanging nodes, cells of
//    three sizes) and a strongly graded one (seven times, cells of eight
//    sizes, the largest 14 times the split length): the product A x differs
//    from dense by less than the tolerance (relative 2-norm) at 1e-4 and at the
//    default 1e-6, for a smooth pressure and one with node-to-node parts;
//  - the product is symmetric: y^T A x = x^T A y to 1e-12;
//  - on the meshes of equal cells (rectangle, quarter square) more than
//    half the near pairs take the block of an earlier translate, so the
//    product checks cover the shared blocks;
//  - a uniform pressure on the rectangle: the weak settlement within 1e-5
//    of the closed-form integral of 1/|x - y| over the rectangle, and no
//    further from it than dense's (both carry the singular pairs'
//    quadrature error);
//  - the diagonal of T^T A T for the plate-on-springs preconditioner lies
//    within 10 % of the dense operator's (measured: 2 %);
//  - the approximate inverse (the soil-inverse preconditioner, the
//    fractional Laplacian) lets CG recover a pressure from its settlement
//    to 1e-6 within 40 iterations (measured 14 to 23 on the other six meshes).


#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>
#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/halfspace/split_kernel_operator.h>
#include <plate_on_halfspace/soil/boussinesq_kernel.h>
#include <plate_on_halfspace/soil/half_space.h>

#include <cmath>
#include <memory>

#include "../tests.h"

#include "../foundation_scene.h"

using namespace PlateOnHalfspace;

namespace
{
  using Scene = TestTools::FoundationScene;

  Vector<double>
  rough_vector(const unsigned int n)
  {
    Vector<double> x(n);
    for (unsigned int i = 0; i < n; ++i)
      x[i] = 1. + std::cos(0.37 * i) + 0.3 * std::sin(2.1 * i * i);
    return x;
  }

  /** A smooth pressure: a bump over the plate's nodes. */
  Vector<double>
  smooth_vector(const FoundationSpace &space)
  {
    Vector<double> x(space.n_nodes());
    for (unsigned int i = 0; i < x.size(); ++i)
      {
        const Point<2> &p = space.node_locations[i];
        x[i] = 1. + 0.5 * std::cos(0.4 * p[0]) * std::sin(0.3 * p[1]);
      }
    return x;
  }

  /** A x with the operator's apply on nodal values. */
  class ValuesOperator
  {
  public:
    explicit ValuesOperator(const SplitKernelFftOperator &op)
      : op(op)
    {}
    void
    vmult(Vector<double> &y, const Vector<double> &x) const
    {
      op.apply_to_values(x, y);
    }

  private:
    const SplitKernelFftOperator &op;
  };

  void
  compare(const std::string &name, const Scene &scene)
  {
    BoussinesqGalerkinOperator dense(scene.alpha,
                                     scene.singular_order,
                                     false); // the plain A
    dense.build(scene.space, {});
    const unsigned int n = scene.space.n_nodes();
    deallog << name << ": " << n << " foundation nodes" << std::endl;
    const auto soil =
      std::make_shared<HomogeneousHalfSpace>(scene.alpha, scene.singular_order);
    for (const double tolerance : {1e-4, 1e-6})
      {
        SplitKernelFftOperator fft(soil, tolerance);
        fft.build(scene.space, {});
        double worst = 0;
        for (const Vector<double> &x :
             {rough_vector(n), smooth_vector(scene.space)})
          {
            Vector<double> y_dense(n), y_fft;
            dense.flexibility_matrix().vmult(y_dense, x);
            fft.apply_to_values(x, y_fft);
            worst = std::max(worst, relative_difference(y_fft, y_dense));
          }
        std::ostringstream label;
        label << name << ", tolerance " << tolerance
              << ": product error below the tolerance";
        require(label.str(), worst < tolerance);
      }

    SplitKernelFftOperator fft(soil, 1e-6);
    fft.build(scene.space, {});
    const Vector<double> x = rough_vector(n), y = smooth_vector(scene.space);
    Vector<double>       ax, ay;
    fft.apply_to_values(x, ax);
    fft.apply_to_values(y, ay);
    require(name + ": symmetric",
            std::abs(y * ax - x * ay) < 1e-12 * std::abs(y * ax));
    // The near field's translates (split_kernel_operator.cc): most pairs
    // of a mesh of equal cells repeat an earlier pair's block, which the
    // product checks above have verified.
    if (name == "rectangle" || name == "quarter square")
      require(name + ": most near pairs take a translate's block",
              fft.layout().translated_pairs > 0.5 * fft.layout().near_pairs);

    // The diagonal in the positive pressure basis against T^T A T's.
    {
      BoussinesqGalerkinOperator dense_basis(scene.alpha, scene.singular_order);
      dense_basis.build(scene.space, {});
      const Vector<double> diagonal = fft.flexibility_diagonal();
      double               low = 1e300, high = 0;
      for (unsigned int i = 0; i < n; ++i)
        {
          const double ratio =
            diagonal[i] / dense_basis.flexibility_matrix()(i, i);
          low  = std::min(low, ratio);
          high = std::max(high, ratio);
        }
      require(name + ": diagonal within 10 % of dense's",
              low > 0.9 && high < 1.1);

      // The approximate inverse preconditions CG on F q = s (F = T^T A T).
      const auto inverse = fft.make_approximate_inverse();
      struct Flexibility
      {
        const SplitKernelFftOperator &op;
        void
        vmult(Vector<double> &out, const Vector<double> &in) const
        {
          op.apply(in, out);
        }
      } flexibility{fft};
      struct Preconditioner
      {
        const ApproximateInverse &inverse;
        void
        vmult(Vector<double> &out, const Vector<double> &in) const
        {
          inverse.vmult(out, in);
        }
      } preconditioner{*inverse};
      Vector<double> s(n), q(n);
      fft.apply(smooth_vector(scene.space), s);
      // no log: its iteration count and residuals depend on the BLAS
      // kernel's rounding
      // 1e-12: the strongly graded mesh's A is ill-conditioned enough that
      // a residual of 1e-10 leaves q's error near 1e-5
      SolverControl            control(40, 1e-12 * s.l2_norm(), false, false);
      SolverCG<Vector<double>> cg(control);
      try
        {
          cg.solve(flexibility, q, s, preconditioner);
        }
      catch (const SolverControl::NoConvergence &)
        {
          // q as far as it got: the check below fails
        }
      q -= smooth_vector(scene.space);
      require(name + ": preconditioned CG recovers q to 1e-6 within 40 "
                     "iterations",
              q.l2_norm() < 1e-6 * smooth_vector(scene.space).l2_norm());
    }
  }
  /**
   * The weak settlement s_i = ∫ psi_i u of a uniform pressure 1 on the
   * whole rectangle of @p scene (no mirror images): u(x) = alpha times the
   * closed-form integral of 1/|x - y| over the rectangle, s_i by 10 x 10
   * Gauss points per cell. Independent of every cell-pair rule.
   */
  Vector<double>
  exact_uniform_settlement(const Scene &scene)
  {
    const FoundationSpace &space = scene.space;
    Point<2>               low = space.node_locations[0], high = low;
    for (const Point<2> &p : space.node_locations)
      for (unsigned int d = 0; d < 2; ++d)
        {
          low[d]  = std::min(low[d], p[d]);
          high[d] = std::max(high[d], p[d]);
        }
    const CellPairIntegrator integrator(space.cells, scene.singular_order);
    const QGauss<2>          rule(24);
    Vector<double>           s(space.n_nodes());
    std::vector<Point<2>>    points;
    std::vector<double>      weighted;
    for (unsigned int c = 0; c < space.cells.size(); ++c)
      {
        integrator.tabulate(c, rule, points, weighted);
        const auto &nodes = integrator.nodes(c);
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            const double u =
              scene.alpha * integral_of_inverse_distance_over_rectangle(
                              points[q], low[0], high[0], low[1], high[1]);
            for (unsigned int a = 0; a < nodes.size(); ++a)
              s[nodes[a]] += weighted[q * nodes.size() + a] * u;
          }
      }
    return s;
  }

  double
  max_relative_difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> d(a);
    d -= b;
    return d.linfty_norm() / b.linfty_norm();
  }
} // namespace

int
main()
{
  initlog();
  compare("rectangle",
          TestTools::make_foundation_scene(
            "example2-bonded.prm",
            "subsection Discretization\n set Subdivisions x = 24\n"
            " set Subdivisions y = 16\n set Symmetry = none\nend\n"));
  {
    // The uniform pressure on the rectangle against the closed form.
    const Scene rectangle = TestTools::make_foundation_scene(
      "example2-bonded.prm",
      "subsection Discretization\n set Subdivisions x = 24\n"
      " set Subdivisions y = 16\n set Symmetry = none\nend\n");
    const Vector<double> exact = exact_uniform_settlement(rectangle);
    const unsigned int   n     = rectangle.space.n_nodes();
    Vector<double>       ones(n), dense_s(n), fft_s;
    ones = 1.;
    BoussinesqGalerkinOperator dense(rectangle.alpha,
                                     rectangle.singular_order,
                                     false);
    dense.build(rectangle.space, {});
    dense.flexibility_matrix().vmult(dense_s, ones);
    SplitKernelFftOperator fft(std::make_shared<HomogeneousHalfSpace>(
                                 rectangle.alpha, rectangle.singular_order),
                               1e-6);
    fft.build(rectangle.space, {});
    fft.apply_to_values(ones, fft_s);
    // Both differ from the closed form by the singular pairs' quadrature
    // (Discretization/Singular quadrature order), measured 2.6e-6 (dense)
    // and 2.3e-6 (fft) at the largest node.
    require("rectangle, uniform pressure: settlement within 1e-5 of the "
            "closed form",
            max_relative_difference(fft_s, exact) < 1e-5);
    require("rectangle, uniform pressure: as close as dense's",
            max_relative_difference(fft_s, exact) <
              1.5 * max_relative_difference(dense_s, exact));
  }
  compare("disk",
          TestTools::make_foundation_scene(
            "rigid-disk.prm",
            "subsection Discretization\n set Initial refinements = "
            "3\n set Symmetry = none\nend\n"));
  const Scene quarter = TestTools::make_foundation_scene(
    "flexible-square.prm",
    "subsection Discretization\n set Flexibility = galerkin\n"
    " set Subdivisions x = 32\n set Subdivisions y = 32\n"
    " set Symmetry = xy\nend\n");
  AssertThrow(quarter.space.symmetry.n_copies() == 4,
              ExcMessage("the square must be computed as a quarter"));
  compare("quarter square", quarter);
  // one mirror plane: the whole grid's FFT with the image added
  compare("half rectangle",
          TestTools::make_foundation_scene(
            "example2-bonded.prm",
            "subsection Discretization\n set Subdivisions x = 24\n"
            " set Subdivisions y = 16\n set Symmetry = y\nend\n"));
  compare("gmsh square",
          TestTools::make_foundation_scene(
            "flexible-square.prm",
            "subsection Plate\n set Shape = mesh file\n set Mesh "
            "file = " SOURCE_DIR "/../data/distorted-square.msh\n"
            "end\nsubsection Discretization\n set Flexibility = "
            "galerkin\n set Initial refinements = 2\n set Symmetry "
            "= none\nend\n"));
  compare("graded rectangle",
          TestTools::make_foundation_scene(
            "example2-bonded.prm",
            "subsection Discretization\n set Subdivisions x = 12\n"
            " set Subdivisions y = 8\n set Symmetry = none\nend\n",
            4.));
  // Cells from 2 m down to 2 m / 128: the largest about 14 sigma wide, so
  // their touching pairs need the composite rule of integrate_smooth().
  compare("strongly graded rectangle",
          TestTools::make_foundation_scene(
            "example2-bonded.prm",
            "subsection Discretization\n set Subdivisions x = 6\n"
            " set Subdivisions y = 4\n set Symmetry = none\nend\n",
            2.,
            7));
}
