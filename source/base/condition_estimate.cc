#include <plate_on_halfspace/base/condition_estimate.h>

#include <vector>

extern "C" void
dgecon_(const char   *norm,
        const int    *n,
        const double *a,
        const int    *lda,
        const double *anorm,
        double       *rcond,
        double       *work,
        int          *iwork,
        int          *info);

namespace PlateOnHalfspace
{
  double
  reciprocal_condition_number(const LAPACKFullMatrix<double> &factorised,
                              const double                    l1_norm,
                              const bool                      cholesky)
  {
    const int n = factorised.m();
    if (n == 0)
      return 1.;
    if (cholesky)
      return factorised.reciprocal_condition_number(l1_norm);
    // deal.II 9.4 estimates only after Cholesky; the LU factors are stored
    // in place (column-major, as LAPACK's dgetrf left them).
    double              rcond = 0;
    int                 info  = 0;
    std::vector<double> work(4 * n);
    std::vector<int>    iwork(n);
    const char          norm = '1';
    dgecon_(&norm,
            &n,
            &factorised(0, 0),
            &n,
            &l1_norm,
            &rcond,
            work.data(),
            iwork.data(),
            &info);
    return info == 0 ? rcond : 0.;
  }
} // namespace PlateOnHalfspace
