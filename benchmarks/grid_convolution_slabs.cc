// The split-kernel storage's far-field convolution on P processes: the
// grid split by slabs (halfspace/grid_convolution.h; doc/parallel.md, "The
// grid by slabs") against the whole grid on every rank with the charges
// summed over the ranks first (one MPI_Reduce and MPI_Bcast of the grid,
// then every rank transforms all of it). Not a test: it prints one line of
// timings and memory, nothing is compared but the two answers.
//
// Each rank owns a block of the computed part of the grid (the quarter
// with images in both lines, the half with images in one, the whole grid
// with none), cut in 2 x P/2 blocks like METIS parts, and its charges fill
// the block and a stencil's halo around it (the footprint).
//
// Columns: P, grid nodes, the transforms' lengths, time of one
// convolution [ms] for the whole grid on every rank (with its sums) and
// for the slabs (the slowest rank's mean over the repeats), their ratio,
// the largest rank's bytes of GridConvolution [MB] for both, and the
// largest difference of the slabs' potentials from the whole grid's,
// relative to the largest potential.
//
// usage: mpirun -np P build/benchmark_grid_convolution_slabs
//          [nodes in x] [nodes in y] [images: xy, x, y or none] [repeats]
// defaults: 1500 1500 xy 20

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/halfspace/grid_convolution.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace PlateOnHalfspace;

namespace
{
  double
  kernel(const double r)
  {
    const double s = 8.; // the split length in grid spacings
    return r < 1e-8 ? 2. / (s * std::sqrt(M_PI)) : std::erf(r / s) / r;
  }

  /** Seconds per call of @p f, the slowest rank's mean over @p repeats. */
  template <typename F>
  double
  seconds_per_call(const unsigned int repeats, const F &f)
  {
    f(); // plans and buffers warm
    MPI_Barrier(MPI_COMM_WORLD);
    Timer timer;
    for (unsigned int k = 0; k < repeats; ++k)
      f();
    timer.stop();
    return Utilities::MPI::max(timer.wall_time() / repeats, MPI_COMM_WORLD);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   world = MPI_COMM_WORLD;
  const unsigned int               P = Utilities::MPI::n_mpi_processes(world),
                     rank            = Utilities::MPI::this_mpi_process(world);
  const unsigned int nx              = argc > 1 ? std::atoi(argv[1]) : 1500,
                     ny              = argc > 2 ? std::atoi(argv[2]) : 1500;
  const std::string         images   = argc > 3 ? argv[3] : "xy";
  const unsigned int        repeats  = argc > 4 ? std::atoi(argv[4]) : 20;
  const std::array<bool, 2> mirror{
    {images == "xy" || images == "x", images == "xy" || images == "y"}};

  // spacing 1: the grid's nodes lie within +- n/2 of the origin
  const Point<2>              centre(0., 0.);
  const std::array<double, 2> half_widths{{0.5 * nx, 0.5 * ny}};
  const unsigned int          order = 6;
  const GridConvolution       whole(
    centre, 1., half_widths, order, kernel, mirror, MPI_COMM_SELF);
  GridConvolution split(centre, 1., half_widths, order, kernel, mirror, world);
  const std::array<unsigned int, 2> n = whole.grid_sizes();

  // The computed part: x >= 0 (y >= 0) where mirrored, cut into
  // blocks_x x blocks_y blocks; rank r's block and a stencil's halo.
  const unsigned int blocks_x = P > 1 ? 2 : 1, blocks_y = (P + 1) / blocks_x;
  std::array<unsigned int, 2> low, high;
  for (unsigned int d = 0; d < 2; ++d)
    {
      const unsigned int first = mirror[d] ? n[d] / 2 : 0, count = n[d] - first,
                         parts = d == 0 ? blocks_x : blocks_y,
                         part  = d == 0 ? rank % blocks_x : rank / blocks_x;
      const unsigned int halo  = order / 2;
      const unsigned int begin = first + count * part / parts,
                         end   = first + count * (part + 1) / parts;
      low[d]                   = begin >= first + halo ? begin - halo : first;
      high[d]                  = std::min(n[d], end + halo);
    }
  Vector<double>            charges(whole.n_grid_nodes());
  std::vector<unsigned int> footprint;
  for (unsigned int j = low[1]; j < high[1]; ++j)
    for (unsigned int i = low[0]; i < high[0]; ++i)
      {
        const unsigned int g = j * n[0] + i;
        charges[g]           = std::sin(0.37 * i + 0.11 * j + rank) + 0.5;
        footprint.push_back(g);
      }
  // A split grid takes and gives its footprint's entries only (one
  // process: the whole grid, as the other).
  split.set_footprint(footprint);
  Vector<double> split_charges(charges);
  if (split.split())
    {
      split_charges.reinit(footprint.size());
      for (unsigned int k = 0; k < footprint.size(); ++k)
        split_charges[k] = charges[footprint[k]];
    }

  Vector<double> summed, whole_potentials, split_potentials;
  const double   t_whole    = seconds_per_call(repeats, [&]() {
    summed = charges;
    sum_shared_entries_over_ranks(make_array_view(summed), world);
    whole.convolve(summed, whole_potentials);
  });
  const double   t_split    = seconds_per_call(repeats, [&]() {
    split.convolve(split_charges, split_potentials);
  });
  double         difference = 0, largest = 0;
  for (unsigned int k = 0; k < footprint.size(); ++k)
    {
      const unsigned int g     = footprint[k];
      const double       slabs = split_potentials[split.split() ? k : g];
      difference = std::max(difference, std::abs(slabs - whole_potentials[g]));
      largest    = std::max(largest, std::abs(whole_potentials[g]));
    }
  difference = Utilities::MPI::max(difference, world) /
               Utilities::MPI::max(largest, world);
  const double mb_whole =
    Utilities::MPI::max(double(whole.memory_consumption()), world) / 1048576.;
  const double mb_split =
    Utilities::MPI::max(double(split.memory_consumption()), world) / 1048576.;
  if (rank == 0)
    {
      const auto sizes = whole.fft_sizes();
      std::printf("| P | grid nodes | images | transforms | whole [ms] | "
                  "slabs [ms] | slabs / whole | whole [MB] | slabs [MB] | "
                  "difference |\n");
      std::printf("| %u | %u x %u | %s | %u x %u | %.1f | %.1f | %.2f | %.0f "
                  "| %.0f | %.1e |\n",
                  P,
                  n[0],
                  n[1],
                  images.c_str(),
                  sizes[0],
                  sizes[1],
                  1e3 * t_whole,
                  1e3 * t_split,
                  t_split / t_whole,
                  mb_whole,
                  mb_split,
                  difference);
    }
}
