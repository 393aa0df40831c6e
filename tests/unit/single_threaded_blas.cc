// SingleThreadedBlas (base/single_threaded_blas.h): while a guard lives,
// OpenBLAS reports one thread and in_effect() is true; a guard inside
// another changes nothing; the guard that changed the count restores it,
// also when left by an exception; a guard that found one thread leaves the
// count alone (so a count set inside it stays). The test sets the count to
// two itself, whatever the environment (the suite runs with OpenBLAS's
// default and with OPENBLAS_NUM_THREADS=1), and reads OpenBLAS's own answer
// through the functions the program looks up; scripts/setup.sh installs
// OpenBLAS.

#include <plate_on_halfspace/base/single_threaded_blas.h>

#include <dlfcn.h>

#include <stdexcept>

#include "../tests.h"

using namespace PlateOnHalfspace;

namespace
{
  template <typename Function>
  Function
  open_blas(const char *name)
  {
    const auto function = reinterpret_cast<Function>(dlsym(RTLD_DEFAULT, name));
    AssertThrow(function != nullptr,
                ExcMessage(std::string("this process's BLAS is not OpenBLAS: "
                                       "no ") +
                           name));
    return function;
  }

  int
  blas_threads()
  {
    return open_blas<int (*)()>("openblas_get_num_threads")();
  }

  void
  set_blas_threads(const int n)
  {
    open_blas<void (*)(int)>("openblas_set_num_threads")(n);
  }

  void
  check(const std::string &what, const bool passed)
  {
    deallog << what << ": " << (passed ? "ok" : "FAILED") << std::endl;
  }
} // namespace

int
main()
{
  initlog();
  const int original = blas_threads();
  set_blas_threads(2);
  check("OpenBLAS set to two threads", blas_threads() == 2);
  check("not in effect at two threads", !SingleThreadedBlas::in_effect());
  {
    const SingleThreadedBlas outer;
    check("one thread inside a guard", blas_threads() == 1);
    check("in effect inside a guard", SingleThreadedBlas::in_effect());
    {
      const SingleThreadedBlas inner;
      check("one thread inside a nested guard", blas_threads() == 1);
    }
    check("still one thread after the nested guard", blas_threads() == 1);
  }
  check("two threads again after the guard", blas_threads() == 2);
  try
    {
      const SingleThreadedBlas guard;
      throw std::runtime_error("leave");
    }
  catch (const std::runtime_error &)
    {}
  check("two threads again after a guard left by an exception",
        blas_threads() == 2);

  set_blas_threads(1);
  {
    const SingleThreadedBlas guard;
    set_blas_threads(3);
  }
  check("a guard that found one thread leaves a count set inside it",
        blas_threads() == 3);
  set_blas_threads(original);
}
