/**
 * Minimal deal.II-style test header: every test writes its results to
 * deallog, which initlog() redirects to the file "output" that the test
 * harness compares with NAME.output (numdiff, see tests/CMakeLists.txt).
 */
#ifndef plate_on_halfspace_tests_h
#define plate_on_halfspace_tests_h

#include <deal.II/base/logstream.h>

#include <fstream>
#include <iomanip>

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

#endif
