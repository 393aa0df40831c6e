/**
 * The soil family's interface (doc/architecture.md, "The soil family";
 * doc/soil-models.md): what a soil model states about the ground under
 * the plate, independent of how a foundation operator stores its
 * flexibility (halfspace/interface.h). Every model gives the settlement of
 * the soil surface under a pressure field at any point, the scale of that
 * settlement, and how large a goal estimate it can afford. Continuum
 * models (ElasticSoil) also give their point-load kernel, which the dense,
 * hierarchical and collocation storages integrate; a local model (the
 * dense liquid) has none and is stored sparse.
 */
#ifndef plate_on_halfspace_soil_soil_model_h
#define plate_on_halfspace_soil_soil_model_h

#include <deal.II/base/point.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** A smooth function of the distance r (length^-1 x length/force). */
  class SmoothRadialFunction
  {
  public:
    virtual ~SmoothRadialFunction() = default;

    /** The value at distance @p r, 0 <= r <= the range it was made for. */
    virtual double
    value(const double r) const = 0;

    /**
     * values[i] += value(distances[i]) for i < n: one call per cell pair
     * of the operator's integration, whose inner loop this is (a variant
     * may evaluate faster in bulk).
     */
    virtual void
    add_values(const double      *distances,
               double            *values,
               const unsigned int n) const
    {
      for (unsigned int i = 0; i < n; ++i)
        values[i] += value(distances[i]);
    }

    /**
     * The shortest length over which the function changes appreciably: a
     * quadrature over a cell of diameter H resolves it with about
     * 3 + 3 H / length_scale() points per direction.
     */
    virtual double
    length_scale() const = 0;
  };

  /**
   * The surface settlement at distance r from a unit point load:
   *   K(r) = alpha / r + remainder(r),
   * alpha / r the Boussinesq part (the top layer's, for a layered soil) that
   * the singular cell-pair rules integrate, and a smooth remainder (none for
   * the homogeneous half-space) that regular Gauss rules integrate
   * (doc/soil-models.md, "The kernel"). A number converts to the
   * homogeneous kernel alpha / r.
   */
  struct SurfaceKernel
  {
    SurfaceKernel(const double                                alpha     = 0.,
                  std::shared_ptr<const SmoothRadialFunction> remainder = {})
      : alpha(alpha)
      , remainder(std::move(remainder))
    {}

    /**
     * The Gauss points per direction (2 ... 6) that integrate this kernel
     * times quadratic shape functions over a cell whose centre lies
     * @p separation of its diameters from another cell's centre, or from a
     * point, to @p accuracy of the entry (doc/formulation.md,
     * "Cell-pair quadrature"): the n-point rule's error for 1/r is about
     * c_n separation^-(2n - 2); at the default @p accuracy 6 points (the
     * most) nearer than 1.45 diameters, 5 nearer than 2.6, 4 nearer than
     * 11.2, 3 nearer than 412, 2 beyond. The separation is measured in
     * the larger cell's diameters, so the model holds for cells of
     * similar size and shape; CellPairIntegrator cuts graded or elongated
     * cells into such pieces first.
     * With a remainder at least 3, since it varies over its length scale
     * at any distance (doc/soil-models.md, "How the storages use it").
     */
    unsigned int
    separated_points(const double separation,
                     const double accuracy = separated_accuracy) const
    {
      // c_n of the rules of 2 ... 5 points, measured on pairs of squares
      // side by side and diagonal, the larger of the two
      constexpr double c[4]   = {1.7e-2, 1.6e-3, 3e-5, 2e-6};
      unsigned int     points = 6;
      for (unsigned int n = 2; n < 6; ++n)
        if (c[n - 2] <= accuracy * std::pow(separation, 2. * n - 2.))
          {
            points = n;
            break;
          }
      return remainder ? std::max(points, 3u) : points;
    }

    /** The relative accuracy of separated_points()'s rules for the whole
     *  kernel, a tenth of the default Foundation operator/Tolerance. */
    static constexpr double separated_accuracy = 1e-7;

    double                                      alpha;
    std::shared_ptr<const SmoothRadialFunction> remainder;
  };

  /**
   * The mean of 1/|x - y| over x and y in the unit square,
   * 4 ln(1 + sqrt 2) - 4 (sqrt 2 - 1)/3: the mean settlement of a
   * uniformly loaded square of side a on a half-space is
   * alpha a p times this (0.9464 p a (1 - nu0^2)/E0).
   */
  constexpr double mean_inverse_distance_over_square = 2.9732095982;

  /** The soil model (see the file documentation). */
  class SoilModel
  {
  public:
    virtual ~SoilModel() = default;

    /** The model's name as Foundation/Model spells it. */
    virtual std::string
    name() const = 0;

    /**
     * The settlement u(x) of the soil surface under the pressure with the
     * nodal values @p nodal_pressure at each of @p points of the computed
     * part (the model's own law, not tested with the basis): what a goal's
     * error estimate needs between the nodes (doc/formulation.md,
     * "Goal-oriented refinement").
     */
    virtual std::vector<double>
    settlement_at_points(const FoundationSpace       &space,
                         const Vector<double>        &nodal_pressure,
                         const std::vector<Point<2>> &points) const = 0;

    /**
     * The order of the settlement under the force @p force spread over the
     * area @p area: what the scene's scale checks compare with 1e30.
     */
    virtual double
    typical_settlement(const double force, const double area) const = 0;

    /**
     * The soil's stiffness at the scale @p size: the uniform pressure on a
     * square of side @p size per unit of its mean settlement. It converts
     * a gap into the pressure that would close it, where the measured
     * contact region is located between the nodes (doc/outputs.md,
     * "Contact area").
     */
    virtual double
    patch_stiffness(const double size) const = 0;

    /**
     * The radius of relative stiffness of a plate of flexural rigidity
     * @p flexural_rigidity on this soil: the length l at which the plate's
     * bending stiffness D k^4 equals the soil's 1/G(k), k = 1/l
     * (doc/soil-models.md, "Radius of relative stiffness"); (D/k)^(1/4) on
     * a dense liquid, (2 D (1 - nu0^2)/E0)^(1/3) on a half-space.
     */
    virtual double
    radius_of_relative_stiffness(const double flexural_rigidity) const = 0;

    /**
     * D k^4 G(k) at k = 1/@p length: the bending stiffness of a plate of
     * flexural rigidity @p flexural_rigidity at the wavelength @p length
     * against the soil's, 1 at length = radius_of_relative_stiffness()
     * (doc/soil-models.md, "Radius of relative stiffness"); (l/L)^4 on a
     * dense liquid, (l/L)^3 on a half-space.
     */
    virtual double
    relative_stiffness(const double flexural_rigidity,
                       const double length) const = 0;

    /**
     * How accurately the model's kernel is known, for the log: empty where
     * it is exact (the half-space, the dense liquid); a layered soil's
     * tabulation states its knots, range and error.
     */
    virtual std::string
    kernel_report() const
    {
      return {};
    }

    /**
     * What besides the singular quadrature can make this soil's Galerkin
     * matrix lose its positive definiteness in floating point, for the
     * message that stops such a run; empty where nothing else can.
     */
    virtual std::string
    definiteness_advice() const
    {
      return {};
    }
  };

  /** A continuum soil, given by its point-load kernel (SurfaceKernel). */
  class ElasticSoil : public SoilModel
  {
  public:
    /**
     * @param singular_order Gauss points per direction of the singular
     *   rules (Discretization/Singular quadrature order).
     */
    explicit ElasticSoil(const unsigned int singular_order);

    /**
     * The kernel, valid for distances up to @p max_distance (the plate's
     * diameter with its mirror images, maximal_distance()).
     */
    virtual SurfaceKernel
    kernel(const double max_distance) const = 0;

    /** Integrates kernel() over the cells and their mirror images
     *  (soil/surface_settlement.h). */
    std::vector<double>
    settlement_at_points(const FoundationSpace       &space,
                         const Vector<double>        &nodal_pressure,
                         const std::vector<Point<2>> &points) const override;

    unsigned int
    singular_quadrature_order() const
    {
      return singular_order;
    }

  private:
    const unsigned int singular_order;
  };

  /**
   * The largest distance between two points of the plate: the diagonal of
   * the box around the space's cells and their mirror images.
   */
  double
  maximal_distance(const FoundationSpace &space);

  /**
   * Make the soil of Foundation/Model: half-space, layered or dense liquid
   * (the registration of a new model, doc/architecture.md).
   */
  std::shared_ptr<const SoilModel>
  create_soil_model(const SceneParameters &parameters);
} // namespace PlateOnHalfspace

#endif
