// The fractional soil inverse B ≈ F^{-1} of Storage = fft
// (halfspace/fractional_laplace_inverse.h; doc/formulation.md, "Fractional
// soil inverse"), against independent dense computations:
//  - its rule against the exact power: with the generalized eigenpairs
//    A x = lambda M x (LAPACK, M-orthonormal), 2 pi alpha x^T M B M x lies
//    within 8 % of sqrt(lambda) for every pair (the rule's own bound: 7 %,
//    the fewest Zolotarev poles that keep it), and B M x
//    is parallel to x to 1e-8 (B is a function of M^{-1} A: measured
//    3e-13), on the quarter of the flexible square (mirror images) and a
//    graded rectangle (hanging nodes);
//  - as the preconditioner of the dense Galerkin flexibility F (the whole
//    kernel alpha / r, entry by entry): the extreme generalized eigenvalues
//    of F x = mu B^{-1} x bound the condition number of B F below 4 on the
//    rectangle of example 2 at 12 x 8 and 24 x 16 cells, and the quarter
//    square at 16 x 16 and 32 x 32 (measured 2.60, 2.74, 2.64, 2.80), and
//    refining once raises it by at most 10 % (measured 5 % and 6 %);
//  - the fft storage's memory estimate: the cells' bound on the largest
//    eigenvalue of M^{-1} L lies between the exact one (LAPACK) and four
//    times it, and the factor count it implies covers the factors made;
//  - under a memory limit of 1 KiB the constructor refuses with
//    StorageDoesNotFit before allocating the poles' factors;
//  - SparseCholesky's shared analysis: a factor made on it solves a band
//    matrix like the matrix's own factor (1e-14), and a matrix with
//    entries outside the analysed pattern is refused.

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/halfspace/fractional_laplace_inverse.h>
#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/halfspace/memory_guard.h>

#include <cmath>
#include <cstdlib>

#include "../tests.h"

#include "../foundation_scene.h"

using namespace PlateOnHalfspace;

namespace
{
  using Scene = TestTools::FoundationScene;

  using TestTools::area_with_images;
  using TestTools::flexible_square_quarter;

  /** M and L on the scene's nodes, and B from them. */
  struct Setup : TestTools::PressureSpaceMatrices
  {
    explicit Setup(const Scene &scene)
      : PressureSpaceMatrices(scene)
      , inverse(
          std::make_unique<FractionalLaplaceInverse>(mass,
                                                     laplace,
                                                     scene.alpha,
                                                     area_with_images(scene),
                                                     analysis))
    {}

    std::unique_ptr<FractionalLaplaceInverse> inverse;
  };

  LAPACKFullMatrix<double>
  dense(const SparseMatrix<double> &matrix)
  {
    LAPACKFullMatrix<double> full(matrix.m(), matrix.n());
    for (unsigned int i = 0; i < matrix.m(); ++i)
      for (auto e = matrix.begin(i); e != matrix.end(i); ++e)
        full(i, e->column()) = e->value();
    return full;
  }

  /** B as a dense matrix, column by column. */
  LAPACKFullMatrix<double>
  dense(const FractionalLaplaceInverse &inverse, const unsigned int n)
  {
    LAPACKFullMatrix<double> full(n, n);
    Vector<double>           unit(n), column;
    for (unsigned int j = 0; j < n; ++j)
      {
        unit    = 0.;
        unit[j] = 1.;
        inverse.vmult(column, unit);
        for (unsigned int i = 0; i < n; ++i)
          full(i, j) = column[i];
      }
    return full;
  }

