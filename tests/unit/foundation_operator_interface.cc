// What every half-space operator promises (halfspace/interface.h), checked
// on the dense Galerkin, the collocation and the hierarchical operator
// built on the same foundation space (example 2: 12 x 8 plate, 10 x 10 cells,
// whole plate):
//  - copy_block: a dense storage's own copy equals the interface's default
//    (products with unit vectors) exactly, and the hierarchical block
//    equals the dense Galerkin entries to the compression tolerance;
//  - the couplings: Galerkin B = T^T M is the transpose of the forces'
//    M T, and 1^T B 1 is the footprint's area (T keeps the pressure
//    space, so the constant pressure is still reproduced); collocation
//    tests with B = I;
//  - plate_settlement(w) = B w and gap(w, q) = F q - B w;
//  - make_approximate_inverse: F (F̃^{-1} s) = s to rounding for the dense
//    Cholesky factor, and to the factor's recompression accuracy for the
//    H-Cholesky factor.

#include <deal.II/lac/lapack_full_matrix.h>

#include <plate_on_halfspace/halfspace/collocation_operator.h>
#include <plate_on_halfspace/halfspace/galerkin_operator.h>
#include <plate_on_halfspace/halfspace/hierarchical_operator.h>
#include <plate_on_halfspace/soil/boussinesq_kernel.h>
#include <plate_on_halfspace/soil/half_space.h>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;
using namespace TestTools;

namespace
{
  double
  largest_difference(const LAPACKFullMatrix<double> &a,
                     const LAPACKFullMatrix<double> &b)
  {
    double largest = 0, scale = 0;
    for (unsigned int i = 0; i < a.m(); ++i)
      for (unsigned int j = 0; j < a.n(); ++j)
        {
          largest = std::max(largest, std::abs(a(i, j) - b(i, j)));
          scale   = std::max(scale, std::abs(b(i, j)));
        }
    return largest / scale;
  }

  void
  report(const std::string &name, const double value, const double bound)
  {
    const bool         passed = std::isfinite(value) && value <= bound;
    std::ostringstream b; // the bound as written, 1e-14 not 1.000000000e-14
    b << bound;
    deallog << name << " <= " << b.str() << ": " << (passed ? "ok" : "FAILED")
            << std::endl;
    AssertThrow(passed, ExcMessage(name + ": " + std::to_string(value)));
  }

  /** |F (F̃^{-1} s) - s| / |s| for a smooth s. */
  double
  inverse_residual(FoundationOperator &foundation)
  {
    const unsigned int n = foundation.n_nodes();
    Vector<double>     s(n), q, fq;
    for (unsigned int i = 0; i < n; ++i)
      s[i] = 1. + 0.5 * std::cos(0.37 * i);
    const auto inverse = foundation.make_approximate_inverse();
    inverse->vmult(q, s);
    foundation.apply(q, fq);
    fq -= s;
    return fq.l2_norm() / s.l2_norm();
  }
} // namespace

int
main()
{
  initlog();
  const auto problem =
    solve_scene("example2.prm",
                "subsection Discretization\n set Flexibility = galerkin\n"
                "end\nsubsection Adaptivity\n set Cycles = 1\nend\n");
  const FoundationSpace &space = problem->plate().get_foundation_space();
  const unsigned int     n     = space.n_nodes();
  const double           alpha = boussinesq_flexibility_constant(1e5, 0.3);
  const unsigned int     order = 8; // the default singular order
  deallog << "foundation nodes: " << n << std::endl;

  BoussinesqGalerkinOperator    galerkin(alpha, order);
  BoussinesqCollocationOperator collocation(alpha);
  HierarchicalGalerkinOperator  hierarchical(
    std::make_shared<HomogeneousHalfSpace>(alpha, order), 1e-8);
  galerkin.build(space, {});
  collocation.build(space, {});
  hierarchical.build(space, {});

  // every third node, in reverse order: copy_block keeps the given order
  std::vector<unsigned int> nodes;
  for (unsigned int i = n; i-- > 0;)
    if (i % 3 == 0)
      nodes.push_back(i);
  for (FoundationOperator *foundation :
       std::vector<FoundationOperator *>{&galerkin, &collocation})
    {
      LAPACKFullMatrix<double> own, by_products;
      foundation->copy_block(nodes, own);
      foundation->FoundationOperator::copy_block(nodes, by_products);
      report(std::string(foundation->is_symmetric() ? "galerkin" :
                                                      "collocation") +
               ": copy_block against products with unit vectors",
             largest_difference(own, by_products),
             1e-14);
    }
  {
    LAPACKFullMatrix<double> dense, compressed;
    galerkin.copy_block(nodes, dense);
    hierarchical.copy_block(nodes, compressed);
    report("hierarchical (tolerance 1e-8): copy_block against the dense "
           "Galerkin entries",
           largest_difference(compressed, dense),
           1e-6);
  }

  // Couplings.
  {
    const SparseMatrix<double> &b         = galerkin.test_coupling();
    const SparseMatrix<double> &f         = galerkin.force_coupling();
    double                      asymmetry = 0, area = 0, scale = 0;
    for (unsigned int i = 0; i < n; ++i)
      for (auto entry = b.begin(i); entry != b.end(i); ++entry)
        {
          asymmetry =
            std::max(asymmetry,
                     std::abs(entry->value() - f.el(entry->column(), i)));
          scale = std::max(scale, std::abs(entry->value()));
          area += entry->value();
        }
    report("galerkin: |B - (M T)^T| / max |B|", asymmetry / scale, 1e-15);
    check("galerkin: 1^T B 1 = footprint area 12 x 8", area, 96., 1e-12);
    const SparseMatrix<double> &identity  = collocation.test_coupling();
    double                      deviation = 0;
    for (unsigned int i = 0; i < n; ++i)
      for (auto entry = identity.begin(i); entry != identity.end(i); ++entry)
        deviation =
          std::max(deviation,
                   std::abs(entry->value() - (entry->column() == i ? 1. : 0.)));
    report("collocation: |B - I|", deviation, 0.);
  }

  // plate_settlement and gap.
  {
    Vector<double> w(n), q(n), b(n), by_coupling(n), s(n), gap;
    for (unsigned int i = 0; i < n; ++i)
      {
        w[i] = 1e-3 * (1. + std::sin(0.1 * i));
        q[i] = 10. * (1. + std::cos(0.2 * i));
      }
    galerkin.plate_settlement(w, b);
    galerkin.test_coupling().vmult(by_coupling, w);
    by_coupling -= b;
    report("galerkin: |plate_settlement(w) - B w| / |B w|",
           by_coupling.l2_norm() / b.l2_norm(),
           1e-15);
    galerkin.gap(w, q, gap);
    galerkin.apply(q, s);
    s -= b;
    s -= gap;
    report("galerkin: |gap - (F q - B w)| / |B w|",
           s.l2_norm() / b.l2_norm(),
           1e-15);
  }

  report("galerkin: dense Cholesky, |F F~^-1 s - s| / |s|",
         inverse_residual(galerkin),
         1e-10);
  report("hierarchical: H-Cholesky (recompressed at 1e-3), "
         "|F F~^-1 s - s| / |s|",
         inverse_residual(hierarchical),
         1e-2);
}
