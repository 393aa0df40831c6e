#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/base/distributed_sparse_direct.h>
#include <plate_on_halfspace/base/nested_dissection.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>

#include <dmumps_c.h>

#include <algorithm>
#include <exception>
#include <limits>
#include <mutex>
#include <new>
#include <string>

namespace PlateOnHalfspace
{
  namespace
  {
    // MUMPS's job codes and its one-based control arrays (its user guide)
    constexpr MUMPS_INT initialise_job = -1, end_job = -2, analyse_job = 1,
                        factorise_job = 2, solve_job = 3;

    MUMPS_INT &
    icntl(DMUMPS_STRUC_C &id, const unsigned int i)
    {
      return id.icntl[i - 1];
    }

    MUMPS_INT
    infog(const DMUMPS_STRUC_C &id, const unsigned int i)
    {
      return id.infog[i - 1];
    }

    /**
     * MUMPS's PERM_IN for @p pattern's unknowns: the one-based position of
     * each in the pivot order, the unknowns not @p solved (identity rows,
     * no fill) first, then the solved ones in nested_dissection()'s order;
     * empty where that ordering fails, and MUMPS then orders by itself.
     */
    std::vector<MUMPS_INT>
    pivot_positions(const SparsityPattern   &pattern,
                    const std::vector<bool> &solved)
    {
      std::vector<types::global_dof_index> rows;
      for (types::global_dof_index i = 0; i < solved.size(); ++i)
        if (solved[i])
          rows.push_back(i);
      std::vector<int> order;
      try
        {
          const std::lock_guard<std::mutex> lock(metis_ordering_lock());
          order = nested_dissection(pattern, rows);
        }
      catch (const std::bad_alloc &)
        {
          return {};
        }
      if (order.size() != rows.size())
        return {};
      std::vector<MUMPS_INT> position(solved.size());
      MUMPS_INT              next = 1;
      for (types::global_dof_index i = 0; i < solved.size(); ++i)
        if (!solved[i])
          position[i] = next++;
      for (const int k : order)
        position[rows[k]] = next++;
      return position;
    }
  } // namespace

  /**
   * MUMPS called directly rather than through Amesos: Amesos_Mumps always
   * factorises LU (its SYM is fixed at 0) and scatters the solution over
   * the ranks' rows after every solve, which solve_at() would then gather
   * again (doc/parallel.md, "The plate").
   */
  struct DistributedSparseDirect::Data
  {
    DMUMPS_STRUC_C    id{};
    bool              initialised  = false;
    MPI_Comm          communicator = MPI_COMM_SELF;
    unsigned int      rank         = 0;
    std::vector<bool> solved;
    // this rank's entries of the upper triangle, one-based, which MUMPS
    // reads again in the factorisation
    std::vector<MUMPS_INT> rows, columns;
    std::vector<double>    values;
    // the right-hand side and then the solution, whole on rank 0 only
    mutable std::vector<double> rhs;

    ~Data()
    {
      // Ending MUMPS is collective. A rank that unwinds may be alone, on
      // its way to MPI_Abort (doc/parallel.md, "Choices and their
      // reasons"), where waiting for the others would hang it: it leaves
      // MUMPS's memory to the end of the process instead.
      if (initialised && std::uncaught_exceptions() == 0)
        {
          id.job = end_job;
          dmumps_c(&id);
        }
    }

    /** Runs @p job; throws (throw_if_failed()) if it failed. */
    void
    run(const MUMPS_INT job, const char *what)
    {
      id.job = job;
      dmumps_c(&id);
      throw_if_failed(what);
    }

    /** Throws on every rank (MUMPS's INFOG is global) if the last job
     *  failed, saying that MUMPS could not @p what the plate. */
    void
    throw_if_failed(const char *what) const
    {
      AssertThrow(infog(id, 1) >= 0,
                  ExcMessage(
                    std::string("MUMPS could not ") + what +
                    " the plate (INFOG(1) = " + std::to_string(infog(id, 1)) +
                    ", INFOG(2) = " + std::to_string(infog(id, 2)) + ")."));
    }
  };

  DistributedSparseDirect::DistributedSparseDirect() = default;

  DistributedSparseDirect::~DistributedSparseDirect() = default;

