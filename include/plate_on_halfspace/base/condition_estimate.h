/**
 * LAPACK's estimate of the reciprocal condition number 1/κ₁ of a dense
 * matrix from its factorisation, reported in summary.json so that a user
 * sees how many digits a stiffness ratio leaves (about -log10(rcond) are
 * lost to rounding).
 */
#ifndef plate_on_halfspace_base_condition_estimate_h
#define plate_on_halfspace_base_condition_estimate_h

#include <deal.II/lac/lapack_full_matrix.h>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * 1/κ₁ of the matrix whose Cholesky (@p cholesky) or LU factorisation
   * @p factorised holds, @p l1_norm being the 1-norm of the matrix before
   * it was factorised (LAPACK dpocon / dgecon). 1 for an empty matrix.
   */
  double
  reciprocal_condition_number(const LAPACKFullMatrix<double> &factorised,
                              const double                    l1_norm,
                              const bool                      cholesky);
} // namespace PlateOnHalfspace

#endif
