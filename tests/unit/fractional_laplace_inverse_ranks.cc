// The fractional soil inverse shared out over several processes by its
// poles (halfspace/fractional_laplace_inverse.h; doc/parallel.md, "The
// soil inverse by its poles"), on 3 processes and on 9 (NAME.mpirun=3 and
// NAME.mpirun=9; the rules here have 2 to 4 poles, so 9 ranks leave some
// with no part):
//  - part_owners(), for 1 to 16 poles on 1 to 12 ranks: each part goes to
//    one rank, the ranks' solves (a pole one, the mass chain two) differ
//    by at most two;
//  - on the quarter of the flexible square (mirror images) and a graded
//    rectangle (hanging nodes): each part's factor is held by exactly one
//    rank (the factors held sum to one process's), no rank holds more
//    than n_factors_on_a_rank() of the cells' eigenvalue bound, and none
//    more memory than one process's inverse;
//  - the product of the shared inverse with three vectors (smooth,
//    oscillating, one node) equals one process's to 1e-13 of its largest
//    entry (the ranks' parts are summed in another order), and every rank
//    holds the same bits (the contact decisions of the ranks must agree);
//  - under a memory limit of 1 KiB every rank refuses with
//    StorageDoesNotFit.
// The verdicts only are printed: the differences are rounding.

#include <deal.II/base/mpi.h>

#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/halfspace/fractional_laplace_inverse.h>
#include <plate_on_halfspace/halfspace/memory_guard.h>

#include <algorithm>
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

  void
  check_part_owners()
  {
    bool one_owner = true, balanced = true;
    for (unsigned int n_poles = 1; n_poles <= 16; ++n_poles)
      for (unsigned int n_ranks = 1; n_ranks <= 12; ++n_ranks)
        {
          const std::vector<unsigned int> owners =
            FractionalLaplaceInverse::part_owners(n_poles, n_ranks);
          one_owner = one_owner && owners.size() == n_poles + 1;
          std::vector<unsigned int> solves(n_ranks, 0), parts(n_ranks, 0);
          for (unsigned int part = 0; part < owners.size(); ++part)
            {
              one_owner = one_owner && owners[part] < n_ranks;
              if (owners[part] >= n_ranks)
                continue;
              solves[owners[part]] += part == n_poles ? 2 : 1;
              ++parts[owners[part]];
            }
          balanced =
            balanced && *std::max_element(solves.begin(), solves.end()) -
                            *std::min_element(solves.begin(), solves.end()) <=
                          2;
        }
    require("part_owners: every part on one rank of the range", one_owner);
    require("part_owners: the ranks' solves differ by at most two", balanced);
  }

  /** Three test vectors on @p n nodes. */
  std::vector<Vector<double>>
  test_vectors(const unsigned int n)
  {
    std::vector<Vector<double>> vectors(3, Vector<double>(n));
    for (unsigned int i = 0; i < n; ++i)
      {
        vectors[0][i] = 1. + 0.5 * std::cos(0.01 * i);
        vectors[1][i] = std::sin(1.7 * i) + 0.2 * std::cos(0.3 * i * i);
      }
    vectors[2][n / 3] = 1.;
    return vectors;
  }

  void
  check_scene(const std::string &name, const Scene &scene)
  {
    const MPI_Comm     world   = MPI_COMM_WORLD;
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(world);
    const TestTools::PressureSpaceMatrices m(scene);
    const FractionalLaplaceInverse         whole(m.mass,
                                         m.laplace,
                                         scene.alpha,
                                         area_with_images(scene),
                                         m.analysis,
                                         MPI_COMM_SELF);
    const FractionalLaplaceInverse         shared(m.mass,
                                          m.laplace,
                                          scene.alpha,
                                          area_with_images(scene),
                                          m.analysis,
                                          world);
    const unsigned int                     n = m.mass.m();
    deallog << name << ": " << n << " nodes on " << n_ranks << " ranks"
            << std::endl;

    const unsigned int held  = shared.n_factors_here();
    const unsigned int bound = FractionalLaplaceInverse::n_factors_on_a_rank(
      area_with_images(scene),
      FractionalLaplaceInverse::largest_eigenvalue_estimate(scene.space),
      n_ranks);
    require(name + ": the factors held over the ranks sum to one "
                   "process's",
            Utilities::MPI::sum(held, world) == whole.n_factors_here() &&
              whole.n_factors_here() == whole.n_poles() + 1);
    require(name + ": no rank holds more factors than the memory "
                   "estimate's count",
            Utilities::MPI::max(held, world) <= bound);
    require(name + ": no rank holds more memory than one process",
            Utilities::MPI::max(shared.memory_consumption() <=
                                    whole.memory_consumption() ?
                                  0u :
                                  1u,
                                world) == 0u);

    double worst = 0, spread = 0;
    for (const Vector<double> &s : test_vectors(n))
      {
        Vector<double> q_whole, q_shared;
        whole.vmult(q_whole, s);
        shared.vmult(q_shared, s);
        Vector<double> difference(q_shared);
        difference -= q_whole;
        worst =
          std::max(worst, difference.linfty_norm() / q_whole.linfty_norm());
        Vector<double> first_rank(q_shared);
        Utilities::MPI::broadcast(first_rank.data(), n, 0, world);
        first_rank -= q_shared;
        spread = std::max(spread, first_rank.linfty_norm());
      }
    worst  = Utilities::MPI::max(worst, world);
    spread = Utilities::MPI::max(spread, world);
    require(name + ": the shared product equals one process's to 1e-13",
            worst <= 1e-13);
    require(name + ": every rank holds the same bits", spread == 0.);
  }

  void
  check_memory_guard(const Scene &scene)
  {
    const TestTools::PressureSpaceMatrices m(scene);
    setenv("PLATE_ON_HALFSPACE_MEMORY_LIMIT", "1K", 1);
    unsigned int refused = 0;
    try
      {
        FractionalLaplaceInverse(m.mass,
                                 m.laplace,
                                 scene.alpha,
                                 area_with_images(scene),
                                 m.analysis,
                                 MPI_COMM_WORLD);
      }
    catch (const StorageDoesNotFit &)
      {
        refused = 1;
      }
    unsetenv("PLATE_ON_HALFSPACE_MEMORY_LIMIT");
    require("memory limit of 1 KiB: every rank refuses with "
            "StorageDoesNotFit",
            Utilities::MPI::min(refused, MPI_COMM_WORLD) == 1u);
  }

} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_first_rank(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);
  check_part_owners();
  check_scene("quarter square", flexible_square_quarter(32));
  check_scene("graded rectangle",
              TestTools::make_foundation_scene(
                "example2-bonded.prm",
                "subsection Discretization\n set Subdivisions x = 12\n"
                " set Subdivisions y = 8\n set Symmetry = none\nend\n",
                4.));
  check_memory_guard(flexible_square_quarter(8));
}
