/**
 * While a SingleThreadedBlas lives, OpenBLAS computes on the calling thread
 * alone (doc/performance.md, "BLAS" and "BLAS threads in the contact
 * solve"). OpenBLAS's threads wait for work by spinning, so where the BLAS
 * work comes in small calls, the threads gain nothing and take the cores
 * from everything else that runs:
 *  - inside hmat-oss calls (many small blocks): on a 2-core machine the
 *    H-Cholesky took 5 times and the product 4 times as long with them
 *    (5373 nodes: 10.6 s against 1.9 s) whenever anything else ran;
 *    hmat-oss's own switch for this is compiled out of Debian's build;
 *  - in the iterative contact solve, whose BLAS calls are the sparse
 *    factors' triangular solves (level-2 work on a few columns) while
 *    deal.II's tasks compute the half-space's product beside them: at
 *    10^5 foundation nodes the contact solve of tensionless example 2
 *    took 81 s with them against 55 s without.
 * Factorisations (also the preconditioners' refactorisations for a new
 * contact set) and the dense storage's LAPACK calls and products, which do
 * gain from the threads, run outside.
 *
 * The count is OpenBLAS's process-wide setting, so construct and destroy
 * a guard only where no other thread is inside the BLAS; a guard inside
 * another (the count already 1) changes nothing. Where the BLAS is not
 * OpenBLAS (no openblas_set_num_threads in the process) it does nothing.
 */
#ifndef plate_on_halfspace_base_single_threaded_blas_h
#define plate_on_halfspace_base_single_threaded_blas_h

namespace PlateOnHalfspace
{
  /** See the file documentation. */
  class SingleThreadedBlas
  {
  public:
    SingleThreadedBlas();
    /** Restores the thread count found by the constructor. */
    ~SingleThreadedBlas();
    SingleThreadedBlas(const SingleThreadedBlas &) = delete;
    SingleThreadedBlas &
    operator=(const SingleThreadedBlas &) = delete;

    /** Whether the BLAS runs on one thread now: OpenBLAS's count is 1
     *  (inside a guard, or so set), or the BLAS is not OpenBLAS. */
    static bool
    in_effect();

  private:
    /** OpenBLAS's count before, 0 where there is none to restore. */
    int previous = 0;
  };
} // namespace PlateOnHalfspace

#endif
