// The hierarchical (H-matrix) Galerkin flexibility against the dense one
// (doc/formulation.md, "Default variant": A_ij = alpha ∫∫ φ_i φ_j / |x - y|),
// which BoussinesqGalerkinOperator assembles entry by entry; the dense
// matrix is the independent reference here.
//  - three meshes large enough for admissible (low-rank) blocks: the
//    paper's 12 m x 8 m rectangle (example2-bonded.prm, 24 x 16 cells),
//    the disk of rigid-disk.prm (3 refinements, curved boundary, general
//    quadrilaterals) and the flexible square computed as a quarter
//    (mirror images in the kernel, mirror_symmetry.h): the product A x and
//    the solve A^{-1} b differ from dense by less than the tolerance
//    (relative 2-norms, at the default 1e-6);
//  - a tolerance sweep 1e-2 ... 1e-8 on the rectangle: the product error
//    falls with the tolerance and stays below it;
//  - an absurd tolerance (1, the largest the parameter allows) and
//    tolerances outside (0, 1] stop with a message naming Foundation
//    operator/Tolerance instead of returning a wrong matrix.


#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/halfspace/hierarchical_flexibility.h>
#include <plate_on_halfspace/soil/boussinesq_kernel.h>

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "../tests.h"

#include "../foundation_scene.h"

using namespace PlateOnHalfspace;

namespace
{
  using Scene = TestTools::FoundationScene;

  /** A vector with smooth and node-to-node parts (no special structure). */
  Vector<double>
  test_vector(const unsigned int n)
  {
    Vector<double> x(n);
    for (unsigned int i = 0; i < n; ++i)
      x[i] = 1. + std::cos(0.37 * i) + 0.3 * std::sin(2.1 * i * i);
    return x;
  }

  /** The dense A of the scene (BoussinesqGalerkinOperator's build). */
  LAPACKFullMatrix<double>
  dense_flexibility(const Scene &scene)
  {
    BoussinesqGalerkinOperator dense(scene.alpha,
                                     scene.singular_order,
                                     false); // the plain A
    dense.build(scene.space, {});
    return dense.flexibility_matrix();
  }

  struct Errors
  {
    double product;
    double solve;
  };

  /** Product and solve of the H-matrix at @p tolerance against dense. */
  Errors
  compare(const std::string              &name,
          const Scene                    &scene,
          const LAPACKFullMatrix<double> &dense,
          const double                    tolerance,
          const bool                      print)
  {
    HierarchicalFlexibility::Settings settings;
    settings.tolerance = tolerance;
    // The factor at the same tolerance, so that the solve is compared
    // with dense (by default the factor, a preconditioner, is coarser).
    settings.factor_tolerance = tolerance;
    HierarchicalFlexibility hierarchical(settings);
    hierarchical.build(scene.space, scene.alpha, scene.singular_order);
    hierarchical.factorize();

    const unsigned int   n = scene.space.n_nodes();
    const Vector<double> x = test_vector(n);
    Vector<double>       y_dense(n), y_hierarchical;
    dense.vmult(y_dense, x);
    hierarchical.vmult(y_hierarchical, x);

    LAPACKFullMatrix<double> factor(dense);
    factor.compute_cholesky_factorization();
    Vector<double> q_dense(x), q_hierarchical;
    factor.solve(q_dense);
    hierarchical.solve(q_hierarchical, x);

    const Errors errors{relative_difference(y_hierarchical, y_dense),
                        relative_difference(q_hierarchical, q_dense)};
    if (print)
      {
        deallog << name << ": " << n << " foundation nodes, "
                << hierarchical.n_low_rank_blocks() << " low-rank and "
                << hierarchical.n_full_blocks() << " full blocks" << std::endl;
        require(name + ": some blocks are low-rank",
                hierarchical.n_low_rank_blocks() > 0);
        require(name + ": stores less than 80 % of n^2 entries",
                hierarchical.compression_ratio() < 0.8);
        require(name + ": product error below the tolerance",
                errors.product < tolerance);
        // The solve inherits the product's error times the condition
        // number of A (1e2 ... 1e3 on these meshes).
        require(name + ": solve error below 1e3 x the tolerance",
                errors.solve < 1e3 * tolerance);
        require(name + ": sampled row error below 10 x the tolerance",
                hierarchical.sampled_row_error() < 10 * tolerance);
      }
    return errors;
  }

