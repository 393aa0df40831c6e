#include "hmat_glue.h"

#include <deal.II/base/exceptions.h>

#include <dlfcn.h>

#include <cmath>

namespace PlateOnHalfspace
{
  namespace HmatGlue
  {
    using namespace dealii;

    const std::string tolerance_advice =
      " Lower Foundation operator/Tolerance (e.g. to 1e-6 or 1e-8), or use "
      "Foundation operator/Storage = dense if the mesh is small.";

    hmat_interface_t &
    hmat()
    {
      static hmat_interface_t interface = []() {
        hmat_interface_t i;
        hmat_init_default_interface(&i, HMAT_DOUBLE_PRECISION);
        AssertThrow(i.init() == 0,
                    ExcMessage("Foundation operator/Storage = hierarchical: "
                               "the hmat-oss library could not be "
                               "initialised."));
        return i;
      }();
      return interface;
    }

    void
    check_hmat(const int status, const std::string &what)
    {
      AssertThrow(status == 0,
                  ExcMessage("Foundation operator/Tolerance: hmat-oss failed "
                             "in " +
                             what + " (status " + std::to_string(status) +
                             ")." + tolerance_advice));
    }

    bool
    all_finite(const double *values, const std::size_t n)
    {
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(values[i]))
          return false;
      return true;
    }

    hmat_info_t
    info_of(hmat_matrix_t *matrix)
    {
      hmat_info_t info;
      check_hmat(hmat().get_info(matrix, &info),
                 "reading the H-matrix statistics");
      return info;
    }

    SingleThreadedBlas::SingleThreadedBlas()
      : set_threads(reinterpret_cast<void (*)(int)>(
          dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
      , get_threads(reinterpret_cast<int (*)()>(
          dlsym(RTLD_DEFAULT, "openblas_get_num_threads")))
    {
      if (set_threads != nullptr && get_threads != nullptr)
        {
          previous = get_threads();
          set_threads(1);
        }
    }

    SingleThreadedBlas::~SingleThreadedBlas()
    {
      if (set_threads != nullptr && get_threads != nullptr)
        set_threads(previous);
    }
  } // namespace HmatGlue
} // namespace PlateOnHalfspace
