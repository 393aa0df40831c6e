/**
 * Minimal deal.II-style test header: every test writes its results to
 * deallog, which initlog() redirects to the file "output" that the test
 * harness compares with NAME.output (numdiff, see tests/CMakeLists.txt).
 */
#ifndef plate_on_halfspace_tests_h
#define plate_on_halfspace_tests_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/logstream.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

using namespace dealii;

/** "output", opened by initlog(): a test on several processes opens it on
 *  rank 0 only. */
std::ofstream logfile;

/** Send deallog to "output" only, with a fixed number of digits. */
inline void
initlog()
{
  logfile.open("output");
  deallog.attach(logfile, /*print_job_id=*/false); // no date in the output
  deallog.depth_console(0);
  deallog << std::setprecision(10);
}

/** initlog() on @p is_first_rank; the other ranks of a test on several
 *  processes write nothing (deal.II's NAME.mpirun=N.output is rank 0's). */
inline void
initlog_on_first_rank(const bool is_first_rank)
{
  if (is_first_rank)
    initlog();
  else
    deallog.depth_console(0);
}

/**
 * @p value with the significant digits a relative tolerance resolves:
 * floor(-log10(tolerance)), at least 2 and at most 6. Another CPU's BLAS
 * kernel or thread count changes results in the 8th digit or later
 * (doc/verification.md, "Outputs on any CPU"), so a stored output never
 * holds a digit that rounding can change.
 */
inline std::string
rounded(const double value, const double relative_tolerance)
{
  const int digits =
    relative_tolerance > 0 ?
      std::clamp(static_cast<int>(std::floor(-std::log10(relative_tolerance))),
                 2,
                 6) :
      6;
  std::ostringstream s;
  s << std::setprecision(digits) << value;
  return s.str();
}

/** @p value with all 17 significant digits (a failed check's values). */
inline std::string
rounded_all(const double value)
{
  std::ostringstream s;
  s << std::setprecision(17) << value;
  return s.str();
}

/**
 * Print "name: computed X reference Y (rel. tol. T) ok", X and Y rounded
 * to the digits T resolves (rounded()), and fail the test (non-zero exit)
 * unless |X - Y| <= T |Y|.
 */
inline void
check(const std::string &name,
      const double       computed,
      const double       reference,
      const double       relative_tolerance)
{
  const bool ok =
    std::abs(computed - reference) <= relative_tolerance * std::abs(reference);
  std::ostringstream tolerance;
  tolerance << relative_tolerance;
  // A failure shows every digit, so that the difference is visible.
  deallog << name << ": computed "
          << (ok ? rounded(computed, relative_tolerance) :
                   rounded_all(computed))
          << " reference "
          << (ok ? rounded(reference, relative_tolerance) :
                   rounded_all(reference))
          << " (rel. tol. " << tolerance.str() << ") " << (ok ? "ok" : "FAILED")
          << std::endl;
  AssertThrow(ok, ExcMessage("check '" + name + "' failed"));
}

/** The same for a lower bound: computed > bound, computed printed to 3
 *  digits. */
inline void
check_greater(const std::string &name,
              const double       computed,
              const double       bound)
{
  const bool         ok = (computed > bound);
  std::ostringstream b;
  b << bound;
  deallog << name << ": computed " << rounded(computed, 1e-3) << " above "
          << b.str() << " " << (ok ? "ok" : "FAILED") << std::endl;
  AssertThrow(ok, ExcMessage("check '" + name + "' failed"));
}

/**
 * An error or residual that must not exceed @p bound: print "name: below B
 * ok" and fail the test unless computed <= B. The value itself is printed
 * only on failure: a round-off-sized error changes with the CPU's BLAS
 * kernel and thread count, the verdict does not.
 */
inline void
check_below(const std::string &name, const double computed, const double bound)
{
  const bool         ok = (computed <= bound); // false for NaN
  std::ostringstream b;
  b << bound;
  deallog << name << ": ";
  if (ok)
    deallog << "below " << b.str() << " ok" << std::endl;
  else
    deallog << "computed " << computed << ", not below " << b.str() << " FAILED"
            << std::endl;
  AssertThrow(ok, ExcMessage("check '" + name + "' failed"));
}

/** The norm of relative_difference(). */
enum class Norm
{
  l2,
  max
};

/** |@p a - @p b| / |@p b| in @p norm (deal.II vectors). */
template <typename VectorType>
inline double
relative_difference(const VectorType &a,
                    const VectorType &b,
                    const Norm        norm = Norm::l2)
{
  VectorType d(a);
  d -= b;
  return norm == Norm::l2 ? d.l2_norm() / b.l2_norm() :
                            d.linfty_norm() / b.linfty_norm();
}

/**
 * A condition on numbers that depend on rounding (pivots, round-off-sized
 * errors): print "name: ok" or "name: FAILED" and fail the test unless
 * @p condition holds. The numbers themselves are not printed.
 */
inline void
require(const std::string &name, const bool condition)
{
  deallog << name << ": " << (condition ? "ok" : "FAILED") << std::endl;
  AssertThrow(condition, ExcMessage("check '" + name + "' failed"));
}

#endif
