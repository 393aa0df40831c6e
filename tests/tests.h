/**
 * Minimal deal.II-style test header: every test writes its results to
 * deallog, which initlog() redirects to the file "output" that the test
 * harness compares with NAME.output (numdiff, see tests/CMakeLists.txt).
 */
#ifndef plate_on_halfspace_tests_h
#define plate_on_halfspace_tests_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/logstream.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

using namespace dealii;

std::ofstream logfile("output");

/** Send deallog to "output" only, with a fixed number of digits. */
inline void
initlog()
{
  deallog.attach(logfile, /*print_job_id=*/false); // no date in the output
  deallog.depth_console(0);
  deallog << std::setprecision(10);
}

/**
 * Print "name: computed X reference Y (rel. tol. T) ok" and fail the test
 * (non-zero exit) unless |X - Y| <= T |Y|.
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
  deallog << name << ": computed " << computed << " reference " << reference
          << " (rel. tol. " << tolerance.str() << ") " << (ok ? "ok" : "FAILED")
          << std::endl;
  AssertThrow(ok, ExcMessage("check '" + name + "' failed"));
}

/** The same for a lower bound: computed > bound. */
inline void
check_greater(const std::string &name,
              const double       computed,
              const double       bound)
{
  const bool         ok = (computed > bound);
  std::ostringstream b;
  b << bound;
  deallog << name << ": computed " << computed << " above " << b.str() << " "
          << (ok ? "ok" : "FAILED") << std::endl;
  AssertThrow(ok, ExcMessage("check '" + name + "' failed"));
}

#endif
