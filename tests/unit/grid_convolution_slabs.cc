// The grid convolution split over several processes by slabs
// (halfspace/grid_convolution.h; doc/parallel.md, "The grid by slabs"), on
// the smooth kernel k(r) = erf(r / s) / r (s = 0.4, grid spacing 0.1) of
// a 2.6 x 1.8 plate, with images in neither line, in x, in y and in both
// (the real FFT, the halves' mixed transforms and the quarter's cosine
// transforms), B-splines of order 4 and 8, on 3 processes and on 9 (the
// same test, NAME.mpirun=3 and NAME.mpirun=9):
//  - each rank spreads its own point charges (some in the other ranks'
//    rows, some within a stencil of the centre lines, so that images and
//    several ranks' charges meet in one row) and reads the potentials on
//    its footprint: they equal one process's convolution of all ranks'
//    charges summed, to 1e-12 of the largest (the slabs transform the
//    same rows and columns; only the sums' order differs);
//  - a second convolution of other charges on the same points holds the
//    same bound (the exchanges' buffers are reused);
//  - every rank holds less than 0.6 of one process's buffers and kernel
//    transform (on 3 ranks a third of each slab, plus the exchanges'
//    buffers);
//  - on a grid of 10 x 10 nodes (5 data rows on the quarter and on the
//    half mirrored in x), 9 ranks leave 4 without data rows, which still
//    take part in the transposes; the same bound holds.
// The verdicts only are printed: the differences are rounding.

#include <deal.II/base/mpi.h>

#include <plate_on_halfspace/halfspace/grid_convolution.h>

#include <cmath>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  constexpr double s = 0.4;

  double
  kernel(const double r)
  {
    return r < 1e-8 ? 2. / (s * std::sqrt(M_PI)) : std::erf(r / s) / r;
  }

  /** Rank @p rank's charges spread onto @p grid (their values vary with
   *  @p round, their points do not) in the rectangle [0, @p width] x
   *  [0, @p height], and the grid nodes its charges and read points reach,
   *  in increasing order. */
  std::pair<Vector<double>, std::vector<unsigned int>>
  rank_charges(const GridConvolution &grid,
               const unsigned int     rank,
               const unsigned int     n_ranks,
               const double           width,
               const double           height,
               const unsigned int     round)
  {
    Vector<double>     field(grid.n_grid_nodes());
    std::vector<bool>  reached(grid.n_grid_nodes(), false);
    const unsigned int nx = grid.grid_sizes()[0], p = grid.order();
    const auto         touch = [&](const Point<2> &x, const double q) {
      const GridConvolution::Stencil st = grid.stencil(x);
      for (unsigned int b = 0; b < p; ++b)
        for (unsigned int a = 0; a < p; ++a)
          {
            const std::size_t g =
              std::size_t(st.first_y + b) * nx + st.first_x + a;
            field[g] += q * st.x[a] * st.y[b];
            reached[g] = true;
          }
    };
    for (unsigned int k = 0; k < 25; ++k)
      {
        const double t = 1.3 * k + 0.7 * rank;
        // mostly in rank's own band of y, every fifth anywhere
        const double v = k % 5 == 0 ?
                           0.5 + 0.5 * std::cos(2.3 * t) :
                           (rank + 0.5 + 0.4 * std::sin(t)) / n_ranks;
        Point<2> x(width * (0.5 + 0.5 * std::sin(1.7 * t + 0.3)), height * v);
        if (k % 7 == 0)
          x[0] = 0.01 * width * (k % 3);
        if (k % 11 == 0)
          x[1] = 0.023 * height * (k % 2);
        touch(x, 1. + 0.5 * std::sin(0.9 * t + 1.1 * round));
      }
    // points read only (zero charge)
    for (unsigned int k = 0; k < 5; ++k)
      touch(Point<2>(0.9 * width * (0.5 + 0.5 * std::cos(k + rank)),
                     0.9 * height * k / 5.),
            0.);
    std::vector<unsigned int> nodes;
    for (unsigned int g = 0; g < reached.size(); ++g)
      if (reached[g])
        nodes.push_back(g);
    return {field, nodes};
  }

  void
  check_variant(const unsigned int           order,
                const std::array<bool, 2>   &mirror,
                const std::array<double, 2> &half_widths,
                const std::string           &grid_name)
  {
    const MPI_Comm     world   = MPI_COMM_WORLD;
    const unsigned int rank    = Utilities::MPI::this_mpi_process(world),
                       n_ranks = Utilities::MPI::n_mpi_processes(world);
    const Point<2>        centre(0., 0.);
    const GridConvolution whole(
      centre, 0.1, half_widths, order, kernel, mirror, MPI_COMM_SELF);
    GridConvolution split(
      centre, 0.1, half_widths, order, kernel, mirror, world);
    std::ostringstream name;
    name << grid_name << "order " << order << ", images in "
         << (mirror[0] && mirror[1] ? "x and y" :
             mirror[0]              ? "x" :
             mirror[1]              ? "y" :
                                      "neither");
    require(name.str() + ": the grid is split", split.split());
    const unsigned int without_rows =
      Utilities::MPI::sum(split.slab_sizes()[0] == 0 ? 1u : 0u, world);
    deallog << name.str() << ": ranks without data rows: " << without_rows
            << std::endl;

    for (unsigned int round = 0; round < 2; ++round)
      {
        const auto [own, nodes] = rank_charges(
          split, rank, n_ranks, half_widths[0], half_widths[1], round);
        if (round == 0)
          split.set_footprint(nodes);
        Vector<double> all(own);
        Utilities::MPI::sum(all, world, all);
        Vector<double> reference, footprint_charges(nodes.size()), potentials;
        whole.convolve(all, reference);
        for (unsigned int k = 0; k < nodes.size(); ++k)
          footprint_charges[k] = own[nodes[k]];
        split.convolve(footprint_charges, potentials);
        double difference = 0;
        for (unsigned int k = 0; k < nodes.size(); ++k)
          difference =
            std::max(difference, std::abs(potentials[k] - reference[nodes[k]]));
        difference = Utilities::MPI::max(difference, world);
        check_below(name.str() + (round == 0 ? "" : ", again") +
                      ": the slabs against one process's convolution",
                    difference / reference.linfty_norm(),
                    1e-12);
      }
    const double largest =
      Utilities::MPI::max(static_cast<double>(split.memory_consumption()),
                          world);
    if (n_ranks >= 3 && grid_name.empty())
      require(name.str() + ": each rank's memory below 0.6 of one process's",
              largest < 0.6 * whole.memory_consumption());
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog_on_first_rank(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);
  for (const unsigned int order : {4u, 8u})
    for (const std::array<bool, 2> mirror :
         {std::array<bool, 2>{{false, false}},
          std::array<bool, 2>{{true, false}},
          std::array<bool, 2>{{false, true}},
          std::array<bool, 2>{{true, true}}})
      check_variant(order, mirror, {{1.3, 0.9}}, "");
  for (const std::array<bool, 2> mirror :
       {std::array<bool, 2>{{true, false}}, std::array<bool, 2>{{true, true}}})
    check_variant(4, mirror, {{0.15, 0.15}}, "10 x 10 nodes, ");
}
