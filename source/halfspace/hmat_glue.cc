#include "hmat_glue.h"

#include <deal.II/base/exceptions.h>

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace PlateOnHalfspace
{
  namespace HmatGlue
  {
    using namespace dealii;

    // Lowering the tolerance helps only while it is coarse; it cannot go
    // below 1e-14 (Parameters::FoundationOperator), so the advice says
    // what else to do (doc/errors-and-limits.md).
    const std::string tolerance_advice =
      " If Foundation operator/Tolerance is coarser than 1e-8, lower it (it "
      "is the compression's accuracy); otherwise, or if the mesh is small, "
      "use Foundation operator/Storage = dense (exactly integrated; its "
      "memory grows with the square of the foundation nodes).";

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

    hmat_cluster_tree_t *
    make_cluster_tree(std::vector<double>       &coordinates,
                      std::vector<unsigned int> &span_ends,
                      std::vector<unsigned int> &spans,
                      const unsigned int         leaf_size,
                      std::vector<unsigned int> &position_to_unknown)
    {
      const unsigned int           n      = span_ends.size();
      hmat_clustering_algorithm_t *median = hmat_create_clustering_median();
      hmat_clustering_algorithm_t *clustering =
        hmat_create_clustering_max_dof(median, leaf_size);
      hmat_cluster_tree_builder_t *builder =
        hmat_create_cluster_tree_builder(clustering);
      hmat_cluster_tree_create_context_t context;
      context.dimension         = 2;
      context.number_of_points  = coordinates.size() / 2;
      context.coordinates       = coordinates.data();
      context.number_of_dof     = n;
      context.span_offsets      = span_ends.data();
      context.spans             = spans.data();
      context.group_index       = nullptr;
      context.builder           = builder;
      hmat_cluster_tree_t *tree = hmat_create_cluster_tree_generic(&context);
      hmat_delete_cluster_tree_builder(builder);
      hmat_delete_clustering(clustering);
      hmat_delete_clustering(median);
      AssertThrow(tree != nullptr,
                  ExcMessage("Foundation operator/Storage = hierarchical: "
                             "hmat-oss could not build the cluster tree."));

      const int *indices = hmat_cluster_get_indices(tree);
      position_to_unknown.resize(n);
      std::vector<bool> seen(n, false);
      for (unsigned int k = 0; k < n; ++k)
        {
          const int unknown = indices[k];
          AssertThrow(unknown >= 0 && unknown < static_cast<int>(n) &&
                        !seen[unknown],
                      ExcMessage("HierarchicalFlexibility: the cluster tree's "
                                 "numbering is not a permutation."));
          seen[unknown]          = true;
          position_to_unknown[k] = unknown;
        }
      return tree;
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

    CapturedStandardError::CapturedStandardError()
    {
      // On a terminal the progress reports (base/progress.h) share stderr
      // with the library and are left alone.
      if (isatty(STDERR_FILENO))
        return;
      std::cerr.flush();
      std::fflush(stderr);
      int ends[2];
      if (pipe2(ends, O_NONBLOCK | O_CLOEXEC) != 0)
        return;
      saved = fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 0);
      if (saved < 0 || dup2(ends[1], STDERR_FILENO) < 0)
        {
          if (saved >= 0)
            close(saved);
          saved = -1;
          close(ends[0]);
          close(ends[1]);
          return;
        }
      close(ends[1]);
      reader = ends[0];
    }

    std::string
    CapturedStandardError::release()
    {
      std::string text;
      if (saved < 0)
        return text;
      std::cerr.flush();
      std::fflush(stderr);
      // Restoring fd 2 closes the pipe's last write end: the reads below
      // end at its end of file or, non-blocking, at an empty pipe.
      dup2(saved, STDERR_FILENO);
      close(saved);
      saved = -1;
      char    buffer[4096];
      ssize_t n;
      while ((n = read(reader, buffer, sizeof(buffer))) > 0)
        text.append(buffer, static_cast<std::size_t>(n));
      close(reader);
      reader = -1;
      // One line for the message that quotes it: no trailing blanks or
      // line breaks.
      while (!text.empty() &&
             std::isspace(static_cast<unsigned char>(text.back())))
        text.pop_back();
      return text;
    }

    CapturedStandardError::~CapturedStandardError()
    {
      release();
    }
  } // namespace HmatGlue
} // namespace PlateOnHalfspace
