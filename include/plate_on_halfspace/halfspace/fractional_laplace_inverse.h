/**
 * The inverse of the homogeneous half-space's flexibility as a fractional
 * power of the pressure space's Laplacian (doc/formulation.md,
 * "Preconditioning the contact pressures", "Fractional soil inverse"):
 *
 *   F^{-1} ≈ (1 / (2 pi alpha)) (M^{-1} A)^{1/2} M^{-1},  A = L + c M,
 *
 * with M the mass matrix, L the Laplacian with natural boundary conditions
 * on the same nodes and c = (4 / sqrt(pi area))^2, the rigid disk of the
 * plate's area. On the plane the kernel alpha / r has the symbol
 * 2 pi alpha / k and L that of k^2, so the two agree at every wave number;
 * on the plate, ⟨F^{-1} s, s⟩ and ⟨(M^{-1}A)^{1/2} M^{-1} s, s⟩ are both
 * equivalent to the H^{1/2} norm of the settlement, so on shape-regular,
 * quasi-uniform meshes the preconditioned iterations do not grow with
 * the mesh (elongated cells and strong grading raise them: see the doc).
 *
 * (M^{-1} A)^{1/2} = (M^{-1} A) (M^{-1} A)^{-1/2}, and x^{-1/2} by
 * Zolotarev's best relative rational approximation over the spectrum of
 * M^{-1} A (from c to a power iteration's bound), each pole a sparse
 * Cholesky factor of A + t^2 M; the fewest poles that keep the
 * approximation within about 7 % of the power at every eigenvalue
 * (fractional_laplace_inverse.cc, doc/formulation.md).
 *
 * On several processes the rule's parts (each pole's solve, and the two
 * solves with M) are shared out over the ranks: each rank holds and
 * applies the factors of its own parts only, and one sum over the ranks
 * joins them (doc/parallel.md, "The soil inverse by its poles").
 */
#ifndef plate_on_halfspace_halfspace_fractional_laplace_inverse_h
#define plate_on_halfspace_halfspace_fractional_laplace_inverse_h

#include <deal.II/lac/sparse_matrix.h>

#include <plate_on_halfspace/halfspace/interface.h>

#include <memory>
#include <vector>

namespace PlateOnHalfspace
{
  class SparseCholesky;

  /** See the file documentation; acts on nodal values (no pressure basis). */
  class FractionalLaplaceInverse : public ApproximateInverse
  {
  public:
    /**
     * @p mass and @p laplace on the same pattern (FoundationSpace::
     * assemble_mass_matrix() with every cell, assemble_laplace_matrix()),
     * @p alpha the kernel's alpha / r, @p area the plate's area with its
     * mirror images, @p analysis the symbolic analysis of that pattern
     * (SparseCholesky::analyze()), which every factor shares. Throws
     * StorageDoesNotFit (halfspace/memory_guard.h) before the poles'
     * factors are allocated if they need more than
     * available_memory_bytes(); on several processes the ranks of
     * @p communicator share the parts (part_owners()) and decide that
     * together, each for its own factors (memory_on_machine()). The
     * constructor and vmult() are collective.
     */
    FractionalLaplaceInverse(const SparseMatrix<double> &mass,
                             const SparseMatrix<double> &laplace,
                             const double                alpha,
                             const double                area,
                             const SparseCholesky       &analysis,
                             const MPI_Comm communicator = MPI_COMM_SELF);
    ~FractionalLaplaceInverse() override;

    void
    vmult(Vector<double> &q, const Vector<double> &s) const override;

    std::size_t
    memory_consumption() const override;

    /**
     * The sparse factors the rule needs (one per pole t_l, and M's) where
     * the largest eigenvalue of M^{-1} L is @p largest_eigenvalue, for
     * a plate of @p area: what a storage's memory estimate multiplies
     * SparseCholesky::factor_bytes() by.
     */
    static unsigned int
    n_factors(const double area, const double largest_eigenvalue);

    /**
     * The most sparse factors one of @p n_ranks ranks holds (n_factors()
     * on one rank): what a storage's memory estimate per rank multiplies
     * SparseCholesky::factor_bytes() by.
     */
    static unsigned int
    n_factors_on_a_rank(const double       area,
                        const double       largest_eigenvalue,
                        const unsigned int n_ranks);

    /**
     * The rank that applies each part of a rule of @p n_poles poles on
     * @p n_ranks ranks: entry l < n_poles for pole l's solve, entry
     * n_poles for the mass chain M^{-1} s, M^{-1} A M^{-1} s. Each part
     * goes to the rank with the least work so far (a pole one solve, the
     * chain two), the lowest such rank on a tie: the ranks' shares of
     * the solves differ by at most two.
     */
    static std::vector<unsigned int>
    part_owners(const unsigned int n_poles, const unsigned int n_ranks);

    /**
     * An estimate from above of the largest eigenvalue of M^{-1} L on
     * @p space, from its cells alone: twice the largest of a Q2 cell's
     * own, 60 (1/a^2 + 1/b^2) = 60 d^2 / area^2 on an a x b rectangle of
     * diagonal d; the factor two covers distorted cells.
     */
    static double
    largest_eigenvalue_estimate(const FoundationSpace &space);

    /** The poles t_l of the rule (one factorisation each). */
    unsigned int
    n_poles() const
    {
      return poles.size();
    }

    /** The sparse factors this rank holds: its poles', and M's if it
     *  applies the mass chain. */
    unsigned int
    n_factors_here() const;

  private:
    /** One pole of the rule; its factor only on the rank that applies
     *  it (nullptr elsewhere). */
    struct Pole
    {
      double                          t, weight;
      std::unique_ptr<SparseCholesky> factor;
    };

    MPI_Comm             communicator;
    SparseMatrix<double> shifted; ///< A = L + c M
    /** M's factor, kept only on the rank that applies the mass chain. */
    std::unique_ptr<SparseCholesky> mass_factor;
    std::vector<Pole>               poles;
    /** The weights of M^{-1} s and of M^{-1} A M^{-1} s (the tails). */
    double identity_weight = 0, top_weight = 0;
    double scale = 0; ///< 2 / pi / (2 pi alpha)
  };
} // namespace PlateOnHalfspace

#endif
