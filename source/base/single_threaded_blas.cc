#include <plate_on_halfspace/base/single_threaded_blas.h>

#include <dlfcn.h>

namespace PlateOnHalfspace
{
  namespace
  {
    using GetThreads = int (*)();
    using SetThreads = void (*)(int);

    /** OpenBLAS's functions where the process's BLAS is OpenBLAS, looked
     *  up at run time so that any other BLAS links too. */
    struct OpenBlasThreads
    {
      GetThreads get = nullptr;
      SetThreads set = nullptr;

      OpenBlasThreads()
      {
        get = reinterpret_cast<GetThreads>(
          dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
        set = reinterpret_cast<SetThreads>(
          dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
        if (get == nullptr || set == nullptr)
          get = nullptr, set = nullptr;
      }
    };

    const OpenBlasThreads &
    open_blas_threads()
    {
      static const OpenBlasThreads functions;
      return functions;
    }
  } // namespace

  SingleThreadedBlas::SingleThreadedBlas()
  {
    const OpenBlasThreads &blas = open_blas_threads();
    if (blas.set == nullptr)
      return;
    previous = blas.get();
    if (previous > 1)
      blas.set(1);
    else
      previous = 0;
  }

  bool
  SingleThreadedBlas::in_effect()
  {
    const OpenBlasThreads &blas = open_blas_threads();
    return blas.get == nullptr || blas.get() <= 1;
  }

  SingleThreadedBlas::~SingleThreadedBlas()
  {
    if (previous > 1)
      open_blas_threads().set(previous);
  }
} // namespace PlateOnHalfspace