  void
  check_rule(const std::string &name, const Scene &scene)
  {
    const Setup                     m(scene);
    const unsigned int              n       = m.mass.m();
    const FractionalLaplaceInverse &inverse = *m.inverse;
    // A = L + c M with the class's c: the shift only moves the spectrum.
    const double             c = 16. / (M_PI * area_with_images(scene));
    LAPACKFullMatrix<double> a = dense(m.laplace), mass = dense(m.mass);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        a(i, j) += c * mass(i, j);
    std::vector<Vector<double>> eigenvectors(n, Vector<double>(n));
    LAPACKFullMatrix<double>    mass_copy(mass);
    a.compute_generalized_eigenvalues_symmetric(mass_copy, eigenvectors);
    double         worst_value = 0, worst_direction = 0;
    Vector<double> mx(n), bmx;
    for (unsigned int k = 0; k < n; ++k)
      {
        const double          lambda = a.eigenvalue(k).real();
        const Vector<double> &x      = eigenvectors[k];
        m.mass.vmult(mx, x);
        const double norm = std::sqrt(x * mx);
        inverse.vmult(bmx, mx);
        // B M x = sqrt(lambda) x / (2 pi alpha) for the exact power
        const double along = (bmx * mx) / (norm * norm);
        bmx.add(-along, x);
        Vector<double> m_off(n);
        m.mass.vmult(m_off, bmx);
        const double off      = std::sqrt(bmx * m_off) / norm;
        const double expected = std::sqrt(lambda) / (2 * M_PI * scene.alpha);
        worst_value     = std::max(worst_value, std::abs(along / expected - 1));
        worst_direction = std::max(worst_direction, off / expected);
      }
    deallog << name << ": " << n << " nodes" << std::endl;
    require(name + ": x^T M B M x within 8 % of the exact power",
            worst_value < 0.08);
    require(name + ": B M x parallel to x to 1e-8", worst_direction < 1e-8);
    // The storage's memory estimate: the cells' bound on the spectrum and
    // the factor count it implies.
    double largest = 0;
    for (unsigned int k = 0; k < n; ++k)
      largest = std::max(largest, a.eigenvalue(k).real() - c);
    const double estimate =
      FractionalLaplaceInverse::largest_eigenvalue_estimate(scene.space);
    require(name + ": the cells' bound is above the largest eigenvalue "
                   "of M^-1 L and within 4 times it",
            estimate >= largest && estimate <= 4 * largest);
    require(name + ": the memory estimate counts at least the factors made",
            FractionalLaplaceInverse::n_factors(area_with_images(scene),
                                                estimate) >=
              inverse.n_poles() + 1);
  }

