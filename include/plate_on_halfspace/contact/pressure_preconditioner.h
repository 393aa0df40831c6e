/**
 * Preconditioners of the iterative contact solver's pressure problem
 * (iterative_solver.h; doc/formulation.md, "Preconditioning the contact
 * pressures"): approximate inverses of H = F_CC + S_CC, the soil's
 * flexibility F and the plate's S = B N K^+ N^T B^T added in series on the
 * contact set C. With l the radius of relative stiffness and k the wave
 * number of a pressure mode, S/F is about (k l)^{-3}:
 *  - soil inverse: (F̃^{-1})_CC, the storage's approximate inverse of F
 *    (FoundationOperator::make_approximate_inverse()). The preconditioned
 *    spectrum is 1 + (k l)^{-3}: flat for a plate stiffer than the soil
 *    over its size, unbounded for a flexible one (l below the cells).
 *  - plate on springs: the exact inverse of D_C + S_CC, with D a tenth of
 *    diag(F) (FoundationOperator::flexibility_diagonal()) the soil as
 *    independent springs, by the Woodbury identity
 *      (D + U K^+ U^T)^{-1} = D^{-1} - D^{-1} U (K + U^T D^{-1} U)^{-1}
 *                             U^T D^{-1},   U = B_C N,
 *    one sparse factorisation of the plate with the springs of C. D
 *    resembles F at the mesh scale, so the spectrum is close to 1 where
 *    the plate dominates and spreads as the plate stiffens.
 * Contact/Preconditioner = auto picks the one whose spectral model
 * (estimate_preconditioners()) predicts the smaller condition number.
 */
#ifndef plate_on_halfspace_contact_pressure_preconditioner_h
#define plate_on_halfspace_contact_pressure_preconditioner_h

#include <deal.II/lac/vector.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  class FoundationOperator;
  class MindlinPlate;
  class SoilModel;

  /**
   * The largest residual of the contact pressures, relative to the soil's
   * settlement, that the rounding floor may excuse (iterative_solver.h):
   * the accuracy that the compressed storage promises.
   */
  constexpr double accepted_rounding_floor = 1e-6;

  /** See the file documentation. */
  class PressurePreconditioner
  {
  public:
    virtual ~PressurePreconditioner() = default;

    /**
     * Prepare for the contact set @p contact_set (the nodes whose
     * pressures are iterated); a variant whose inverse depends on the set
     * refactorises here. Collective on several processes.
     */
    virtual void
    use_contact_set(const std::vector<bool> &contact_set) = 0;

    /** y = P^{-1} x on all nodes (the caller restricts it to C). */
    virtual void
    vmult(Vector<double> &y, const Vector<double> &x) const = 0;

    /** Bytes held. */
    virtual std::size_t
    memory_consumption() const = 0;

    /** Wall time of the factorisations so far, seconds. */
    virtual double
    factorization_time() const = 0;

    /** "soil inverse" or "plate on springs" (Contact/Preconditioner). */
    virtual std::string
    name() const = 0;
  };

  /** The soil's approximate inverse (see the file documentation). */
  std::unique_ptr<PressurePreconditioner>
  make_soil_inverse_preconditioner(FoundationOperator &foundation);

  /** The plate on springs (see the file documentation); both arguments
   *  must outlive the result. */
  std::unique_ptr<PressurePreconditioner>
  make_plate_on_springs_preconditioner(const MindlinPlate       &plate,
                                       const FoundationOperator &foundation);

  /**
   * Condition numbers that the spectral model of the file documentation
   * predicts for each preconditioner, from the radius of relative
   * stiffness l, the smallest cell size h and the plate's diameter L.
   */
  struct PreconditionerEstimate
  {
    double soil_inverse     = 0;
    double plate_on_springs = 0;
    /**
     * The residual, relative to the soil's settlement, below which
     * rounding stops either: the gap is a difference of plate deflections
     * x0^-e times the settlement (x0 = 2 pi l/L, e = 3 for a continuum,
     * 4 for the dense liquid), each known to some eps.
     */
    double rounding_floor = 0;
  };

  /** @p continuum_soil: false for the dense liquid, whose flexibility is
   *  local (its springs match it at every wave number). */
  PreconditionerEstimate
  estimate_preconditioners(const double radius_of_relative_stiffness,
                           const double smallest_cell,
                           const double plate_diameter,
                           const bool   continuum_soil);

  /** l, h and L of @p plate on @p soil. */
  PreconditionerEstimate
  estimate_preconditioners(const MindlinPlate &plate, const SoilModel &soil);
} // namespace PlateOnHalfspace

#endif
