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
 * symmetric on a symmetric scene).
 */
#ifndef plate_on_halfspace_halfspace_grid_convolution_h
#define plate_on_halfspace_halfspace_grid_convolution_h

#include <deal.II/base/point.h>

#include <deal.II/lac/vector.h>

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
     */
    GridConvolution(const Point<2>                      &centre,
                    const double                         spacing,
                    const std::array<double, 2>         &half_widths,
                    const unsigned int                   order,
                    const std::function<double(double)> &kernel);
    ~GridConvolution();
    GridConvolution(const GridConvolution &) = delete;
    GridConvolution &
    operator=(const GridConvolution &) = delete;

    /** The grid nodes and weights of point @p x. */
    Stencil
    stencil(const Point<2> &x) const;

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

    /** The padded FFT sizes. */
    std::array<unsigned int, 2>
    fft_sizes() const
    {
      return padded;
    }

    /**
     * Add to @p field its mirror images: for each sign pair (s_x, s_y) of
     * @p reflections the field reflected in the grid's centre lines where
     * the sign is negative (the grid is symmetric about its centre).
     */
    void
    add_reflections(
      Vector<double>                           &field,
      const std::vector<std::array<double, 2>> &reflections) const;

    /** @p potentials = G * @p charges on the grid (in place allowed). */
    void
    convolve(const Vector<double> &charges, Vector<double> &potentials) const;

    /** Bytes held (grids, transform of the kernel). */
    std::size_t
    memory_consumption() const;

  private:
    /** Stencil of coordinate @p x in direction @p d: its first grid
     *  index, and its weights into @p weights (spline_order of them). */
    int
    stencil_1d(const double x, const unsigned int d, double *weights) const;

    unsigned int                spline_order;
    double                      h;
    Point<2>                    origin; ///< node (0, 0)
    std::array<unsigned int, 2> n;      ///< grid nodes per direction
    std::array<unsigned int, 2> padded; ///< FFT sizes
    /**
     * The stencil's weights as polynomials in the point's offset u in
     * [0, 1) from its grid cell: weight k is the sum over m of
     * weight_polynomials[m * max_order + k] u^m, the pieces of the
     * cardinal B-spline.
     */
    std::array<double, max_order * max_order> weight_polynomials{};
    /** The filtered kernel's transform, padded[0] x (padded[1]/2 + 1). */
    std::vector<double> kernel_transform;
    struct Plans;
    std::unique_ptr<Plans> plans;
  };
} // namespace PlateOnHalfspace

#endif
