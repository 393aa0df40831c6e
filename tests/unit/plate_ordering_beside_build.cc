// The plate's K^+ is made in two stages (plate/generalized_inverse.h): the
// symbolic analysis, which the run makes beside the foundation operator's
// build, and the numerical factorisation (doc/performance.md, "The plate's
// ordering beside the operator's build"). This checks that the stages give
// the factor that one call gives, and that two analyses side by side give
// the orderings they give alone: METIS draws from one random generator per
// process, and two orderings interleaving their draws would change the
// factor's rounding with the timing (sparse_cholesky.cc orders one matrix
// at a time).
// - Example 2's free plate on 60 x 40 and 48 x 48 cells (more than 10^4
//   unknowns each, so that SparseCholesky orders by METIS), K^+ f for a
//   load f: the stages against SparseCholesky's one-call factorize(), and
//   both plates analysed side by side (three times) against each alone,
//   bit for bit.
// - An independent check of each: the backward error of K^+ f at the
//   solved DoFs (not constrained, not pinned: those have u_i = 0),
//   max |(K u - f)_i| / (|K| |u| + |f|), below 1e-12.
// - The analysis alone tells the factor's size: factor_bytes() after
//   analyze() equals the numerical factor's memory_consumption().
// - A matrix whose pattern differs from the analysed one (a coupling set
//   to zero, which the factor's matrix drops; and the analysis of that
//   thinned matrix given the full one, whose factor on the thinner
//   structure would lose the coupling) is analysed again, not factorised
//   on the stale structure: its backward error below 1e-12.
// Only verdicts are printed.

#include <deal.II/lac/sparse_matrix.h>

#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/base/tasks.h>
#include <plate_on_halfspace/plate/generalized_inverse.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/plate/plate_mesh.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <cmath>
#include <memory>
#include <numeric>
#include <vector>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  struct Plate
  {
    Plate(const unsigned int nx, const unsigned int ny)
    {
      parameters.read_from_string(
        "include " SOURCE_DIR "/../../parameters/example2-bonded.prm\n"
        "set Output directory = results\n"
        "subsection Discretization\n set Symmetry = none\n"
        " set Subdivisions x = " +
        std::to_string(nx) + "\n set Subdivisions y = " + std::to_string(ny) +
        "\nend\n");
      make_plate_mesh(parameters.plate, parameters.discretization, mesh);
      plate = std::make_unique<MindlinPlate>(parameters.plate,
                                             parameters.discretization);
      plate->setup(mesh);
      load.reinit(plate->get_dof_handler().n_dofs());
      for (unsigned int i = 0; i < load.size(); ++i)
        if (!plate->get_constraints().is_constrained(i))
          load[i] = std::sin(0.37 * i) + 0.5;
    }

    /** K^+ f through @p inverse (factorised). */
    Vector<double>
    response(const PlateGeneralizedInverse &inverse) const
    {
      Vector<double> u;
      inverse.solve(load, u);
      return u;
    }

    /** The backward error at the solved DoFs: max |(K u - f)_i| over
     *  |K| |u| + |f| (max norms), a few eps for a stable solve whatever
     *  K's condition. */
    double
    residual(const SparseMatrix<double> &k, const Vector<double> &u) const
    {
      Vector<double> ku(u.size());
      k.vmult(ku, u);
      double largest = 0;
      for (unsigned int i = 0; i < u.size(); ++i)
        if (!plate->get_constraints().is_constrained(i) && u[i] != 0.)
          largest = std::max(largest, std::abs(ku[i] - load[i]));
      return largest / (k.linfty_norm() * u.linfty_norm() + load.linfty_norm());
    }

    SceneParameters               parameters;
    Triangulation<2>              mesh;
    std::unique_ptr<MindlinPlate> plate;
    Vector<double>                load;
  };

  bool
  same_bits(const Vector<double> &a, const Vector<double> &b)
  {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }

  /** The unconstrained DoFs of @p plate. */
  std::vector<types::global_dof_index>
  unconstrained(const MindlinPlate &plate)
  {
    std::vector<types::global_dof_index> rows;
    for (types::global_dof_index i = 0; i < plate.get_dof_handler().n_dofs();
         ++i)
      if (!plate.get_constraints().is_constrained(i))
        rows.push_back(i);
    return rows;
  }
} // namespace

