/**
 * A radial kernel applied to point charges through a uniform grid and the
 * FFT (doc/formulation.md, "Split-kernel FFT storage"): each charge is
 * spread onto the grid with the tensor product of centred cardinal
 * B-splines of even order p, the grid charges are convolved with the
 * kernel's samples, and the potentials are read back at the points with
 * the same B-splines. The samples are filtered twice by the inverse of the
 * B-splines' own samples (their Fourier symbol squared), which makes the
 * whole chain the spline interpolant of the kernel in both arguments:
 *   sum_g sum_g' W(x - g) W(y - g') G(g - g') ~ k(|x - y|),
 * accurate to about (h / l)^p for a kernel smooth on the length l.
 * The convolution is aperiodic: the grid is padded to more than twice its
 * size (Hockney's zero padding), with a margin for the filter.
 *
 * The grid is symmetric about its centre, so a mirror-symmetric set of
 * points sees a mirror-symmetric interpolation (the operator stays
 * symmetric on a symmetric scene). The charges' mirror images in the
 * grid's centre lines are convolved with them where the grid is told so.
 * In a direction with images the grid has an even number of nodes, so the
 * charges with their images are even about the centre between two nodes,
 * and that direction is transformed on its half with cosine transforms
 * (FFTW's REDFT10 and REDFT01, the DFT of the padded grid restricted to
 * even sequences; doc/formulation.md, "Split-kernel FFT storage"): with
 * images in both lines the quarter of the points and no complex
 * arithmetic, with images in one line half of the points, the other
 * direction by the real FFT.
 *
 * On several processes the transformed grid is split (doc/parallel.md,
 * "The grid by slabs"): each rank owns a slab of the rows that hold data
 * for the first direction's transforms and a slab of the spectrum's
 * columns for the second's, and two all-to-all exchanges transpose
 * between them. A rank sends the charges of its footprint (the grid
 * nodes its points spread to, set_footprint()) to the rows' owners, which
 * sum them, and receives the potentials there back: in a convolution no
 * rank touches the whole grid, and no whole grid is summed over the ranks.
 * The kernel's transform is made whole on every rank once, in the
 * constructor, and each keeps its columns.
 */
#ifndef plate_on_halfspace_halfspace_grid_convolution_h
#define plate_on_halfspace_halfspace_grid_convolution_h

#include <deal.II/base/config.h>

#include <deal.II/base/point.h>

#include <deal.II/lac/vector.h>

#include <mpi.h>

