/**
 * The layered elastic soil (Foundation/Model = layered; doc/soil-models.md,
 * "Layered soil"): layers over a half-space or a rigid base. Its kernel is
 * the top layer's Boussinesq part plus a smooth remainder, the Hankel
 * integral
 *   R(r) = 1/(2 pi) Int_0^inf (k G(k) - C1) J0(k r) dk,  C1 = 2 (1 - nu1^2)/E1,
 * of the profile's surface compliance G (layered_profile.h), tabulated once
 * per range of distances to a stated accuracy.
 */
#ifndef plate_on_halfspace_soil_layered_soil_h
#define plate_on_halfspace_soil_layered_soil_h

#include <plate_on_halfspace/soil/layered_profile.h>
#include <plate_on_halfspace/soil/soil_model.h>

#include <mutex>

namespace PlateOnHalfspace
{
  /**
   * R(r) on [0, range] as a cubic B-spline in t = asinh(r / h1) (even in t,
   * so its slope at t = 0 is zero), with as many knots as make the spline
   * agree with the integral at every knot interval's midpoint to
   * @p tolerance times alpha / r + |R(r)| there (alpha / r the top layer's
   * point-load settlement).
   *
   * The integral: R = (C_b - C1) / (2 pi sqrt(r^2 + 4 D^2)) + 1/(2 pi) Int
   * [k G - C1 - (C_b - C1) exp(-2 k D)] J0(k r) dk, C_b the base's k G(0),
   * D the depth of the layers: the subtracted term carries the 1/r far
   * field in closed form, so that the rest vanishes at k = 0 and decays
   * like exp(-2 k h1). It is integrated by 10-point Gauss-Legendre panels
   * no wider than pi / range, growing geometrically from k = 0 so that
   * every small-k scale of G is resolved; halving the panels bounds that
   * quadrature's error, which is part of error().
   */
  class TabulatedLayeredRemainder : public SmoothRadialFunction
  {
  public:
    TabulatedLayeredRemainder(const LayeredProfile &profile,
                              const double          range,
                              const double          tolerance);
    ~TabulatedLayeredRemainder() override;

    double
    value(const double r) const override;

    void
    add_values(const double      *distances,
               double            *values,
               const unsigned int n) const override;

    /** The top layer's thickness h1. */
    double
    length_scale() const override;

    /** The range of distances tabulated. */
    double
    range() const;

    /** The largest error found, over alpha / r + |R| (see the class
     *  doc). */
    double
    error() const;

    /** The largest |R(r)| / (alpha / r + |R(r)|) over the table's knots:
     *  the share of the kernel the remainder is. */
    double
    largest_share() const;

    /** Number of knots of the spline. */
    unsigned int
    n_knots() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> data;
  };

  class LayeredSoil : public ElasticSoil
  {
  public:
    /** The tabulation's accuracy (TabulatedLayeredRemainder). */
    static constexpr double kernel_tolerance = 1e-9;

    LayeredSoil(const LayeredProfile &profile,
                const unsigned int    singular_order);

    std::string
    name() const override;

    /** alpha1 / r plus the remainder, tabulated on first use and again
     *  when a longer range is asked for; alpha1 / r alone where the
     *  remainder is below the tabulation's tolerance everywhere. */
    SurfaceKernel
    kernel(const double max_distance) const override;

    /** The softest material's half-space settlement. */
    double
    typical_settlement(const double force, const double area) const override;

    double
    patch_stiffness(const double size) const override;

    /** Where D k^4 G(k) = 1, G the profile's surface compliance. */
    double
    radius_of_relative_stiffness(const double flexural_rigidity) const override;

    double
    relative_stiffness(const double flexural_rigidity,
                       const double length) const override;

    const LayeredProfile &
    get_profile() const
    {
      return profile;
    }

    /**
     * What the last tabulation achieved, for the log: knots, range, error
     * and wall time; empty before the first kernel().
     */
    std::string
    kernel_report() const override;

    /** Cells much wider than the top layer (doc/soil-models.md, "Limits"). */
    std::string
    definiteness_advice() const override;

  private:
    /** The table's remainder is below kernel_tolerance everywhere (the
     *  table exists and table_mutex is held). */
    bool
    remainder_negligible() const;

    const LayeredProfile                                     profile;
    mutable std::shared_ptr<const TabulatedLayeredRemainder> table;
    mutable std::mutex                                       table_mutex;
    /** Wall seconds the last tabulation took. */
    mutable double table_seconds = 0;
  };
} // namespace PlateOnHalfspace

#endif