int
main()
{
  initlog();
  const Plate first(60, 40), second(48, 48);
  // SparseCholesky orders by METIS from 10^4 unknowns on
  check_greater("unknowns of the first plate",
                unconstrained(*first.plate).size(),
                10000);
  check_greater("unknowns of the second plate",
                unconstrained(*second.plate).size(),
                10000);

  // each alone, the stages one after the other
  std::vector<Vector<double>> alone;
  for (const Plate *p : {&first, &second})
    {
      PlateGeneralizedInverse inverse(*p->plate);
      inverse.factorize();
      alone.push_back(p->response(inverse));
      check_below("backward error of K^+ f at the solved DoFs",
                  p->residual(p->plate->get_stiffness_matrix(), alone.back()),
                  1e-12);
    }

  // side by side, three times: the same bits as alone
  bool side_by_side_same = true;
  for (unsigned int round = 0; round < 3; ++round)
    {
      std::unique_ptr<PlateGeneralizedInverse> inverses[2];
      run_tasks(2, [&](const unsigned int t) {
        inverses[t] = std::make_unique<PlateGeneralizedInverse>(
          *(t == 0 ? first : second).plate);
      });
      for (unsigned int t = 0; t < 2; ++t)
        {
          inverses[t]->factorize();
          side_by_side_same =
            side_by_side_same &&
            same_bits((t == 0 ? first : second).response(*inverses[t]),
                      alone[t]);
        }
    }
  require("K^+ f of two plates analysed side by side, bit for bit as alone",
          side_by_side_same);

  // SparseCholesky: analyze() then factorize() against factorize() alone
  const SparseMatrix<double> &k = first.plate->get_stiffness_matrix();
  const std::vector<types::global_dof_index> rows = unconstrained(*first.plate);
  // the free plate's block is singular (its rigid motions): shift it
  SparseMatrix<double> shifted(k.get_sparsity_pattern());
  shifted.copy_from(k);
  const double diagonal_shift = 1e-3 * shifted.diag_element(rows[0]);
  for (const auto i : rows)
    shifted.diag_element(i) += diagonal_shift;
  const auto solve = [&](const SparseCholesky &factor) {
    std::vector<double> block(rows.size());
    for (unsigned int c = 0; c < rows.size(); ++c)
      block[c] = first.load[rows[c]];
    factor.solve(block, 1);
    Vector<double> u(first.load.size());
    for (unsigned int c = 0; c < rows.size(); ++c)
      u[rows[c]] = block[c];
    return u;
  };
  SparseCholesky one_call("the shifted plate");
  one_call.factorize(shifted, rows);
  SparseCholesky staged("the shifted plate");
  staged.analyze(shifted, rows);
  const std::size_t announced = staged.factor_bytes();
  staged.factorize(shifted, rows);
  require("analyze() then factorize(), bit for bit as factorize() alone",
          same_bits(solve(staged), solve(one_call)));
  require("factor_bytes() after analyze() = the factor's memory",
          announced > 0 && announced == staged.memory_consumption() &&
            announced == one_call.memory_consumption());
  check_below("backward error of the shifted plate's solve",
              first.residual(shifted, solve(staged)),
              1e-12);

  // another pattern than the analysed one: one coupling set to zero
  SparseMatrix<double> thinned(k.get_sparsity_pattern());
  thinned.copy_from(shifted);
  types::global_dof_index i = rows[rows.size() / 2], j = i;
  for (auto e = thinned.begin(i); e != thinned.end(i); ++e)
    if (e->column() != i && e->value() != 0. &&
        !first.plate->get_constraints().is_constrained(e->column()))
      {
        j = e->column();
        break;
      }
  require("a coupling to remove found", j != i);
  // the diagonal keeps the thinned matrix positive definite
  thinned.diag_element(i) += std::abs(thinned.el(i, j));
  thinned.diag_element(j) += std::abs(thinned.el(i, j));
  thinned.set(i, j, 0.);
  thinned.set(j, i, 0.);
  SparseCholesky stale("the thinned plate");
  stale.analyze(shifted, rows);
  stale.factorize(thinned, rows);
  check_below("backward error of the thinned plate's solve on a stale analysis",
              first.residual(thinned, solve(stale)),
              1e-12);
  // the other way: the analysis lacks a coupling of the matrix, whose
  // factor on that structure would drop it
  SparseCholesky lacking("the shifted plate");
  lacking.analyze(thinned, rows);
  lacking.factorize(shifted, rows);
  check_below("backward error of the shifted plate's solve on an analysis "
              "without one of its couplings",
              first.residual(shifted, solve(lacking)),
              1e-12);
}