  void
  DistributedSparseDirect::factorize(const SparseMatrix<double> &matrix,
                                     const std::vector<bool>    &solved,
                                     const IndexSet             &owned_rows,
                                     const MPI_Comm              communicator)
  {
    AssertDimension(solved.size(), matrix.m());
    AssertDimension(owned_rows.size(), matrix.m());
    AssertThrow(matrix.m() < static_cast<std::size_t>(
                               std::numeric_limits<MUMPS_INT>::max()),
                ExcMessage("The plate has more unknowns than MUMPS's "
                           "integers count."));
    data               = std::make_unique<Data>();
    data->communicator = communicator;
    data->rank         = rank_in(communicator);
    data->solved       = solved;

    // The upper triangle of the rows and columns solved, every stored
    // entry kept (the one process's CHOLMOD factor takes the same); an
    // identity row for each index not solved, so that its solution is
    // zero. Each rank gives its own rows.
    for (const auto i : owned_rows)
      {
        if (!solved[i])
          {
            data->rows.push_back(i + 1);
            data->columns.push_back(i + 1);
            data->values.push_back(1.);
            continue;
          }
        for (auto entry = matrix.begin(i); entry != matrix.end(i); ++entry)
          if (entry->column() >= i && solved[entry->column()])
            {
              data->rows.push_back(i + 1);
              data->columns.push_back(entry->column() + 1);
              data->values.push_back(entry->value());
            }
      }

    DMUMPS_STRUC_C &id = data->id;
    id.comm_fortran    = static_cast<MUMPS_INT>(MPI_Comm_c2f(communicator));
    id.par             = 1; // rank 0 takes part in the work
    id.sym             = 1; // symmetric positive definite: LDL^T, no pivoting
    data->run(initialise_job, "start for");
    data->initialised = true;
    // silent: failures come back through INFOG and become exceptions
    for (unsigned int i = 1; i <= 3; ++i)
      icntl(id, i) = -1;
    icntl(id, 4)  = 0;
    icntl(id, 5)  = 0; // assembled entries
    icntl(id, 18) = 3; // each rank gives its own entries
    icntl(id, 20) = 0; // dense right-hand side on rank 0
    icntl(id, 21) = 0; // the solution gathered on rank 0
    id.n          = matrix.m();
    id.nnz_loc    = data->rows.size();
    id.irn_loc    = data->rows.data();
    id.jcn_loc    = data->columns.data();
    id.a_loc      = data->values.data();
    // MUMPS's own ordering is PORD here (Debian's MUMPS has neither METIS
    // nor SCOTCH), on rank 0 alone while the others wait, and it took
    // most of the factorisation's time; the nested dissection that CHOLMOD
    // takes on one process instead (doc/performance.md, "The plate's
    // ordering on several processes"). Only the host reads it.
    std::vector<MUMPS_INT> order;
    if (data->rank == 0)
      order = pivot_positions(matrix.get_sparsity_pattern(), solved);
    if (!order.empty())
      {
        icntl(id, 7) = 1; // the ordering given in PERM_IN
        id.perm_in   = order.data();
      }
    data->run(analyse_job, "analyse");
    id.perm_in = nullptr;
    // MUMPS sizes its workspace from the analysis and asks for more when
    // the factorisation needs it (INFOG(1) = -8, -9: its integer and real
    // workspace; -17, -20: its send and receive buffers): a few tries,
    // each with twice the margin
    const auto needs_more_workspace = [&id]() {
      const MUMPS_INT error = infog(id, 1);
      return error == -8 || error == -9 || error == -17 || error == -20;
    };
    for (unsigned int attempt = 0;; ++attempt)
      {
        id.job = factorise_job;
        dmumps_c(&id);
        if (!needs_more_workspace() || attempt == 3)
          break;
        icntl(id, 14) = 2 * std::max<MUMPS_INT>(icntl(id, 14), 20);
      }
    // Without pivoting, a matrix that is not positive definite shows as
    // negative pivots (INFOG(12)), as a zero pivot (INFOG(1) = -10), or, in
    // the root front that ScaLAPACK factorises on several ranks, as its
    // Cholesky's failure (INFOG(1) = -40).
    const MUMPS_INT error = infog(id, 1);
    AssertThrow(error != -10 && error != -40 && infog(id, 12) == 0,
                ExcMessage("MUMPS found the matrix not positive definite (" +
                           (error < 0 ? "INFOG(1) = " + std::to_string(error) :
                                        std::to_string(infog(id, 12)) +
                                          " negative pivots") +
                           ")."));
    data->throw_if_failed("factorise");
  }

  std::size_t
  DistributedSparseDirect::memory_consumption() const
  {
    if (data == nullptr)
      return 0;
    // MUMPS gives a count above 2^31 as minus its millions
    const auto entries = [](const MUMPS_INT count) -> std::size_t {
      return count >= 0 ? std::size_t(count) : std::size_t(-count) * 1000000;
    };
    return entries(data->id.info[8]) * sizeof(double) +
           entries(data->id.info[9]) * sizeof(MUMPS_INT) +
           data->values.size() * (sizeof(double) + 2 * sizeof(MUMPS_INT));
  }

  void
  DistributedSparseDirect::solve_on_first_rank(const Vector<double> &f) const
  {
    Assert(data != nullptr, ExcMessage("solve() before factorize()."));
    AssertDimension(f.size(), data->solved.size());
    DMUMPS_STRUC_C &id = data->id;
    if (data->rank == 0)
      {
        data->rhs.resize(f.size());
        for (unsigned int i = 0; i < f.size(); ++i)
          data->rhs[i] = data->solved[i] ? f[i] : 0.;
        id.rhs  = data->rhs.data();
        id.nrhs = 1;
        id.lrhs = f.size();
      }
    data->run(solve_job, "solve for");
  }

  void
  DistributedSparseDirect::solve(const Vector<double> &f,
                                 Vector<double>       &u) const
  {
    solve_on_first_rank(f);
    u.reinit(f.size());
    if (data->rank == 0)
      for (unsigned int i = 0; i < f.size(); ++i)
        u[i] = data->solved[i] ? data->rhs[i] : 0.;
    // rank 0's bits on every rank
    broadcast_from_first_rank(make_array_view(u), data->communicator);
  }

  void
  DistributedSparseDirect::solve_at(
    const Vector<double>                       &f,
    const std::vector<types::global_dof_index> &rows,
    Vector<double>                             &values) const
  {
    solve_on_first_rank(f);
    values.reinit(rows.size());
    if (data->rank == 0)
      for (unsigned int k = 0; k < rows.size(); ++k)
        values[k] = data->solved[rows[k]] ? data->rhs[rows[k]] : 0.;
    broadcast_from_first_rank(make_array_view(values), data->communicator);
  }
} // namespace PlateOnHalfspace