  /** The condition number of B F, F the dense Galerkin flexibility. */
  double
  condition_number(const Scene &scene)
  {
    const Setup                     m(scene);
    const unsigned int              n       = m.mass.m();
    const FractionalLaplaceInverse &inverse = *m.inverse;
    BoussinesqGalerkinOperator      flexibility(scene.alpha,
                                           scene.singular_order,
                                           false); // the plain A
    flexibility.build(scene.space, {});
    LAPACKFullMatrix<double> f(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        f(i, j) = flexibility.flexibility_matrix()(i, j);
    LAPACKFullMatrix<double> b_inverse = dense(inverse, n);
    // symmetric to rounding; average the two triangles for LAPACK
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < i; ++j)
        b_inverse(i, j) = b_inverse(j, i) =
          0.5 * (b_inverse(i, j) + b_inverse(j, i));
    b_inverse.invert();
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < i; ++j)
        b_inverse(i, j) = b_inverse(j, i) =
          0.5 * (b_inverse(i, j) + b_inverse(j, i));
    std::vector<Vector<double>> eigenvectors(n, Vector<double>(n));
    f.compute_generalized_eigenvalues_symmetric(b_inverse, eigenvectors);
    double low = std::numeric_limits<double>::max(), high = 0;
    for (unsigned int k = 0; k < n; ++k)
      {
        low  = std::min(low, f.eigenvalue(k).real());
        high = std::max(high, f.eigenvalue(k).real());
      }
    return high / low;
  }

  void
  check_growth(const std::string &name, const Scene &coarse, const Scene &fine)
  {
    const double kappa_coarse = condition_number(coarse),
                 kappa_fine   = condition_number(fine);
    deallog << name << ": " << coarse.space.n_nodes() << " and "
            << fine.space.n_nodes() << " nodes" << std::endl;
    require(name + ": condition number of B F below 4 on both meshes",
            kappa_coarse < 4 && kappa_fine < 4);
    require(name + ": refining raises it by at most 10 %",
            kappa_fine < 1.1 * kappa_coarse);
  }

  /** Under a memory limit below the poles' factors the inverse refuses
   *  with StorageDoesNotFit, which names the bytes and the remedy. */
  void
  check_memory_guard(const Scene &scene)
  {
    const TestTools::PressureSpaceMatrices m(scene);
    setenv("PLATE_ON_HALFSPACE_MEMORY_LIMIT", "1K", 1);
    std::string message;
    try
      {
        FractionalLaplaceInverse(
          m.mass, m.laplace, scene.alpha, area_with_images(scene), m.analysis);
      }
    catch (const StorageDoesNotFit &shortfall)
      {
        message = shortfall.what();
      }
    unsetenv("PLATE_ON_HALFSPACE_MEMORY_LIMIT");
    require("memory limit of 1 KiB: the inverse refuses with "
            "StorageDoesNotFit naming Contact/Preconditioner",
            message.find("Contact/Preconditioner = plate on springs") !=
              std::string::npos);
  }

  /** The shared analysis: a factor on it solves like its own, and a
   *  matrix with another pattern is refused. */
  void
  check_shared_analysis()
  {
    const unsigned int     n = 50;
    DynamicSparsityPattern diagonal(n), band(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        diagonal.add(i, i);
        for (unsigned int j = (i > 0 ? i - 1 : 0); j < std::min(n, i + 2); ++j)
          band.add(i, j);
      }
    SparsityPattern      diagonal_pattern, band_pattern;
    SparseMatrix<double> d, t;
    diagonal_pattern.copy_from(diagonal);
    band_pattern.copy_from(band);
    d.reinit(diagonal_pattern);
    t.reinit(band_pattern);
    for (unsigned int i = 0; i < n; ++i)
      {
        d.set(i, i, 2.);
        t.set(i, i, 4.);
        if (i > 0)
          {
            t.set(i, i - 1, -1.);
            t.set(i - 1, i, -1.);
          }
      }
    SparseCholesky analysis("a band matrix"), shared("a band matrix"),
      own("a band matrix");
    analysis.analyze(t);
    shared.factorize_as(analysis, t);
    own.factorize(t);
    std::vector<double> x(n, 1.), y(n, 1.);
    shared.solve(x, 1);
    own.solve(y, 1);
    double difference = 0;
    for (unsigned int i = 0; i < n; ++i)
      difference = std::max(difference, std::abs(x[i] - y[i]));
    require("shared analysis: the same solution as an own factor to 1e-14",
            difference < 1e-14);
    SparseCholesky diagonal_analysis("a diagonal matrix"),
      refused("a band matrix");
    diagonal_analysis.analyze(d);
    bool thrown = false;
    try
      {
        refused.factorize_as(diagonal_analysis, t);
      }
    catch (const std::exception &)
      {
        thrown = true;
      }
    require("shared analysis: a matrix with entries outside the analysed "
            "pattern is refused",
            thrown);
  }

  Scene
  rectangle(const unsigned int nx, const unsigned int ny)
  {
    return TestTools::make_foundation_scene(
      "example2-bonded.prm",
      "subsection Discretization\n set Subdivisions x = " + std::to_string(nx) +
        "\n set Subdivisions y = " + std::to_string(ny) +
        "\n set Symmetry = none\nend\n");
  }

} // namespace

int
main()
{
  initlog();
  check_rule("quarter square", flexible_square_quarter(32));
  check_rule("graded rectangle",
             TestTools::make_foundation_scene(
               "example2-bonded.prm",
               "subsection Discretization\n set Subdivisions x = 12\n"
               " set Subdivisions y = 8\n set Symmetry = none\nend\n",
               4.));
  check_growth("rectangle", rectangle(12, 8), rectangle(24, 16));
  check_growth("quarter square",
               flexible_square_quarter(16),
               flexible_square_quarter(32));
  check_memory_guard(flexible_square_quarter(8));
  check_shared_analysis();
}