#include <array>
#include <complex>
#include <functional>
#include <memory>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** See the file documentation. */
  class GridConvolution
  {
  public:
    /** Largest supported spline order. */
    static constexpr unsigned int max_order = 8;

    /** The grid nodes a point spreads to and their weights. */
    struct Stencil
    {
      /** Grid index of the first node in x and y. */
      int first_x, first_y;
      /** Weights of the nodes first_x + k (first_y + k), k < order. */
      std::array<double, max_order> x, y;
    };

    /**
     * @param centre the grid's centre.
     * @param spacing the grid spacing h.
     * @param half_widths the points lie within centre +- half_widths.
     * @param order the B-splines' order p (even, 4 to max_order).
     * @param kernel k(r), smooth (also at r = 0).
     * @param mirror_images whether convolve() adds the charges' mirror
     *   images in the grid's centre line x = centre[0] (first) and
     *   y = centre[1] (second).
     * @param communicator the ranks that split the grid (see the file
     *   documentation); collective on it, every rank with the same
     *   arguments.
     */
    GridConvolution(const Point<2>                      &centre,
                    const double                         spacing,
                    const std::array<double, 2>         &half_widths,
                    const unsigned int                   order,
                    const std::function<double(double)> &kernel,
                    const std::array<bool, 2> &mirror_images = {{false, false}},
                    const MPI_Comm             communicator  = MPI_COMM_SELF);
    ~GridConvolution();
    GridConvolution(const GridConvolution &) = delete;
    GridConvolution &
    operator=(const GridConvolution &) = delete;

    /** The grid nodes and weights of point @p x. */
    Stencil
    stencil(const Point<2> &x) const;

    /** Whether the whole stencil of point @p x lies on the grid (every
     *  point given to the constructor's extent does). */
    bool
    covers(const Point<2> &x) const;

    unsigned int
    order() const
    {
      return spline_order;
    }

    /** Grid nodes in x and y; node (i, j) is number i + j * sizes[0]. */
    std::array<unsigned int, 2>
    grid_sizes() const
    {
      return n;
    }

    /** Number of grid nodes (not the padded FFT size). */
    std::size_t
    n_grid_nodes() const
    {
      return std::size_t(n[0]) * n[1];
    }

    /** The transforms' lengths: the padded grid's, or in a direction
     *  with cosine transforms half of it. */
    std::array<unsigned int, 2>
    fft_sizes() const
    {
      return padded;
    }

    /** The directions transformed by cosine transforms on their half:
     *  those with mirror images. */
    std::array<bool, 2>
    cosine_transform_directions() const
    {
      return mirrored;
    }

    /** Whether the grid is split over more than one rank. */
    bool
    split() const;

    /** This rank's data rows of the first direction's transforms and
     *  spectrum columns of the second's (all of them on one rank; none
     *  on a rank beyond their number). */
    std::array<unsigned int, 2>
    slab_sizes() const;

    /**
     * This rank's footprint: the grid nodes (numbered as in grid_sizes(),
     * distinct and in increasing order) whose charges it adds and whose
     * potentials it reads in convolve(). Collective on a split grid, and
     * needed there before the first convolve(); called once.
     */
    void
    set_footprint(const std::vector<unsigned int> &grid_nodes);

    /**
     * @p potentials = G * (@p charges and their mirror images) on the
     * grid (in place allowed); the potentials are mirror symmetric where
     * the images are. On one rank both vectors hold every grid node. On a
     * split grid, collective: both hold this rank's footprint, in its
     * order, and the charges convolved are every rank's summed.
     */
    void
    convolve(const Vector<double> &charges, Vector<double> &potentials) const;

    /** Bytes held by this rank (its slabs, its part of the kernel's
     *  transform, the exchanges' buffers). */
    std::size_t
    memory_consumption() const;

  private:
    /** Grid node (@p i, @p j)'s place in the rows of the first
     *  direction's transforms (row times the row length plus position;
     *  a node and its mirror images share one). */
    std::size_t
    place(const unsigned int i, const unsigned int j) const;

    /** Stencil of coordinate @p x in direction @p d: its first grid
     *  index, and its weights into @p weights (spline_order of them). */
    int
    stencil_1d(const double x, const unsigned int d, double *weights) const;

    /** The plans and the kernel's transform: real-to-complex both ways
     *  (no images), cosine transforms both ways (the quarter), or one of
     *  each (the half). */
    void
    make_whole_plans(const std::function<double(double)> &kernel);
    void
    make_quarter_plans(const std::function<double(double)> &kernel);
    void
    make_half_plans(const std::function<double(double)> &kernel);

    /** The B-splines' Fourier symbol at the frequencies 2 pi k / @p period,
     *  k < @p count. */
    std::vector<double>
    spline_symbols(const unsigned int count, const unsigned int period) const;

    unsigned int                spline_order;
    double                      h;
    Point<2>                    origin;   ///< node (0, 0)
    std::array<unsigned int, 2> n;        ///< grid nodes per direction
    std::array<unsigned int, 2> padded;   ///< transform lengths
    std::array<bool, 2>         mirrored; ///< images in the centre lines
    /**
     * The stencil's weights as polynomials in the point's offset u in
     * [0, 1) from its grid cell: weight k is the sum over m of
     * weight_polynomials[m * max_order + k] u^m, the pieces of the
     * cardinal B-spline.
     */
    std::array<double, max_order * max_order> weight_polynomials{};
    /** The filtered kernel's transform, real, laid out as the transformed
     *  grid: rows along x (along y on the half mirrored in x),
     *  padded[d] / 2 + 1 entries in a direction of the real FFT,
     *  padded[d] in one of cosine transforms; on a split grid this rank's
     *  columns of each row. */
    std::vector<double> kernel_transform;
    MPI_Comm            communicator;
    struct Plans;
    std::unique_ptr<Plans> plans;
  };
} // namespace PlateOnHalfspace

#endif