  /**
   * Run @p action, which must throw a message containing @p expected;
   * print the message from there up to " by " (a measured number follows)
   * or its end.
   */
  template <typename Action>
  void
  expect_failure(const std::string &name,
                 const std::string &expected,
                 const Action      &action)
  {
    std::string message;
    try
      {
        action();
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        // one line, single spaces
        std::istringstream words(info.str());
        for (std::string word; words >> word;)
          message += (message.empty() ? "" : " ") + word;
      }
    const std::size_t at = message.find(expected);
    AssertThrow(at != std::string::npos,
                ExcMessage(name + ": expected an error naming <" + expected +
                           ">, got <" + message + ">"));
    deallog << name << ": " << message.substr(at, message.find(" by ", at) - at)
            << std::endl;
  }
} // namespace

int
main()
{
  initlog();

  const Scene rectangle = TestTools::make_foundation_scene(
    "example2-bonded.prm",
    "subsection Discretization\n set Subdivisions x = 24\n"
    " set Subdivisions y = 16\n set Symmetry = none\nend\n");
  const LAPACKFullMatrix<double> rectangle_dense = dense_flexibility(rectangle);
  compare("rectangle", rectangle, rectangle_dense, 1e-6, true);

  {
    const Scene disk = TestTools::make_foundation_scene(
      "rigid-disk.prm",
      "subsection Discretization\n set Initial refinements = 3\n"
      " set Symmetry = none\nend\n");
    compare("disk", disk, dense_flexibility(disk), 1e-6, true);
  }
  {
    const Scene quarter = TestTools::make_foundation_scene(
      "flexible-square.prm",
      "subsection Discretization\n set Flexibility = galerkin\n"
      " set Subdivisions x = 48\n set Subdivisions y = 48\n"
      " set Symmetry = xy\nend\n");
    AssertThrow(quarter.space.symmetry.n_copies() == 4,
                ExcMessage("the square must be computed as a quarter"));
    compare("quarter square", quarter, dense_flexibility(quarter), 1e-6, true);
  }

  // The tolerance sweep: each hundredfold tighter tolerance gives a
  // smaller difference from dense.
  double previous = std::numeric_limits<double>::infinity();
  for (const double tolerance : {1e-2, 1e-4, 1e-6, 1e-8})
    {
      const Errors errors =
        compare("sweep", rectangle, rectangle_dense, tolerance, false);
      std::ostringstream name;
      name << "tolerance " << tolerance;
      require(name.str() + ": product error below the tolerance",
              errors.product < tolerance);
      require(name.str() + ": product error below the previous one",
              errors.product < previous);
      previous = errors.product;
    }

  // A factor tolerance at which the factor is useless (every block
  // recompressed to nothing): factorize() makes it again finer.
  {
    HierarchicalFlexibility::Settings settings;
    settings.tolerance        = 1e-6;
    settings.factor_tolerance = 1.;
    HierarchicalFlexibility hierarchical(settings);
    hierarchical.build(rectangle.space,
                       rectangle.alpha,
                       rectangle.singular_order);
    hierarchical.factorize();
    require("factor tolerance 1: the factor is made again finer",
            hierarchical.factor_tolerance() < 1.);
    require("factor tolerance 1: the final factor solves the test system "
            "to 1e-2",
            hierarchical.factorization_residual() <= 1e-2);
  }

  // Failures: a clear message, no matrix.
  expect_failure("tolerance 1", "Foundation operator/Tolerance", [&]() {
    HierarchicalFlexibility::Settings settings;
    settings.tolerance = 1.;
    HierarchicalFlexibility hierarchical(settings);
    hierarchical.build(rectangle.space,
                       rectangle.alpha,
                       rectangle.singular_order);
    hierarchical.factorize();
  });
  for (const double tolerance :
       {0., -1e-6, 2., std::numeric_limits<double>::quiet_NaN()})
    expect_failure("tolerance out of range",
                   "Foundation operator/Tolerance must lie in (0, 1]",
                   [&]() {
                     HierarchicalFlexibility::Settings settings;
                     settings.tolerance = tolerance;
                     HierarchicalFlexibility hierarchical(settings);
                   });
}
